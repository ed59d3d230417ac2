//! Benchmarks: the atmosphere pass (per-pass GPU time, and the LUT path against the brute-force
//! per-pixel march), the camera passes (auto-exposure, bloom) and the object pass (Gouraud
//! against Phong shading).
//!
//! Each pass is submitted alone and waited for. Where the device has timestamp queries inside
//! command encoders ([`pass_timing_supported`]; [`GpuContext::from_adapter`] requests them
//! whenever the adapter offers them) the figure is the GPU's own time between two timestamps
//! around the pass, taken by the renderer's own recorder ([`PassTimer`]); elsewhere (llvmpipe's
//! GL) it is wall time with full synchronisation, which includes submission and the wait and so
//! overstates sub-millisecond passes. [`AtmosphereBench::timing`] says which; compare figures
//! taken side by side in one run.
//!
//! [`pass_timing_supported`]: firmament_render::pass_timing_supported
//! [`GpuContext::from_adapter`]: firmament_render::GpuContext::from_adapter
//! [`PassTimer`]: firmament_render::pass_timing::PassTimer

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use firmament_core::auto_exposure::{AutoExposure, ExposureMode};
use firmament_core::classic::scene::{ObjectLayer, ObjectLighting, Shading};
use firmament_core::frame::AtmosphereSky;
use firmament_core::{Camera, Frame};

use firmament_render::pass_timing::{FrameTiming, PassTimer, pass_timing_supported};
use firmament_render::passes::atmosphere::MEDIUM_BUILD_STEPS;
use firmament_render::passes::{AtmospherePass, BloomPass, ExposurePass, ObjectPass, SkyMethod, begin_clear_pass};
use firmament_render::readback::{decode_f16, read_texture};
use firmament_render::wgpu;
use firmament_render::{FrameTargets, GpuContext, RenderError};

/// How a benchmark figure was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Timing {
    /// The GPU's timestamps around the pass.
    GpuTimestamps,
    /// Wall time from submission until the pass's output could be read (full synchronisation).
    WallTime,
}

impl Timing {
    /// A short description for reports.
    pub(crate) fn describe(self) -> &'static str {
        match self {
            Self::GpuTimestamps => "GPU timestamps",
            Self::WallTime => "wall time with full synchronisation",
        }
    }
}

/// Median milliseconds per pass, and how far the LUT path is from the brute-force march.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub(crate) struct AtmosphereBench {
    /// Adapter name and backend.
    pub(crate) adapter: String,
    /// Image size, pixels.
    pub(crate) width: u32,
    /// Image height, pixels.
    pub(crate) height: u32,
    /// Frames timed per figure (the median is reported).
    pub(crate) frames: u32,
    /// Number of suns in the scene.
    pub(crate) suns: usize,
    /// How the times were measured.
    pub(crate) timing: Timing,
    /// Transmittance, multiple-scattering and irradiance LUTs (rebuilt when the medium changes).
    pub(crate) medium_luts_ms: f64,
    /// The longest step of an incremental rebuild of those LUTs (one step per frame).
    pub(crate) medium_lut_step_max_ms: f64,
    /// Each step of that rebuild: the transmittance LUT, each order of multiple scattering (the
    /// last with their sum, the sky irradiance LUT and the copy into the live set).
    pub(crate) medium_lut_steps_ms: Vec<f64>,
    /// The sky-view LUT tiles.
    pub(crate) sky_view_lut_ms: f64,
    /// The sky pass reading the sky-view LUT, as the renderer's own targets run it (compute).
    pub(crate) sky_ms: f64,
    /// The same as a full-screen draw, as callers' render passes run it.
    pub(crate) sky_fragment_ms: f64,
    /// The aerial-perspective volume (froxels).
    pub(crate) aerial_volume_ms: f64,
    /// Applying aerial perspective to a depth buffer covered by geometry everywhere (the worst
    /// case: no pixel is skipped), as the renderer's own targets do it (compute and a copy).
    pub(crate) aerial_apply_ms: f64,
    /// The same as the two full-screen draws callers' render passes get.
    pub(crate) aerial_apply_fragment_ms: f64,
    /// A whole LUT-path frame: sky-view LUT and sky.
    pub(crate) lut_frame_ms: f64,
    /// A brute-force frame: every pixel marches its ray.
    pub(crate) march_frame_ms: f64,
    /// The cloud layers over the whole image (`None` for a sky without clouds): the compute
    /// march and its copy back, after the aerial-perspective volume.
    pub(crate) clouds_ms: Option<f64>,
    /// A whole frame with every LUT rebuilt, in one span: the medium LUTs, the sky-view LUT, the
    /// sky (compute) and the aerial-perspective volume (issue 23's goal).
    pub(crate) rebuild_frame_ms: f64,
    /// Median and largest relative difference between the two images (largest channel
    /// difference over the march's largest channel, pixels above 1 cd/m²).
    pub(crate) difference: (f64, f64),
}

