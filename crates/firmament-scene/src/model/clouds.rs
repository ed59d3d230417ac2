//! `[[clouds]]`: volumetric cloud layers inside the physical atmosphere (issue 26).
//!
//! Each entry is one layer on a shell that follows the planet's ellipsoid, between two altitudes.
//! The keys keep the file's units: metres, m⁻¹, m/s. Like `[[suns]]`, the entries are checked in
//! every scene, whatever `sky.model` is, and drawn only by the physical atmosphere
//! (`sky.model = "atmosphere"` with `atmosphere.model = "physical"`); the gradient and clear skies
//! and the seed's model ignore them.

use firmament_core::atmosphere::clouds::CloudKind;
use serde::Deserialize;
use serde::de::{Deserializer, Error as _};

use crate::error::did_you_mean;

/// One `[[clouds]]` entry: a layer of clouds. `bottom`, `top`, `coverage`, `density` and `kind`
/// are required; the others take the defaults noted.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudEntry {
    /// Altitude of the layer's base above the ellipsoid surface, metres, >= 0.
    #[serde(rename = "bottom")]
    pub bottom_m: f64,
    /// Altitude of the layer's top above the ellipsoid surface, metres, above `bottom` and at most
    /// the top of the atmosphere (`planet.atmosphere_height`).
    #[serde(rename = "top")]
    pub top_m: f64,
    /// The share of the sky the layer covers, in [0, 1] (checked but not used by `"uniform"`).
    pub coverage: f64,
    /// Extinction coefficient of the cloud at full density, m⁻¹, in [0, 10] (typical cumulus
    /// 0.02–0.1).
    #[serde(rename = "density")]
    pub density_per_m: f64,
    /// Shape and vertical profile: `"cumulus"`, `"stratocumulus"`, `"stratus"`, `"altostratus"`,
    /// `"cirrus"`, or `"uniform"` (a homogeneous slab of `density` over the whole sky, no noise).
    #[serde(deserialize_with = "kind_by_name")]
    pub kind: CloudKind,
    /// Wind `[east, north]`, m/s, each finite and at most 1000 in size (default `[0, 0]`): it
    /// carries the layer with the scene's time.
    #[serde(default, rename = "wind", deserialize_with = "wind_pair")]
    pub wind_mps: [f64; 2],
    /// Seed of the procedural noise, 0 to 4294967295 (default 0).
    #[serde(default)]
    pub seed: u32,
    /// An image giving the coverage over the planet, equirectangular: longitude −180° to 180°
    /// from left to right, latitude 90° to −90° from top to bottom; each texel's mean of red,
    /// green and blue (0–255 as 0–1) multiplies `coverage`. Relative paths are taken from the
    /// scene file's folder. Absent: the same coverage everywhere.
    #[serde(default)]
    pub coverage_map: Option<String>,
    /// Single-scattering albedo, in [0, 1] (default 1: cloud droplets absorb almost nothing in
    /// the visible).
    #[serde(default = "one")]
    pub albedo: f64,
    /// Dual-lobe Henyey–Greenstein phase function `[g_forward, g_back, blend]`: each `g` in
    /// (−1, 1), `blend` (the forward lobe's weight) in [0, 1]. Absent: the core's fit to a cloud
    /// droplet's Mie phase function.
    #[serde(default, deserialize_with = "phase_triple")]
    pub phase: Option<[f64; 3]>,
}

fn one() -> f64 {
    1.0
}

/// `kind` by its name, with the names the format takes and the closest one when it is unknown.
fn kind_by_name<'de, D: Deserializer<'de>>(deserializer: D) -> Result<CloudKind, D::Error> {
    let name = String::deserialize(deserializer)?;
    CloudKind::from_name(&name).ok_or_else(|| {
        let names = CloudKind::ALL.map(|kind| format!("`{}`", kind.name())).join(", ");
        let suggestion = did_you_mean(&name, CloudKind::ALL.map(CloudKind::name))
            .map(|best| format!(" (did you mean `{best}`?)"))
            .unwrap_or_default();
        D::Error::custom(format!("unknown variant `{name}`, expected one of {names}{suggestion}"))
    })
}

/// `wind`: exactly two numbers.
fn wind_pair<'de, D: Deserializer<'de>>(deserializer: D) -> Result<[f64; 2], D::Error> {
    let values = Vec::<f64>::deserialize(deserializer)?;
    <[f64; 2]>::try_from(values.as_slice()).map_err(|_| {
        D::Error::custom(format!(
            "must be 2 numbers, [east, north] in m/s; found {} number{}",
            values.len(),
            if values.len() == 1 { "" } else { "s" }
        ))
    })
}

/// `phase`: exactly three numbers.
fn phase_triple<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<[f64; 3]>, D::Error> {
    let values = Vec::<f64>::deserialize(deserializer)?;
    <[f64; 3]>::try_from(values.as_slice()).map(Some).map_err(|_| {
        D::Error::custom(format!(
            "must be 3 numbers, [g_forward, g_back, blend]; found {} number{}",
            values.len(),
            if values.len() == 1 { "" } else { "s" }
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYER: &str = "bottom = 1500.0\ntop = 3000.0\ncoverage = 0.4\ndensity = 0.05\nkind = \"cumulus\"\n";

    #[test]
    fn absent_keys_take_their_defaults() {
        let entry: CloudEntry = toml::from_str(LAYER).expect("a layer");
        assert_eq!(entry.kind, CloudKind::Cumulus);
        assert_eq!((entry.bottom_m, entry.top_m, entry.coverage), (1500.0, 3000.0, 0.4));
        assert_eq!((entry.wind_mps, entry.seed, entry.albedo), ([0.0, 0.0], 0, 1.0));
        assert_eq!((entry.phase, entry.coverage_map), (None, None));
    }

    #[test]
    fn kinds_wind_and_phase_say_what_they_take() {
        let text = format!("{LAYER}wind = [3.0, -1.5]\nphase = [0.7, -0.2, 0.9]\nseed = 7\n");
        let entry: CloudEntry = toml::from_str(&text).expect("a layer");
        assert_eq!(entry.wind_mps, [3.0, -1.5]);
        assert_eq!(entry.phase, Some([0.7, -0.2, 0.9]));
        assert_eq!(entry.seed, 7);

        let bad = LAYER.replace("cumulus", "cumulos");
        let error = toml::from_str::<CloudEntry>(&bad)
            .expect_err("no such kind")
            .to_string();
        assert!(error.contains("did you mean `cumulus`"), "{error}");
        assert!(error.contains("`uniform`"), "{error}");
        let error = toml::from_str::<CloudEntry>(&format!("{LAYER}wind = [1.0, 2.0, 3.0]\n"))
            .expect_err("three numbers")
            .to_string();
        assert!(
            error.contains("must be 2 numbers, [east, north] in m/s; found 3 numbers"),
            "{error}"
        );
        let error = toml::from_str::<CloudEntry>(&format!("{LAYER}phase = [0.8]\n"))
            .expect_err("one number")
            .to_string();
        assert!(
            error.contains("must be 3 numbers, [g_forward, g_back, blend]; found 1 number"),
            "{error}"
        );
    }
}
