//! Rendering into the caller's frame (`Renderer::prepare_into` / `record_into`): on a device this
//! test creates, with its own HDR colour target and depth buffer holding a "cube" face drawn by
//! its own pipeline, in both depth conventions, the sky pixels are the renderer's own HDR
//! pixels for the same frame, the sky lies behind the face, and the face is fogged as the f64
//! reference integrator predicts (`Reference::radiance_before`, as in `aerial_perspective.rs`).
//! A scene with a cube, read as `firmament render` reads it, gives the same 8-bit pixels — every
//! one, the cube's included — through the embedding path (the user's own pipeline drawing the
//! cube, standard and reversed Z, finite and infinite far plane, firmament's output pass into the
//! user's view) as through `HeadlessRenderer::render_ldr`, and the cube is fogged as the
//! reference predicts. Cloud layers lie over the user's frame as over the renderer's own, hidden
//! by the user's geometry. Bad targets and output formats give an error naming what is needed.

use crate::support::{self, direction};

use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer};
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::atmosphere::{Planet, presets};
use firmament_core::display::DisplaySettings;
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::geometry::Ray;
use firmament_core::{Camera, Frame};
use firmament_render::headless::HeadlessRenderer;
use firmament_render::readback::{decode_f16, read_texture};
use firmament_render::{DepthConvention, EmbedTarget, GpuContext, RenderError, Renderer, wgpu};
use glam::{DVec3, DVec4};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 64;
/// The face covers NDC `[-FACE, FACE]²`.
const FACE: f64 = 0.4;
/// Radiance of the face that shows the transmittance, cd/m² (well inside half-float range).
const BRIGHT: f64 = 30_000.0;

/// Earth on Bruneton's sphere, ENU at (0°, 0°), a sun at 25°, a narrow camera 2 m up looking
/// along `view` (so every pixel of the face is about as far as its centre).
fn frame(view: DVec3, far: Option<f64>) -> Frame {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0).posed_at(0.0, 0.0);
    let eye = DVec3::Z * 2.0;
    let camera = Camera::looking_at(eye, eye + view, DVec3::Z).expect("a view direction");
    Frame {
        camera: Camera {
            fov_y: 0.5_f64.to_radians(),
            far,
            ..camera
        },
        sky: Sky::Atmosphere(AtmosphereSky {
            atmosphere,
            suns: vec![presets::earth_sun(direction(90.0, 25.0))],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        }),
        display: DisplaySettings::default(),
        objects: Default::default(),
        flares: Default::default(),
        night: Default::default(),
    }
}

/// The user's targets: an HDR colour texture and a depth buffer.
struct UserTargets {
    color: wgpu::Texture,
    color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
}

fn texture(
    ctx: &GpuContext,
    label: &str,
    (width, height, samples): (u32, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: samples,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

fn user_targets(ctx: &GpuContext) -> UserTargets {
    use wgpu::TextureUsages as U;
    let color = texture(
        ctx,
        "user colour",
        (WIDTH, HEIGHT, 1),
        wgpu::TextureFormat::Rgba16Float,
        U::RENDER_ATTACHMENT | U::COPY_SRC,
    );
    let depth = texture(
        ctx,
        "user depth",
        (WIDTH, HEIGHT, 1),
        wgpu::TextureFormat::Depth32Float,
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
    );
    UserTargets {
        color_view: color.create_view(&Default::default()),
        depth_view: depth.create_view(&Default::default()),
        color,
    }
}

/// The user's pipeline: a face-on square of colour `COLOR` at clip depth `DEPTH`, depth-tested
/// in the user's convention and written.
const USER_SHADER: &str = r"
override DEPTH: f32 = 0.5;
override COLOR: f32 = 1.0;
override FACE: f32 = 0.5;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32(i & 1u), f32((i >> 1u) & 1u)) * 2.0 - 1.0;
    return vec4<f32>(corner * FACE, DEPTH, 1.0);
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return vec4<f32>(COLOR, COLOR, COLOR, 1.0);
}
";

/// The user's pipeline of `module` (entry points `vs_main`, `fs_main`; override `constants`)
/// into an `Rgba16Float` target, depth-tested and written in `convention` (`Depth32Float`).
fn user_pipeline(
    ctx: &GpuContext,
    (module, constants): (&wgpu::ShaderModule, &[(&str, f64)]),
    buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    topology: wgpu::PrimitiveTopology,
    convention: DepthConvention,
) -> wgpu::RenderPipeline {
    let options = || wgpu::PipelineCompilationOptions {
        constants,
        ..Default::default()
    };
    let compare = match convention {
        DepthConvention::Standard => wgpu::CompareFunction::Less,
        _ => wgpu::CompareFunction::Greater,
    };
    ctx.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("user pipeline"),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: options(),
            buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: options(),
            targets: &[Some(wgpu::TextureFormat::Rgba16Float.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The user's pass over its colour target and depth buffer, cleared to black and to the
/// convention's far depth.
fn begin_user_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    (color, depth): (&wgpu::TextureView, &wgpu::TextureView),
    convention: DepthConvention,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("user pass"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: color,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(convention.far_depth() as f32),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    })
}

/// Clears the user's targets (black; the convention's far depth) and draws the square of
/// radiance `color` at view depth `distance`.
fn draw_user_geometry(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    targets: &UserTargets,
    camera: &Camera,
    convention: DepthConvention,
    (color, distance): (f64, f64),
) {
    let clip = camera.projection_matrix_for(convention) * DVec4::new(0.0, 0.0, -distance, 1.0);
    let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("user square shader"),
        source: wgpu::ShaderSource::Wgsl(USER_SHADER.into()),
    });
    let constants = [("DEPTH", clip.z / clip.w), ("COLOR", color), ("FACE", FACE)];
    let strip = wgpu::PrimitiveTopology::TriangleStrip;
    let pipeline = user_pipeline(ctx, (&module, &constants), &[], strip, convention);
    let views = (&targets.color_view, &targets.depth_view);
    let mut pass = begin_user_pass(encoder, views, convention);
    pass.set_pipeline(&pipeline);
    pass.draw(0..4, 0..1);
}

