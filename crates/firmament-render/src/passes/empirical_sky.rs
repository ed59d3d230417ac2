//! The seed's own atmosphere model, the empirical one (`atmosphere.model = "seed"`): a
//! full-screen triangle at the far plane running `shaders/empirical_sky.wgsl`, the GPU twin of
//! [`EmpiricalAtmosphere::color`](firmament_core::atmosphere::empirical::EmpiricalAtmosphere::color).
//!
//! # What lands in the HDR target
//! The seed's colour (unitless, in [0, 1]) times [`EmpiricalSky::luminance`] (cd/m² per unit
//! colour), as linear RGB, blended like the seed blends it (`ONE, ONE_MINUS_SRC_ALPHA`, seed line
//! 252): where the seed's alpha is 1 (a star disc was on the ray and its colour started the
//! integration) the sky replaces what is behind it, where it is 0 the sky is added to it. Nothing
//! else draws at the far plane today, so over the cleared (black) target the result is the colour
//! itself, which [`EmpiricalSky::radiance`] gives in `f64`. The seed draws its planet's surface
//! with other code; here a ray that meets the ground gets the seed's colour of the air in front of
//! it, as the f64 port does, over black.

use firmament_core::Camera;
use firmament_core::frame::EmpiricalSky;

use crate::gpu_types::EmpiricalSkyUniforms;
use crate::passes::common::SkyTarget;
use crate::passes::far_plane::FarPlaneDraw;
use crate::shaders;

/// The seed's blend (`glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA)`, seed line 252), for colour
/// and alpha alike (alpha stays 1 over an opaque target).
const EMPIRICAL_BLEND: wgpu::BlendState = wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING;

/// Draws the seed's atmosphere behind everything already in the depth buffer.
#[derive(Debug)]
pub struct EmpiricalSkyPass {
    sky: FarPlaneDraw<EmpiricalSkyUniforms>,
}

impl EmpiricalSkyPass {
    /// Builds the pipeline for an HDR target of [`HDR_FORMAT`](crate::HDR_FORMAT) and depth of [`DEPTH_FORMAT`](crate::DEPTH_FORMAT).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::for_target(device, SkyTarget::OWN)
    }

    /// Builds the pipeline for `target`'s colour and depth formats and depth convention
    /// (drawn at its far plane, tested against it).
    pub fn for_target(device: &wgpu::Device, target: SkyTarget) -> Self {
        Self {
            sky: FarPlaneDraw::new(device, "EmpiricalSkyPass", &shaders::EMPIRICAL_SKY, target, Some(EMPIRICAL_BLEND)),
        }
    }

    /// Uploads the seed's parameters, stars and the camera's view for this frame.
    pub fn prepare(&self, queue: &wgpu::Queue, sky: &EmpiricalSky, camera: &Camera) {
        let data = EmpiricalSkyUniforms::new(sky, camera);
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
