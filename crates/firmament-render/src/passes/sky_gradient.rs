//! The gradient sky pass: a full-screen triangle at the far plane, coloured by elevation.

use firmament_core::Camera;
use firmament_core::gradient_sky::GradientSkyState;

use crate::gpu_types::GradientSkyUniforms;
use crate::passes::{PassPipeline, begin_load_pass, far_plane_depth_state, uniform_buffer, uniform_entry};
use crate::shaders;
use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};

/// Draws the keyframed gradient sky behind everything already in the depth buffer.
///
/// The triangle sits at reversed-Z depth 0 and is tested with `GreaterEqual` and no depth writes:
/// it fills exactly the pixels where nothing nearer was drawn, so it may run after the opaque
/// geometry (saving the fill of hidden sky) or first, on a cleared depth buffer.
#[derive(Debug)]
pub struct GradientSkyPass {
    pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl GradientSkyPass {
    /// Builds the pipeline for an HDR target of [`HDR_FORMAT`] and depth of [`DEPTH_FORMAT`].
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_formats(device, HDR_FORMAT, DEPTH_FORMAT)
    }

    /// Builds the pipeline for other colour and depth formats (for embedding in another renderer).
    pub fn with_formats(device: &wgpu::Device, color: wgpu::TextureFormat, depth: wgpu::TextureFormat) -> Self {
        let (pipeline, layout) = PassPipeline {
            owner: "GradientSkyPass",
            source: shaders::SKY_GRADIENT,
            entries: &[uniform_entry(0)],
            color,
            depth_stencil: Some(far_plane_depth_state(depth)),
            vertex_buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            constants: &[],
        }
        .build(device);
        let uniforms = uniform_buffer::<GradientSkyUniforms>(device, "firmament GradientSkyPass uniforms");
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament GradientSkyPass bind group"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        Self {
            pipeline,
            uniforms,
            bind_group,
        }
    }

    /// Uploads the sky's colours and the camera's view rotation for this frame.
    pub fn prepare(&self, queue: &wgpu::Queue, sky: &GradientSkyState, camera: &Camera) {
        let data = GradientSkyUniforms::new(sky, camera);
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&data));
    }

    /// Draws into a render pass the caller already began (with a depth attachment).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// Draws into `color` (loaded, not cleared) behind what `depth` already holds.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, depth: &wgpu::TextureView) {
        let mut pass = begin_load_pass(encoder, "firmament GradientSkyPass", color, depth);
        self.draw(&mut pass);
    }
}
