//! Benchmarks of the atmosphere pass: per-pass wall time with full synchronisation (each pass
//! submitted alone and waited for), and the LUT path against the brute-force per-pixel march.
//!
//! Wall time includes submission and the wait, so on a real GPU it overstates sub-millisecond
//! passes; compare figures taken side by side in one run.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use firmament_core::Camera;
use firmament_core::frame::AtmosphereSky;

use crate::context::GpuContext;
use crate::error::RenderError;
use crate::passes::{AtmospherePass, SkyMethod};
use crate::readback::{decode_f16, read_texture};
use crate::targets::FrameTargets;

/// Median milliseconds per pass, and how far the LUT path is from the brute-force march.
#[derive(Debug, Clone, PartialEq)]
pub struct AtmosphereBench {
    /// Adapter name and backend.
    pub adapter: String,
    /// Image size, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Frames timed per figure (the median is reported).
    pub frames: u32,
    /// Number of suns in the scene.
    pub suns: usize,
    /// Transmittance, multiple-scattering and irradiance LUTs (rebuilt when the medium changes).
    pub medium_luts_ms: f64,
    /// The sky-view LUT tiles.
    pub sky_view_lut_ms: f64,
    /// The sky pass reading the sky-view LUT.
    pub sky_ms: f64,
    /// The aerial-perspective volume (froxels).
    pub aerial_volume_ms: f64,
    /// Applying aerial perspective to a depth buffer covered by geometry everywhere (the worst
    /// case: no pixel is skipped).
    pub aerial_apply_ms: f64,
    /// A whole LUT-path frame: sky-view LUT and sky.
    pub lut_frame_ms: f64,
    /// A brute-force frame: every pixel marches its ray.
    pub march_frame_ms: f64,
    /// Median and largest relative difference between the two images (largest channel
    /// difference over the march's largest channel, pixels above 1 cd/m²).
    pub difference: (f64, f64),
}

/// Median wall time of `frames` submissions of `encode`, each ending with a copy of one texel of
/// `written` (a texture the work writes) that is then mapped: GL fences give up after 2³¹ ns, but
/// reading the copy back waits for the work itself.
fn median_ms(
    ctx: &GpuContext,
    frames: u32,
    written: &wgpu::Texture,
    mut encode: impl FnMut(&mut wgpu::CommandEncoder),
) -> f64 {
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("firmament bench sync buffer"),
        size: 256,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut times: Vec<f64> = (0..frames.max(1))
        .map(|_| {
            let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("firmament bench encoder"),
            });
            encode(&mut encoder);
            encoder.copy_texture_to_buffer(
                written.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &staging,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: None,
                        rows_per_image: None,
                    },
                },
                wgpu::Extent3d {
                    width: 1,
                    height: 1,
                    depth_or_array_layers: 1,
                },
            );
            let mapped = Arc::new(AtomicBool::new(false));
            let signal = Arc::clone(&mapped);
            let start = Instant::now();
            ctx.queue.submit([encoder.finish()]);
            staging
                .slice(..)
                .map_async(wgpu::MapMode::Read, move |_| signal.store(true, Ordering::Release));
            // Errors here are device loss, which the readback afterwards reports.
            while !mapped.load(Ordering::Acquire) {
                if ctx.device.poll(wgpu::PollType::wait_indefinitely()).is_err() {
                    break;
                }
            }
            let elapsed = start.elapsed().as_secs_f64() * 1e3;
            staging.unmap();
            elapsed
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Clears the depth target to `depth` (reversed-Z) in a pass of its own.
fn clear_depth(encoder: &mut wgpu::CommandEncoder, targets: &FrameTargets, depth: f32) {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("firmament bench depth clear"),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &targets.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(depth),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    });
}

fn hdr_pixels(ctx: &GpuContext, targets: &FrameTargets) -> Result<Vec<f32>, RenderError> {
    Ok(decode_f16(&read_texture(ctx, &targets.hdr)?))
}

/// Times the atmosphere pass on `sky` seen by `camera` at `width` × `height`.
pub fn bench_atmosphere(
    ctx: &GpuContext,
    sky: &AtmosphereSky,
    camera: &Camera,
    width: u32,
    height: u32,
    frames: u32,
) -> Result<AtmosphereBench, RenderError> {
    ctx.check_image_size(width, height)?;
    let camera = Camera {
        aspect: f64::from(width) / f64::from(height),
        ..*camera
    };
    let targets = FrameTargets::new(&ctx.device, width, height);
    let mut pass = AtmospherePass::new(&ctx.device);
    pass.prepare(&ctx.queue, sky, &camera);
    let luts = pass.luts();
    let medium_luts_ms = median_ms(ctx, frames, &luts.irradiance.texture, |e| pass.record_medium_luts(e));
    let sky_view_lut_ms = median_ms(ctx, frames, &luts.sky_view.texture, |e| pass.record_sky_view_lut(e));
    let sky_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record(e, &targets.hdr_view, &targets.depth_view)
    });
    let lut_frame_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record_sky_view_lut(e);
        pass.record(e, &targets.hdr_view, &targets.depth_view);
    });
    let lut_image = hdr_pixels(ctx, &targets)?;
    pass.set_method(SkyMethod::March);
    pass.prepare(&ctx.queue, sky, &camera);
    let march_frame_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record(e, &targets.hdr_view, &targets.depth_view)
    });
    let march_image = hdr_pixels(ctx, &targets)?;
    let aerial_volume_ms = median_ms(ctx, frames, &pass.luts().aerial_transmittance.texture, |e| {
        pass.record_aerial_perspective_volume(e)
    });
    pass.bind_depth(&ctx.device, &targets.depth_view);
    // Last, since it covers the depth buffer: geometry 1 km away (at the centre) in every pixel.
    let geometry_depth = (camera.projection_matrix() * glam::DVec4::new(0.0, 0.0, -1_000.0, 1.0)).z / 1_000.0;
    let aerial_apply_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        clear_depth(e, &targets, geometry_depth as f32);
        pass.record_aerial_perspective(e, &targets.hdr_view);
    });
    let mut differences: Vec<f64> = lut_image
        .chunks_exact(4)
        .zip(march_image.chunks_exact(4))
        .filter_map(|(a, b)| {
            let reference = b[..3].iter().fold(0f32, |m, v| m.max(*v));
            (reference > 1.0).then(|| {
                let diff = (0..3).fold(0f32, |m, i| m.max((a[i] - b[i]).abs()));
                f64::from(diff / reference)
            })
        })
        .collect();
    differences.sort_by(f64::total_cmp);
    let difference = match differences.last() {
        Some(worst) => (differences[differences.len() / 2], *worst),
        None => (0.0, 0.0),
    };
    let info = ctx.adapter.get_info();
    Ok(AtmosphereBench {
        adapter: format!("{} ({:?})", info.name, info.backend),
        width,
        height,
        frames,
        suns: sky.suns.len(),
        medium_luts_ms,
        sky_view_lut_ms,
        sky_ms,
        aerial_volume_ms,
        aerial_apply_ms,
        lut_frame_ms,
        march_frame_ms,
        difference,
    })
}