/// The phase name benchmarks time with the renderer's pass timer.
const BENCH_PHASE: &str = "bench";

/// Median wall time of `frames` submissions of `encode`, each ending with a copy of one texel of
/// `written` (a texture the work writes) that is then mapped: GL fences give up after 2³¹ ns, but
/// reading the copy back waits for the work itself.
///
/// With [`Timing::GpuTimestamps`] the time is the GPU's between timestamps written before and
/// after `encode`'s commands.
pub(super) fn median_ms(
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
    let timer = PassTimer::new(ctx);
    let mut times: Vec<f64> = (0..frames.max(1))
        .map(|_| {
            let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("firmament bench encoder"),
            });
            let mut timing = FrameTiming::begin(timer.as_ref(), &mut encoder);
            encode(&mut encoder);
            timing.mark(&mut encoder, BENCH_PHASE);
            let frame = timing.finish(&mut encoder);
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
            timer
                .as_ref()
                .zip(frame)
                .and_then(|(timer, frame)| timer.wait_for_frame(ctx, frame))
                .and_then(|times| times.get(BENCH_PHASE))
                .unwrap_or(elapsed)
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Clears the depth target to `depth` (reversed-Z) in a pass of its own.
fn clear_depth(encoder: &mut wgpu::CommandEncoder, targets: &FrameTargets, depth: f32) {
    begin_clear_pass(encoder, "firmament bench depth clear", None, &targets.depth_view, depth);
}

/// How this device's benchmarks are timed.
fn timing(ctx: &GpuContext) -> Timing {
    if pass_timing_supported(&ctx.device) {
        Timing::GpuTimestamps
    } else {
        Timing::WallTime
    }
}

fn hdr_pixels(ctx: &GpuContext, targets: &FrameTargets) -> Result<Vec<f32>, RenderError> {
    Ok(decode_f16(&read_texture(ctx, &targets.hdr)?))
}

/// Times the atmosphere pass on `sky` seen by `camera` at `width` × `height`.
pub(crate) fn bench_atmosphere(
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
    pass.bind_sky_target(&ctx.device, &targets.hdr, &targets.depth_view);
    pass.prepare(&ctx.queue, sky, &camera);
    let luts = pass.luts();
    let medium_luts_ms = median_ms(ctx, frames, &luts.irradiance.texture, |e| pass.record_medium_luts(e));
    let medium_lut_steps_ms: Vec<f64> = (0..MEDIUM_BUILD_STEPS)
        .map(|step| {
            median_ms(ctx, frames, &luts.irradiance.texture, |e| {
                pass.record_medium_lut_step(e, step)
            })
        })
        .collect();
    let medium_lut_step_max_ms = medium_lut_steps_ms.iter().copied().fold(0.0, f64::max);
    // Each step was repeated, and a repeated order is the next order: build the LUTs whole again
    // for the images compared below.
    median_ms(ctx, 1, &luts.irradiance.texture, |e| pass.record_medium_luts(e));
    let sky_view_lut_ms = median_ms(ctx, frames, &luts.sky_view.texture, |e| pass.record_sky_view_lut(e));
    let sky_fragment_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record(e, &targets.hdr_view, &targets.depth_view)
    });
    let sky_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record_sky(e);
    });
    let lut_frame_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record_sky_view_lut(e);
        pass.record_sky(e);
    });
    let lut_image = hdr_pixels(ctx, &targets)?;
    let rebuild_frame_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record_medium_luts(e);
        pass.record_sky_view_lut(e);
        pass.record_sky(e);
        pass.record_aerial_perspective_volume(e);
    });
    pass.set_method(SkyMethod::March);
    pass.prepare(&ctx.queue, sky, &camera);
    let march_frame_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        pass.record_sky(e);
    });
    let march_image = hdr_pixels(ctx, &targets)?;
    let aerial_volume_ms = median_ms(ctx, frames, &pass.luts().aerial_transmittance.texture, |e| {
        pass.record_aerial_perspective_volume(e)
    });
    // The clouds over the sky (the depth buffer still holds the far plane everywhere).
    let clouds_ms = pass.has_clouds().then(|| {
        median_ms(ctx, frames, &targets.hdr, |e| {
            pass.record_clouds_on_target(e);
        })
    });
    pass.bind_depth(&ctx.device, &targets.depth_view);
    // Last, since it covers the depth buffer: geometry 1 km away (at the centre) in every pixel.
    let geometry_depth = (camera.projection_matrix() * glam::DVec4::new(0.0, 0.0, -1_000.0, 1.0)).z / 1_000.0;
    let aerial_apply_fragment_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        clear_depth(e, &targets, geometry_depth as f32);
        pass.record_aerial_perspective_apply(e, &targets.hdr_view);
    });
    let aerial_apply_ms = median_ms(ctx, frames, &targets.hdr, |e| {
        clear_depth(e, &targets, geometry_depth as f32);
        pass.record_aerial_perspective_apply_on_target(e);
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
    let info = ctx.device.adapter_info();
    Ok(AtmosphereBench {
        adapter: format!("{} ({:?})", info.name, info.backend),
        width,
        height,
        frames,
        suns: sky.suns.len(),
        timing: timing(ctx),
        medium_luts_ms,
        medium_lut_step_max_ms,
        medium_lut_steps_ms,
        sky_view_lut_ms,
        sky_ms,
        sky_fragment_ms,
        aerial_volume_ms,
        aerial_apply_ms,
        aerial_apply_fragment_ms,
        lut_frame_ms,
        march_frame_ms,
        rebuild_frame_ms,
        clouds_ms,
        difference,
    })
}

/// Median milliseconds of the object pass drawing the same objects with Gouraud and with Phong
/// shading (classic lighting, all lights on).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub(crate) struct ObjectBench {
    /// Adapter name and backend.
    pub(crate) adapter: String,
    /// Image size, pixels.
    pub(crate) width: u32,
    /// Image height, pixels.
    pub(crate) height: u32,
    /// Frames timed per figure (the median is reported).
    pub(crate) frames: u32,
    /// Objects drawn.
    pub(crate) objects: usize,
    /// Triangles drawn, all objects together.
    pub(crate) triangles: usize,
    /// Lights on.
    pub(crate) lights: usize,
    /// How the times were measured.
    pub(crate) timing: Timing,
    /// Lit per vertex.
    pub(crate) gouraud_ms: f64,
    /// Lit per fragment.
    pub(crate) phong_ms: f64,
    /// Lit per fragment with the sun shadow maps drawn and sampled, when the layer has shadows
    /// (`phong_ms` is then without them).
    pub(crate) shadows_ms: Option<f64>,
}

