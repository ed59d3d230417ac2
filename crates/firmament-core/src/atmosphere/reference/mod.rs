//! The f64 reference: transmittance, single scattering, multiple scattering and ground
//! irradiance, computed slowly and carefully. Every GPU atmosphere pass is tested against it.
//!
//! # Method
//! - **Optical depth**: adaptive Simpson quadrature of the extinction along the segment, split at
//!   the point of closest approach to the planet centre (where the density peaks), to a relative
//!   accuracy of about 1e-9. Altitudes are exact geodetic heights ([`Planet::altitude`]).
//! - **Single scattering** and the sunlit ground seen directly: composite Simpson over the visible
//!   part of the view ray ([`ReferenceSettings::view_steps`] panels) with the optical depth
//!   between nodes and towards each sun integrated adaptively. Suns are points for scattering
//!   (their disc is drawn separately) and light a point only when the straight path to them
//!   misses the ground.
//! - **Multiple scattering** (orders ≥ 2, ground bounces included): Monte Carlo path tracing,
//!   see `path_tracer.rs`, in parallel with rayon and deterministic for a given seed however many
//!   threads run. Paths end by Russian roulette, never at a fixed order, so every order is
//!   included without bias; [`MultipleScattering::per_order`] shows how each order adds.
//! - **Second order alone** ([`Reference::second_order`]): nested Gauss–Legendre quadrature, no
//!   Monte Carlo, see `order_two.rs`: a deterministic check of the path tracer's `per_order[2]`.
//!
//! All inputs are in the world frame; the computation runs in the planet frame.
//!
//! [`Planet::altitude`]: crate::atmosphere::Planet::altitude

mod inputs;
mod order_two;
mod path_tracer;
mod quadrature;

use glam::DVec3;

use crate::atmosphere::spectrum::Spectrum;
use crate::atmosphere::{Atmosphere, Sun};
use crate::camera::Camera;
use crate::geometry::Ray;
use inputs::segment;
use quadrature::adaptive_simpson;

pub use inputs::{Reference, ReferenceSettings};
pub use order_two::SecondOrderSettings;
pub use path_tracer::{MultipleScattering, TALLIED_ORDERS};

/// The radiance reaching the eye along one view ray, by source, W·m⁻²·sr⁻¹·nm⁻¹.
#[derive(Debug, Clone, PartialEq)]
pub struct RadianceParts {
    /// Sunlight scattered once by the air.
    pub single: Spectrum,
    /// Sunlight reflected once by the ground, attenuated on its way to the eye.
    pub ground: Spectrum,
    /// Everything scattered or reflected twice or more.
    pub multiple: MultipleScattering,
    /// The suns' discs seen through the atmosphere.
    pub sun_discs: Spectrum,
    /// Transmittance from the eye along the ray to space (zero when the ray meets the ground).
    pub transmittance: Spectrum,
}

impl RadianceParts {
    /// The sum of all parts.
    pub fn total(&self) -> Spectrum {
        self.single + self.ground + self.multiple.total + self.sun_discs
    }

    /// Everything but the sun discs: the scattered light the sky-view passes produce.
    pub fn scattered(&self) -> Spectrum {
        self.single + self.ground + self.multiple.total
    }
}

/// Irradiance on a horizontal surface (perpendicular to the geodetic up), W·m⁻²·nm⁻¹.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundIrradiance {
    /// From the suns directly, attenuated by the atmosphere.
    pub direct: Spectrum,
    /// From the whole sky (all orders of scattering and ground inter-reflection).
    pub sky: Spectrum,
}

impl Reference {
    /// A reference for `atmosphere` lit by `suns` (directions in the world frame).
    pub fn new(atmosphere: Atmosphere, suns: &[Sun], settings: ReferenceSettings) -> Self {
        let planet = atmosphere.planet;
        let suns = suns
            .iter()
            .map(|sun| Sun {
                direction: planet.direction_to_planet_frame(sun.direction).normalize(),
                ..*sun
            })
            .collect();
        Self {
            atmosphere,
            suns,
            settings,
        }
    }