/// The user's frame after firmament drew into it: RGBA f32, top row first.
fn embedded_image(
    ctx: &GpuContext,
    renderer: &mut Renderer,
    frame: &Frame,
    convention: DepthConvention,
    square: (f64, f64),
    aerial_perspective: bool,
) -> Vec<f32> {
    let targets = user_targets(ctx);
    let mut target = EmbedTarget::new(&targets.color_view, &targets.depth_view, convention);
    if !aerial_perspective {
        target = target.without_aerial_perspective();
    }
    renderer.prepare_into(ctx, frame, &target).expect("a valid target");
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("user frame"),
    });
    let camera = Camera {
        aspect: f64::from(WIDTH) / f64::from(HEIGHT),
        ..frame.camera
    };
    draw_user_geometry(ctx, &mut encoder, &targets, &camera, convention, square);
    renderer.record_into(&mut encoder, &target).expect("prepared");
    ctx.queue.submit([encoder.finish()]);
    decode_f16(&read_texture(ctx, &targets.color).expect("readback"))
}

/// Whether pixel (`x`, `y`) is inside the square (a pixel's margin either way counts as neither).
fn in_square(x: u32, y: u32) -> Option<bool> {
    let ndc = |p: u32, n: u32| (2.0 * (f64::from(p) + 0.5) / f64::from(n) - 1.0).abs();
    let (dx, dy) = (ndc(x, WIDTH), ndc(y, HEIGHT));
    let margin = 2.0 * 1.5 / f64::from(HEIGHT);
    if dx < FACE - margin && dy < FACE - margin {
        Some(true)
    } else if dx > FACE + margin || dy > FACE + margin {
        Some(false)
    } else {
        None
    }
}

fn mean_rgb(pixels: &[f32], inside: bool) -> DVec3 {
    let mut sum = DVec3::ZERO;
    let mut n = 0.0;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            if in_square(x, y) == Some(inside) {
                let i = ((y * WIDTH + x) * 4) as usize;
                sum += DVec3::new(f64::from(pixels[i]), f64::from(pixels[i + 1]), f64::from(pixels[i + 2]));
                n += 1.0;
            }
        }
    }
    sum / n
}

/// The f64 reference's air over `distance` metres of `ray` under `sky`: the light it scatters
/// towards the camera (linear sRGB, cd/m²) and its transmittance (R, G, B).
fn reference_air(sky: &AtmosphereSky, ray: &Ray, distance: f64) -> (DVec3, DVec3) {
    let settings = ReferenceSettings {
        paths: 4096,
        ..Default::default()
    };
    let want = Reference::new(sky.atmosphere.clone(), &sky.suns, settings).radiance_before(ray, distance);
    let s = sky.atmosphere.spectral_conversion().linear_srgb(want.scattered());
    let t = want.transmittance;
    (DVec3::new(s.r, s.g, s.b), DVec3::new(t.x, t.y, t.z))
}