/// `count` GLTools spheres of `slices × stacks` (1000 triangles each at 25 × 20) in a square grid
/// filling the view of the 45° camera at the origin looking down −z, lit by 8 lights of every
/// kind: the object benchmark's scene (issue 5: 1000 spheres, about 1 M triangles).
pub(crate) fn sphere_grid(count: usize, slices: u32, stacks: u32) -> Result<(ObjectLayer, Camera), RenderError> {
    use firmament_core::classic::lighting::{Light, LightModel, Material, SpecularModel};
    use firmament_core::classic::scene::{ClassicLighting, LightSpace, SceneFog, SceneLight, SceneObject};
    use glam::{DMat4, DQuat, DVec3, DVec4};
    let mesh = Arc::new(firmament_core::classic::mesh::Mesh::glt_sphere(0.4, slices, stacks)?);
    let side = (count as f64).sqrt().ceil() as usize;
    let objects = (0..count)
        .map(|i| {
            let (x, y) = ((i % side) as f64, (i / side) as f64);
            let centre = DVec3::new(x - (side as f64 - 1.0) / 2.0, y - (side as f64 - 1.0) / 2.0, -40.0);
            SceneObject {
                back: Material::default(),
                ..SceneObject::new(
                    Arc::clone(&mesh),
                    DMat4::from_translation(centre),
                    Material {
                        specular: DVec4::new(0.8, 0.8, 0.8, 1.0),
                        shininess: 40.0,
                        ..Material::default()
                    },
                )
            }
        })
        .collect();
    let lights = (0..8)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 8.0;
            SceneLight {
                light: Light {
                    diffuse: DVec4::new(0.3, 0.3, 0.3, 1.0),
                    specular: DVec4::new(0.3, 0.3, 0.3, 1.0),
                    position: if i % 2 == 0 {
                        DVec4::new(a.cos(), a.sin(), 1.0, 0.0)
                    } else {
                        DVec4::new(10.0 * a.cos(), 10.0 * a.sin(), -30.0, 1.0)
                    },
                    spot_cutoff: if i % 4 == 1 { 60.0 } else { 180.0 },
                    linear_attenuation: 0.01,
                    ..Light::gl_default(i)
                },
                space: LightSpace::Eye,
            }
        })
        .collect();
    let layer = ObjectLayer {
        objects,
        lighting: ObjectLighting::Classic(ClassicLighting {
            lights,
            model: LightModel::default(),
            shading: Shading::Gouraud,
            specular: SpecularModel::Blinn,
        }),
        fog: SceneFog::None,
        ..Default::default()
    };
    let camera = Camera {
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
        fov_y: 45f64.to_radians(),
        aspect: 16.0 / 9.0,
        near: 1.0,
        far: Some(100.0),
    };
    Ok((layer, camera))
}

