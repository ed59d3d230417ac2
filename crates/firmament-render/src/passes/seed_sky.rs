//! The seed's own atmosphere model (`atmosphere.model = "seed"`): a full-screen triangle at the
//! far plane running `shaders/seed_sky.wgsl`, the GPU twin of
//! [`SeedAtmosphere::color`](firmament_core::atmosphere::seed::SeedAtmosphere::color).
//!
//! # What lands in the HDR target
//! The seed's colour (unitless, in [0, 1]) times [`SeedSky::luminance`] (cd/m² per unit colour),
//! as linear RGB, blended like the seed blends it (`ONE, ONE_MINUS_SRC_ALPHA`, seed line 252):
//! where the seed's alpha is 1 (a star disc was on the ray and its colour started the
//! integration) the sky replaces what is behind it, where it is 0 the sky is added to it. Nothing
//! else draws at the far plane today, so over the cleared (black) target the result is the colour
//! itself, which [`SeedSky::radiance`] gives in `f64`. The seed draws its planet's surface with
//! other code; here a ray that meets the ground gets the seed's colour of the air in front of it,
//! as the f64 port does, over black.

use firmament_core::Camera;
use firmament_core::frame::SeedSky;

use crate::gpu_types::SeedSkyUniforms;
use crate::passes::SkyTarget;
use crate::passes::far_plane::FarPlaneDraw;
use crate::shaders;

/// The seed's blend (`glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA)`, seed line 252), for colour
/// and alpha alike (alpha stays 1 over an opaque target).
const SEED_BLEND: wgpu::BlendState = wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING;

/// Draws the seed's atmosphere behind everything already in the depth buffer.
#[derive(Debug)]
pub struct SeedSkyPass {
    sky: FarPlaneDraw<SeedSkyUniforms>,
}

impl SeedSkyPass {
    /// Builds the pipeline for an HDR target of [`HDR_FORMAT`](crate::HDR_FORMAT) and depth of [`DEPTH_FORMAT`](crate::DEPTH_FORMAT).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::for_target(device, SkyTarget::OWN)
    }

    /// Builds the pipeline for `target`'s colour and depth formats and depth convention
    /// (drawn at its far plane, tested against it).
    pub fn for_target(device: &wgpu::Device, target: SkyTarget) -> Self {
        Self {
            sky: FarPlaneDraw::new(device, "SeedSkyPass", &shaders::SEED_SKY, target, Some(SEED_BLEND)),
        }
    }

    /// Uploads the seed's parameters, stars and the camera's view for this frame.
    pub fn prepare(&self, queue: &wgpu::Queue, sky: &SeedSky, camera: &Camera) {
        let data = SeedSkyUniforms::new(sky, camera);
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
