//! Rendering to memory: 8-bit sRGB images for PNG and linear float images for EXR and tests.
//!
//! [`HeadlessRenderer::render_ldr`] and [`render_hdr`](HeadlessRenderer::render_hdr) render and
//! wait. A sequence of frames overlaps instead: [`HeadlessRenderer::submit`] frame N + 1, then
//! [`SubmittedFrame::collect`] frame N while the GPU renders N + 1.

use firmament_core::Frame;

use crate::context::GpuContext;
use crate::error::RenderError;
use crate::gpu_types::ExposureStateGpu;
use crate::readback::{PendingRead, TextureCopy};
pub use crate::readback::{decode_f16, read_texture};
use crate::renderer::Renderer;
use crate::targets::FrameTargets;

/// Format of the display image: 8-bit RGBA, sRGB-encoded by the hardware.
pub const LDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// A `width` × `height` texture of [`LDR_FORMAT`] a [`Renderer`] built for it can record into
/// (`RENDER_ATTACHMENT`, plus `usage`), labelled `label`.
pub fn ldr_texture(device: &wgpu::Device, label: &str, size: (u32, u32), usage: wgpu::TextureUsages) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | usage;
    crate::targets::texture_2d(device, label, size, LDR_FORMAT, usage)
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

impl Image<half::f16> {
    /// The same image widened to `f32` (exact: every half float is an `f32`).
    pub fn to_f32(&self) -> Image<f32> {
        Image {
            width: self.width,
            height: self.height,
            pixels: widen_f16(&self.pixels),
        }
    }
}

/// Half floats widened to `f32`, with the CPU's conversion instructions where it has them.
fn widen_f16(values: &[half::f16]) -> Vec<f32> {
    use half::slice::HalfFloatSliceExt as _;
    let mut out = vec![0.0; values.len()];
    values.convert_to_f32_slice(&mut out);
    out
}

/// Which images [`HeadlessRenderer::submit`] reads back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Readback {
    /// The display image ([`LDR_FORMAT`]: exposure, tone curve, sRGB; 8 bits).
    pub ldr: bool,
    /// The linear HDR radiance, as the half-float target holds it.
    pub hdr: bool,
}

/// A frame [`HeadlessRenderer::submit`] sent to the GPU, its images on their way back.
#[derive(Debug)]
#[must_use = "a submitted frame's images come back only through collect"]
pub struct SubmittedFrame {
    width: u32,
    height: u32,
    ldr: Option<PendingRead>,
    hdr: Option<PendingRead>,
}

/// The images of a [`SubmittedFrame`], each present when [`Readback`] asked for it.
#[derive(Debug, Clone, PartialEq)]
pub struct FramePixels {
    /// The display image: exposure, tone curve, sRGB; 8 bits RGBA.
    pub ldr: Option<Image<u8>>,
    /// The linear HDR radiance (scene-referred), RGBA half floats as rendered; widen with
    /// [`Image::to_f32`].
    pub hdr: Option<Image<half::f16>>,
}

impl SubmittedFrame {
    /// Waits for this frame's images (not for frames submitted after it) and returns them.
    pub fn collect(self, ctx: &GpuContext) -> Result<FramePixels, RenderError> {
        let (width, height) = (self.width, self.height);
        let ldr = match self.ldr {
            Some(read) => Some(Image {
                width,
                height,
                pixels: read.wait::<u8>(ctx)?,
            }),
            None => None,
        };
        let hdr = match self.hdr {
            Some(read) => {
                let mut bits = read.wait::<u16>(ctx)?;
                // The texture's bytes are little-endian; `wait` copied them as they are.
                if cfg!(target_endian = "big") {
                    bits.iter_mut().for_each(|b| *b = u16::from_le(*b));
                }
                Some(Image {
                    width,
                    height,
                    pixels: half::vec::HalfBitsVecExt::reinterpret_into(bits),
                })
            }
            None => None,
        };
        Ok(FramePixels { ldr, hdr })
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
        let readback = Readback { ldr: true, hdr: false };
        let pixels = self.submit(ctx, frame, width, height, readback)?.collect(ctx)?;
        pixels
            .ldr
            .ok_or_else(|| RenderError::Readback("no display image".into()))
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
        let readback = Readback { ldr: false, hdr: true };
        let pixels = self.submit(ctx, frame, width, height, readback)?.collect(ctx)?;
        let hdr = pixels.hdr.ok_or_else(|| RenderError::Readback("no HDR image".into()))?;
        Ok(hdr.to_f32())
    }

