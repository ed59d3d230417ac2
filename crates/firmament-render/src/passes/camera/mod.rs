//! The camera's passes between the HDR image and the output pass: auto-exposure (a luminance
//! histogram and the exposure it asks for, [`ExposurePass`]) and bloom (a blur pyramid,
//! [`BloomPass`]). Both are compute passes that read the HDR image and leave their results in
//! small textures the output pass (`TonemapPass`) reads; the HDR image itself, and so EXR output,
//! stays the scene's radiance.

mod bloom;
mod exposure;

pub use bloom::{BLOOM_LEVELS, BLOOM_SPREAD, BloomPass};
pub use exposure::ExposurePass;

use firmament_core::auto_exposure::ExposureMode;
use firmament_core::{Camera, Frame};

use crate::context::GpuContext;
use crate::pass_timing::{FrameTiming, PHASE_BLOOM, PHASE_EXPOSURE};
use crate::passes::tonemap::CameraImages;

/// Both camera passes, and which of them the prepared frame runs.
#[derive(Debug)]
pub(crate) struct CameraPasses {
    pub(crate) exposure: ExposurePass,
    pub(crate) bloom: BloomPass,
    metered: bool,
    bloomed: bool,
}

impl CameraPasses {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        Self {
            exposure: ExposurePass::new(device),
            bloom: BloomPass::new(device),
            metered: false,
            bloomed: false,
        }
    }

    /// Prepares the passes `frame.display` asks for on `hdr`, the image of `size` that `camera`
    /// (aspect set) sees; `None` for a frame that runs neither.
    pub(crate) fn prepare(
        &mut self,
        ctx: &GpuContext,
        frame: Option<(&Frame, &Camera)>,
        hdr: &wgpu::TextureView,
        size: (u32, u32),
    ) {
        self.metered = false;
        self.bloomed = false;
        let Some((frame, camera)) = frame else {
            return;
        };
        if let ExposureMode::Auto(auto) = &frame.display.exposure_mode {
            self.exposure
                .prepare(&ctx.device, &ctx.queue, frame, camera, auto, hdr, size);
            self.metered = true;
        }
        if frame.display.bloom > 0.0 {
            self.bloom.prepare(&ctx.device, hdr, size);
            self.bloomed = true;
        }
    }

    /// What the output pass reads.
    pub(crate) fn images(&self) -> CameraImages<'_> {
        CameraImages {
            exposure: self.exposure.exposure_view(),
            bloom: self.bloom.bloom_view(),
        }
    }

    /// Encodes the passes prepared for this frame: the meter, then bloom (after everything is
    /// drawn into the HDR image, before the output pass).
    pub(crate) fn record(&self, encoder: &mut wgpu::CommandEncoder, timing: &mut FrameTiming<'_>) {
        if self.metered {
            self.exposure.record(encoder);
            timing.mark(encoder, PHASE_EXPOSURE);
        }
        if self.bloomed {
            self.bloom.record(encoder);
            timing.mark(encoder, PHASE_BLOOM);
        }
    }
}

/// Binding numbers shared by every camera shader: those `shaders/camera/bindings.wgsl` declares
/// (a test compares the two).
pub(crate) mod binding {
    pub(crate) const METERING: u32 = 0;
    pub(crate) const HDR_IN: u32 = 1;
    pub(crate) const HISTOGRAM: u32 = 2;
    pub(crate) const EXPOSURE_STATE: u32 = 3;
    pub(crate) const EXPOSURE_OUT: u32 = 4;
    pub(crate) const BLOOM_IN: u32 = 5;
    pub(crate) const BLOOM_COARSER: u32 = 6;
    pub(crate) const BLOOM_SAMPLER: u32 = 7;
    pub(crate) const BLOOM_OUT: u32 = 8;
}

#[cfg(test)]
mod tests {
    use super::binding;

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let mut rust: Vec<(String, u32)> = [
            ("metering", binding::METERING),
            ("hdr_in", binding::HDR_IN),
            ("histogram", binding::HISTOGRAM),
            ("exposure_state", binding::EXPOSURE_STATE),
            ("exposure_out", binding::EXPOSURE_OUT),
            ("bloom_in", binding::BLOOM_IN),
            ("bloom_coarser", binding::BLOOM_COARSER),
            ("bloom_sampler", binding::BLOOM_SAMPLER),
            ("bloom_out", binding::BLOOM_OUT),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into();
        rust.sort();
        assert_eq!(crate::shaders::declared_bindings("camera/bindings"), rust);
    }
}
