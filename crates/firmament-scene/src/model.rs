//! The scene file's data model: plain serde structs, parsed strictly.
//!
//! Fields keep the file's units (degrees, metres, `"HH:MM"`); a field in degrees carries `_deg` in
//! its Rust name (`fov_y_deg`), since the core it is converted for speaks radians, while its key
//! in the file stays as it is (`fov_y`, by `#[serde(rename)]`): messages name the file's keys.

mod atmosphere;
mod bodies;
mod clouds;
mod flare;
mod medium_terms;
mod objects;
mod rings;
mod shadows;

use serde::Deserialize;

pub use self::atmosphere::{
    AtmosphereModelName, AtmosphereSection, Body, EmpiricalSection, MiePhaseName, PlanetSection, SunEntry, SurfaceName,
};
pub use self::bodies::BodyEntry;
pub use self::clouds::CloudEntry;
pub use self::flare::{FlareElementEntry, FlareKindName, FlarePresetName, FlareSection};
pub use self::medium_terms::{LayerEntry, PhaseName, ProfileName, TermEntry};
pub use self::objects::{
    CheckerboardEntry, FilterName, FogCoordinateName, FogModeName, FogSection, GlColor, LightEntry, LightSpaceName,
    LightingModelName, LightingSection, MaterialEntry, MeshEntry, ObjectEntry, ShadingName, SpecularName, SpinEntry,
    TextureEntry, TransformEntry,
};
pub use self::rings::{RingBandEntry, RingsSection};
pub use self::shadows::{GroundSection, ShadowsSection};
use crate::color::SceneColor;
use crate::error::{SceneError, did_you_mean};

/// A whole scene, as parsed from the layered TOML.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The preset the scene was built on (informational once layered).
    #[serde(default)]
    pub preset: Option<String>,
    /// Image size.
    pub render: RenderSection,
    /// The camera.
    pub camera: CameraSection,
    /// The time of day.
    pub time: TimeSection,
    /// The sun's path and look.
    pub sun: SunSection,
    /// Exposure and tone curve.
    pub display: DisplaySection,
    /// The sky model.
    pub sky: SkySection,
    /// The planet under the atmosphere (used by `sky.model = "atmosphere"`).
    pub planet: PlanetSection,
    /// Overrides of the body's atmosphere (used by `sky.model = "atmosphere"`).
    #[serde(default)]
    pub atmosphere: AtmosphereSection,
    /// The suns lighting the atmosphere, 0 to 8 (used by `sky.model = "atmosphere"`). Like every
    /// array, a layer's list replaces the one below it as a whole.
    #[serde(default)]
    pub suns: Vec<SunEntry>,
    /// Cloud layers inside the air, 0 to 8 (drawn by the physical atmosphere; checked in every
    /// scene). Like every array, a layer's list replaces the one below it as a whole.
    #[serde(default)]
    pub clouds: Vec<CloudEntry>,
    /// The planet's rings (drawn by the physical atmosphere).
    #[serde(default)]
    pub rings: RingsSection,
    /// Airless bodies beside the planet, 0 to 4 (drawn by the physical atmosphere; checked in
    /// every scene). Like every array, a layer's list replaces the one below it as a whole.
    #[serde(default)]
    pub bodies: Vec<BodyEntry>,
    /// How objects are lit.
    pub lighting: LightingSection,
    /// The lights of classic lighting, 0 to 8, `glLight` style. A layer's list replaces the one
    /// below it as a whole.
    #[serde(default)]
    pub lights: Vec<LightEntry>,
    /// Objects in front of the sky, drawn in order. A layer's list replaces the one below it.
    #[serde(default)]
    pub objects: Vec<ObjectEntry>,
    /// Fog over objects.
    pub fog: FogSection,
    /// The suns' shadows over objects (`lighting.model = "sky"`).
    #[serde(default)]
    pub shadows: ShadowsSection,
    /// The planet's surface near the camera, shadowed and bouncing light (`lighting.model =
    /// "sky"`).
    #[serde(default)]
    pub ground: GroundSection,
    /// Lens flares of the suns and the lights marked `flare = true`.
    pub flare: FlareSection,
    /// The folder relative mesh and texture paths are taken from: the scene file's folder (the
    /// working directory for presets and text without a file).
    #[serde(skip)]
    pub base_dir: std::path::PathBuf,
    /// The folder and limits a stranger's scene is held to (untrusted mode), or `None` for files
    /// from anywhere the process can read. With one, every file the scene names must resolve
    /// inside its folder — [`validate`](Self::validate) checks that before anything is read —
    /// and the loaders hold files to its [`AssetLimits`](crate::assets::AssetLimits).
    #[serde(skip)]
    pub confinement: Option<crate::assets::Confinement>,
}

