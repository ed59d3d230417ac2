//! What the gradient and seed skies share: a full-screen triangle at the far plane drawn from one
//! uniform buffer, filling exactly the pixels nothing nearer covered.

use std::marker::PhantomData;

use crate::passes::common::{
    PassPipeline, SkyTarget, begin_load_pass, far_depth_constant, far_plane_depth_state, uniform_buffer, uniform_entry,
};

/// A far-plane full-screen pipeline with its uniform buffer of `T` at binding 0.
#[derive(Debug)]
pub(crate) struct FarPlaneDraw<T> {
    owner: &'static str,
    pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    _uniform: PhantomData<T>,
}

impl<T: bytemuck::Pod> FarPlaneDraw<T> {
    /// Builds the pipeline of `source` (`vs_main`, `fs_main`, one uniform at binding 0) for
    /// `target`, blending with `blend`; labels name `owner`.
    pub(crate) fn new(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        SkyTarget {
            color,
            depth,
            convention,
        }: SkyTarget,
        blend: Option<wgpu::BlendState>,
    ) -> Self {
        let (pipeline, layout) = PassPipeline {
            owner,
            source,
            entries: &[uniform_entry(0)],
            color,
            depth_stencil: Some(far_plane_depth_state(depth, convention)),
            vertex_buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            constants: &[far_depth_constant(convention)],
        }
        .build_blended(device, blend);
        let uniforms = uniform_buffer::<T>(device, &format!("firmament {owner} uniforms"));
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("firmament {owner} bind group")),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        Self {
            owner,
            pipeline,
            uniforms,
            bind_group,
            _uniform: PhantomData,
        }
    }

    /// Uploads this frame's uniforms.
    pub(crate) fn write(&self, queue: &wgpu::Queue, data: &T) {
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(data));
    }

    /// Draws into a render pass the caller already began (with a depth attachment).
    pub(crate) fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// Draws into `color` (loaded, not cleared) behind what `depth` already holds.
    pub(crate) fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
    ) {
        let mut pass = begin_load_pass(encoder, &format!("firmament {}", self.owner), color, depth);
        self.draw(&mut pass);
    }
}