#[test]
fn the_sky_goes_behind_the_users_geometry_and_fogs_it_in_both_conventions() {
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target user device");
    let view = direction(60.0, 1.0);
    let distance = 4_000.0;
    let eye = DVec3::Z * 2.0;
    let Sky::Atmosphere(sky) = frame(view, None).sky else {
        unreachable!("an atmosphere frame")
    };
    let (want_s, want_t) = reference_air(
        &sky,
        &Ray {
            origin: eye,
            direction: view,
        },
        distance,
    );

    let mut own = HeadlessRenderer::new(&ctx);
    let mut renderer = Renderer::new(&ctx, wgpu::TextureFormat::Rgba8UnormSrgb);
    for far in [None, Some(100_000.0)] {
        let frame = frame(view, far);
        let sky = own
            .render_hdr(&ctx, &frame, WIDTH, HEIGHT)
            .expect("own HDR render")
            .pixels;
        for convention in [DepthConvention::Reversed, DepthConvention::Standard] {
            let dark = embedded_image(&ctx, &mut renderer, &frame, convention, (0.0, distance), true);
            let bright = embedded_image(&ctx, &mut renderer, &frame, convention, (BRIGHT, distance), true);
            // Without firmament's aerial perspective the face keeps the user's own colour.
            let raw = embedded_image(&ctx, &mut renderer, &frame, convention, (BRIGHT, distance), false);
            let raw_face = mean_rgb(&raw, true);
            assert!(
                (raw_face - DVec3::splat(BRIGHT)).abs().max_element() < BRIGHT * 1e-3,
                "{convention:?}: without aerial perspective the face is {raw_face}, not the user's {BRIGHT}"
            );
            // The sky: the renderer's own pixels, to half-float rounding.
            let mut worst_sky = 0.0_f64;
            let mut sky_pixels = 0;
            for y in 0..HEIGHT {
                for x in 0..WIDTH {
                    if in_square(x, y) != Some(false) {
                        continue;
                    }
                    sky_pixels += 1;
                    let i = ((y * WIDTH + x) * 4) as usize;
                    for c in 0..3 {
                        for image in [&dark, &bright] {
                            let (got, want) = (f64::from(image[i + c]), f64::from(sky[i + c]));
                            let error = (got - want).abs() / want.abs().max(1e-3);
                            worst_sky = worst_sky.max(error);
                        }
                    }
                }
            }
            // The face: the user's colour · T + S.
            let s = mean_rgb(&dark, true);
            let t = (mean_rgb(&bright, true) - s) / BRIGHT;
            let s_error = (s - want_s).abs().max_element() / want_s.max_element();
            let t_error = (t - want_t).abs().max_element();
            println!(
                "{convention:?}, far {far:?}: sky vs own HDR path worst {:.2e} relative over {sky_pixels} \
                 pixels; face S {s:.4} vs {want_s:.4} ({:.2} %), T {t:.4} vs {want_t:.4} ({t_error:.1e})",
                worst_sky,
                100.0 * s_error
            );
            assert!(
                worst_sky <= 1e-3,
                "{convention:?}: the sky differs from the renderer's own by {worst_sky}"
            );
            // The sky is behind the face: no sky light on it beyond the air's.
            assert!(
                s_error < 0.06,
                "{convention:?}: scattered light off by {:.1} %",
                100.0 * s_error
            );
            assert!(t_error < 3e-3, "{convention:?}: transmittance off by {t_error}");
        }
    }
}

