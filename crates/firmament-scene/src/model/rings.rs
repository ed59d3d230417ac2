//! `[rings]`: the planet's rings (`sky.model = "atmosphere"`), off unless `enabled`. With
//! `planet.body = "saturn"` every other key defaults to Saturn's main rings
//! ([`firmament_core::atmosphere::rings::Rings::saturn`]); any other body needs `bands`.

use serde::Deserialize;

use crate::spectrum::SceneSpectrum;

/// `[rings]`.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RingsSection {
    /// Whether the planet has rings (default false).
    #[serde(default)]
    pub enabled: bool,
    /// The bands from the inside out, 1 to 16 (default: the body's).
    #[serde(default)]
    pub bands: Option<Vec<RingBandEntry>>,
    /// The particles' single-scattering albedo, a number or `[a, b, c]` at the model
    /// wavelengths, in [0, 1] (default: the body's).
    #[serde(default)]
    pub albedo: Option<SceneSpectrum>,
    /// The particles' Henyey–Greenstein asymmetry, (−1, 1): negative scatters back (default: the
    /// body's).
    #[serde(default)]
    pub g: Option<f64>,
}

/// One band: `{ inner_radius = 92000000.0, outer_radius = 117580000.0, optical_depth = 2.5 }`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RingBandEntry {
    /// Inner radius, metres from the planet's centre, outside its equator and the band before.
    pub inner_radius: f64,
    /// Outer radius, metres, greater than the inner.
    pub outer_radius: f64,
    /// Normal optical depth, >= 0.
    pub optical_depth: f64,
}
