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
//! - **Occluders** ([`Reference::with_occluders`]): opaque black shapes, to check the GPU's light
//!   shafts and shadows. A view ray ends at the first one it meets, exactly as at the surface of
//!   [`Reference::radiance_before`] (no ground or sun disc behind it; every part, multiple
//!   scattering included, stops there). **Occluders shadow single scattering and the direct sun
//!   on the ground; multiple scattering and the sky's irradiance do not see them** — nor does
//!   [`Reference::second_order`], not even on its view ray — which is what the GPU's shadowed
//!   in-scattering models too. A point is lit by a sun only when the straight path from it
//!   towards the sun misses every occluder (as well as the ground). The in-scattered light jumps
//!   where the view ray crosses a shadow's edge, so the view ray's Simpson panels are split
//!   there ([`Occluder::shadow_along`]): each piece between edges gets its share of
//!   [`ReferenceSettings::view_steps`] (at least two panels) and is either lit or shadowed
//!   throughout, so the quadrature stays accurate however thin the shaft.
//! - **Clouds** ([`Reference::with_clouds`]): layers of [`CloudLayer`], planet frame. The
//!   medium's extinction becomes the air's plus every layer's density (grey), its scattering the
//!   air's plus each layer's `albedo ×` density with the layer's dual Henyey–Greenstein phase
//!   function. Every integral along a ray is split where the ray crosses a layer's bottom or top
//!   shell (spheres in closed form; on an ellipsoid the exact geodetic-height surfaces, by root
//!   finding, see `cloud_media.rs`):
//!   - optical depth and transmittance: the air's adaptive Simpson as before, plus the clouds'
//!     optical depth — a uniform layer's density times the exact length inside its shell, any
//!     other kind by composite Simpson with panels no longer than a fraction of the field's
//!     finest feature (1/32 of its detail cell and a quarter of its base and top fades: the
//!     optical depth agrees with a 0.25 m rule to 7e-4);
//!   - single scattering: the view ray's Simpson pieces are split at the shells too, and a piece
//!     inside clouds gets at least enough panels for a quarter of an optical depth each (of the
//!     view ray's extinction and of the change of the sun's optical depth along it) and the
//!     feature step; the clouds add `σ_s,cloud·P_cloud(ν)·E·T_sun` at every node, with the sun's
//!     transmittance through the clouds (so clouds shadow the air, the ground and each other).
//!     The quadrature stops where the view ray's optical depth passes 60 at every wavelength
//!     (what lies beyond is dimmed by 1e-26), the transmittance itself is integrated to the end;
//!   - multiple scattering: the path tracer splits each segment at the shells and tracks inside
//!     them by delta tracking, with next-event estimation through the clouds by ratio tracking
//!     (see `path_tracer.rs`).
//!
//!   What clouds leave out: [`ReferenceSettings::line_samples`] (gathering along segments) is
//!   ignored when there are clouds (collisions gather instead: unbiased, noisier at twilight);
//!   [`Reference::second_order`] integrates the air alone; suns are points, so the clouds'
//!   forward peak narrower than the sun's disc (the aureole) is not resolved; occluders act on
//!   the clouds as on the air (they shadow single scattering, not multiple scattering). Without
//!   clouds every result is bit for bit what it was.
//!
//! All inputs are in the world frame; the computation runs in the planet frame.
//!
//! [`Planet::altitude`]: crate::atmosphere::Planet::altitude

mod cloud_media;
mod inputs;
mod order_two;
mod path_tracer;
pub(crate) mod quadrature;

use glam::DVec3;

use crate::atmosphere::clouds::CloudLayer;
use crate::atmosphere::eclipse::visible_fraction;
use crate::atmosphere::rings::Rings;
use crate::atmosphere::spectrum::Spectrum;
use crate::atmosphere::surface::{GroundSample, Surface};
use crate::atmosphere::{Atmosphere, Eclipser, Sun};
use crate::camera::Camera;
use crate::geometry::Ray;
use crate::occluder::Occluder;
use inputs::segment;
use quadrature::adaptive_simpson;

pub use inputs::{Reference, ReferenceSettings};
pub use order_two::SecondOrderSettings;
pub use path_tracer::{MultipleScattering, TALLIED_ORDERS};

/// Optical depth (every wavelength) past which single scattering stops along a view ray in a
/// cloud: what lies beyond is dimmed by e⁻⁶⁰ ≈ 1e-26 or more.
const OPAQUE_DEPTH: f64 = 60.0;

