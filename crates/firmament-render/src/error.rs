//! The renderer's one error type.

/// What can go wrong on the GPU side. More variants may come, hence `#[non_exhaustive]`.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
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
    /// The device lacks features firmament needs (see [`crate::required_features`]).
    #[error(
        "the GPU `{adapter}` lacks the features {missing:?} that firmament needs (for a device of your own: \
         request `firmament_render::required_features()`)"
    )]
    MissingFeatures {
        /// The adapter the device came from.
        adapter: String,
        /// The features firmament needs that the device does not have.
        missing: wgpu::Features,
    },
    /// Device limits below what firmament needs (see [`crate::required_limits`]).
    #[error(
        "the GPU `{adapter}` falls short of firmament's limits: {} (for a device of your own: request \
         `firmament_render::required_limits()`, raised to your own needs)",
        shortfalls.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
    )]
    LimitsTooLow {
        /// The adapter the device came from.
        adapter: String,
        /// Every limit that falls short, in `wgpu::Limits`' field order (never empty).
        shortfalls: Vec<LimitShortfall>,
    },
    /// The image is larger than the GPU allows, or empty.
    #[error(
        "image size {width}x{height}: each side must be 1 to {max} pixels on this GPU (its \
         max_texture_dimension_2d, a limit of the GPU and its driver that firmament cannot raise): ask for a \
         smaller image (--width/--height, render.width/height); firmament does not render an image in tiles"
    )]
    ImageSize {
        /// Requested width, pixels.
        width: u32,
        /// Requested height, pixels.
        height: u32,
        /// The device's largest 2D texture side, pixels.
        max: u32,
    },
    /// A target given to [`Renderer::prepare_into`](crate::Renderer::prepare_into) or
    /// [`Renderer::record_into`](crate::Renderer::record_into) cannot be drawn into: its colour
    /// format, sample count, usages or depth buffer (the message names what is needed).
    #[error("unsupported embedding target: {0}")]
    InvalidTarget(String),
    /// A texture given to [`EnvironmentMapPass`](crate::envmap::EnvironmentMapPass) cannot hold
    /// the map asked for: its dimension, layers, size, format, usages, or half floats asked to
    /// hold the suns' discs (the message names the rule).
    #[error("unsupported environment-map target: {0}")]
    EnvironmentMapTarget(String),
    /// The output format given to [`Renderer::new`](crate::Renderer::new) cannot be drawn into
    /// (each [`Renderer::prepare`](crate::Renderer::prepare) refuses it; the message names what
    /// is needed).
    #[error("unsupported output format: {0}")]
    OutputFormat(String),
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

/// Pops `oom` then `validation` (pushed in that order's reverse around a submission) and returns
/// the first error either caught as [`RenderError::Gpu`], `during` saying what was being done.
pub(crate) fn pop_error_scopes(
    oom: wgpu::ErrorScopeGuard,
    validation: wgpu::ErrorScopeGuard,
    during: &'static str,
) -> Result<(), RenderError> {
    for scope in [oom, validation] {
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu {
                during,
                reason: error.to_string(),
            });
        }
    }
    Ok(())
}

/// One device limit below what firmament needs.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct LimitShortfall {
    /// The `wgpu::Limits` field, e.g. `"max_storage_buffers_per_shader_stage"`.
    pub name: &'static str,
    /// What firmament needs ([`crate::required_limits`]).
    pub required: u64,
    /// What the device allows.
    pub available: u64,
}

impl std::fmt::Display for LimitShortfall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The alignments (`min_…`) are the only limits where smaller is better.
        let relation = if self.name.starts_with("min_") {
            "at most"
        } else {
            "at least"
        };
        write!(
            f,
            "`{}` is {}, firmament needs {relation} {}",
            self.name, self.available, self.required
        )
    }
}
