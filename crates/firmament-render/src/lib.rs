//! firmament's wgpu renderer: skies, atmospheres, the objects under them and lens flares, drawn
//! from a [`firmament_core::Frame`] into a `wgpu` texture view.
//!
//! It owns every GPU object and is the only place where the `f64` core becomes `f32`
//! (`gpu_types/`). Each pass is a struct in `passes/` that builds its pipeline once in `new`,
//! uploads per-frame data in `prepare` and only encodes commands in `record`; every pass draws
//! into any `&wgpu::TextureView`, so the CLI, the viewer and the tests share one path.
//!
//! The [`Renderer`] strings the passes together: the objects, the sky behind them and the flares
//! into an HDR target with reversed-Z depth, then the tonemap pass into the caller's output view.
//! [`headless`] renders to memory for files and tests.
//!
//! # Quick start
//!
//! Bring your own device — ask the adapter for [`required_features`] and [`required_limits`] —
//! hand it to [`GpuContext::from_device`], and render a frame. Here the frame is the scene
//! format's default scene (the `firmament-scene` crate, which this one does not depend on); a
//! [`firmament_core::Frame`] built in code works the same.
//!
//! ```
//! use firmament_render::{GpuContext, headless::HeadlessRenderer, wgpu};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // Your device, made your way with the `wgpu` firmament re-exports.
//! let instance = wgpu::Instance::default();
//! let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
//! let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
//!     label: Some("my device"),
//!     required_features: firmament_render::required_features(),
//!     required_limits: firmament_render::required_limits().using_resolution(adapter.limits()),
//!     ..Default::default()
//! }))?;
//!
//! // firmament on that device (checked against what it needs), with no instance or adapter.
//! let ctx = GpuContext::from_device(device.clone(), queue.clone())?;
//!
//! let scene = firmament_scene::load(firmament_scene::SceneSource::Preset("default"), None, &[])?;
//! let frame = scene.frame_at(None)?;
//!
//! let mut renderer = HeadlessRenderer::new(&ctx);
//! let image = renderer.render_ldr(&ctx, &frame, 64, 36)?; // 8-bit sRGB RGBA, top row first
//! assert_eq!((image.width, image.height), (64, 36));
//! assert_eq!(image.pixels.len(), 64 * 36 * 4);
//! # Ok(())
//! # }
//! ```
//!
//! # Conventions
//!
//! - **Units**: SI, as in [`firmament_core`]: metres, radians, seconds (scene files speak degrees
//!   and `HH:MM` for people). The HDR target holds linear radiance — cd/m² in linear sRGB for the
//!   physical atmosphere, display units for the gradient and seed skies — clamped to
//!   [`HDR_MAX`].
//! - **Frames**: right-handed, +Z up. The world is East-North-Up (`x` east, `y` north, `z` up);
//!   the planet frame is planet-centred with `z` through the north pole; view space is OpenGL's
//!   (the camera looks down −z, +y up on screen).
//! - **Depth**: *reversed-Z*: clip `z ∈ [0, 1]`, the near plane → 1, the far plane → 0 (the
//!   camera's far plane is infinite unless it sets one). The depth target is [`DEPTH_FORMAT`]
//!   (`Depth32Float`), cleared to 0 and tested `Greater`; the sky is drawn at depth 0
//!   (`GreaterEqual`), filling exactly what nothing nearer covered. Your own depth buffer
//!   ([`EmbedTarget`]) may be standard-Z instead ([`DepthConvention::Standard`]: near → 0, far →
//!   1, the sky drawn at 1 and tested `LessEqual`).
//! - **Colour**: linear RGB everywhere until the tonemap pass (exposure, tone curve, then sRGB —
//!   by the hardware into `*Srgb` views, by the shader into others). The camera's aspect ratio
//!   is always the image's.
//!
//! # Embedding
//!
//! - **Your device and queue**: [`GpuContext::from_device`] wraps them (cheap `wgpu` handles,
//!   shared with your renderer) after [`check_device`] — a device short of a feature or limit
//!   gives [`RenderError::MissingFeatures`] or [`RenderError::LimitsTooLow`] naming it and its
//!   value, never a wgpu validation panic. [`pub use wgpu`](wgpu) pins the version.
//! - **Your encoder and view**: [`Renderer::new`] for an output format, then per frame
//!   [`Renderer::prepare`] and [`Renderer::record`] into your command encoder and any view of
//!   that format and the prepared size. It writes every pixel of the view: the finished,
//!   tone-mapped image (firmament's own objects included). An output format the output pass
//!   cannot draw into ([`check_output_format`]) is refused by `prepare` with
//!   [`RenderError::OutputFormat`].
//! - **Images in memory**: [`headless::HeadlessRenderer`] (8-bit display or linear HDR).
//! - **Environment maps** (HDRIs for image-based lighting): [`envmap`] —
//!   [`HeadlessRenderer::render_equirect`](headless::HeadlessRenderer::render_equirect) and
//!   [`render_cube_faces`](headless::HeadlessRenderer::render_cube_faces), linear radiance with
//!   the suns' discs at their true radiance (or left out, the suns given apart by
//!   [`envmap::suns_at_eye`]); into your own cube or 2D texture, with no read-back, by
//!   [`envmap::EnvironmentMapPass`].
//! - **Your frame: your HDR target, depth buffer and depth convention**:
//!   [`Renderer::prepare_into`] and [`Renderer::record_into`] with an [`EmbedTarget`] (your
//!   colour view of one of [`EMBED_COLOR_FORMATS`], your depth view of one of
//!   [`EMBED_DEPTH_FORMATS`] holding your geometry, and its [`DepthConvention`]: reversed or
//!   standard Z, the far plane finite or infinite as the camera says). The sky lies behind your
//!   geometry, aerial perspective falls on it, flares are hidden by it. Linear radiance for your
//!   own tone mapping — or, with [`EmbedTarget::with_output`], firmament's output pass writes the
//!   finished image into your displayable view (a window's surface, an 8-bit texture): the same
//!   pixels `firmament render` writes for the same scene, your geometry included (tested within
//!   1/255 in both depth conventions, finite and infinite far plane). Bad targets — format,
//!   usages, sample counts (MSAA is refused: resolve first), sizes, textures with layers or mips
//!   — give [`RenderError::InvalidTarget`] naming what is needed.
//! - **Lighting and fogging your materials** with a physical sky: [`Renderer::sky_lighting_buffer`]
//!   (each sun's direction and colour at the camera, the sky's irradiance as spherical harmonics;
//!   [`sky_lighting_layout_entry`], [`firmament_lighting_wgsl`]) and
//!   [`Renderer::aerial_perspective_bindings`] (the aerial-perspective froxel volume and its
//!   uniforms; [`aerial_perspective_layout_entries`], [`firmament_aerial_perspective_wgsl`]'s
//!   `firmament_apply_aerial_perspective(color, ndc_xy, distance_m)`);
//!   [`Renderer::record_lighting`] encodes this frame's values before your geometry. The renderer
//!   builds the volume only in atmosphere frames with its own objects, or in every atmosphere
//!   frame after [`Renderer::set_aerial_perspective_for_users`]. The `custom_material` example
//!   (`firmament-examples`) uses both; `embed_minimal` is a winit app drawing its own cube lit by
//!   firmament's sun and sky, with firmament's sky, air and flares around it.
//! - **Scenes in code**: `firmament_scene::SceneBuilder` (a separate crate; this one draws any
//!   [`firmament_core::Frame`]).
//!
//! Limits:
//! - On the [`Renderer::record_into`] path, a clear-colour sky (the background is left to you)
//!   and firmament's own objects (`frame.objects`) are not drawn.
//! - wgpu's `TextureView` does not say which layer, mip level or format it shows, so
//!   [`EmbedTarget`] checks the texture behind each view: pass views of whole single-image
//!   textures in their own format.
//! - GPU errors of [`Renderer::prepare`] / [`Renderer::record`] go to your device's error handler
//!   (wgpu's default panics); [`headless::HeadlessRenderer`] captures them as
//!   [`RenderError::Gpu`]. Everything firmament can check beforehand it checks, and returns as
//!   an error.