/// The most Simpson panels in one piece of a view ray inside clouds.
const MAX_CLOUD_PANELS: usize = 1 << 20;

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
    /// Transmittance from the eye along the ray to space (zero when the ray meets the ground), or
    /// to the surface or occluder that ends it.
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
            occluders: Vec::new(),
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            rings: None,
            surface: None,
        }
    }

    /// Sets the cloud layers (replacing any set before), planet frame as they are (their
    /// [`CloudLayer::drift`] turns each pattern in the planet frame). With clouds the medium's
    /// extinction is the air's plus every layer's density (grey), its scattering the air's plus
    /// each layer's `albedo ×` density with the layer's phase function; see the module docs for
    /// how each part integrates them and what they leave out. The layers should pass
    /// [`validate_layers`](crate::atmosphere::clouds::validate_layers) (at most
    /// [`MAX_CLOUD_LAYERS`](crate::atmosphere::clouds::MAX_CLOUD_LAYERS)).
    ///
    /// # Panics
    /// With more than [`MAX_CLOUD_LAYERS`](crate::atmosphere::clouds::MAX_CLOUD_LAYERS) layers.
    pub fn with_clouds(mut self, layers: &[CloudLayer]) -> Self {
        assert!(
            layers.len() <= crate::atmosphere::clouds::MAX_CLOUD_LAYERS,
            "at most {} cloud layers",
            crate::atmosphere::clouds::MAX_CLOUD_LAYERS
        );
        self.clouds = layers.to_vec();
        self
    }

    /// The cloud layers ([`with_clouds`](Self::with_clouds)).
    pub fn clouds(&self) -> &[CloudLayer] {
        &self.clouds
    }

    /// Sets the opaque occluders (world frame, metres; replacing any set before) that shadow
    /// single scattering and the direct sun on the ground and end view rays; see the module docs
    /// for what they leave out. Each should pass [`Occluder::validate`].
    pub fn with_occluders(mut self, occluders: &[Occluder]) -> Self {
        let planet = self.atmosphere.planet;
        self.occluders = occluders.iter().map(|o| o.to_planet_frame(&planet)).collect();
        self
    }

    /// Sets the bodies that eclipse the suns (world frame, metres; replacing any set before):
    /// every sun's light at every point — single scattering, the path tracer's every event, the
    /// ground's direct light — is scaled by the fraction of its disc they leave visible there
    /// ([`visible_fraction`]), and a view ray that meets one sees no sun disc behind it. With
    /// eclipsers the suns' coronae are drawn ([`Sun::corona_radiance`]). Each should pass
    /// [`Eclipser::validate`].
    pub fn with_eclipsers(mut self, eclipsers: &[Eclipser]) -> Self {
        let planet = self.atmosphere.planet;
        self.eclipsers = eclipsers.iter().map(|e| e.to_planet_frame(&planet)).collect();
        self
    }

    /// Sets the planet's rings (planet frame, as [`Rings`] are given): every sun's light at every
    /// point is times the rings' transmittance along the ray from it towards the sun — their
    /// shadow on the globe and the air. The rings' own light is [`Rings::radiance`]; a view ray
    /// here does not see them. They should pass [`Rings::validate`].
    pub fn with_rings(mut self, rings: Option<&Rings>) -> Self {
        self.rings = rings.cloned();
        self
    }

    /// Sets the planet's surface ([`crate::atmosphere::surface`]): the ground's albedo wherever
    /// light meets it is the surface's there (not the medium's `ground_albedo`), and its water
    /// adds each sun's glint to the sunlight it reflects towards the eye or the next event. A
    /// path's bounce off the ground stays Lambertian: the sky's and the air's light reflected
    /// specularly by the water is left out, as on the GPU.
    pub fn with_surface(mut self, surface: Option<&Surface>) -> Self {
        self.surface = surface.cloned();
        self
    }

    /// The ground at planet-frame point `p` with geodetic up `up`.
    pub(super) fn ground_at(&self, up: DVec3) -> GroundSample {
        match &self.surface {
            Some(surface) => surface.at(up),
            None => GroundSample {
                albedo: self.atmosphere.medium.ground_albedo,
                water: 0.0,
            },
        }
    }

    /// Sunlight the ground under `from` (a point 1 mm above it, geodetic up `up`) reflects
    /// towards `to_eye`, W·m⁻²·sr⁻¹·nm⁻¹, with each sun's transmittance to `from` given by
    /// `transmittance`; suns an occluder hides give nothing when `occluders` (single scattering
    /// sees the occluders, multiple scattering does not: see the module docs).
    pub(super) fn ground_reflected(
        &self,
        from: DVec3,
        up: DVec3,
        to_eye: DVec3,
        occluders: bool,
        mut transmittance: impl FnMut(&Sun) -> Spectrum,
    ) -> Spectrum {
        let ground = self.ground_at(up);
        let mut radiance = Spectrum::ZERO;
        for sun in &self.suns {
            if up.dot(sun.direction) <= 0.0 || (occluders && self.occluded(from, sun.direction)) {
                continue;
            }
            let factor = match &self.surface {
                Some(surface) => surface.reflectance_factor(&ground, up, sun.direction, to_eye),
                None => ground.albedo * (up.dot(sun.direction) / std::f64::consts::PI),
            };
            radiance += sun.irradiance * transmittance(sun) * self.sun_visible(from, sun) * factor;
        }
        radiance
    }

    /// The fraction of sun `index`'s disc (in the order given to [`Reference::new`]) that the
    /// eclipsers and the rings leave visible from world-frame `point`: 1 without either.
    ///
    /// # Panics
    /// When there is no sun `index`.
    pub fn sun_visible_fraction(&self, point: DVec3, index: usize) -> f64 {
        let p = self.atmosphere.planet.to_planet_frame(point);
        self.sun_visible(p, &self.suns[index])
    }

    /// The fraction of `sun`'s light the eclipsers and the rings leave at planet-frame point `p`.
    pub(super) fn sun_visible(&self, p: DVec3, sun: &Sun) -> f64 {
        let rings = self.rings.as_ref().map_or(1.0, |r| r.transmittance(p, sun.direction));
        if self.eclipsers.is_empty() {
            rings
        } else {
            rings * visible_fraction(p, sun, &self.eclipsers)
        }
    }

    /// Whether a planet-frame ray meets an eclipser (which hides the suns' discs behind it).
    fn meets_eclipser(&self, ray: &Ray) -> bool {
        self.eclipsers.iter().any(|e| e.hides(ray.origin, ray.direction))
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

    /// The air's extinction coefficient at a planet-frame point, m⁻¹ (clouds not included).
    fn extinction(&self, p: DVec3) -> Spectrum {
        self.atmosphere.medium.at(self.atmosphere.planet.altitude(p)).extinction
    }

    /// Optical depth of the planet-frame ray between parameters `t0` and `t1`: the air's, plus
    /// the clouds' when there are any (grey, split at their shells; see the module docs).
    pub fn optical_depth_along(&self, ray: &Ray, t0: f64, t1: f64) -> Spectrum {
        if t1 <= t0 {
            return Spectrum::ZERO;
        }
        let f = |t: f64| self.extinction(ray.at(t));
        // Split where the ray passes closest to the centre: the densest point of a long chord.
        let closest = (-ray.origin.dot(ray.direction)).clamp(t0, t1);
        let air = adaptive_simpson(&f, t0, closest, 1e-10) + adaptive_simpson(&f, closest, t1, 1e-10);
        if self.clouds.is_empty() {
            return air;
        }
        air + Spectrum::splat(cloud_media::optical_depth(
            &self.atmosphere.planet,
            &self.clouds,
            ray,
            t0,
            t1,
        ))
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
    /// [`radiance`](Self::radiance). An occluder nearer than `distance` ends the ray in the same
    /// way.
    pub fn radiance_before(&self, view: &Ray, distance: f64) -> RadianceParts {
        let planet = &self.atmosphere.planet;
        let ray = planet.ray_to_planet_frame(view);
        let distance = self.view_limit(&ray, distance);
        let (single, ground, transmittance) = self.single_scattering(&ray, distance);
        let multiple = path_tracer::multiple_scattering(self, &ray, 2, self.settings.paths, distance);
        let sun_discs = if distance.is_finite() || self.meets_eclipser(&ray) {
            Spectrum::ZERO
        } else {
            self.suns
                .iter()
                .map(|sun| {
                    let angle = ray.direction.dot(sun.direction).clamp(-1.0, 1.0).acos();
                    // The corona shows only in an eclipse: drawn only when there are eclipsers.
                    let corona = if self.eclipsers.is_empty() {
                        Spectrum::ZERO
                    } else {
                        sun.corona_radiance(angle)
                    };
                    (sun.disc_radiance(angle) + corona) * transmittance
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
    ///
    /// **Clouds are left out**: the second order is that of the air alone, as if
    /// [`with_clouds`](Self::with_clouds) had not been called.
    pub fn second_order(&self, view: &Ray, settings: &SecondOrderSettings) -> Spectrum {
        let ray = self.atmosphere.planet.ray_to_planet_frame(view);
        if self.clouds.is_empty() {
            return order_two::second_order(self, &ray, settings);
        }
        let clear = Self {
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            rings: None,
            ..self.clone()
        };
        order_two::second_order(&clear, &ray, settings)
    }

    /// Single scattering along a world-frame view ray that ends on an opaque black surface at
    /// `distance` metres (infinite: none) or at the first occluder, W·m⁻²·sr⁻¹·nm⁻¹, and the
    /// transmittance to where it ends (to space; zero when it meets the ground) — the
    /// `single` and `transmittance` of [`radiance_before`](Self::radiance_before) without its
    /// path tracing, so cheap enough to check light shafts pixel by pixel.
    pub fn single_scattering_before(&self, view: &Ray, distance: f64) -> (Spectrum, Spectrum) {
        let ray = self.atmosphere.planet.ray_to_planet_frame(view);
        let (single, _, transmittance) = self.single_scattering(&ray, self.view_limit(&ray, distance));
        (single, transmittance)
    }

    /// Where a planet-frame view ray ends: at `distance`, or nearer at the first occluder it meets
    /// (0 when it starts inside one).
    fn view_limit(&self, ray: &Ray, distance: f64) -> f64 {
        self.occluders
            .iter()
            .filter_map(|o| o.hit(ray))
            .filter(|&(_, far)| far > 0.0)
            .fold(distance, |nearest, (near, _)| nearest.min(near.max(0.0)))
    }

    /// Whether an occluder stands between planet-frame point `p` and the sun in `direction`.
    fn occluded(&self, p: DVec3, direction: DVec3) -> bool {
        self.occluders.iter().any(|o| o.blocks(p, direction, f64::INFINITY))
    }

    /// Single scattering, the directly sunlit ground seen along the ray, and the transmittance to
    /// space (or to an opaque surface at `limit` along the ray), for a planet-frame ray.
    fn single_scattering(&self, ray: &Ray, limit: f64) -> (Spectrum, Spectrum, Spectrum) {
        let planet = &self.atmosphere.planet;
        let medium = &self.atmosphere.medium;
        let Some(segment) = segment(planet, ray).and_then(|s| s.before(limit).0) else {
            return (Spectrum::ZERO, Spectrum::ZERO, Spectrum::ONE);
        };
        // Pieces between the occluders' shadow edges, where the integrand jumps (one piece when
        // nothing is shadowed).
        let mut edges = vec![segment.start, segment.end];
        for sun in &self.suns {
            for occluder in &self.occluders {
                if let Some((a, b)) = occluder.shadow_along(ray, sun.direction, segment.start, segment.end) {
                    edges.extend([a, b]);
                }
            }
        }
        // With clouds, also where the ray crosses their shells: the scattering jumps there.
        let clouds = !self.clouds.is_empty();
        if clouds {
            edges.extend(cloud_media::crossings(
                planet,
                &self.clouds,
                ray,
                segment.start,
                segment.end,
            ));
        }
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        let panels = self.settings.view_steps.max(2).next_multiple_of(2);
        let length = segment.end - segment.start;
        // The medium is the shell: nothing to attenuate before the ray enters it.
        let mut depth = Spectrum::ZERO;
        let mut previous = segment.start;
        let mut single = Spectrum::ZERO;
        // Where the view ray became opaque in a cloud (nothing beyond adds anything).
        let mut opaque_from = None;
        for piece in edges.windows(2) {
            let (a, b) = (piece[0], piece[1]);
            let mut n = if edges.len() == 2 {
                panels
            } else {
                ((panels as f64 * (b - a) / length).round() as usize)
                    .max(2)
                    .next_multiple_of(2)
            };
            // Each sun lights all of the piece or none of it: ask at its middle, clear of edges.
            let middle = ray.at(0.5 * (a + b));
            let lit: Vec<bool> = self
                .suns
                .iter()
                .map(|sun| !self.occluded(middle, sun.direction))
                .collect();
            // The layers the piece lies in (none between shells), and the panels they need.
            let inside = if clouds {
                let h = planet.altitude(middle);
                self.clouds
                    .iter()
                    .enumerate()
                    .filter(|(_, l)| h >= l.bottom_m && h <= l.top_m)
                    .fold(0u32, |mask, (i, _)| mask | (1 << i))
            } else {
                0
            };
            if inside != 0 {
                n = n.max(self.cloud_panels(ray, a, b, inside, &lit));
            }
            let dt = (b - a) / n as f64;
            let mut sum = Spectrum::ZERO;
            for i in 0..=n {
                if opaque_from.is_some() {
                    break;
                }
                let t = a + dt * i as f64;
                depth += self.optical_depth_along(ray, previous, t);
                previous = t;
                if clouds && depth.min_element() > OPAQUE_DEPTH {
                    opaque_from = Some(t);
                }
                let p = ray.at(t);
                let h = planet.altitude(p);
                let coefficients = medium.at(h);
                let mut densities = [0.0; crate::atmosphere::clouds::MAX_CLOUD_LAYERS];
                for l in (0..self.clouds.len()).filter(|l| inside & (1 << l) != 0) {
                    densities[l] = cloud_media::density_inside(planet, &self.clouds[l], p, h);
                }
                let mut in_scattered = Spectrum::ZERO;
                for (sun, _) in self.suns.iter().zip(&lit).filter(|(_, lit)| **lit) {
                    let nu = ray.direction.dot(sun.direction);
                    let sun_transmittance = self.transmittance_to_space(p, sun.direction) * self.sun_visible(p, sun);
                    let mut scattering = medium.scattering_phase(&coefficients, nu);
                    if inside != 0 {
                        scattering += Spectrum::splat(cloud_media::scattering_phase(&self.clouds, &densities, nu));
                    }
                    in_scattered += scattering * sun_transmittance * sun.irradiance;
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
            single += sum * (dt / 3.0);
        }
        if let Some(t) = opaque_from {
            depth += self.optical_depth_along(ray, t, segment.end);
        }
        let end_transmittance = (-depth).exp();
        if !segment.ends_on_ground {
            return (single, Spectrum::ZERO, end_transmittance);
        }
        let ground_point = ray.at(segment.end);
        let up = planet.up(ground_point);
        let from = ground_point + up * 1e-3;
        let reflected = self.ground_reflected(from, up, -ray.direction, true, |sun| {
            self.transmittance_to_space(from, sun.direction)
        });
        (single, end_transmittance * reflected, Spectrum::ZERO)
    }

    /// Simpson panels (even) for a piece `[a, b]` of a view ray lying in the cloud layers of the
    /// bit mask `inside`: at most a quarter of an optical depth each — of the view ray's
    /// extinction, and of the sun's optical depth, which changes along the ray by `|μ_view/μ_sun|`
    /// times that (μ: cosines to the local up, the sun's taken as at least 0.05) — and at most
    /// the layers' feature step; [`MAX_CLOUD_PANELS`] at most.
    fn cloud_panels(&self, ray: &Ray, a: f64, b: f64, inside: u32, lit: &[bool]) -> usize {
        let planet = &self.atmosphere.planet;
        let middle = ray.at(0.5 * (a + b));
        let up = planet.up(middle);
        let mu_view = ray.direction.dot(up).abs();
        let slope = self
            .suns
            .iter()
            .zip(lit)
            .filter(|(_, lit)| **lit)
            .map(|(sun, _)| mu_view / sun.direction.dot(up).max(0.05))
            .fold(0.0, f64::max);
        let layers = || {
            (0..self.clouds.len())
                .filter(|l| inside & (1 << l) != 0)
                .map(|l| &self.clouds[l])
        };
        let extinction: f64 = layers().map(|l| l.density_per_m).sum();
        let mut step = 0.25 / (extinction * (1.0 + slope));
        for layer in layers() {
            if let Some(feature) = cloud_media::feature_step(layer) {
                step = step.min(feature);
            }
        }
        if !(step.is_finite() && step > 0.0) {
            return 2;
        }
        (((b - a) / step).ceil() as usize)
            .clamp(2, MAX_CLOUD_PANELS)
            .next_multiple_of(2)
    }

    /// Direct sun irradiance on a surface with normal `up` at a planet-frame point: nothing from
    /// a sun an occluder hides. Seen from 1 mm above the point, so that the ground under it
    /// does not hide the sun by rounding.
    fn direct_irradiance(&self, p: DVec3, up: DVec3) -> Spectrum {
        let from = p + up * 1e-3;
        self.suns
            .iter()
            .filter(|sun| !self.occluded(from, sun.direction))
            .map(|sun| {
                let cos = up.dot(sun.direction).max(0.0);
                sun.irradiance * self.transmittance_to_space(from, sun.direction) * cos * self.sun_visible(from, sun)
            })
            .sum()
    }

    /// Irradiance on a horizontal surface at a world-frame point on (or above) the ground;
    /// occluders hide the suns from `direct` but not the sky from `sky`.
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
mod cloud_tests;
#[cfg(test)]
mod occluder_tests;
#[cfg(test)]
mod order_two_tests;
#[cfg(test)]
mod tests;
