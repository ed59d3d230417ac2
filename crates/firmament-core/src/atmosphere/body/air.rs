//! A body's own air: a thin shell of molecules, aerosols and an absorbing gas around a body
//! beside the planet (Mars seen from Phobos, a second Earth in the sky), drawn in the same view
//! as the planet's air.
//!
//! # Model
//! The air is [`Constituents`] (the classic three terms, as the presets' Earth, Mars and Saturn
//! give them) up to `top_altitude_m` above the body. Altitude is measured on the body's ellipsoid
//! scaled about its centre: `h = (|q| − 1)·R`, `q` the point in the body's axes over its semi-axes
//! and `R` its volumetric mean radius — exact on a ball, and the top of the air is the ellipsoid
//! of semi-axes `radii·(1 + top/R)`.
//!
//! The light it sends towards a viewer is **single scattering** (O'Neil, "Accurate Atmospheric
//! Scattering", *GPU Gems 2* ch. 16, 2005; Nishita et al., "Display of the Earth Taking into
//! Account Atmospheric Scattering", SIGGRAPH 1993): along the view ray through the shell, each
//! sun's light reaches a point after the air's transmittance towards it (zero where the body
//! itself is in the way) and the shadows the caller supplies, and is scattered towards the viewer
//! by Rayleigh's and the aerosols' phase functions, then dimmed by the air back to the viewer —
//! **plus the light scattered more than once** and **the sky's light on the body's ground** from
//! the air's [`AirLight`] tables (Hillaire 2020's multiple-scattering approximation; [`light`]
//! gives the model), where the caller passes them. That approximation holds for thin airs
//! (Earth's, Mars's); thick ones (Venus's, Titan's) belong to the planet, whose air has every
//! order. The body's ground gets each sun's light after the air's transmittance down to it
//! ([`Body::air_transmittance`], which [`super::sunlight_share`] applies) and the sky's
//! ([`Body::skylight_radiance`]).
//!
//! The functions here are the reference the GPU's march is checked against: they integrate by
//! fine midpoint sums ([`VIEW_STEPS`] along the view, [`SUN_STEPS`] towards each sun), not by
//! the GPU's few nodes crowded about the ray's lowest point.

use glam::DVec3;

pub use light::AirLight;

use super::Body;
use crate::atmosphere::medium::{Constituents, Phase};
use crate::atmosphere::spectrum::Spectrum;
use crate::atmosphere::{Sun, medium};
use crate::error::CoreError;
use crate::geometry::{Ellipsoid, Ray};

/// Midpoint steps of [`Body::air_along`] along the view ray's path through the air.
pub const VIEW_STEPS: usize = 2048;

/// Midpoint steps of [`Body::air_transmittance`] towards a sun.
pub const SUN_STEPS: usize = 256;

/// A body's air (the module docs give the model).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyAir {
    /// Molecules, aerosols and an absorbing gas: coefficients at density 1 (m⁻¹, at the sky's
    /// model wavelengths) and density profiles by altitude above the body's surface.
    pub constituents: Constituents,
    /// Height of the air's top above the surface, metres, > 0.
    pub top_altitude_m: f64,
}

/// What a body's air does to a view ray: the light it scatters towards the viewer and its
/// transmittance along the ray's path through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirSegment {
    /// Spectral radiance towards the viewer, the suns' irradiance units per steradian.
    pub radiance: Spectrum,
    /// Transmittance through the air along the ray, per model wavelength.
    pub transmittance: Spectrum,
}

impl AirSegment {
    /// No air along the ray.
    pub const CLEAR: Self = Self {
        radiance: Spectrum::ZERO,
        transmittance: Spectrum::ONE,
    };
}

impl BodyAir {
    /// The air of `atmosphere`'s medium where it is made of [`Constituents`] (Earth's, Mars's,
    /// Saturn's), up to its height; `None` for an air of other terms (Venus's, Titan's tables).
    pub fn from_atmosphere(atmosphere: &crate::atmosphere::Atmosphere) -> Option<Self> {
        Some(Self {
            constituents: atmosphere.medium.constituents()?,
            top_altitude_m: atmosphere.planet.atmosphere_height,
        })
    }

