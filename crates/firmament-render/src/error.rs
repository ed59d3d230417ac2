//! The renderer's one error type.

/// What can go wrong on the GPU side.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No adapter for the requested backend.
    #[error(
        "no GPU adapter found for backend `{backend}` ({reason}). firmament needs a Vulkan, Metal, DX12 or \
         OpenGL ES 3 driver; on Linux without a GPU install Mesa's software drivers: \
         `apt-get install libegl1 libgl1-mesa-dri` (OpenGL, llvmpipe) or `apt-get install mesa-vulkan-drivers` \
         (Vulkan, lavapipe), or try `--backend gl`"
    )]
    NoAdapter {
        /// The backend asked for.
        backend: String,
        /// What wgpu said.
        reason: String,
    },
    /// The adapter refused to create a device.
    #[error("the GPU adapter `{adapter}` could not create a device: {reason}")]
    RequestDevice {
        /// The adapter's name.
        adapter: String,
        /// What wgpu said.
        reason: String,
    },
    /// The image is larger than the GPU allows, or empty.
    #[error("image size {width}x{height}: each side must be 1 to {max} pixels on this GPU")]
    ImageSize {
        /// Requested width, pixels.
        width: u32,
        /// Requested height, pixels.
        height: u32,
        /// The device's largest 2D texture side, pixels.
        max: u32,
    },
    /// A value given to the renderer broke its rule.
    #[error("{0}")]
    Invalid(#[from] firmament_core::CoreError),
    /// Reading the image back from the GPU failed.
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
    /// The GPU reported an error while rendering (validation, out of memory, device lost).
    #[error("the GPU reported an error while {during}: {reason}")]
    Gpu {
        /// What we were doing.
        during: &'static str,
        /// What wgpu said.
        reason: String,
    },
}
