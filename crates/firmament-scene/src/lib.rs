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
//! `[[suns]]`, with the cloud layers of `[[clouds]]`; the world frame is East-North-Up at
//! `planet.latitude`, `planet.longitude` on the surface). `[planet]`, `[atmosphere]`, `[[suns]]`
//! and `[[clouds]]` are checked in every scene but used only by the atmosphere (the clouds only by
//! the physical one). `atmosphere.model = "seed"` draws the seed's own atmosphere model instead of
//! the physical one, with `[atmosphere.seed]` (checked when chosen) and the suns as its stars.
//!
//! A [`SceneDocument`] keeps the layered table for editing key by key and saves it as a complete
//! scene file; [`load`] and [`load_file`] build their scene through one.
//!
//! **Scenes in code**: a [`Scene`] is plain data — the TOML format is a serde layer over these
//! structs, and every field documents its unit and rule. A field in degrees says so in its name
//! (`camera.fov_y_deg`, `suns[i].elevation_deg`) while its key in a file does not (`fov_y`,
//! `elevation`); errors name the file's keys. [`SceneBuilder`] (`Scene::builder()`)
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
//! scene.camera.fov_y_deg = 40.0; // the file's `camera.fov_y`
//! scene.suns[0].elevation_deg = Some(1.5); // degrees above the horizon
//! scene.validate()?;
//! let frame = scene.frame_at(None)?; // what firmament_render draws
//! assert_eq!(frame.camera.fov_y, 40f64.to_radians());
//!
//! scene.camera.fov_y_deg = 0.0;
//! assert!(scene.validate().unwrap_err().to_string().contains("camera.fov_y"));
//! # Ok::<(), firmament_scene::SceneError>(())
//! ```
//!
//! `[flare]` (off by default) gives every sun of the sky and every `[[lights]]` entry marked
//! `flare = true` a lens flare: a built-in preset's elements or the scene's own `flare.elements`.

pub mod assets;
mod builder;
mod checks;
mod color;
mod convert;
mod document;
mod error;
mod layers;
mod model;
mod presets;
mod spectrum;
mod validate;

pub use builder::SceneBuilder;
pub use color::SceneColor;
pub use convert::{
    EMPIRICAL_STAR_DISTANCE, EMPIRICAL_STAR_INTENSITY, MOON_DISPLAY_RADIANCE, add_seconds, parse_date_time,
};
pub use document::{SceneDocument, SceneOrigin, SceneSource, load, load_file};
pub use error::SceneError;
pub use model::{
    AtmosphereModelName, AtmosphereSection, Body, BodyEntry, CameraSection, CloudEntry, DisplaySection,
    EmpiricalSection, ExposureModeName, GradientSection, GroundSection, KeyframeSection, KeyframesBy, MiePhaseName,
    PlanetSection, RenderSection, RingBandEntry, RingsSection, Scene, SkyModelName, SkySection, SunEntry, SunSection,
    SurfaceName, TimeSection,
};
pub use model::{
    CheckerboardEntry, FilterName, FlareElementEntry, FlareKindName, FlarePresetName, FlareSection, FogCoordinateName,
    FogModeName, FogSection, GlColor, LightEntry, LightSpaceName, LightingModelName, LightingSection, MaterialEntry,
    MeshEntry, ObjectEntry, ShadingName, ShadowsSection, SpecularName, SpinEntry, TextureEntry, TransformEntry,
};
pub use model::{LayerEntry, PhaseName, ProfileName, TermEntry};
pub use presets::{PRESETS, Preset};
pub use spectrum::SceneSpectrum;
pub use validate::{MAX_CAMERA_DISTANCE, MAX_IMAGE_SIDE};
