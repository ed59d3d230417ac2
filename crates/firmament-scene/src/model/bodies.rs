//! `[[bodies]]`: bodies drawn beside the planet, airless or with an air of their own (`sky.model = "atmosphere"`), up to 4
//! ([`firmament_core::atmosphere::body`]).

use serde::Deserialize;

use crate::spectrum::SceneSpectrum;

/// One `[[bodies]]` entry. Either `preset` or a size (`radius` or `radii`) is required; the
/// others take the defaults noted.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyEntry {
    /// `"moon"`: the Moon's mean radius (1737.4 km), geometric albedo (0.12) and its own law
    /// (`"lunar"`); with a date (`time.date_time`) and no `position` it stands where the
    /// Moon stood then. Keys given beside it replace the preset's.
    #[serde(default)]
    pub preset: Option<String>,
    /// Centre, metres, in the scene's world frame (east, north, up from the point of
    /// `[planet]`'s latitude and longitude on its surface, like `camera.position`).
    #[serde(default)]
    pub position: Option<[f64; 3]>,
    /// Radius of a round body, metres, > 0.
    #[serde(default)]
    pub radius: Option<f64>,
    /// Semi-axes `[a, b, c]` of an ellipsoidal body, metres, each > 0: `c` along its pole.
    #[serde(default)]
    pub radii: Option<[f64; 3]>,
    /// World direction of the body's pole (its `c` axis); default the planet's polar axis. Its
    /// `a` axis (the Moon's 0° N 0° E) turns as near the planet as the pole allows, so a moon's
    /// near side faces it.
    #[serde(default)]
    pub pole: Option<[f64; 3]>,
    /// Normal albedo, a number or `[a, b, c]` at the model wavelengths, in [0, 1] (default 0.12,
    /// the Moon's).
    #[serde(default)]
    pub albedo: Option<SceneSpectrum>,
    /// `"lambert"` (a matte diffuser), `"lommel-seeliger"` (a dark regolith, as bright at the
    /// limb as at the centre) or `"lunar"` (that with the Moon's measured phase curve); default
    /// `"lambert"` (`"lunar"` for the Moon).
    #[serde(default)]
    pub reflectance: Option<String>,
    /// The body's own air: `"earth"`, `"mars"` or `"saturn"` — that preset's molecules, aerosols
    /// and absorbing gas up to its height (60, 80 and 600 km), around this body; default none.
    /// Drawn with single scattering (docs/ATMOSPHERE.md, "Bodies' airs"); not with
    /// `atmosphere.wavelengths` (the presets' coefficients are at 680, 550 and 440 nm).
    #[serde(default)]
    pub atmosphere: Option<String>,
    /// An equirectangular image of the body's surface (PNG, JPEG, …; sRGB-encoded), longitude
    /// −180° to 180° from left to right in the body's axes (0° along its `a` axis: a moon's
    /// sub-planet point), north up. It gives the pattern and the colour; `albedo` (or the
    /// preset's) the level: the map's mean brightness over the sphere becomes it. A Moon's map
    /// replaces its maria. A path relative to the scene file.
    #[serde(default)]
    pub albedo_map: Option<String>,
    /// Whether the body's sunlit face lights the planet, its air, the objects and the other
    /// bodies (a Moon body is the night's moonlight): one more light in every pass, so `false`
    /// saves its cost where it cannot show. Default `true`; by day under the air (a sun above the
    /// camera's horizon) it is left out anyway.
    #[serde(default)]
    pub light: Option<bool>,
}