/// The error of `prepare_into` for `color` and `depth` (and that `record_into` refuses it too).
fn target_error(ctx: &GpuContext, renderer: &mut Renderer, color: &wgpu::Texture, depth: &wgpu::Texture) -> String {
    let (color_view, depth_view) = (
        color.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    view_error(
        ctx,
        renderer,
        EmbedTarget::new(&color_view, &depth_view, DepthConvention::Standard),
    )
}

/// The error of `prepare_into` for `target`, which must be `InvalidTarget`.
fn view_error(ctx: &GpuContext, renderer: &mut Renderer, target: EmbedTarget<'_>) -> String {
    let frame = frame(direction(0.0, 5.0), None);
    let error = renderer
        .prepare_into(ctx, &frame, &target)
        .expect_err("an invalid target");
    assert!(matches!(error, RenderError::InvalidTarget(_)), "{error:?}");
    error.to_string()
}

/// A texture of `format`, `usage`, `layers` deep in `dimension` with `mips` mip levels.
fn texture_of(
    ctx: &GpuContext,
    (dimension, layers, mips): (wgpu::TextureDimension, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("odd texture"),
        size: wgpu::Extent3d {
            width: WIDTH,
            height: HEIGHT,
            depth_or_array_layers: layers,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension,
        format,
        usage,
        view_formats: &[],
    })
}

#[test]
fn bad_targets_are_refused_with_what_is_needed() {
    use wgpu::TextureFormat as F;
    use wgpu::TextureUsages as U;
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target user device");
    let mut renderer = Renderer::new(&ctx, F::Rgba8UnormSrgb);
    let rt = U::RENDER_ATTACHMENT;
    let depth_usage = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING;
    let size = (WIDTH, HEIGHT, 1);
    let color = texture(&ctx, "good colour", size, F::Rgba16Float, rt);
    let depth = texture(&ctx, "good depth", size, F::Depth32Float, depth_usage);
    let cases: Vec<(&str, wgpu::Texture, wgpu::Texture, &str)> = vec![
        (
            "depth of another size",
            texture(&ctx, "colour", size, F::Rgba16Float, rt),
            texture(
                &ctx,
                "small depth",
                (WIDTH / 2, HEIGHT, 1),
                F::Depth32Float,
                depth_usage,
            ),
            "must be the same size",
        ),
        (
            "MSAA colour",
            texture(&ctx, "msaa colour", (WIDTH, HEIGHT, 4), F::Rgba16Float, rt),
            texture(&ctx, "msaa depth", (WIDTH, HEIGHT, 4), F::Depth32Float, rt),
            "resolve",
        ),
        (
            "8-bit colour",
            texture(&ctx, "bgra colour", size, F::Bgra8Unorm, rt),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "Rgba16Float",
        ),
        (
            "depth-stencil",
            texture(&ctx, "colour", size, F::Rgba16Float, rt),
            texture(&ctx, "depth stencil", size, F::Depth24PlusStencil8, depth_usage),
            "Depth32Float",
        ),
        (
            "depth not bindable",
            texture(&ctx, "colour", size, F::Rgba16Float, rt),
            texture(&ctx, "depth", size, F::Depth32Float, rt),
            "TEXTURE_BINDING",
        ),
    ];
    let odd = |shape, format, usage| texture_of(&ctx, shape, format, usage);
    let d2 = wgpu::TextureDimension::D2;
    let cases2: Vec<(&str, wgpu::Texture, wgpu::Texture, &str)> = vec![
        (
            "colour not a render attachment",
            texture(&ctx, "colour", size, F::Rgba16Float, U::TEXTURE_BINDING),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "lack RENDER_ATTACHMENT",
        ),
        (
            "3D colour",
            odd((wgpu::TextureDimension::D3, 2, 1), F::Rgba16Float, U::TEXTURE_BINDING),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "one layer and one mip level",
        ),
        (
            "array colour",
            odd((d2, 2, 1), F::Rgba16Float, rt),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "one layer and one mip level",
        ),
        (
            "colour with mips",
            odd((d2, 1, 2), F::Rgba16Float, rt),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "one layer and one mip level",
        ),
        (
            "depth with mips",
            texture(&ctx, "colour", size, F::Rgba16Float, rt),
            odd((d2, 1, 2), F::Depth32Float, depth_usage),
            "one layer and one mip level",
        ),
        (
            "single-sampled colour, MSAA depth",
            texture(&ctx, "colour", size, F::Rgba16Float, rt),
            texture(&ctx, "msaa depth", (WIDTH, HEIGHT, 4), F::Depth32Float, rt),
            "sample counts must match",
        ),
        (
            "MSAA colour, single-sampled depth",
            texture(&ctx, "msaa colour", (WIDTH, HEIGHT, 4), F::Rgba16Float, rt),
            texture(&ctx, "depth", size, F::Depth32Float, depth_usage),
            "sample counts must match",
        ),
    ];
    for (what, color, depth, needed) in cases.iter().chain(&cases2) {
        let message = target_error(&ctx, &mut renderer, color, depth);
        println!("{what}: {message}");
        assert!(message.contains(needed), "{what}: `{message}` does not name `{needed}`");
    }
    // A view of mip 1 of a texture with two: the view's own size is half, and the texture's rule
    // refuses it before its size could mislead.
    let mipped = odd((d2, 1, 2), F::Rgba16Float, rt);
    let mip1 = mipped.create_view(&wgpu::TextureViewDescriptor {
        base_mip_level: 1,
        mip_level_count: Some(1),
        ..Default::default()
    });
    let half_depth = texture(
        &ctx,
        "half depth",
        (WIDTH / 2, HEIGHT / 2, 1),
        F::Depth32Float,
        depth_usage,
    );
    let half_depth_view = half_depth.create_view(&Default::default());
    let message = view_error(
        &ctx,
        &mut renderer,
        EmbedTarget::new(&mip1, &half_depth_view, DepthConvention::Reversed),
    );
    println!("view of mip 1: {message}");
    assert!(message.contains("one mip level"), "{message}");
    // Rgba32Float needs FLOAT32_BLENDABLE, which this device (firmament's required features
    // only) was not given.
    assert!(!ctx.device.features().contains(wgpu::Features::FLOAT32_BLENDABLE));
    // (Without RENDER_ATTACHMENT: GL's downlevel limits refuse it on Rgba32Float, and the
    // feature is checked first.)
    let wide = texture(&ctx, "rgba32 colour", size, F::Rgba32Float, U::TEXTURE_BINDING);
    let message = target_error(&ctx, &mut renderer, &wide, &depth);
    println!("Rgba32Float without the feature: {message}");
    assert!(message.contains("FLOAT32_BLENDABLE"), "{message}");
    // Recording into a target nothing was prepared for is refused too, and encodes nothing.
    let (color_view, depth_view) = (
        color.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    let target = EmbedTarget::new(&color_view, &depth_view, DepthConvention::Reversed);
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    let error = renderer.record_into(&mut encoder, &target).expect_err("not prepared");
    assert!(error.to_string().contains("prepare_into"), "{error}");
    // Recording into another target of the prepared kind and size is checked by the same rules:
    // one that breaks them is refused (was a wgpu validation panic when the encoder finished).
    let prepared = EmbedTarget::new(&color_view, &depth_view, DepthConvention::Standard);
    renderer
        .prepare_into(&ctx, &frame(direction(0.0, 5.0), None), &prepared)
        .expect("a valid target");
    let unrenderable = texture(&ctx, "colour", size, F::Rgba16Float, U::TEXTURE_BINDING);
    let unrenderable_view = unrenderable.create_view(&Default::default());
    let other = EmbedTarget::new(&unrenderable_view, &depth_view, DepthConvention::Standard);
    let error = renderer
        .record_into(&mut encoder, &other)
        .expect_err("an invalid target");
    println!("record_into another, bad target: {error}");
    assert!(error.to_string().contains("lack RENDER_ATTACHMENT"), "{error}");
    renderer
        .record_into(&mut encoder, &prepared)
        .expect("the prepared target");
    ctx.queue.submit([encoder.finish()]);
}

#[test]
fn an_output_view_gets_the_pixels_firmament_render_writes() {
    use wgpu::TextureFormat as F;
    use wgpu::TextureUsages as U;
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target user device");
    let frame = frame(direction(60.0, 1.0), None);
    // What `firmament render` writes to a PNG for this frame.
    let png = HeadlessRenderer::new(&ctx)
        .render_ldr(&ctx, &frame, WIDTH, HEIGHT)
        .expect("own LDR render");
    let mut renderer = Renderer::new(&ctx, F::Rgba8UnormSrgb);
    let size = (WIDTH, HEIGHT, 1);
    for convention in [DepthConvention::Reversed, DepthConvention::Standard] {
        // The user's HDR target (readable by the output pass), depth and 8-bit sRGB output.
        let color = texture(
            &ctx,
            "colour",
            size,
            F::Rgba16Float,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
        );
        let depth = texture(
            &ctx,
            "depth",
            size,
            F::Depth32Float,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
        );
        let output = texture(
            &ctx,
            "output",
            size,
            F::Rgba8UnormSrgb,
            U::RENDER_ATTACHMENT | U::COPY_SRC,
        );
        let targets = UserTargets {
            color_view: color.create_view(&Default::default()),
            depth_view: depth.create_view(&Default::default()),
            color,
        };
        let output_view = output.create_view(&Default::default());
        let target = EmbedTarget::new(&targets.color_view, &targets.depth_view, convention).with_output(&output_view);
        renderer.prepare_into(&ctx, &frame, &target).expect("a valid target");
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("user frame with output"),
        });
        let camera = Camera {
            aspect: f64::from(WIDTH) / f64::from(HEIGHT),
            ..frame.camera
        };
        if convention == DepthConvention::Standard {
            // This frame's lighting before the user's geometry: record_into then skips the LUTs,
            // and the pixels are the same.
            renderer.record_lighting(&mut encoder);
        }
        draw_user_geometry(&ctx, &mut encoder, &targets, &camera, convention, (0.0, 4_000.0));
        renderer.record_into(&mut encoder, &target).expect("prepared");
        ctx.queue.submit([encoder.finish()]);
        let got = read_texture(&ctx, &output).expect("readback");
        let mut worst = 0;
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                if in_square(x, y) != Some(false) {
                    continue;
                }
                let i = ((y * WIDTH + x) * 4) as usize;
                for c in 0..4 {
                    worst = worst.max(got[i + c].abs_diff(png.pixels[i + c]));
                }
            }
        }
        println!("{convention:?}: output vs firmament render's PNG, worst {worst}/255 outside the face");
        assert!(
            worst <= 1,
            "{convention:?}: the output differs from render's PNG by {worst}/255"
        );
    }

    // An output of another size, or a colour target the output pass cannot read, is refused.
    let color = texture(
        &ctx,
        "colour",
        size,
        F::Rgba16Float,
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
    );
    let unreadable = texture(&ctx, "colour", size, F::Rgba16Float, U::RENDER_ATTACHMENT);
    let depth = texture(
        &ctx,
        "depth",
        size,
        F::Depth32Float,
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
    );
    let small = texture(
        &ctx,
        "small output",
        (WIDTH / 2, HEIGHT, 1),
        F::Rgba8UnormSrgb,
        U::RENDER_ATTACHMENT,
    );
    let good = texture(&ctx, "output", size, F::Rgba8UnormSrgb, U::RENDER_ATTACHMENT);
    let depth_view = depth.create_view(&Default::default());
    let msaa = texture(
        &ctx,
        "msaa output",
        (WIDTH, HEIGHT, 4),
        F::Rgba8UnormSrgb,
        U::RENDER_ATTACHMENT,
    );
    let snorm = texture(&ctx, "snorm output", size, F::Rgba8Snorm, U::TEXTURE_BINDING);
    let integer = texture(&ctx, "integer output", size, F::Rgba8Uint, U::RENDER_ATTACHMENT);
    let unrenderable = texture(&ctx, "output", size, F::Rgba8UnormSrgb, U::TEXTURE_BINDING);
    let array = texture_of(
        &ctx,
        (wgpu::TextureDimension::D2, 2, 1),
        F::Rgba8UnormSrgb,
        U::RENDER_ATTACHMENT,
    );
    for (what, color, output, needed) in [
        ("small output", &color, &small, "same size"),
        ("unreadable colour", &unreadable, &good, "TEXTURE_BINDING"),
        ("MSAA output", &color, &msaa, "single-sampled"),
        (
            "non-renderable output format",
            &color,
            &snorm,
            "colour-renderable float format",
        ),
        (
            "integer output format",
            &color,
            &integer,
            "colour-renderable float format",
        ),
        (
            "output not a render attachment",
            &color,
            &unrenderable,
            "lack RENDER_ATTACHMENT",
        ),
        ("array output", &color, &array, "one layer and one mip level"),
    ] {
        let (color_view, output_view) = (
            color.create_view(&Default::default()),
            output.create_view(&Default::default()),
        );
        let target = EmbedTarget::new(&color_view, &depth_view, DepthConvention::Reversed).with_output(&output_view);
        let error = renderer.prepare_into(&ctx, &frame, &target).expect_err(what);
        println!("{what}: {error}");
        assert!(error.to_string().contains(needed), "{what}: {error}");
    }
    // An output format the renderer's own output pass cannot draw into: refused by `prepare`,
    // never a wgpu validation panic.
    for format in [F::Depth32Float, F::Rgba8Uint, F::Rgba8Snorm] {
        let mut bad = Renderer::new(&ctx, format);
        let error = bad
            .prepare(&ctx, &frame, WIDTH, HEIGHT)
            .expect_err("an unusable output format");
        println!("Renderer::new({format:?}): {error}");
        assert!(matches!(error, RenderError::OutputFormat(_)), "{error:?}");
        assert!(error.to_string().contains("colour-renderable float format"), "{error}");
    }
}