/// Times the object pass on `layer` seen by `camera` at `width` × `height`, once with Gouraud
/// and once with Phong shading, both without shadows (other classic settings as given; unlit
/// layers are timed as is), and, when the layer has shadows, with Phong and its shadows.
pub(crate) fn bench_objects(
    ctx: &GpuContext,
    layer: &ObjectLayer,
    camera: &Camera,
    width: u32,
    height: u32,
    frames: u32,
) -> Result<ObjectBench, RenderError> {
    ctx.check_image_size(width, height)?;
    let camera = Camera {
        aspect: f64::from(width) / f64::from(height),
        ..*camera
    };
    let targets = FrameTargets::new(&ctx.device, width, height);
    let mut pass = ObjectPass::new(&ctx.device, &ctx.queue);
    let mut time = |shading: Shading, shadows: bool| {
        let mut layer = layer.clone();
        if let ObjectLighting::Classic(c) | ObjectLighting::Sky(c) = &mut layer.lighting {
            c.shading = shading;
        }
        if !shadows {
            layer.shadows = Default::default();
        }
        pass.prepare(&ctx.device, &ctx.queue, &layer, &camera);
        median_ms(ctx, frames, &targets.hdr, |e| {
            clear_depth(e, &targets, 0.0);
            pass.record(e, &targets.hdr_view, &targets.depth_view);
        })
    };
    let gouraud_ms = time(Shading::Gouraud, false);
    let phong_ms = time(Shading::Phong, false);
    let shadows_ms = layer.shadows.any().then(|| time(Shading::Phong, true));
    let info = ctx.device.adapter_info();
    Ok(ObjectBench {
        adapter: format!("{} ({:?})", info.name, info.backend),
        width,
        height,
        frames,
        objects: layer.objects.len(),
        triangles: layer.objects.iter().map(|o| o.mesh.triangle_count()).sum(),
        lights: layer.lighting.equations().map_or(0, |c| c.lights.len()),
        timing: timing(ctx),
        gouraud_ms,
        phong_ms,
        shadows_ms,
    })
}

/// Median milliseconds of the lens-flare passes for one source count.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub(crate) struct FlareTiming {
    /// Sources flaring (all on screen, none hidden).
    pub(crate) sources: usize,
    /// The occlusion compute pass alone.
    pub(crate) occlusion_ms: f64,
    /// Occlusion and the element pass together.
    pub(crate) total_ms: f64,
}

/// The lens-flare passes timed for 1, 8 and 64 sources (issue 6's benchmark).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub(crate) struct FlareBench {
    /// Adapter name and backend.
    pub(crate) adapter: String,
    /// Image width, pixels.
    pub(crate) width: u32,
    /// Image height, pixels.
    pub(crate) height: u32,
    /// Frames timed per figure (the median is reported).
    pub(crate) frames: u32,
    /// Elements per flare (the `classic` preset's).
    pub(crate) elements: usize,
    /// Occlusion samples per source.
    pub(crate) samples: u32,
    /// How the times were measured.
    pub(crate) timing: Timing,
    /// One row per source count.
    pub(crate) rows: Vec<FlareTiming>,
}

