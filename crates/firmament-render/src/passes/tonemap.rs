//! The output pass: HDR radiance → bloom → night vision → exposure → tone curve → sRGB, into
//! the caller's view. Bloom and the metered exposure come from the camera passes
//! ([`crate::passes::camera`]) as textures.

use firmament_core::display::DisplaySettings;

use crate::gpu_types::TonemapUniforms;
use crate::passes::common::{PassPipeline, linear_clamp_sampler, uniform_buffer, uniform_entry};
use crate::passes::compute::{bind_group, sampler_entry, texture_entry};
use crate::shaders;

/// The output pass's binding numbers (declared in `tonemap.wgsl`; a test compares them).
mod binding {
    pub(super) const PARAMS: u32 = 0;
    pub(super) const HDR: u32 = 1;
    pub(super) const METERED_EXPOSURE: u32 = 2;
    pub(super) const BLOOM: u32 = 3;
    pub(super) const BLOOM_SAMPLER: u32 = 4;
}

/// What the camera passes give the output pass: the meter's exposure (a 1 × 1 `R32Float`
/// texture, read when the display's exposure mode is auto) and the bloom (read when its strength
/// is above 0).
#[derive(Debug, Clone, Copy)]
pub struct CameraImages<'a> {
    /// [`ExposurePass::exposure_view`](crate::passes::ExposurePass::exposure_view).
    pub exposure: &'a wgpu::TextureView,
    /// [`BloomPass::bloom_view`](crate::passes::BloomPass::bloom_view).
    pub bloom: &'a wgpu::TextureView,
}

/// Turns the HDR target into a display image in any colour format (`*Srgb` formats are encoded
/// by the hardware, others by the shader).
#[derive(Debug)]
pub struct TonemapPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniforms: wgpu::Buffer,
    sampler: wgpu::Sampler,
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
                uniform_entry(binding::PARAMS),
                texture_entry(binding::HDR, false),
                texture_entry(binding::METERED_EXPOSURE, false),
                texture_entry(binding::BLOOM, true),
                sampler_entry(binding::BLOOM_SAMPLER),
            ],
            color: output_format,
            depth_stencil: None,
            vertex_buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            constants: &[],
        }
        .build(device);
        let uniforms = uniform_buffer::<TonemapUniforms>(device, "firmament TonemapPass uniforms");
        let sampler = linear_clamp_sampler(device, "firmament TonemapPass bloom sampler");
        Self {
            pipeline,
            layout,
            uniforms,
            sampler,
            output_format,
            bind_group: None,
        }
    }

    /// The output format this pass was built for.
    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    /// Uploads exposure, curve, bloom's strength and night vision, and binds `hdr` (a view of
    /// the same size as the output) with the camera passes' `images`.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        display: &DisplaySettings,
        hdr: &wgpu::TextureView,
        images: CameraImages<'_>,
    ) {
        let data = TonemapUniforms::new(display, self.output_format);
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&data));
        let view = wgpu::BindingResource::TextureView;
        self.bind_group = Some(bind_group(
            device,
            "TonemapPass",
            &self.layout,
            &[
                (binding::PARAMS, self.uniforms.as_entire_binding()),
                (binding::HDR, view(hdr)),
                (binding::METERED_EXPOSURE, view(images.exposure)),
                (binding::BLOOM, view(images.bloom)),
                (binding::BLOOM_SAMPLER, wgpu::BindingResource::Sampler(&self.sampler)),
            ],
        ));
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

#[cfg(test)]
mod tests {
    use super::binding;

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let rust: Vec<(String, u32)> = [
            ("bloom_image", binding::BLOOM),
            ("bloom_sampler", binding::BLOOM_SAMPLER),
            ("hdr", binding::HDR),
            ("metered_exposure", binding::METERED_EXPOSURE),
            ("params", binding::PARAMS),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into();
        assert_eq!(crate::shaders::declared_bindings("tonemap"), rust);
    }
}
