//! The gradient sky pass: a full-screen triangle at the far plane, coloured by elevation.

use firmament_core::Camera;
use firmament_core::sky::gradient::GradientSkyState;

use crate::gpu_types::GradientSkyUniforms;
use crate::passes::common::SkyTarget;
use crate::passes::far_plane::FarPlaneDraw;
use crate::shaders;

/// Draws the keyframed gradient sky behind everything already in the depth buffer.
///
/// The triangle sits at reversed-Z depth 0 and is tested with `GreaterEqual` and no depth writes:
/// it fills exactly the pixels where nothing nearer was drawn, so it may run after the opaque
/// geometry (saving the fill of hidden sky) or first, on a cleared depth buffer.
#[derive(Debug)]
pub struct GradientSkyPass {
    sky: FarPlaneDraw<GradientSkyUniforms>,
}

impl GradientSkyPass {
    /// Builds the pipeline for an HDR target of [`HDR_FORMAT`](crate::HDR_FORMAT) and depth of [`DEPTH_FORMAT`](crate::DEPTH_FORMAT).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::for_target(device, SkyTarget::OWN)
    }

    /// Builds the pipeline for `target`'s colour and depth formats and depth convention
    /// (drawn at its far plane, tested against it).
    pub fn for_target(device: &wgpu::Device, target: SkyTarget) -> Self {
        Self {
            sky: FarPlaneDraw::new(device, "GradientSkyPass", &shaders::SKY_GRADIENT, target, None),
        }
    }

    /// Uploads the sky's colours and the camera's view rotation for this frame.
    pub fn prepare(&self, queue: &wgpu::Queue, sky: &GradientSkyState, camera: &Camera) {
        let data = GradientSkyUniforms::new(sky, camera);
        self.sky.write(queue, &data);
    }

    /// Draws into a render pass the caller already began (with a depth attachment).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.sky.draw(pass);
    }

    /// Draws into `color` (loaded, not cleared) behind what `depth` already holds.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, depth: &wgpu::TextureView) {
        self.sky.record(encoder, color, depth);
    }
}