/// A scene as `firmament render` reads it: Earth at 45° N, the Sun 25° up behind a camera 300 m up
/// looking north, and an unlit cube 200 m on a side whose near face is 2 km away, straight ahead.
/// (Geometry at a street's horizon, between a froxel row above it and one below, is checked
/// against the reference by `aerial_perspective`'s
/// `geometry_at_the_horizon_of_a_wide_view_gets_its_air`.)
const CUBE_SCENE: &str = r#"
preset = "earth-noon"

[camera]
position = [0.0, 0.0, 300.0]
heading = 0.0
pitch = 0.0
fov_y = 20.0

[display]
ev100 = 14.0

[[suns]]
name = "Sun"
azimuth = 180.0
elevation = 25.0

[lighting]
model = "unlit"

[[objects]]
name = "cube"
mesh = { kind = "cube", size = 1.0 }
transform = [{ translate = [0.0, 2100.0, 300.0] }, { scale = [200.0, 200.0, 200.0] }]
material = { diffuse = [0.9, 0.6, 0.3] }
"#;
/// Distance from the camera to the cube's near face along the view axis, metres.
const CUBE_DISTANCE: f64 = 2000.0;
/// The cube test's image size (small: a software rasterizer draws it).
const CUBE_SIZE: (u32, u32) = (64, 48);

