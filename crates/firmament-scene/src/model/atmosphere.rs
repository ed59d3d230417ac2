//! `[planet]`, `[atmosphere]` and `[[suns]]`: the physically based sky (`sky.model =
//! "atmosphere"`). Every key but `planet.body`, `planet.latitude` and `planet.longitude` is
//! optional and, when given, overrides the body's value.

use firmament_core::atmosphere::{Atmosphere, Sun, presets};
use glam::DVec3;
use serde::Deserialize;

use crate::color::SceneColor;
use crate::model::TermEntry;
use crate::spectrum::SceneSpectrum;

/// The bodies whose planet, atmosphere and sun the core has presets for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Body {
    /// The Earth on the WGS84 ellipsoid ([`firmament_core::atmosphere::presets::earth`]).
    Earth,
    /// Mars in a clear season ([`firmament_core::atmosphere::presets::mars`]).
    Mars,
    /// Saturn above its cloud deck ([`firmament_core::atmosphere::presets::saturn`]).
    Saturn,
    /// Venus under its cloud deck ([`firmament_core::atmosphere::presets::venus`]).
    Venus,
    /// Titan at the Huygens landing site ([`firmament_core::atmosphere::presets::titan`]).
    Titan,
}

impl Body {
    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Earth => "earth",
            Self::Mars => "mars",
            Self::Saturn => "saturn",
            Self::Venus => "venus",
            Self::Titan => "titan",
        }
    }

    /// The body's planet (unposed, at the origin), medium and wavelengths from the core presets.
    pub fn atmosphere(self) -> Atmosphere {
        match self {
            Self::Earth => presets::earth(),
            Self::Mars => presets::mars(),
            Self::Saturn => presets::saturn(),
            Self::Venus => presets::venus(),
            Self::Titan => presets::titan(),
        }
    }

    /// The Sun as seen from this body, towards `direction` (world frame).
    pub fn sun(self, direction: DVec3) -> Sun {
        match self {
            Self::Earth => presets::earth_sun(direction),
            Self::Mars => presets::mars_sun(direction),
            Self::Saturn => presets::saturn_sun(direction),
            Self::Venus => presets::venus_sun(direction),
            Self::Titan => presets::titan_sun(direction),
        }
    }
}

/// `[planet]`: which body, any changes to its shape, and where on it the world frame sits.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanetSection {
    /// The body: `"earth"`, `"mars"`, `"saturn"`, `"venus"` or `"titan"`.
    pub body: Body,
    /// Equatorial radius, metres, > 0 (default: the body's).
    #[serde(default)]
    pub equatorial_radius: Option<f64>,
    /// Polar radius, metres, > 0 and within 10× of the equatorial radius (default: the body's).
    #[serde(default)]
    pub polar_radius: Option<f64>,
    /// Both radii at once (a sphere), metres, > 0; not together with the two above.
    #[serde(default)]
    pub radius: Option<f64>,
    /// Height of the top of the atmosphere above the surface, metres, > 0 (default: the body's).
    #[serde(default)]
    pub atmosphere_height: Option<f64>,
    /// Geodetic latitude of the world origin on the surface, degrees north, in [-90, 90]. The
    /// world frame (and `camera.position`) is East-North-Up there.
    #[serde(rename = "latitude")]
    pub latitude_deg: f64,
    /// Longitude of the world origin, degrees east, finite.
    #[serde(rename = "longitude")]
    pub longitude_deg: f64,
    /// A built-in surface: `"earth"` (Natural Earth's land and ice, dark seas) or
    /// `"procedural"` (seeded continents, seas and ice caps); not with `albedo_map`. Absent and
    /// without `albedo_map`: the atmosphere's `ground_albedo` everywhere, no water.
    #[serde(default)]
    pub surface: Option<SurfaceName>,
    /// An equirectangular image of the ground's albedo (colours read as sRGB-encoded albedo; top
    /// row at latitude 90°, left column at longitude −180°); a path relative to the scene file.
    #[serde(default)]
    pub albedo_map: Option<String>,
    /// With `albedo_map`: an equirectangular image of where the ground is water (each texel's
    /// mean of red, green and blue, 0 land … 1 water), for the suns' glint; without it, no water.
    #[serde(default)]
    pub water_map: Option<String>,
    /// The seed of `surface = "procedural"`, an integer >= 0 (default 1).
    #[serde(default)]
    pub surface_seed: Option<i64>,
    /// Wind speed over the water, m/s, in [0, 30] (default 7): how rough the sea is, so how wide
    /// and dim the suns' glint; needs a surface.
    #[serde(default)]
    pub wind_speed: Option<f64>,
}