/// Times the occlusion and element passes with the `classic` flare (16 elements, `samples`
/// depth samples each) for 1, 8 and 64 point sources spread over the screen of a 45° camera.
pub(crate) fn bench_flares(
    ctx: &GpuContext,
    width: u32,
    height: u32,
    frames: u32,
    samples: u32,
) -> Result<FlareBench, RenderError> {
    use firmament_core::flare::{FlareLayer, FlareSource, LensFlare, sample_pattern};
    use glam::{DQuat, DVec3, DVec4};
    ctx.check_image_size(width, height)?;
    let camera = Camera {
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
        fov_y: 45f64.to_radians(),
        aspect: f64::from(width) / f64::from(height),
        near: 1.0,
        far: Some(1000.0),
    };
    let flare = LensFlare {
        samples,
        ..LensFlare::classic()
    };
    let targets = FrameTargets::new(&ctx.device, width, height);
    let mut pass = firmament_render::passes::FlarePass::new(&ctx.device);
    pass.bind_depth(&ctx.device, &targets.depth_view, width, height);
    let mut rows = Vec::new();
    for count in [1usize, 8, 64] {
        // A golden-angle spiral of lights 100 m ahead, all inside the view.
        let sources = sample_pattern(count as u32)
            .into_iter()
            .map(|p| FlareSource {
                position: DVec4::new(25.0 * p.x * camera.aspect, 25.0 * p.y, -100.0, 1.0),
                radius: 1.0,
                color: DVec3::ONE,
            })
            .collect();
        let layer = FlareLayer {
            flare: Some(flare.clone()),
            sources,
        };
        pass.prepare(&ctx.device, &ctx.queue, &layer, &camera, 1.0, None);
        let occlusion_ms = median_ms(ctx, frames, &targets.hdr, |e| {
            clear_depth(e, &targets, 0.0);
            pass.record_occlusion(e);
        });
        let total_ms = median_ms(ctx, frames, &targets.hdr, |e| {
            clear_depth(e, &targets, 0.0);
            pass.record(e, &targets.hdr_view);
        });
        rows.push(FlareTiming {
            sources: count,
            occlusion_ms,
            total_ms,
        });
    }
    let info = ctx.device.adapter_info();
    Ok(FlareBench {
        adapter: format!("{} ({:?})", info.name, info.backend),
        width,
        height,
        frames,
        elements: flare.elements.len(),
        samples,
        timing: timing(ctx),
        rows,
    })
}

/// The same frame drawn by the CLI's path and by the embedded path, median milliseconds each
/// ([`bench_embedding`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub(crate) struct EmbeddingBench {
    /// Adapter name and backend.
    pub(crate) adapter: String,
    /// Image width, pixels.
    pub(crate) width: u32,
    /// Image height, pixels.
    pub(crate) height: u32,
    /// Frames timed per figure (the median is reported).
    pub(crate) frames: u32,
    /// How the times were measured.
    pub(crate) timing: Timing,
    /// [`Renderer::record`](firmament_render::Renderer::record) into an 8-bit sRGB view: firmament's own
    /// targets, cleared, sky, tone mapping.
    pub(crate) cli_ms: f64,
    /// The caller's clear of their HDR target and depth buffer, then
    /// [`Renderer::record_into`](firmament_render::Renderer::record_into) (linear radiance left for the
    /// caller's tone mapping).
    pub(crate) embedded_hdr_ms: f64,
    /// The same, finished by firmament's output pass into an 8-bit sRGB view
    /// ([`EmbedTarget::with_output`](firmament_render::EmbedTarget::with_output)): the CLI frame's
    /// counterpart.
    pub(crate) embedded_output_ms: f64,
    /// The same without firmament's aerial perspective
    /// ([`EmbedTarget::without_aerial_perspective`](firmament_render::EmbedTarget::without_aerial_perspective)):
    /// the work of a CLI frame without objects.
    pub(crate) embedded_output_no_aerial_ms: f64,
    /// The CLI frame without its sun shadows and light shafts, when it has them.
    pub(crate) cli_no_shadows_ms: Option<f64>,
}