/// The user's cube pipeline: the same triangles as firmament's object pass, projected the same
/// way (`projection · (model_view · position)`, so `x`, `y` and `w` are the same floats and the
/// same pixels are covered) and the colour firmament gives an unlit object.
const USER_CUBE_SHADER: &str = r"
struct User {
    projection: mat4x4<f32>,
    model_view: mat4x4<f32>,
    color: vec4<f32>,
}
@group(0) @binding(0) var<uniform> user: User;

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    let eye = user.model_view * vec4<f32>(position, 1.0);
    return user.projection * eye;
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return clamp(user.color, vec4<f32>(0.0), vec4<f32>(1.0));
}
";

/// Clears the user's targets (black; the convention's far depth) and draws `object` (the scene's
/// cube) with the user's own pipeline, seen by `camera` in `convention`.
fn draw_user_cube(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    (color, depth): (&wgpu::TextureView, &wgpu::TextureView),
    camera: &Camera,
    convention: DepthConvention,
    object: &firmament_core::classic::scene::SceneObject,
) {
    use wgpu::util::DeviceExt;
    let device = &ctx.device;
    let mut uniforms = Vec::new();
    uniforms.extend(camera.projection_matrix_for(convention).as_mat4().to_cols_array());
    uniforms.extend((camera.view_matrix() * object.model).as_mat4().to_cols_array());
    uniforms.extend(object.front.diffuse.as_vec4().to_array());
    let buffer = |label, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let uniforms = buffer(
        "user cube uniforms",
        bytemuck::cast_slice(&uniforms),
        wgpu::BufferUsages::UNIFORM,
    );
    let positions = buffer(
        "user cube positions",
        bytemuck::cast_slice(&object.mesh.positions),
        wgpu::BufferUsages::VERTEX,
    );
    let indices = buffer(
        "user cube indices",
        bytemuck::cast_slice(&object.mesh.indices),
        wgpu::BufferUsages::INDEX,
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("user cube shader"),
        source: wgpu::ShaderSource::Wgsl(USER_CUBE_SHADER.into()),
    });
    let layout = wgpu::VertexBufferLayout {
        array_stride: 12,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3],
    };
    let triangles = wgpu::PrimitiveTopology::TriangleList;
    let pipeline = user_pipeline(ctx, (&module, &[]), &[Some(layout)], triangles, convention);
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("user cube bind group"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniforms.as_entire_binding(),
        }],
    });
    let mut pass = begin_user_pass(encoder, (color, depth), convention);
    pass.set_pipeline(&pipeline);
    pass.set_bind_group(0, &bind_group, &[]);
    pass.set_vertex_buffer(0, positions.slice(..));
    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(0..object.mesh.indices.len() as u32, 0, 0..1);
}