/// The built-in surfaces `planet.surface` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceName {
    /// Earth from Natural Earth's data (`firmament-scene/data/earth-surface.png`).
    Earth,
    /// Continents, seas and ice caps from seeded noise (`planet.surface_seed`).
    Procedural,
}

/// The aerosol phase functions a scene can choose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MiePhaseName {
    /// Cornette & Shanks (1992), as Bruneton and Hillaire use.
    CornetteShanks,
    /// Henyey & Greenstein (1941).
    HenyeyGreenstein,
}

/// The atmosphere models `sky.model = "atmosphere"` can draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AtmosphereModelName {
    /// The physically based atmosphere (the body's medium with `[atmosphere]`'s overrides).
    #[default]
    Physical,
    /// The seed's own empirical model (seed 000, version 3.1), with `[atmosphere.seed]`; `"seed"`
    /// in scene files.
    #[serde(rename = "seed")]
    Empirical,
}

/// `[atmosphere.seed]`: the empirical model's values, all optional; the defaults are the seed's
/// own for the body (`seed_earth`, `seed_mars`; Saturn, Venus and Titan have none, so their scenes
/// must give `view_depth`, `b0` and `overglow`). The radii are the planet's when `[planet]` sets them, else
/// the seed's (Earth 6 378 141.2 / 6 356 754.795 m, Mars 3 397 000 / 3 374 919.5 m).
///
/// `expecting` keeps the wrong-type message ("expected struct SeedSection") as it was before the
/// Rust name changed.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields, expecting = "struct SeedSection")]
pub struct EmpiricalSection {
    /// Height of the atmosphere above the surface, metres, > 0 (also the density's length scale;
    /// default `planet.atmosphere_height` when set, else the seed's: 60 km Earth, 30 km Mars).
    #[serde(default)]
    pub height: Option<f64>,
    /// Path length at which the air's colour saturates, metres, > 0 (the seed's: 250 km Earth,
    /// 300 km Mars).
    #[serde(default)]
    pub view_depth: Option<f64>,
    /// The "100 % scattered" colour B0, `[r, g, b]` linear, unitless, each finite and >= 0.
    #[serde(default)]
    pub b0: Option<[f64; 3]>,
    /// Overglow, unitless, finite: lights the sky before the sun rises (0.75 Earth, 0.5 Mars).
    #[serde(default)]
    pub overglow: Option<f64>,
    /// Luminance of the seed's colour 1 in the HDR image, cd/m², > 0 (default 10 000).
    #[serde(default)]
    pub luminance: Option<f64>,
}