impl Scene {
    /// Whether the suns cast shadows: `shadows.enabled`, or when it is absent, whether
    /// `lighting.model = "sky"` and `lighting.shading = "phong"`.
    pub fn shadows_enabled(&self) -> bool {
        self.shadows
            .enabled
            .unwrap_or(self.lighting.model == LightingModelName::Sky && self.lighting.shading == ShadingName::Phong)
    }

    /// Every file the scene reads — mesh files (`objects[i].mesh.path`), texture files
    /// (`objects[i].texture.file`), flare images (`flare.elements[i].file`), cloud coverage
    /// maps (`clouds[i].coverage_map`) and surface maps (`planet.albedo_map`,
    /// `planet.water_map`, `bodies[i].albedo_map`) — as its key and
    /// its path as the loaders open it: relative paths joined to [`base_dir`](Self::base_dir),
    /// absolute ones as written.
    pub fn asset_paths(&self) -> Vec<(String, std::path::PathBuf)> {
        self.written_asset_paths()
            .into_iter()
            .map(|(key, written)| (key, self.base_dir.join(written)))
            .collect()
    }

    /// Every file the scene reads, as its key and the path as written.
    pub(crate) fn written_asset_paths(&self) -> Vec<(String, &str)> {
        let mut paths = Vec::new();
        for (i, object) in self.objects.iter().enumerate() {
            if let MeshEntry::File { path } = &object.mesh {
                paths.push((format!("objects[{i}].mesh.path"), path.as_str()));
            }
            if let Some(file) = object.texture.as_ref().and_then(|t| t.file.as_ref()) {
                paths.push((format!("objects[{i}].texture.file"), file.as_str()));
            }
        }
        for (i, element) in self.flare.elements.iter().flatten().enumerate() {
            if let Some(file) = &element.file {
                paths.push((format!("flare.elements[{i}].file"), file.as_str()));
            }
        }
        for (i, layer) in self.clouds.iter().enumerate() {
            if let Some(file) = &layer.coverage_map {
                paths.push((format!("clouds[{i}].coverage_map"), file.as_str()));
            }
        }
        for (i, body) in self.bodies.iter().enumerate() {
            if let Some(file) = &body.albedo_map {
                paths.push((format!("bodies[{i}].albedo_map"), file.as_str()));
            }
        }
        for (key, file) in [
            ("planet.albedo_map", &self.planet.albedo_map),
            ("planet.water_map", &self.planet.water_map),
        ] {
            if let Some(file) = file {
                paths.push((key.to_owned(), file.as_str()));
            }
        }
        paths
    }

    /// The path to open for the file that `key` names as `written`: joined to
    /// [`base_dir`](Self::base_dir), or resolved inside the [`confinement`](Self::confinement)'s
    /// folder when there is one.
    ///
    /// # Errors
    /// Under a confinement, a path it refuses ([`Confinement::resolve`](crate::assets::Confinement::resolve)).
    pub(crate) fn asset_file(&self, key: &str, written: &str) -> Result<std::path::PathBuf, SceneError> {
        match &self.confinement {
            None => Ok(self.base_dir.join(written)),
            Some(confinement) => confinement.resolve(key, &self.base_dir, std::path::Path::new(written)),
        }
    }
}

/// `[render]`: the image.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSection {
    /// Image width, pixels, 1 to 16384.
    pub width: u32,
    /// Image height, pixels, 1 to 16384.
    pub height: u32,
}

/// `[camera]`: where we look from, in the local East-North-Up frame.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    /// Eye position `[east, north, up]`, metres. Over the gradient sky `up` must be >= 0; over an
    /// atmosphere the eye must be at a geodetic altitude >= 0 above the planet's (curved) surface.
    pub position: [f64; 3],
    /// Direction of view from north, clockwise towards east, degrees.
    #[serde(rename = "heading")]
    pub heading_deg: f64,
    /// Angle of view above the horizon, degrees, in [-90, 90].
    #[serde(rename = "pitch")]
    pub pitch_deg: f64,
    /// Rotation of the image about the view direction, clockwise, degrees.
    #[serde(rename = "roll")]
    pub roll_deg: f64,
    /// Vertical field of view, degrees, in (0, 180).
    #[serde(rename = "fov_y")]
    pub fov_y_deg: f64,
    /// Near plane distance, metres, > 0.
    pub near: f64,
    /// Far plane distance, metres, > `near`; absent for an infinite far plane.
    #[serde(default)]
    pub far: Option<f64>,
}

