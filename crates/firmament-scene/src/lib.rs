//! firmament's scene files: a TOML format, built-in presets, `--set` overrides and validation.
//!
//! A scene is built in layers, each over the one before:
//! 1. the built-in `default` preset (`presets/default.toml`, which lists every key),
//! 2. the preset named by the file's `preset` key (or the caller's), itself built the same way,
//! 3. the scene file's own keys,
//! 4. `key.path=value` overrides.
//!
//! Tables merge key by key; any other value (arrays included) replaces what was there: a layer's
//! `[[suns]]` (or `[[sky.gradient.keyframes]]`) list replaces the whole list below it, so a scene
//! file that lists suns lists all of them. `--set` reaches into arrays by index
//! (`suns.0.elevation=3`), and an index one past the end appends a new table (`suns.1.azimuth=90`
//! then `suns.1.elevation=5` adds a second sun). The result is parsed strictly — unknown keys
//! are errors with a "did you mean" — and every value is checked against its rule. Errors name
//! the key path, the value and the rule.
//!
//! Scene files speak human units: angles in **degrees**, times as `"HH:MM"`, lengths in metres.
//! Colours are `"#rrggbb"` (sRGB-encoded, as colour pickers give them) or `[r, g, b]` (linear).
//!
//! Two sky models: `sky.model = "gradient"` (the keyframed gradient, with `[time]` and `[sun]`)
//! and `"atmosphere"` (a planet from `[planet]` with the medium of `[atmosphere]`, lit by
//! `[[suns]]`; the world frame is East-North-Up at `planet.latitude`, `planet.longitude` on the
//! surface). `[planet]`, `[atmosphere]` and `[[suns]]` are checked in every scene but used only by
//! the atmosphere. `atmosphere.model = "seed"` draws the seed's own atmosphere model instead of the
//! physical one, with `[atmosphere.seed]` (checked when chosen) and the suns as its stars.
//!
//! A [`SceneDocument`] keeps the layered table for editing key by key and saves it as a complete
//! scene file; [`load`] and [`load_file`] build their scene through one.
//!
//! **Scenes in code**: a [`Scene`] is plain data — the TOML format is a serde layer over these
//! structs, and every field documents its unit and rule. [`SceneBuilder`] (`Scene::builder()`)
//! sets them with typed, unit-named setters (`fov_y_deg`, `camera_position_m`,
//! `rayleigh_per_m`, …) over the `default` preset every scene file starts from, and `build`
//! checks the result with [`Scene::validate`] — the same model and the same rules as a file, so a
//! builder and a file saying the same things give equal scenes, and a bad value the same message.
//! Or start from a preset, change fields, check the rules, and draw. A change shows in the next
//! frame built, and the renderer rebuilds the atmosphere's medium LUTs only when the medium
//! itself changed (moving a sun or the camera re-renders only the per-frame sky-view LUT).
//!
//! ```
//! use firmament_scene::{Body, Scene};
//!
//! let scene = Scene::builder()
//!     .atmosphere(Body::Earth)
//!     .sun_at_deg(262.0, 6.0) // azimuth, elevation
//!     .fov_y_deg(40.0)
//!     .build()?; // the rules a scene file is checked against
//! assert_eq!(scene.frame_at(None)?.camera.fov_y, 40f64.to_radians());
//!
//! let mut scene = Scene::preset("earth-sunset")?;
//! scene.camera.fov_y = 40.0; // degrees
//! scene.suns[0].elevation = Some(1.5); // degrees above the horizon
//! scene.validate()?;
//! let frame = scene.frame_at(None)?; // what firmament_render draws
//! assert_eq!(frame.camera.fov_y, 40f64.to_radians());
//!
//! scene.camera.fov_y = 0.0;
//! assert!(scene.validate().unwrap_err().to_string().contains("camera.fov_y"));
//! # Ok::<(), firmament_scene::SceneError>(())
//! ```
//!
//! `[flare]` (off by default) gives every sun of the sky and every `[[lights]]` entry marked
//! `flare = true` a lens flare: a built-in preset's elements or the scene's own `flare.elements`.