/// `[atmosphere]`: overrides of the body's medium, all optional. Spectral values are a number
/// (the same at every wavelength) or `[a, b, c]` in the order of `wavelengths`. Coefficients are
/// at density 1, i.e. at the surface for exponential profiles and at the peak for ozone.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereSection {
    /// Which model draws the atmosphere: `"physical"` (default) or `"seed"`.
    #[serde(default)]
    pub model: AtmosphereModelName,
    /// The empirical model's values, `[atmosphere.seed]` (used when `model = "seed"`).
    #[serde(default, rename = "seed")]
    pub empirical: EmpiricalSection,
    /// Rayleigh (molecular) scattering coefficient, m⁻¹, >= 0.
    #[serde(default)]
    pub rayleigh_scattering: Option<SceneSpectrum>,
    /// Rayleigh scale height, metres, > 0 (the profile becomes `e^(−h/H)`).
    #[serde(default)]
    pub rayleigh_scale_height: Option<f64>,
    /// Aerosol (Mie) scattering coefficient, m⁻¹, >= 0 and <= `mie_extinction`.
    #[serde(default)]
    pub mie_scattering: Option<SceneSpectrum>,
    /// Aerosol extinction coefficient (scattering + absorption), m⁻¹, >= `mie_scattering`.
    #[serde(default)]
    pub mie_extinction: Option<SceneSpectrum>,
    /// Aerosol scale height, metres, > 0 (the profile becomes `e^(−h/H)`).
    #[serde(default)]
    pub mie_scale_height: Option<f64>,
    /// Aerosol asymmetry parameter `g`, in (−1, 1).
    #[serde(default)]
    pub mie_g: Option<f64>,
    /// Aerosol phase function: `"cornette_shanks"` or `"henyey_greenstein"`.
    #[serde(default)]
    pub mie_phase: Option<MiePhaseName>,
    /// Ozone (absorbing gas) absorption coefficient at the peak of its tent, m⁻¹, >= 0.
    #[serde(default)]
    pub ozone_absorption: Option<SceneSpectrum>,
    /// Altitude where the ozone tent starts rising from 0, metres, >= 0.
    #[serde(default)]
    pub ozone_bottom: Option<f64>,
    /// Altitude of the ozone tent's peak (density 1), metres, > `ozone_bottom`.
    #[serde(default)]
    pub ozone_peak: Option<f64>,
    /// Altitude where the ozone tent is back to 0, metres, > `ozone_peak`.
    #[serde(default)]
    pub ozone_top: Option<f64>,
    /// Lambertian ground albedo, in [0, 1].
    #[serde(default)]
    pub ground_albedo: Option<SceneSpectrum>,
    /// The three model wavelengths, nanometres, distinct, in [360, 830] (default 680, 550, 440).
    #[serde(default)]
    pub wavelengths: Option<[f64; 3]>,
    /// `[[atmosphere.terms]]`: the whole medium as 1 to 8 terms, in place of the body's medium
    /// and the shorthand keys above (`rayleigh_*`, `mie_*`, `ozone_*`).
    #[serde(default)]
    pub terms: Option<Vec<TermEntry>>,
}

/// One `[[suns]]` entry: a distant star lighting the atmosphere. Its direction is given either
/// by `azimuth` and `elevation` or by `position`, never both.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SunEntry {
    /// A label for people (`"primary"`); not used by the renderer.
    #[serde(default)]
    pub name: Option<String>,
    /// Direction from north, clockwise towards east, degrees, in the world (East-North-Up) frame.
    #[serde(default, rename = "azimuth")]
    pub azimuth_deg: Option<f64>,
    /// Elevation above the world frame's horizontal plane, degrees, in [-90, 90].
    #[serde(default, rename = "elevation")]
    pub elevation_deg: Option<f64>,
    /// Where the sun is, `[east, north, up]` metres in the world frame; its direction is the one
    /// from the planet's centre to this point, which must lie above the atmosphere.
    #[serde(default)]
    pub position: Option<[f64; 3]>,
    /// Angular radius of the disc, degrees, in (0, 90) (default: the body's sun, e.g. 0.2679°
    /// seen from Earth).
    #[serde(default, rename = "angular_radius")]
    pub angular_radius_deg: Option<f64>,
    /// Colour as a black-body temperature, kelvin, in [500, 1000000]; not with `color`.
    #[serde(default)]
    pub temperature: Option<f64>,
    /// Colour as `"#rrggbb"` (sRGB) or `[r, g, b]` (linear), read as relative spectral irradiance
    /// at the three model wavelengths (red at the first); green must be > 0. Not with
    /// `temperature`. Neither: the body's solar spectrum.
    #[serde(default)]
    pub color: Option<SceneColor>,
    /// Spectral irradiance at the top of the atmosphere at the middle model wavelength (550 nm),
    /// W·m⁻²·nm⁻¹, >= 0 (default: the body's sun, 1.8504 at Earth).
    #[serde(default)]
    pub irradiance: Option<f64>,
    /// Linear limb-darkening coefficient, in [0, 1] (default: the body's sun, 0.6).
    #[serde(default)]
    pub limb_darkening: Option<f64>,
}
