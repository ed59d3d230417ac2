//! One module per pass. Each pass builds its pipeline in `new`, uploads per-frame data in
//! `prepare` and encodes commands in `record` (into its own render pass) or `draw` (into one the
//! caller already began).

pub mod atmosphere;
pub mod camera;
mod common;
mod compute;
pub mod empirical_sky;
mod far_plane;
pub mod flare;
mod flare_images;
pub mod night_sky;
pub mod objects;
pub mod sky_gradient;
pub mod tonemap;

pub use atmosphere::{AtmospherePass, SkyMethod};
pub use camera::{BloomPass, ExposurePass};
pub use empirical_sky::EmpiricalSkyPass;
pub use flare::FlarePass;
pub use night_sky::NightSkyPass;
pub use objects::{GpuMesh, ObjectPass};
pub use sky_gradient::GradientSkyPass;
pub use tonemap::TonemapPass;
pub use common::{SkyTarget, begin_clear_pass};
pub(crate) use common::begin_load_pass;