mod context;
pub mod envmap;
mod error;
pub mod headless;
mod renderer;
mod requirements;
mod targets;

/// Declares the modules behind the public API: private, or public with the `internals` feature,
/// for firmament's own tests and tools (the CLI's benchmarks and probes). No compatibility promise
/// is made for them; an embedder needs only the names re-exported below.
macro_rules! internal_modules {
    ($($(#[$doc:meta])* $name:ident;)*) => {
        $(
            $(#[$doc])*
            #[cfg(feature = "internals")]
            pub mod $name;
            $(#[$doc])*
            #[cfg(not(feature = "internals"))]
            #[allow(
                unreachable_pub,
                dead_code,
                unused_imports,
                reason = "public, and used, only by the crate's own tests and tools with the internals feature"
            )]
            mod $name;
        )*
    };
}

internal_modules! {
    /// The one place the `f64` core becomes `f32` GPU data, camera- or planet-relative.
    gpu_types;
    /// Timestamp queries around a frame's phases: the viewer's panel and the benchmarks.
    pass_timing;
    /// One module per pass: `new` builds pipelines, `prepare` uploads, `record` encodes.
    passes;
    /// Texture and buffer read-back.
    readback;
    /// The WGSL sources and their composition.
    shaders;
}

/// The wgpu this crate is built against: use it for your own device so that versions cannot drift.
pub use wgpu;

pub use context::{Backend, GpuContext};
pub use error::{LimitShortfall, RenderError};
pub use firmament_core::DepthConvention;
pub use gpu_types::SkyLightingGpu;
pub use pass_timing::{
    PHASE_AERIAL_PERSPECTIVE, PHASE_BLOOM, PHASE_EXPOSURE, PHASE_FLARES, PHASE_LUTS, PHASE_SHADOWS,
    PHASE_SKY_AND_OBJECTS, PHASE_TONEMAP, PHASES, PassTime, PassTimes, pass_timing_supported,
};
pub use passes::atmosphere::{AerialPerspectiveBindings, aerial_perspective_layout_entries, sky_lighting_layout_entry};
pub use renderer::Renderer;
pub use requirements::{TIMESTAMP_FEATURES, check_device, required_features, required_limits};
pub use shaders::{
    FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING, FIRMAMENT_AERIAL_PERSPECTIVE_GROUP, FIRMAMENT_AERIAL_PERSPECTIVE_WGSL,
    FIRMAMENT_LIGHTING_BINDING, FIRMAMENT_LIGHTING_GROUP, FIRMAMENT_LIGHTING_WGSL, Shader,
    firmament_aerial_perspective_wgsl, firmament_lighting_wgsl,
};
pub use targets::{
    DEPTH_FORMAT, EMBED_COLOR_FORMATS, EMBED_DEPTH_FORMATS, EmbedTarget, FrameTargets, HDR_FORMAT, HDR_MAX,
    check_output_format,
};