    /// Checks the rules: the top finite and > 0 m; every coefficient finite and ≥ 0, the
    /// aerosols' extinction at least their scattering; the aerosols' phase Cornette–Shanks or
    /// Henyey–Greenstein with |g| < 1.
    pub fn validate(&self) -> Result<(), CoreError> {
        if !(self.top_altitude_m.is_finite() && self.top_altitude_m > 0.0) {
            return Err(invalid(
                "body.air.top_altitude_m",
                self.top_altitude_m.to_string(),
                "must be a finite height > 0 m",
            ));
        }
        let c = &self.constituents;
        let coefficients = [
            ("body.air.rayleigh.scattering", c.rayleigh.scattering),
            ("body.air.mie.scattering", c.mie.scattering),
            ("body.air.mie.extinction", c.mie.extinction),
            ("body.air.absorber.absorption", c.absorber.absorption),
        ];
        for (field, value) in coefficients {
            if !(value.is_finite() && value.min_element() >= 0.0) {
                return Err(invalid(
                    field,
                    format!("{:?}", value.to_array()),
                    "must be finite m⁻¹ ≥ 0",
                ));
            }
        }
        if (c.mie.extinction - c.mie.scattering).min_element() < 0.0 {
            return Err(invalid(
                "body.air.mie.extinction",
                format!("{:?}", c.mie.extinction.to_array()),
                "must be at least the scattering",
            ));
        }
        match c.mie.phase {
            Phase::CornetteShanks { g } | Phase::HenyeyGreenstein { g } if g.abs() < 1.0 => Ok(()),
            _ => Err(invalid(
                "body.air.mie.phase",
                format!("{:?}", c.mie.phase),
                "must be Cornette–Shanks or Henyey–Greenstein with |g| < 1",
            )),
        }
    }

    /// Extinction at altitude `h` metres, m⁻¹.
    pub fn extinction_at(&self, h: f64) -> Spectrum {
        let c = &self.constituents;
        c.rayleigh.scattering * c.rayleigh.density.density(h)
            + c.mie.extinction * c.mie.density.density(h)
            + c.absorber.absorption * c.absorber.density.density(h)
    }

    /// Scattering coefficient at altitude `h` metres, every scatterer without its phase, m⁻¹.
    pub fn scattering_at(&self, h: f64) -> Spectrum {
        let c = &self.constituents;
        c.rayleigh.scattering * c.rayleigh.density.density(h) + c.mie.scattering * c.mie.density.density(h)
    }

    /// Light scattered at altitude `h` per unit irradiance and length, Σ σ_s·p (m⁻¹·sr⁻¹), for
    /// `nu` the cosine between the view ray's direction and the direction to the sun.
    pub fn scattering_phase(&self, h: f64, nu: f64) -> Spectrum {
        let c = &self.constituents;
        c.rayleigh.scattering * (c.rayleigh.density.density(h) * medium::rayleigh_phase(nu))
            + c.mie.scattering * (c.mie.density.density(h) * c.mie.phase.eval(nu))
    }
}

impl Body {
    /// Altitude of point `p` (same frame as the body) over the body, metres, as its air counts
    /// it (module docs): `(|q| − 1)·R`.
    pub fn air_altitude(&self, p: DVec3) -> f64 {
        let q = self.orientation.inverse() * (p - self.center) / self.radii;
        (q.length() - 1.0) * self.mean_radius()
    }

    /// The top of the body's air, in its axes about its centre.
    fn air_top(&self, air: &BodyAir) -> Ellipsoid {
        Ellipsoid {
            center: DVec3::ZERO,
            radii: self.radii * (1.0 + air.top_altitude_m / self.mean_radius()),
        }
    }

    /// `ray` in the body's axes about its centre.
    fn local_ray(&self, ray: &Ray) -> Ray {
        let inverse = self.orientation.inverse();
        Ray {
            origin: inverse * (ray.origin - self.center),
            direction: inverse * ray.direction,
        }
    }

    /// Transmittance of the body's air from point `p` (same frame as the body) along the unit
    /// `direction` out to its top: 1 without air, 0 where the ray meets the body.
    pub fn air_transmittance(&self, p: DVec3, direction: DVec3) -> Spectrum {
        let Some(air) = &self.air else { return Spectrum::ONE };
        let Some(ray) = Ray::new(p, direction) else {
            return Spectrum::ONE;
        };
        if self.hit(&ray).is_some_and(|t| t > 1e-6 * self.mean_radius()) {
            return Spectrum::ZERO;
        }
        let Some(top) = self.air_top(air).intersect(&self.local_ray(&ray)) else {
            return Spectrum::ONE;
        };
        let (start, end) = (top.near.max(0.0), top.far);
        if end <= start {
            return Spectrum::ONE;
        }
        let depth = midpoint_sum(start, end, SUN_STEPS, |t| {
            air.extinction_at(self.air_altitude(ray.at(t)))
        });
        (-depth).exp()
    }