/// Times one frame of `frame` at `width` × `height` on the CLI's path and on the embedded path
/// (reversed Z, no geometry of the caller's: the same work as the CLI frame of a scene without
/// objects, plus the aerial perspective the embedded path applies in every atmosphere frame).
pub(crate) fn bench_embedding(
    ctx: &GpuContext,
    frame: &firmament_core::Frame,
    width: u32,
    height: u32,
    frames: u32,
) -> Result<EmbeddingBench, RenderError> {
    use firmament_render::headless::{LDR_FORMAT, ldr_texture};
    use firmament_render::{EmbedTarget, Renderer};
    ctx.check_image_size(width, height)?;
    let output = ldr_texture(
        &ctx.device,
        "firmament bench embedding output",
        (width, height),
        wgpu::TextureUsages::COPY_SRC,
    );
    let output_view = output.create_view(&wgpu::TextureViewDescriptor::default());
    let mut renderer = Renderer::new(ctx, LDR_FORMAT);
    renderer.prepare(ctx, frame, width, height)?;
    let cli_ms = median_ms(ctx, frames, &output, |e| renderer.record(e, &output_view));
    let cli_no_shadows_ms = if frame.objects.shadows.any() {
        let mut unshadowed = frame.clone();
        unshadowed.objects.shadows = Default::default();
        renderer.prepare(ctx, &unshadowed, width, height)?;
        let ms = median_ms(ctx, frames, &output, |e| renderer.record(e, &output_view));
        renderer.prepare(ctx, frame, width, height)?;
        Some(ms)
    } else {
        None
    };

    // The caller's targets: firmament's own formats, with the usages embedding needs.
    let user = FrameTargets::new(&ctx.device, width, height);
    let convention = firmament_core::DepthConvention::Reversed;
    let mut embedded = |target: &EmbedTarget<'_>, written: &wgpu::Texture| -> Result<f64, RenderError> {
        renderer.prepare_into(ctx, frame, target)?;
        let mut result = Ok(());
        let ms = median_ms(ctx, frames, written, |e| {
            // The caller's own frame start: clear colour and depth.
            drop(begin_clear_pass(
                e,
                "firmament bench caller's clear",
                Some((&user.hdr_view, wgpu::Color::BLACK)),
                &user.depth_view,
                convention.far_depth() as f32,
            ));
            if let Err(error) = renderer.record_into(e, target) {
                result = Err(error);
            }
        });
        result.map(|()| ms)
    };
    let hdr_only = EmbedTarget::new(&user.hdr_view, &user.depth_view, convention);
    let embedded_hdr_ms = embedded(&hdr_only, &user.hdr)?;
    let embedded_output_ms = embedded(&hdr_only.with_output(&output_view), &output)?;
    let embedded_output_no_aerial_ms = embedded(
        &hdr_only.with_output(&output_view).without_aerial_perspective(),
        &output,
    )?;
    let info = ctx.device.adapter_info();
    Ok(EmbeddingBench {
        adapter: format!("{} ({:?})", info.name, info.backend),
        width,
        height,
        frames,
        timing: timing(ctx),
        cli_ms,
        embedded_hdr_ms,
        embedded_output_ms,
        embedded_output_no_aerial_ms,
        cli_no_shadows_ms,
    })
}

/// Median milliseconds of the camera passes on a frame's HDR image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CameraBench {
    /// Auto-exposure: the luminance histogram and the adaptation.
    pub(crate) exposure_ms: f64,
    /// Bloom: the pyramid's way down and up.
    pub(crate) bloom_ms: f64,
}

/// Times auto-exposure and bloom on `frame` (its display's settings or the defaults) at `width` ×
/// `height`: their cost depends on the image's size, not its content.
pub(crate) fn bench_camera(
    ctx: &GpuContext,
    frame: &Frame,
    width: u32,
    height: u32,
    frames: u32,
) -> Result<CameraBench, RenderError> {
    ctx.check_image_size(width, height)?;
    let targets = FrameTargets::new(&ctx.device, width, height);
    let camera = Camera {
        aspect: f64::from(width) / f64::from(height),
        ..frame.camera
    };
    let auto = match frame.display.exposure_mode {
        ExposureMode::Auto(auto) => auto,
        ExposureMode::Manual => AutoExposure::default(),
    };
    let mut exposure = ExposurePass::new(&ctx.device);
    exposure.prepare(
        &ctx.device,
        &ctx.queue,
        frame,
        &camera,
        &auto,
        &targets.hdr_view,
        (width, height),
    );
    let mut bloom = BloomPass::new(&ctx.device);
    bloom.prepare(&ctx.device, &targets.hdr_view, (width, height));
    Ok(CameraBench {
        exposure_ms: median_ms(ctx, frames, &targets.hdr, |encoder| exposure.record(encoder)),
        bloom_ms: median_ms(ctx, frames, &targets.hdr, |encoder| bloom.record(encoder)),
    })
}
