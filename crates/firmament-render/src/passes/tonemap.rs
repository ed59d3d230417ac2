//! The tonemap pass: HDR radiance → exposure → tone curve → sRGB, into the caller's view.

use firmament_core::display::DisplaySettings;

use crate::gpu_types::TonemapUniforms;
use crate::passes::common::{PassPipeline, uniform_buffer, uniform_entry};
use crate::shaders;

/// Turns the HDR target into a display image in any colour format (`*Srgb` formats are encoded
/// by the hardware, others by the shader).
#[derive(Debug)]
pub struct TonemapPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniforms: wgpu::Buffer,
    output_format: wgpu::TextureFormat,
    bind_group: Option<wgpu::BindGroup>,
}

impl TonemapPass {
    /// Builds the pipeline for output views of `output_format`.
    pub fn new(device: &wgpu::Device, output_format: wgpu::TextureFormat) -> Self {
        let (pipeline, layout) = PassPipeline {
            owner: "TonemapPass",
            source: &shaders::TONEMAP,
            entries: &[
                uniform_entry(0),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
            color: output_format,
            depth_stencil: None,
            vertex_buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            constants: &[],
        }
        .build(device);
        let uniforms = uniform_buffer::<TonemapUniforms>(device, "firmament TonemapPass uniforms");
        Self {
            pipeline,
            layout,
            uniforms,
            output_format,
            bind_group: None,
        }
    }

    /// The output format this pass was built for.
    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    /// Uploads exposure and curve, and binds `hdr` (a view of the same size as the output).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        display: &DisplaySettings,
        hdr: &wgpu::TextureView,
    ) {
        let data = TonemapUniforms::new(display, self.output_format);
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&data));
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament TonemapPass bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(hdr),
                },
            ],
        }));
    }

    /// Writes every pixel of `output`. Does nothing before the first `prepare`.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, output: &wgpu::TextureView) {
        let Some(bind_group) = &self.bind_group else {
            tracing::warn!("TonemapPass::record before prepare: nothing drawn");
            return;
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("firmament TonemapPass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: output,
                depth_slice: None,
                resolve_target: None,
                // Every pixel is overwritten; clearing only tells tilers they need not load.
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
