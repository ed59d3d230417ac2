//! A planet's surface: its albedo over the globe, where it is water, and the suns' glint on the
//! water.
//!
//! # Model
//! Each point of the ground reflects like a mix of two surfaces, weighted by the *water fraction*
//! `w` there (0 on land, 1 on open water, between them along coasts):
//! - a Lambertian surface of the map's albedo (on water the albedo stands for the light the water
//!   body sends back up, a few per cent), lit by the suns and the sky;
//! - on the water share only, the rough sea's specular reflection of each sun — Cox & Munk's
//!   Gaussian wave slopes with a Fresnel reflection at each facet ([`glint`]).
//!
//! The sky's own specular reflection in the water is not modelled (by the GPU or by the reference),
//! nor are the map's albedos a function of the sun's or the eye's direction.
//!
//! # Units and frames
//! Albedos are dimensionless per model wavelength ([`Spectrum`]); a map's colours are read as
//! linear sRGB albedo, red for the first model wavelength (680 nm by default), green for the
//! second, blue for the third — as `ground_albedo` is. Latitudes and longitudes are geodetic,
//! radians, read off a planet-frame "up" ([`Planet::up`](super::Planet::up)): longitude 0 along
//! the planet frame's +x, +90° along +y, north along +z.
//!
//! # Files
//! - [`map`]: [`SurfaceMap`], the equirectangular map of albedo and water.
//! - [`glint`]: Cox–Munk sea slopes and the Fresnel reflectance of water.
//! - [`procedural`]: seeded continents, oceans and ice caps baked into a map.

use std::sync::Arc;

use glam::DVec3;

use super::Spectrum;
use crate::error::CoreError;

pub mod glint;
pub mod map;
pub mod procedural;

pub use map::SurfaceMap;

/// The wind speed glint is drawn with when a scene names none, m/s (10 m above the sea): a
/// moderate breeze, about the mean over the world's oceans in satellite scatterometer
/// climatologies.
pub const DEFAULT_WIND_SPEED_MPS: f64 = 7.0;

/// The largest wind speed accepted, m/s: Cox & Munk's fit was made for 1–14 m/s; beyond about
/// 30 m/s (a storm) foam, which it leaves out, covers the sea.
pub const MAX_WIND_SPEED_MPS: f64 = 30.0;

/// A planet's surface: an albedo and water map over the globe and the wind over the water.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// The albedo and water fraction over the globe.
    pub map: Arc<SurfaceMap>,
    /// Wind speed over the water, m/s (10 m above the sea): the sea's roughness
    /// ([`glint::slope_variance`]).
    pub wind_speed_mps: f64,
}

/// What the ground is at one point: its Lambertian albedo and its water fraction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundSample {
    /// Lambertian albedo per model wavelength.
    pub albedo: Spectrum,
    /// The share of the point that is water, 0–1 (the glint's weight).
    pub water: f64,
}

impl Surface {
    /// A surface of `map` with the default wind.
    pub fn new(map: SurfaceMap) -> Self {
        Self {
            map: Arc::new(map),
            wind_speed_mps: DEFAULT_WIND_SPEED_MPS,
        }
    }

    /// Checks the wind: finite and in 0–[`MAX_WIND_SPEED_MPS`].
    pub fn validate(&self) -> Result<(), CoreError> {
        if !(self.wind_speed_mps.is_finite() && (0.0..=MAX_WIND_SPEED_MPS).contains(&self.wind_speed_mps)) {
            return Err(CoreError::Invalid {
                field: "surface.wind_speed_mps",
                value: self.wind_speed_mps.to_string(),
                rule: "must be finite and in 0-30 m/s",
            });
        }
        Ok(())
    }

    /// The ground at the point whose geodetic up is `up` (planet frame, unit).
    pub fn at(&self, up: DVec3) -> GroundSample {
        let (latitude, longitude) = latitude_longitude(up);
        let [r, g, b, water] = self.map.sample(latitude, longitude);
        GroundSample {
            albedo: Spectrum::new(r, g, b),
            water,
        }
    }

    /// The albedo over the whole globe, weighted by area (what the multiple-scattering LUTs,
    /// which assume one albedo everywhere, are built with).
    pub fn mean_albedo(&self) -> Spectrum {
        let [r, g, b, _] = self.map.mean();
        Spectrum::new(r, g, b)
    }

    /// The radiance the ground at `up` reflects towards `to_eye` (unit, planet frame) per unit
    /// of a sun's irradiance `irradiance` arriving from `to_sun` (unit; the irradiance on a
    /// surface facing the sun, after the air): the Lambertian part and the water's glint.
    /// Per steradian: multiply by the irradiance (W·m⁻²·nm⁻¹) for radiance.
    pub fn reflectance_factor(&self, sample: &GroundSample, up: DVec3, to_sun: DVec3, to_eye: DVec3) -> Spectrum {
        let mu_s = up.dot(to_sun).max(0.0);
        let lambert = sample.albedo * (mu_s / std::f64::consts::PI);
        if sample.water <= 0.0 {
            return lambert;
        }
        let sigma2 = glint::slope_variance(self.wind_speed_mps);
        lambert + Spectrum::splat(sample.water * glint::brdf(up, to_sun, to_eye, sigma2) * mu_s)
    }
}

/// Geodetic latitude and longitude (radians) of the point whose geodetic up is `up` (planet
/// frame, unit).
pub fn latitude_longitude(up: DVec3) -> (f64, f64) {
    (up.z.clamp(-1.0, 1.0).asin(), up.y.atan2(up.x))
}