/// The embedding path for `frame`: the user's cube, then firmament into the user's frame with an
/// 8-bit sRGB output view. The output's pixels and the composited HDR colour (RGBA f32).
fn embedded_cube(
    ctx: &GpuContext,
    renderer: &mut Renderer,
    frame: &Frame,
    convention: DepthConvention,
) -> (Vec<u8>, Vec<f32>) {
    use wgpu::TextureFormat as F;
    use wgpu::TextureUsages as U;
    let size = (CUBE_SIZE.0, CUBE_SIZE.1, 1);
    let color = texture(
        ctx,
        "colour",
        size,
        F::Rgba16Float,
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
    );
    let depth = texture(
        ctx,
        "depth",
        size,
        F::Depth32Float,
        U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
    );
    let output = texture(
        ctx,
        "output",
        size,
        F::Rgba8UnormSrgb,
        U::RENDER_ATTACHMENT | U::COPY_SRC,
    );
    let (color_view, depth_view, output_view) = (
        color.create_view(&Default::default()),
        depth.create_view(&Default::default()),
        output.create_view(&Default::default()),
    );
    let target = EmbedTarget::new(&color_view, &depth_view, convention).with_output(&output_view);
    renderer.prepare_into(ctx, frame, &target).expect("a valid target");
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("user cube frame"),
    });
    let camera = Camera {
        aspect: f64::from(CUBE_SIZE.0) / f64::from(CUBE_SIZE.1),
        ..frame.camera
    };
    let cube = &frame.objects.objects[0];
    draw_user_cube(ctx, &mut encoder, (&color_view, &depth_view), &camera, convention, cube);
    renderer.record_into(&mut encoder, &target).expect("prepared");
    ctx.queue.submit([encoder.finish()]);
    let ldr = read_texture(ctx, &output).expect("readback");
    let hdr = decode_f16(&read_texture(ctx, &color).expect("readback"));
    (ldr, hdr)
}

#[test]
fn the_users_cube_matches_firmament_render_and_is_fogged_as_the_reference_predicts() {
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target user device");
    let (width, height) = CUBE_SIZE;
    let scene = firmament_scene::load(
        firmament_scene::SceneSource::Text {
            text: CUBE_SCENE,
            origin: "cube scene",
        },
        None,
        &[],
    )
    .expect("the cube scene");

    let mut frame = scene.frame_at(None).expect("a frame");
    assert_eq!(frame.objects.objects.len(), 1, "one cube");

    // The cube's colour · T + S along the view axis to its face, from the f64 reference.
    let Sky::Atmosphere(sky) = frame.sky.clone() else {
        unreachable!("an atmosphere scene")
    };
    let axis = Ray {
        origin: frame.camera.position,
        direction: frame.camera.forward(),
    };
    let (s, t) = reference_air(&sky, &axis, CUBE_DISTANCE);
    let want_face = frame.objects.objects[0].front.diffuse.truncate() * t + s;

    let mut renderer = Renderer::new(&ctx, wgpu::TextureFormat::Rgba8UnormSrgb);
    let mut own = HeadlessRenderer::new(&ctx);
    for far in [None, Some(20_000.0)] {
        frame.camera.far = far;
        // What `firmament render` writes to a PNG for this scene.
        let png = own.render_ldr(&ctx, &frame, width, height).expect("own LDR render");
        for convention in [DepthConvention::Reversed, DepthConvention::Standard] {
            let (ldr, hdr) = embedded_cube(&ctx, &mut renderer, &frame, convention);
            let worst = ldr
                .iter()
                .zip(&png.pixels)
                .map(|(a, b)| a.abs_diff(*b))
                .max()
                .expect("pixels");
            // The four pixels about the centre look at the face (within 0.3° of the axis).
            let mut face = DVec3::ZERO;
            for (x, y) in [(width / 2 - 1, height / 2 - 1), (width / 2, height / 2)] {
                for (x, y) in [(x, y), (width - 1 - x, y)] {
                    let i = ((y * width + x) * 4) as usize;
                    face += DVec3::new(f64::from(hdr[i]), f64::from(hdr[i + 1]), f64::from(hdr[i + 2])) / 4.0;
                }
            }
            let face_error = (face - want_face).abs().max_element() / want_face.max_element();
            println!(
                "{convention:?}, far {far:?}: every pixel vs firmament render's PNG, worst {worst}/255; the \
                 face {face:.1} vs the reference's colour·T + S {want_face:.1} ({:.2} %)",
                100.0 * face_error
            );
            assert!(
                worst <= 1,
                "{convention:?}, far {far:?}: differs from render's PNG by {worst}/255"
            );
            assert!(
                face_error < 0.06,
                "{convention:?}, far {far:?}: the face's fog is off the reference by {:.1} %",
                100.0 * face_error
            );
        }
    }
}