/// `[time]`: the scene's moment. Without `date_time`, a local solar time of day drives the
/// gradient sky (the atmosphere's suns stand where `[[suns]]` puts them); with it, the real sun
/// (NREL SPA), moon and stars stand where they were at that instant over `[planet]`'s latitude
/// and longitude.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSection {
    /// Local solar time of day, `"HH:MM"` or `"HH:MM:SS"` (ignored when `date_time` is given).
    pub time_of_day: String,
    /// A real instant, ISO 8601 (`"2024-06-21T22:00:00+02:00"`, `"…Z"`, or no offset for UTC).
    #[serde(default)]
    pub date_time: Option<String>,
    /// ΔT = TT − UT, seconds, |ΔT| <= 10000; absent: Espenak & Meeus's estimate for the date.
    #[serde(default)]
    pub delta_t: Option<f64>,
    /// Air pressure at the observer for the sun's refraction, millibars, in (0, 5000].
    pub pressure: f64,
    /// Air temperature at the observer for the refraction, °C, in (−273, 6000).
    pub temperature: f64,
    /// Whether the night sky's stars are drawn (with `date_time`).
    pub stars: bool,
    /// Faintest star drawn, visual magnitude, <= 6.5 (the catalogue's limit).
    pub star_limit: f64,
    /// Whether the moon is drawn (with `date_time`).
    pub moon: bool,
}

/// `[sun]`: the gradient sky's sun, its path over the day and how its disc and glow look (the
/// atmosphere's suns are `[[suns]]`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SunSection {
    /// Observer latitude, degrees, in [-90, 90], north positive.
    #[serde(rename = "latitude")]
    pub latitude_deg: f64,
    /// Solar declination, degrees, in [-23.44, 23.44] (0 at the equinoxes).
    #[serde(rename = "declination")]
    pub declination_deg: f64,
    /// Angular radius of the disc, degrees, in (0, 10] (the real sun: 0.2666).
    #[serde(rename = "angular_radius")]
    pub angular_radius_deg: f64,
    /// Disc radiance as a multiple of the keyframe's sun colour, >= 0.
    pub disc_intensity: f64,
    /// Glow radiance at the centre as a multiple of the keyframe's sun colour, >= 0.
    pub glow_intensity: f64,
    /// Angle over which the glow falls by a factor e, degrees, in (0, 180].
    #[serde(rename = "glow_falloff")]
    pub glow_falloff_deg: f64,
    /// Fraction of the disc's radius over which its edge fades, in (0, 1].
    pub edge_softness: f64,
}

/// `[display]`: from radiance to a picture (PNG only; EXR stays scene-referred).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisplaySection {
    /// Plain exposure multiplier, > 0. Ignored when `ev100` is given.
    pub exposure: f64,
    /// Exposure value at ISO 100; when present it sets the exposure to `1 / (1.2 · 2^ev100)`.
    #[serde(default)]
    pub ev100: Option<f64>,
    /// `"none"` (clamp), `"aces_fitted"`, `"pbr_neutral"` or `"agx"`.
    pub tone_curve: firmament_core::display::ToneCurve,
    /// How PNG pixels store the result: `"srgb"` (default) or `"none"` (`round(255·v)`, as an
    /// 8-bit GL framebuffer holds it; classic presets use it).
    pub encoding: firmament_core::display::Encoding,
    /// `"manual"` (`ev100` or `exposure`) or `"auto"` (metered from each frame; `ev100` then
    /// only scales the lens flares).
    pub exposure_mode: ExposureModeName,
    /// Auto-exposure's lowest EV100, in [-20, 40] and <= `auto_ev_max`.
    pub auto_ev_min: f64,
    /// Auto-exposure's highest EV100, in [-20, 40].
    pub auto_ev_max: f64,
    /// Exposure compensation, EV, in [-10, 10]: positive brightens.
    pub auto_compensation: f64,
    /// How fast the EV100 rises as the scene brightens, EV per second, > 0 (time-lapses and
    /// the viewer; stills meter at once).
    pub auto_speed_up: f64,
    /// How fast the EV100 falls as the scene darkens, EV per second, > 0.
    pub auto_speed_down: f64,
    /// Bloom's strength in [0, 1] (0 = off): the share of light spread around each pixel.
    pub bloom: f64,
    /// The eye's night vision (rods: blue shift, colour fading) below a few cd/m² (PNG only).
    pub night_vision: bool,
}

/// `display.exposure_mode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExposureModeName {
    /// The scene's `ev100` or `exposure`.
    Manual,
    /// Metered from each frame.
    Auto,
}

/// The sky models a scene can choose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SkyModelName {
    /// The keyframed gradient sky (`[sky.gradient]`).
    Gradient,
    /// The physically based atmosphere of `[planet]` and `[atmosphere]`, lit by `[[suns]]`.
    Atmosphere,
    /// One colour, `sky.clear_color` (a GL program's `glClearColor`).
    Clear,
}