    /// Renders `frame` and starts copying the images `readback` names back, without waiting:
    /// submit the next frame, then [`SubmittedFrame::collect`] this one. Each submitted frame
    /// holds its own staging buffers (its images' size) until collected.
    pub fn submit(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        width: u32,
        height: u32,
        readback: Readback,
    ) -> Result<SubmittedFrame, RenderError> {
        if readback.ldr {
            crate::readback::check_readback(ctx, width, height, LDR_FORMAT)?;
        }
        if readback.hdr {
            crate::readback::check_readback(ctx, width, height, crate::targets::HDR_FORMAT)?;
        }
        let (ldr, hdr) = self.render(ctx, frame, width, height, readback)?;
        Ok(SubmittedFrame {
            width,
            height,
            ldr,
            hdr,
        })
    }

    /// See [`Renderer::set_flare_interval`]: seconds between frames for the flares' fade rates
    /// (`None`, the default, for stills).
    pub fn set_flare_interval(&mut self, seconds: Option<f64>) {
        self.renderer.set_flare_interval(seconds);
    }

    /// See [`Renderer::set_exposure_interval`]: seconds between frames over which auto-exposure
    /// adapts (`None`, the default, meters each frame afresh).
    pub fn set_exposure_interval(&mut self, seconds: Option<f64>) {
        self.renderer.set_exposure_interval(seconds);
    }

    /// The auto-exposure state after the last metered render (the EV100 it chose and what it
    /// metered; for tests and logs: the rendering path itself never reads it back).
    pub fn exposure_state(&self, ctx: &GpuContext) -> Result<ExposureStateGpu, RenderError> {
        let size = std::mem::size_of::<ExposureStateGpu>();
        let bytes = crate::readback::read_buffer(ctx, self.renderer.exposure().state_buffer(), size as u64)?;
        Ok(bytemuck::pod_read_unaligned(&bytes[..size]))
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

    /// Renders `frame` into the output texture and records copies of the images `readback`
    /// names in the same submission; returns them mapping.
    fn render(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        width: u32,
        height: u32,
        readback: Readback,
    ) -> Result<(Option<PendingRead>, Option<PendingRead>), RenderError> {
        // The copies follow the render in the queue, so the next frame may reuse the targets.
        let ((ldr, hdr), submission) = self.render_then(ctx, frame, (width, height), |encoder, output, targets| {
            let ldr = match readback.ldr {
                true => Some(TextureCopy::record(ctx, encoder, output)?),
                false => None,
            };
            let hdr = match readback.hdr {
                true => Some(TextureCopy::record(ctx, encoder, &targets.hdr)?),
                false => None,
            };
            Ok((ldr, hdr))
        })?;
        Ok((
            ldr.map(|copy| copy.map(submission.clone())),
            hdr.map(|copy| copy.map(submission)),
        ))
    }

    /// Renders `frame` at `width` × `height` into the output texture, then records what `then`
    /// adds to the same encoder (given the output texture and the renderer's HDR and depth
    /// targets, holding this frame), and submits: `then`'s result and the submission. GPU
    /// validation and out-of-memory errors of the whole submission are returned as
    /// [`RenderError::Gpu`].
    pub(crate) fn render_then<R>(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        (width, height): (u32, u32),
        then: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Texture, &FrameTargets) -> Result<R, RenderError>,
    ) -> Result<(R, wgpu::SubmissionIndex), RenderError> {
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
        let output = self
            .output
            .as_ref()
            .ok_or_else(|| RenderError::Readback("no output texture".into()))?;
        let targets = self
            .renderer
            .targets()
            .ok_or_else(|| RenderError::Readback("no HDR target".into()))?;
        let view = output.create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("firmament HeadlessRenderer encoder"),
        });
        self.renderer.record(&mut encoder, &view);
        let result = then(&mut encoder, output, targets)?;
        let submission = ctx.queue.submit([encoder.finish()]);
        crate::error::pop_error_scopes(oom, scope, "rendering")?;
        Ok((result, submission))
    }
}