    /// The tables of the light the body's air scatters more than once and of the sky's light on
    /// its ground, for its air around a ball of its mean radius over ground of its albedo; `None`
    /// without air. Far dearer than a frame (docs/PERFORMANCE.md): make them once per air.
    pub fn air_light(&self) -> Option<AirLight> {
        let air = self.air.as_ref()?;
        Some(AirLight::new(air, self.mean_radius(), self.albedo))
    }

    /// The light the body's air scatters towards the viewer along `ray` (same frame as the body)
    /// from its origin up to `far` metres (where something opaque stands; `f64::INFINITY`: none),
    /// lit by `suns`, sun `s` reaching point `x` after its transmittance through the air and
    /// times `light(x, s)` (the shadows of the planet, the rings and other bodies, e.g.
    /// [`super::shadows_share`]); once-scattered light only, or every order with the air's
    /// tables `more` ([`Self::air_light`]); [`AirSegment::CLEAR`] without air.
    pub fn air_along(
        &self,
        ray: &Ray,
        far: f64,
        suns: &[Sun],
        light: impl Fn(DVec3, usize) -> Spectrum,
        more: Option<&AirLight>,
    ) -> AirSegment {
        let Some(air) = &self.air else { return AirSegment::CLEAR };
        let Some(top) = self.air_top(air).intersect(&self.local_ray(ray)) else {
            return AirSegment::CLEAR;
        };
        let surface = self.hit(ray).unwrap_or(f64::INFINITY);
        let (start, end) = (top.near.max(0.0), top.far.min(far).min(surface));
        if end <= start {
            return AirSegment::CLEAR;
        }
        let dt = (end - start) / VIEW_STEPS as f64;
        let directions: Vec<DVec3> = suns.iter().map(|sun| sun.direction.normalize()).collect();
        let mut depth = Spectrum::ZERO;
        let mut radiance = Spectrum::ZERO;
        for k in 0..VIEW_STEPS {
            let x = ray.at(start + (k as f64 + 0.5) * dt);
            let h = self.air_altitude(x);
            let extinction = air.extinction_at(h);
            // The transmittance to the step's midpoint: all steps before it and half of it.
            let to_x = (-(depth + extinction * (0.5 * dt))).exp();
            let up = self.normal_at(x);
            for (s, (sun, &direction)) in suns.iter().zip(&directions).enumerate() {
                let shadows = sun.irradiance * light(x, s);
                let once = self.air_transmittance(x, direction) * air.scattering_phase(h, ray.direction.dot(direction));
                let again = more.map_or(Spectrum::ZERO, |more| {
                    air.scattering_at(h) * more.multiple_scattering(h, up.dot(direction))
                });
                radiance += shadows * (once + again) * to_x * dt;
            }
            depth += extinction * dt;
        }
        AirSegment {
            radiance,
            transmittance: (-depth).exp(),
        }
    }

    /// The radiance the sky of the body's air sends back from surface point `p` (same frame as
    /// the body) towards a viewer along `to_viewer`, the ground taken as Lambertian: its albedo
    /// over π times each sun's irradiance, times `light(s)` (the shadows of the planet, the rings
    /// and other bodies, e.g. [`super::shadows_share`]), times the sky's irradiance per unit of
    /// it at the sun's height there (`tables`, [`Self::air_light`]).
    pub fn skylight_radiance(
        &self,
        p: DVec3,
        to_viewer: DVec3,
        suns: &[Sun],
        tables: &AirLight,
        light: impl Fn(usize) -> Spectrum,
    ) -> Spectrum {
        let n = self.normal_at(p);
        if n.dot(to_viewer) <= 0.0 {
            return Spectrum::ZERO;
        }
        let received = suns.iter().enumerate().fold(Spectrum::ZERO, |sum, (s, sun)| {
            sum + sun.irradiance * light(s) * tables.sky_irradiance(n.dot(sun.direction.normalize()))
        });
        received * self.albedo_at(p) / std::f64::consts::PI
    }
}

/// Σ f(t)·dt over `steps` midpoints of [start, end].
fn midpoint_sum(start: f64, end: f64, steps: usize, f: impl Fn(f64) -> Spectrum) -> Spectrum {
    let dt = (end - start) / steps as f64;
    (0..steps).map(|k| f(start + (k as f64 + 0.5) * dt)).sum::<Spectrum>() * dt
}

fn invalid(field: &'static str, value: String, rule: &'static str) -> CoreError {
    CoreError::Invalid { field, value, rule }
}

pub mod light;

#[cfg(test)]
mod tests;