    /// A whole image seen by `camera` (its aspect ratio replaced by `width / height`): the total
    /// spectral radiance through each pixel's centre, row-major, top row first. Rows run in
    /// parallel; each pixel's Monte Carlo estimate is seeded by its ray, so the image does not
    /// depend on the thread count.
    pub fn image(&self, camera: &Camera, width: u32, height: u32) -> Vec<Spectrum> {
        use rayon::prelude::*;
        let camera = Camera {
            aspect: f64::from(width) / f64::from(height),
            ..*camera
        };
        (0..height)
            .into_par_iter()
            .flat_map_iter(|y| {
                (0..width).map(move |x| {
                    let ndc = glam::DVec2::new(
                        (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0,
                        1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0,
                    );
                    self.radiance(&Ray {
                        origin: camera.position,
                        direction: camera.view_direction(ndc),
                    })
                    .total()
                })
            })
            .collect()
    }

    /// The atmosphere.
    pub fn atmosphere(&self) -> &Atmosphere {
        &self.atmosphere
    }

    /// Extinction coefficient at a planet-frame point, m⁻¹.
    fn extinction(&self, p: DVec3) -> Spectrum {
        self.atmosphere.medium.at(self.atmosphere.planet.altitude(p)).extinction
    }

    /// Optical depth of the planet-frame ray between parameters `t0` and `t1`.
    pub fn optical_depth_along(&self, ray: &Ray, t0: f64, t1: f64) -> Spectrum {
        if t1 <= t0 {
            return Spectrum::ZERO;
        }
        let f = |t: f64| self.extinction(ray.at(t));
        // Split where the ray passes closest to the centre: the densest point of a long chord.
        let closest = (-ray.origin.dot(ray.direction)).clamp(t0, t1);
        adaptive_simpson(&f, t0, closest, 1e-10) + adaptive_simpson(&f, closest, t1, 1e-10)
    }

    /// Optical depth between two planet-frame points inside the atmosphere (straight line; the
    /// ground is ignored).
    pub fn optical_depth(&self, a: DVec3, b: DVec3) -> Spectrum {
        let Some(ray) = Ray::new(a, b - a) else {
            return Spectrum::ZERO;
        };
        self.optical_depth_along(&ray, 0.0, (b - a).length())
    }

    /// Transmittance from a planet-frame point along a direction to space: zero when the ray
    /// meets the ground.
    pub fn transmittance_to_space(&self, p: DVec3, direction: DVec3) -> Spectrum {
        let Some(ray) = Ray::new(p, direction) else {
            return Spectrum::ZERO;
        };
        match segment(&self.atmosphere.planet, &ray) {
            None => Spectrum::ONE,
            Some(s) if s.ends_on_ground => Spectrum::ZERO,
            Some(s) => (-self.optical_depth_along(&ray, s.start, s.end)).exp(),
        }
    }

    /// Radiance along a world-frame view ray, by source.
    pub fn radiance(&self, view: &Ray) -> RadianceParts {
        self.radiance_before(view, f64::INFINITY)
    }

    /// Radiance along a world-frame view ray that ends on an opaque black surface at `distance`
    /// metres (the ray's direction is normalised): the aerial perspective in front of that
    /// surface. `transmittance` is then the transmittance from the eye to the surface, and
    /// nothing behind the surface (sun discs, ground, sky) is seen; the surface casts no shadow
    /// (the GPU's aerial perspective makes the same assumption). An infinite `distance` is
    /// [`radiance`](Self::radiance).
    pub fn radiance_before(&self, view: &Ray, distance: f64) -> RadianceParts {
        let planet = &self.atmosphere.planet;
        let ray = planet.ray_to_planet_frame(view);
        let (single, ground, transmittance) = self.single_scattering(&ray, distance);
        let multiple = path_tracer::multiple_scattering(self, &ray, 2, self.settings.paths, distance);
        let sun_discs = if distance.is_finite() {
            Spectrum::ZERO
        } else {
            self.suns
                .iter()
                .map(|sun| {
                    let angle = ray.direction.dot(sun.direction).clamp(-1.0, 1.0).acos();
                    sun.disc_radiance(angle) * transmittance
                })
                .sum()
        };
        RadianceParts {
            single,
            ground,
            multiple,
            sun_discs,
            transmittance,
        }
    }

    /// The radiance along a world-frame view ray of light scattered or reflected exactly twice,
    /// W·m⁻²·sr⁻¹·nm⁻¹ — what [`MultipleScattering::per_order`]`[2]` of
    /// [`radiance`](Self::radiance) estimates — by nested quadrature instead of Monte Carlo:
    /// deterministic, and refined by [`SecondOrderSettings::refinement`] until it converges.
    /// About a second at the default settings on a spherical planet (two cores); tens of times
    /// longer on any other (22 s on the WGS84 Earth), whose transmittance towards the suns is
    /// integrated at every point. The reference's own [`ReferenceSettings`] play no part: in
    /// particular no `background` light enters.
    pub fn second_order(&self, view: &Ray, settings: &SecondOrderSettings) -> Spectrum {
        order_two::second_order(self, &self.atmosphere.planet.ray_to_planet_frame(view), settings)
    }

    /// Single scattering, the directly sunlit ground seen along the ray, and the transmittance to
    /// space (or to an opaque surface at `limit` along the ray), for a planet-frame ray.
    fn single_scattering(&self, ray: &Ray, limit: f64) -> (Spectrum, Spectrum, Spectrum) {
        let planet = &self.atmosphere.planet;
        let medium = &self.atmosphere.medium;
        let Some(segment) = segment(planet, ray).and_then(|s| s.before(limit).0) else {
            return (Spectrum::ZERO, Spectrum::ZERO, Spectrum::ONE);
        };
        let n = self.settings.view_steps.max(2).next_multiple_of(2);
        let dt = (segment.end - segment.start) / n as f64;
        // The medium is the shell: nothing to attenuate before the ray enters it.
        let mut depth = Spectrum::ZERO;
        let mut sum = Spectrum::ZERO;
        for i in 0..=n {
            let t = segment.start + dt * i as f64;
            if i > 0 {
                depth += self.optical_depth_along(ray, t - dt, t);
            }
            let p = ray.at(t);
            let coefficients = medium.at(planet.altitude(p));
            let mut in_scattered = Spectrum::ZERO;
            for sun in &self.suns {
                let nu = ray.direction.dot(sun.direction);
                let sun_transmittance = self.transmittance_to_space(p, sun.direction);
                in_scattered += medium.scattering_phase(&coefficients, nu) * sun_transmittance * sun.irradiance;
            }
            let weight = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            sum += in_scattered * (-depth).exp() * weight;
        }
        let single = sum * (dt / 3.0);
        let end_transmittance = (-depth).exp();
        if !segment.ends_on_ground {
            return (single, Spectrum::ZERO, end_transmittance);
        }
        let ground_point = ray.at(segment.end);
        let up = planet.up(ground_point);
        let irradiance = self.direct_irradiance(ground_point, up);
        let ground = end_transmittance * medium.ground_albedo * irradiance / std::f64::consts::PI;
        (single, ground, Spectrum::ZERO)
    }

    /// Direct sun irradiance on a surface with normal `up` at a planet-frame point.
    fn direct_irradiance(&self, p: DVec3, up: DVec3) -> Spectrum {
        self.suns
            .iter()
            .map(|sun| {
                let cos = up.dot(sun.direction).max(0.0);
                sun.irradiance * self.transmittance_to_space(p + up * 1e-3, sun.direction) * cos
            })
            .sum()
    }

    /// Irradiance on a horizontal surface at a world-frame point on (or above) the ground.
    pub fn ground_irradiance(&self, world_point: DVec3) -> GroundIrradiance {
        let p = self.atmosphere.planet.to_planet_frame(world_point);
        let up = self.atmosphere.planet.up(p);
        GroundIrradiance {
            direct: self.direct_irradiance(p, up),
            sky: path_tracer::sky_irradiance(self, p + up * 1e-3, up, self.settings.paths),
        }
    }
}

#[cfg(test)]
mod order_two_tests;
#[cfg(test)]
mod tests;
