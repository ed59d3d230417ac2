//! Rendering to memory: 8-bit sRGB images for PNG and linear float images for EXR and tests.

use firmament_core::Frame;

use crate::context::GpuContext;
use crate::error::RenderError;
pub use crate::readback::{decode_f16, read_texture};
use crate::renderer::Renderer;

/// Format of the display image: 8-bit RGBA, sRGB-encoded by the hardware.
pub const LDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// A `width` × `height` texture of [`LDR_FORMAT`] a [`Renderer`] built for it can record into
/// (`RENDER_ATTACHMENT`, plus `usage`), labelled `label`.
pub fn ldr_texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: LDR_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
        view_formats: &[],
    })
}

/// An image read back from the GPU, rows top first.
#[derive(Debug, Clone, PartialEq)]
pub struct Image<T> {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// `width × height × 4` channels (RGBA), row-major, top row first.
    pub pixels: Vec<T>,
}

impl<T: Copy> Image<T> {
    /// The RGBA channels of pixel (`x`, `y`), `y = 0` at the top; `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[T; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = ((y * self.width + x) * 4) as usize;
        Some([
            self.pixels[i],
            self.pixels[i + 1],
            self.pixels[i + 2],
            self.pixels[i + 3],
        ])
    }
}

/// A [`Renderer`] with its own output texture, for rendering without a window.
#[derive(Debug)]
pub struct HeadlessRenderer {
    renderer: Renderer,
    output: Option<wgpu::Texture>,
}

impl HeadlessRenderer {
    /// Builds the pipelines.
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            renderer: Renderer::new(ctx, LDR_FORMAT),
            output: None,
        }
    }

    /// Renders `frame` and returns the display image (exposure, tone curve, sRGB; 8 bits).
    pub fn render_ldr(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        width: u32,
        height: u32,
    ) -> Result<Image<u8>, RenderError> {
        crate::readback::check_readback(ctx, width, height, LDR_FORMAT)?;
        self.render(ctx, frame, width, height)?;
        let output = self
            .output
            .as_ref()
            .ok_or_else(|| RenderError::Readback("no output texture".into()))?;
        Ok(Image {
            width,
            height,
            pixels: read_texture(ctx, output)?,
        })
    }

    /// Renders `frame` and returns the linear HDR radiance (scene-referred: no exposure, no
    /// tone curve), RGBA `f32` widened from the half-float target.
    pub fn render_hdr(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        width: u32,
        height: u32,
    ) -> Result<Image<f32>, RenderError> {
        crate::readback::check_readback(ctx, width, height, crate::targets::HDR_FORMAT)?;
        self.render(ctx, frame, width, height)?;
        let targets = self
            .renderer
            .targets()
            .ok_or_else(|| RenderError::Readback("no HDR target".into()))?;
        let bytes = read_texture(ctx, &targets.hdr)?;
        let pixels = crate::readback::decode_f16(&bytes);
        Ok(Image { width, height, pixels })
    }

    /// See [`Renderer::set_flare_interval`]: seconds between frames for the flares' fade rates
    /// (`None`, the default, for stills).
    pub fn set_flare_interval(&mut self, seconds: Option<f64>) {
        self.renderer.set_flare_interval(seconds);
    }

    /// The lens-flare visibility the last render computed on the GPU, one share per source the
    /// flare pass kept (for tests: the rendering path itself never reads it back).
    pub fn flare_visibility(&self, ctx: &GpuContext) -> Result<Vec<f32>, RenderError> {
        let flares = self.renderer.flares();
        let count = u64::from(flares.source_count());
        let bytes = crate::readback::read_buffer(ctx, flares.visibility_buffer(), count * 4)?;
        Ok(bytes
            .chunks_exact(4)
            .take(count as usize)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect())
    }

    fn render(&mut self, ctx: &GpuContext, frame: &Frame, width: u32, height: u32) -> Result<(), RenderError> {
        ctx.check_image_size(width, height)?;
        let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let oom = ctx.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        if self.output.as_ref().map(|t| (t.width(), t.height())) != Some((width, height)) {
            self.output = Some(ldr_texture(
                &ctx.device,
                "firmament HeadlessRenderer output",
                (width, height),
                wgpu::TextureUsages::COPY_SRC,
            ));
        }
        self.renderer.prepare(ctx, frame, width, height)?;
        if let Some(output) = &self.output {
            let view = output.create_view(&wgpu::TextureViewDescriptor::default());
            let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("firmament HeadlessRenderer encoder"),
            });
            self.renderer.record(&mut encoder, &view);
            ctx.queue.submit([encoder.finish()]);
        }
        if let Some(error) = pollster::block_on(oom.pop()) {
            return Err(RenderError::Gpu {
                during: "rendering",
                reason: error.to_string(),
            });
        }
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu {
                during: "rendering",
                reason: error.to_string(),
            });
        }
        Ok(())
    }
}
