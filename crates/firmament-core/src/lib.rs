//! firmament's f64 core: the physics and geometry that every GPU pass is checked against.
//!
//! Nothing here touches a GPU, a window or an image file; it is plain data and math in `f64`.
//!
//! # Conventions (for the whole crate)
//! - **Units**: SI. Distances in metres, angles in radians, times in seconds — unless a field's
//!   name or doc says otherwise (the scene file, for people, speaks degrees and `HH:MM`).
//! - **Frames**: right-handed, **+Z up**.
//!   - *Local frame* (a scene on the ground): East-North-Up, `x` east, `y` north, `z` up, origin
//!     on the ground under the scene's reference point.
//!   - *Planet frame*: planet-centred, `z` along the rotation axis towards the north pole, `x`
//!     through the prime meridian on the equator (like ECEF).
//!   - *View space* (OpenGL style): the camera looks down `-z`, `+y` is up on screen, `+x` right.
//! - **Clip space**: our own passes use wgpu's `z ∈ [0, 1]` with *reversed* depth (near → 1,
//!   far/infinity → 0). The `glu_*` functions reproduce OpenGL's `z ∈ [-1, 1]` exactly.
//! - **Directions** are unit vectors; **elevation** is the angle above the local horizon plane,
//!   **heading** (azimuth) is measured from north (+y) clockwise towards east (+x).
//! - **Colours** are linear RGB (not sRGB-encoded) unless a name says `srgb`.
//!
//! # Where things are
//! - [`atmosphere`]: the physical sky — planet ellipsoid, media, suns, presets and the `f64`
//!   reference integrator every GPU pass is checked against.
//! - [`astro`]: time scales, NREL's SPA for the Sun, Meeus's Moon, sidereal time, the stars.
//! - [`camera`]: the camera, its projections (reversed-Z and `glu*`-exact), frustum, viewport.
//! - [`sky`]: the keyframed gradient sky, the sun's diurnal path, the time of day, the night sky.
//! - [`classic`]: OpenGL 2.1 fixed-function lighting and fog, and the GLTools/GLU meshes.
//! - [`flare`]: lens-flare elements and their placement; [`texture`]: texture images.
//! - [`occluder`]: opaque spheres and boxes whose shadows the reference casts, to check the GPU's
//!   light shafts and shadows.
//! - [`frame`]: everything one rendered frame needs, gathered; [`display`] and [`color`]: exposure,
//!   tone curves, colour spaces; [`geometry`]: rays, spheres, ellipsoids.

pub mod astro;
pub mod atmosphere;
pub mod auto_exposure;
pub mod camera;
pub mod classic;
pub mod color;
pub mod display;
pub mod envmap;
pub mod error;
pub mod flare;
pub mod frame;
pub mod geometry;
pub mod night_vision;
pub mod occluder;
pub mod sky;
pub mod texture;

pub use camera::{Camera, DepthConvention};
pub use color::LinearRgb;
pub use error::CoreError;
pub use frame::Frame;
pub use sky::time_of_day::TimeOfDay;