pub mod assets;
mod atmosphere;
mod builder;
mod color;
mod document;
mod error;
mod flare;
mod layers;
mod model;
mod night;
mod objects;
mod presets;
mod spectrum;
mod time;
mod to_frame;
mod validate;

pub use atmosphere::{SEED_STAR_DISTANCE, SEED_STAR_INTENSITY};
pub use builder::SceneBuilder;
pub use color::SceneColor;
pub use document::{SceneDocument, SceneOrigin};
pub use error::SceneError;
pub use model::{
    AtmosphereModelName, AtmosphereSection, Body, CameraSection, DisplaySection, GradientSection, KeyframeSection,
    KeyframesBy, MiePhaseName, PlanetSection, RenderSection, Scene, SeedSection, SkyModelName, SkySection, SunEntry,
    SunSection, TimeSection,
};
pub use model::{
    CheckerboardEntry, FilterName, FlareElementEntry, FlareKindName, FlarePresetName, FlareSection, FogCoordinateName,
    FogModeName, FogSection, GlColor, LightEntry, LightSpaceName, LightingModelName, LightingSection, MaterialEntry,
    MeshEntry, ObjectEntry, ShadingName, SpecularName, SpinEntry, TextureEntry, TransformEntry,
};
pub use night::MOON_DISPLAY_RADIANCE;
pub use presets::{PRESETS, Preset};
pub use spectrum::SceneSpectrum;
pub use time::{add_seconds, parse_date_time};

/// Largest image side the scene format accepts, pixels. The GPU's own limit may be lower; the
/// renderer checks that one.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// Farthest the camera may be from the world origin, metres (10¹⁵ m, about 6700 AU): far past
/// the 100 AU firmament is tested to, and short of distances where a planet is a speck below
/// a pixel and `f64` positions themselves lose the metre.
pub const MAX_CAMERA_DISTANCE: f64 = 1.0e15;

/// Where a scene comes from before overrides.
#[derive(Debug, Clone, Copy)]
pub enum SceneSource<'a> {
    /// A built-in preset, by name.
    Preset(&'a str),
    /// TOML text read from `origin` (a path, for messages). A `preset` given alongside replaces
    /// the file's own `preset` key.
    Text {
        /// The TOML text.
        text: &'a str,
        /// Where it came from, for messages (usually the file path).
        origin: &'a str,
    },
}

/// Builds and validates a scene: `source`, with an optional preset to start from, then
/// `overrides` (each `key.path=value`, the value in TOML syntax or a bare string). The same as
/// [`SceneDocument::load`] then [`SceneDocument::scene`].
pub fn load(source: SceneSource<'_>, preset: Option<&str>, overrides: &[String]) -> Result<Scene, SceneError> {
    SceneDocument::load(source, preset, overrides)?.scene()
}

/// Reads a scene file from disk and builds it like [`load`]; relative asset paths resolve against
/// the file's folder. The same as [`SceneDocument::load_file`] then [`SceneDocument::scene`].
pub fn load_file(path: &std::path::Path, preset: Option<&str>, overrides: &[String]) -> Result<Scene, SceneError> {
    SceneDocument::load_file(path, preset, overrides)?.scene()
}

impl Scene {
    /// The built-in preset `name` as a scene, to change in code (see the crate docs); an unknown
    /// name is an error with a "did you mean".
    pub fn preset(name: &str) -> Result<Self, SceneError> {
        load(SceneSource::Preset(name), None, &[])
    }

    /// Checks every rule of the scene format, as loading a file does: after changing fields in
    /// code, before drawing. The error names the key, the value and the rule.
    pub fn validate(&self) -> Result<(), SceneError> {
        validate::validate(self)
    }
}
