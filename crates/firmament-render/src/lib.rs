//! firmament's wgpu renderer.
//!
//! It owns every GPU object and is the only place where the `f64` core becomes `f32`
//! ([`gpu_types`]). Each pass is a struct in [`passes`] that builds its pipeline once in `new`,
//! uploads per-frame data in `prepare` and only encodes commands in `record`; every pass draws
//! into any `&wgpu::TextureView`, so the CLI, the viewer and the tests share one path.
//!
//! The [`Renderer`] strings the passes together: the sky into an HDR (`Rgba16Float`) target with
//! reversed-Z depth, then the tonemap pass into the caller's output view. [`headless`] renders to
//! memory for files and tests.

pub mod bench;
pub mod context;
pub mod error;
pub mod gpu_types;
pub mod headless;
pub mod passes;
pub mod probe;
pub mod readback;
pub mod renderer;
pub mod shaders;
pub mod targets;

pub use context::{Backend, GpuContext};
pub use error::RenderError;
pub use renderer::Renderer;
pub use targets::{DEPTH_FORMAT, FrameTargets, HDR_FORMAT};