/// `[sky]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkySection {
    /// Which sky model draws the sky.
    pub model: SkyModelName,
    /// The background of `model = "clear"`, linear RGB(A) as given to `glClearColor`.
    pub clear_color: GlColor,
    /// The gradient sky's layout and keyframes.
    pub gradient: GradientSection,
}

/// `[sky.gradient]`: band layout (elevations in degrees) and the day's keyframes.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GradientSection {
    /// Elevation where the zenith colour begins, degrees, in (`horizon_half_width`, 90].
    #[serde(rename = "zenith_start")]
    pub zenith_start_deg: f64,
    /// Half-height of the horizon band, degrees, in (0, 90).
    #[serde(rename = "horizon_half_width")]
    pub horizon_half_width_deg: f64,
    /// Elevation where the ground colour begins, degrees, in [-90, -`horizon_half_width`).
    #[serde(rename = "ground_start")]
    pub ground_start_deg: f64,
    /// Exponent shaping the upper gradient, > 0 (< 1 reaches the zenith colour sooner).
    pub upper_exponent: f64,
    /// Exponent shaping the lower gradient, > 0.
    pub lower_exponent: f64,
    /// How colours blend across bands: `"smooth"` or `"linear"`.
    pub blend: firmament_core::sky::gradient::Blend,
    /// How colours blend between keyframes in time: `"smooth"` or `"linear"`.
    pub keyframe_blend: firmament_core::sky::gradient::Blend,
    /// What the keyframes follow: `"clock"` (local solar time) or `"sun-elevation"` (the sun's
    /// elevation, mapped to the time of day at which `[sun]`'s path has it).
    pub by: KeyframesBy,
    /// The keyframes, any order, distinct times, at least one.
    pub keyframes: Vec<KeyframeSection>,
}

/// `sky.gradient.by`: what the gradient sky's keyframes follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum KeyframesBy {
    /// The local solar time of day.
    Clock,
    /// The sun's elevation: the keyframes' times are read on `[sun]`'s path (its latitude and
    /// declination), so the colours follow the real sun wherever and whenever it is.
    SunElevation,
}

/// One `[[sky.gradient.keyframes]]` entry: the band colours at a time of day.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyframeSection {
    /// A label for people (`"dawn"`); not used by the renderer.
    #[serde(default)]
    pub name: Option<String>,
    /// When these colours hold, `"HH:MM"` or `"HH:MM:SS"`.
    pub time: String,
    /// Colour at and above `zenith_start`.
    pub zenith: SceneColor,
    /// Colour at the top of the horizon band.
    pub upper: SceneColor,
    /// Colour exactly at the horizon.
    pub horizon: SceneColor,
    /// Colour at the bottom of the horizon band.
    pub lower: SceneColor,
    /// Colour at and below `ground_start`.
    pub ground: SceneColor,
    /// The sun's colour at this time.
    pub sun: SceneColor,
}

/// Deserialises the layered table strictly, turning serde's errors into key-path messages.
pub(crate) fn from_table(table: toml::Table) -> Result<Scene, SceneError> {
    let value = toml::Value::Table(table);
    serde_path_to_error::deserialize::<_, Scene>(value).map_err(|err| {
        let path = err.path().to_string();
        let message = err.inner().message().to_owned();
        classify(&path, &message)
    })
}

/// Turns serde's message into our error: unknown fields get a "did you mean".
fn classify(path: &str, message: &str) -> SceneError {
    // serde's derive writes "unknown field `x`, expected one of `a`, `b`" (or "expected `a`").
    if let Some(rest) = message.strip_prefix("unknown field `") {
        let (field, expected) = rest.split_once('`').unwrap_or((rest, ""));
        let candidates: Vec<&str> = expected.split('`').skip(1).step_by(2).collect();
        // serde_path_to_error's path already ends in the unknown field.
        let key = if path == "." || path.is_empty() {
            field.to_owned()
        } else {
            path.to_owned()
        };
        let suggestion = match did_you_mean(field, candidates.iter().copied()) {
            Some(best) => format!(" (did you mean `{best}`?)"),
            None if candidates.is_empty() => String::new(),
            None => format!(" (known keys here: {})", candidates.join(", ")),
        };
        return SceneError::UnknownKey { key, suggestion };
    }
    if let Some(rest) = message.strip_prefix("missing field `") {
        let field = rest.split('`').next().unwrap_or(rest);
        let key = if path == "." {
            field.to_owned()
        } else {
            format!("{path}.{field}")
        };
        return SceneError::WrongType {
            key,
            message: "missing: this key is required".to_owned(),
        };
    }
    SceneError::WrongType {
        key: path.to_owned(),
        message: message.to_owned(),
    }
}