/// A cumulus layer over the user's frame is the renderer's own clouds: the same march, laid over
/// the user's colour by blending instead of in place, looking up at the layer and down at the
/// ground it shadows. Geometry in front of the layer hides it (only the air in front of the
/// geometry loses light, to the clouds' shadows).
#[test]
fn clouds_lie_over_the_users_frame_as_over_the_renderers_own() {
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target clouds device");
    let mut own = HeadlessRenderer::new(&ctx);
    let mut renderer = Renderer::new(&ctx, wgpu::TextureFormat::Rgba8UnormSrgb);
    for view in [direction(60.0, 25.0), direction(60.0, -20.0)] {
        let clear = Frame {
            camera: Camera {
                fov_y: 40_f64.to_radians(),
                position: DVec3::new(0.0, 0.0, 300.0),
                ..frame(view, None).camera
            },
            ..frame(view, None)
        };
        let mut cloudy = clear.clone();
        if let Sky::Atmosphere(sky) = &mut cloudy.sky {
            sky.clouds = vec![CloudLayer {
                seed: 7,
                ..CloudLayer::new(1_500.0, 3_000.0, 0.5, 0.05, CloudKind::Cumulus)
            }];
        }
        let own_cloudy = own
            .render_hdr(&ctx, &cloudy, WIDTH, HEIGHT)
            .expect("own HDR render")
            .pixels;
        let own_clear = own
            .render_hdr(&ctx, &clear, WIDTH, HEIGHT)
            .expect("own HDR render")
            .pixels;
        // Differences are relative to the pixel, or to a hundredth of the mean where darker (a
        // shadowed ground is the difference of two half floats).
        let floor = 1e-2 * own_clear.iter().map(|&v| f64::from(v)).sum::<f64>() / own_clear.len() as f64;
        // A dark square 100 m away, well in front of the layer and above the ground.
        let square = (0.0, 100.0);
        for convention in [DepthConvention::Reversed, DepthConvention::Standard] {
            let with = embedded_image(&ctx, &mut renderer, &cloudy, convention, square, true);
            let without = embedded_image(&ctx, &mut renderer, &clear, convention, square, true);
            let (mut worst, mut changed, mut around) = (0.0_f64, 0, 0);
            for y in 0..HEIGHT {
                for x in 0..WIDTH {
                    let i = ((y * WIDTH + x) * 4) as usize;
                    match in_square(x, y) {
                        // The square hides the clouds: its pixels keep the air in front of it,
                        // less what the clouds' shadows take off that air, never more.
                        Some(true) => {
                            for c in i..i + 3 {
                                assert!(
                                    (0.0..=without[c] * 1.001).contains(&with[c]),
                                    "{convention:?}: the square at ({x}, {y}) shows {} with clouds, {} without",
                                    with[c],
                                    without[c]
                                );
                            }
                        }
                        Some(false) => {
                            around += 1;
                            for c in i..i + 3 {
                                let want = f64::from(own_cloudy[c]);
                                worst = worst.max((f64::from(with[c]) - want).abs() / want.abs().max(floor));
                            }
                            let lum = |p: &[f32]| f64::from(p[i] + p[i + 1] + p[i + 2]);
                            if (lum(&own_cloudy) - lum(&own_clear)).abs() > 0.05 * lum(&own_clear) {
                                changed += 1;
                            }
                        }
                        None => {}
                    }
                }
            }
            println!("{view:.2}, {convention:?}: worst {worst:.2e} relative over {around} pixels; {changed} changed");
            assert!(changed > around / 10, "the clouds show: {changed} of {around} pixels");
            // Both images pass through half floats (the layer and the target), and the own target
            // clamps the image behind the cloud at the air in front of it (the layer cannot).
            assert!(
                worst <= 1e-2,
                "{convention:?}: the clouds differ from the own target's by {worst}"
            );
        }
    }
}

/// Light shafts: an absorbing layer overhead shadows the air between the camera and the user's
/// square, which loses the sunlight it scattered once as the `f64` reference's air loses it
/// (`single_scattering_before`, with and without the layer: the reference's sunlight crosses the
/// clouds). Only the air changes: the ray ends on the square, below the layer.
#[test]
fn the_clouds_shadow_the_air_in_front_of_the_users_geometry_as_the_reference_does() {
    let _gpu = support::gpu();
    let ctx = support::user_context("gpu_embed_target shafts device");
    let mut renderer = Renderer::new(&ctx, wgpu::TextureFormat::Rgba8UnormSrgb);
    let (view, distance) = (direction(60.0, 3.0), 3_000.0);
    let clear = frame(view, None);
    let mut cloudy = clear.clone();
    let layer = CloudLayer {
        albedo: 0.0,
        ..CloudLayer::new(1_000.0, 2_000.0, 1.0, 1.0e-3, CloudKind::Uniform)
    };
    if let Sky::Atmosphere(sky) = &mut cloudy.sky {
        sky.clouds = vec![layer];
    }
    let face = |frame: &Frame, renderer: &mut Renderer| {
        let image = embedded_image(&ctx, renderer, frame, DepthConvention::Reversed, (0.0, distance), true);
        mean_rgb(&image, true)
    };
    let gpu_lost = face(&clear, &mut renderer) - face(&cloudy, &mut renderer);
    let single = |frame: &Frame| {
        let Sky::Atmosphere(sky) = &frame.sky else {
            unreachable!("an atmosphere frame")
        };
        let reference =
            Reference::new(sky.atmosphere.clone(), &sky.suns, ReferenceSettings::default()).with_clouds(&sky.clouds);
        let ray = Ray {
            origin: frame.camera.position,
            direction: view,
        };
        let rgb = sky
            .atmosphere
            .spectral_conversion()
            .linear_srgb(reference.single_scattering_before(&ray, distance).0);
        DVec3::new(rgb.r, rgb.g, rgb.b)
    };
    let want_lost = single(&clear) - single(&cloudy);
    let error = ((gpu_lost - want_lost) / want_lost).abs().max_element();
    println!(
        "the shadowed air loses {gpu_lost:.2}, the reference's {want_lost:.2} ({:.2} %)",
        100.0 * error
    );
    assert!(
        error < 0.03,
        "the clouds take {gpu_lost:.2} off the air in front of the square, the reference {want_lost:.2}"
    );
}
