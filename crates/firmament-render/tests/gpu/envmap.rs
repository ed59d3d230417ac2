//! GPU tests of the environment maps (`firmament_render::envmap`): the sun-less map's sky
//! irradiance on the ground against the `f64` reference path tracer, the disc's irradiance
//! against the sun's after the air, and where the sun lands in both layouts; the maps written
//! into the caller's textures (`EnvironmentMapPass`) against the in-memory ones, and the
//! textures it refuses.

use crate::support::{Gpu, direction, gpu, street_sky};

use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::envmap::{CubeFace, cube_position, equirect_position, sun_at_eye};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::{Camera, Frame};
use firmament_render::envmap::{EnvironmentMapPass, SunDiscs};
use firmament_render::headless::Image;
use firmament_render::{GpuContext, RenderError};
use glam::DVec3;

/// The camera 1.7 m above the ground (its orientation does not matter to a map).
fn street_frame(sky: &AtmosphereSky) -> Frame {
    let camera = Camera::from_heading_pitch(DVec3::new(0.0, 0.0, 1.7), 0.3, 0.1);
    Frame::new(camera, Sky::Atmosphere(sky.clone()))
}

/// `Σ L·dω` over a whole equirectangular map.
fn total_irradiance(map: &Image<f32>) -> DVec3 {
    let (w, h) = (map.width, map.height);
    (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| {
            let p = map.pixel(i, j).expect("inside");
            DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
                * firmament_core::envmap::equirect_pixel_solid_angle(j, w, h)
        })
        .sum()
}

fn relative(got: DVec3, want: DVec3) -> DVec3 {
    (got - want) / want
}

/// Paths of each of the reference's two estimates (two seeds) of the sky irradiance.
const REFERENCE_PATHS: usize = 65_536;

/// Check (2): a sun-less 256 × 128 map's `∫ L·cos θ dω` over the upper hemisphere against the
/// reference's sky irradiance on the ground (the quantity `firmament sky-sample` reports), sun
/// 45° and 10° up, in linear sRGB (lux).
#[test]
fn the_maps_sky_irradiance_matches_the_reference() {
    let mut gpu = gpu();
    let mut worst: f64 = 0.0;
    for elevation in [45.0, 10.0] {
        let sky = street_sky(90.0, elevation);
        let frame = street_frame(&sky);
        let Gpu { ctx, renderer } = &mut *gpu;
        let map = renderer
            .render_equirect(ctx, &frame, 256, SunDiscs::Omitted)
            .expect("render");
        assert_eq!((map.width, map.height), (256, 128));
        let got = crate::support::hemisphere_flux(&map, true);
        let conversion = sky.atmosphere.spectral_conversion();
        let reference = |seed| {
            let settings = ReferenceSettings {
                paths: REFERENCE_PATHS,
                seed,
                ..ReferenceSettings::default()
            };
            let e =
                Reference::new(sky.atmosphere.clone(), &sky.suns, settings).ground_irradiance(frame.camera.position);
            let c = conversion.linear_srgb(e.sky);
            DVec3::new(c.r, c.g, c.b)
        };
        let (a, b) = (reference(ReferenceSettings::default().seed), reference(7));
        let want = 0.5 * (a + b);
        let noise = 0.5 * relative(a, b).abs().max_element();
        let error = relative(got, want);
        println!(
            "sun {elevation}° up: map {got:.1} reference {want:.1} lux (noise ±{:.2} %): {:+.2} % {:+.2} % {:+.2} %",
            100.0 * noise,
            100.0 * error.x,
            100.0 * error.y,
            100.0 * error.z
        );
        worst = worst.max(error.abs().max_element());
    }
    println!("worst channel {:.2} %", 100.0 * worst);
    assert!(worst < 0.01, "worst channel {:.2} %", 100.0 * worst);
}

/// Check (3): the disc added into the map carries the sun's irradiance after the air — the map
/// with the disc less the map without, `Σ ΔL·dω`, against `E·T` at the disc's centre — and lands
/// where the sun is (azimuth 100°, 30° up) in both layouts, far beyond the half-float range.
#[test]
fn the_disc_carries_the_suns_irradiance_and_lands_where_the_sun_is() {
    let mut gpu = gpu();
    let sky = street_sky(100.0, 30.0);
    let frame = street_frame(&sky);
    let Gpu { ctx, renderer } = &mut *gpu;
    let with = renderer
        .render_equirect(ctx, &frame, 128, SunDiscs::Included)
        .expect("render");
    let without = renderer
        .render_equirect(ctx, &frame, 128, SunDiscs::Omitted)
        .expect("render");
    let sun = sun_at_eye(&sky.atmosphere, &[], &[], &sky.suns[0], frame.camera.position);
    let want = DVec3::new(sun.irradiance_rgb.r, sun.irradiance_rgb.g, sun.irradiance_rgb.b);
    let got = total_irradiance(&with) - total_irradiance(&without);
    let error = relative(got, want);
    println!("disc: map {got:.1} lux, E·T {want:.1} lux: relative {error:.6}");
    assert!(error.abs().max_element() < 0.01, "{error}");

    // The brightest pixel holds the sun's centre.
    let brightest = |image: &Image<f32>| {
        (0..image.width * image.height)
            .max_by(|&a, &b| image.pixels[4 * a as usize + 1].total_cmp(&image.pixels[4 * b as usize + 1]))
            .map(|k| (k % image.width, k / image.width))
            .expect("pixels")
    };
    let centre = direction(100.0, 30.0);
    let p = equirect_position(centre, 128, 64);
    assert_eq!(brightest(&with), (p.x as u32, p.y as u32), "the sun at {p}");
    assert_eq!(
        (p.x as u32, p.y as u32),
        (67, 21),
        "10° past east, the middle column; 30° up"
    );
    let peak = with.pixel(p.x as u32, p.y as u32).expect("inside")[1];
    assert!(peak > firmament_render::HDR_MAX * 10.0, "{peak}");

    let cube = renderer
        .render_cube_faces(ctx, &frame, 32, SunDiscs::Included)
        .expect("render");
    let (face, q) = cube_position(centre, 32);
    assert_eq!(face, CubeFace::PositiveX, "east is +X");
    assert_eq!(brightest(cube.face(face)), (q.x as u32, q.y as u32));
}

/// In totality the map keeps the sun's corona — the GPU draws it though the map leaves the discs
/// to the CPU: every pixel 3.5 to 5 solar radii from the hidden sun (a 1024 × 512 map, sun 60°
/// up) holds at least 92 % of the reference's corona through the air (Baumbach's law,
/// `Sun::corona_radiance`; measured 96 %, the map's bilinear resampling of the cube's 0.35°
/// texels over a corona falling as r^−2.5 to r^−7) and at most 125 % of it plus twice the
/// reference's sky light there (the GPU's umbra sky is near the reference's, `eclipse.rs`).
#[test]
fn a_total_eclipse_s_map_keeps_the_corona() {
    let mut gpu = gpu();
    let mut sky = street_sky(180.0, 60.0);
    let sun = sky.suns[0];
    let frame = street_frame(&sky);
    let eye = frame.camera.position;
    sky.eclipsers = vec![firmament_core::atmosphere::Eclipser {
        center: eye + sun.direction * 3.6e8,
        radius_m: 1.7374e6,
    }];
    let frame = street_frame(&sky);
    let Gpu { ctx, renderer } = &mut *gpu;
    let (width, height) = (1024, 512);
    let map = renderer
        .render_equirect(ctx, &frame, width, SunDiscs::Omitted)
        .expect("render");
    let settings = ReferenceSettings {
        paths: 512,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings).with_eclipsers(&sky.eclipsers);
    let conversion = sky.atmosphere.spectral_conversion();
    let rgb = |s| {
        let c = conversion.linear_srgb(s);
        DVec3::new(c.r, c.g, c.b)
    };
    // Every pixel whose centre lies 3.5 to 5 radii from the sun: the map there, the reference's
    // corona, and its sky light (noisy at 512 paths; averaged over the ring, where it is smooth).
    let s = equirect_position(sun.direction, width, height);
    let (si, sj) = (s.x as i64, s.y as i64);
    let mut ring = Vec::new();
    for (i, j) in (sj - 8..=sj + 8).flat_map(|j| (si - 12..=si + 12).map(move |i| (i as u32, j as u32))) {
        let centre = firmament_core::envmap::equirect_direction(f64::from(i) + 0.5, f64::from(j) + 0.5, width, height);
        let at = centre.angle_between(sun.direction) / sun.angular_radius;
        if !(3.5..=5.0).contains(&at) {
            continue;
        }
        let px = map.pixel(i, j).expect("inside");
        let got = DVec3::new(f64::from(px[0]), f64::from(px[1]), f64::from(px[2]));
        let parts = reference.radiance(&firmament_core::geometry::Ray {
            origin: eye,
            direction: centre,
        });
        ring.push((at, got, rgb(parts.sun_discs), rgb(parts.scattered())));
    }
    assert!(ring.len() >= 10, "{} pixels in the ring", ring.len());
    let sky_light = ring.iter().map(|r| r.3).sum::<DVec3>() / ring.len() as f64;
    for (at, got, corona, _) in ring {
        println!("{at:.2} radii out: map {got:.2}, reference corona {corona:.2}, the ring's sky {sky_light:.2}");
        assert!(
            corona.x > 2.0 * sky_light.x,
            "the corona outshines the sky there in red: {corona} {sky_light}"
        );
        // The map holds the corona (less only by its resampling) and the GPU's sky in the
        // umbra, which is near the reference's (docs/ATMOSPHERE.md, "Eclipses").
        assert!(
            got.cmpge(0.92 * corona).all() && got.cmple(1.25 * corona + 2.0 * sky_light).all(),
            "{at:.2} radii: map {got} vs corona {corona} (sky {sky_light})"
        );
    }
}

/// A `width` × `height` texture of `layers` layers and `format` for `EnvironmentMapPass`.
fn map_texture(
    ctx: &GpuContext,
    (width, height, layers): (u32, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("envmap test target"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// The usages the tests' targets have: copied into, read back, sampled.
const TARGET_USAGE: wgpu::TextureUsages = wgpu::TextureUsages::COPY_DST
    .union(wgpu::TextureUsages::COPY_SRC)
    .union(wgpu::TextureUsages::TEXTURE_BINDING);

/// Layer `layer` of a float RGBA `texture` read back as `f32`, rows top first.
fn read_layer(ctx: &GpuContext, texture: &wgpu::Texture, layer: u32) -> Image<f32> {
    let (width, height) = (texture.width(), texture.height());
    let texel = texture.format().block_copy_size(None).expect("a colour format");
    let row = firmament_render::readback::padded_bytes_per_row(width, texel);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("envmap test layer"),
        size: u64::from(row * height),
        usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    ctx.queue.submit([encoder.finish()]);
    let bytes = firmament_render::readback::read_buffer(ctx, &buffer, buffer.size()).expect("read back");
    let pixels = bytes
        .chunks_exact(row as usize)
        .flat_map(|line| {
            let line = &line[..(width * texel) as usize];
            match texel {
                16 => bytemuck::pod_collect_to_vec::<u8, f32>(line),
                _ => firmament_render::headless::decode_f16(line),
            }
        })
        .collect();
    Image { width, height, pixels }
}

/// What a `texture_cube` samples (nearest) at the centre of each face's texel `(i, j)`, by
/// OpenGL's table (the direction `cube_direction` gives, in the Y-up frame), into an `atlas` of
/// the six faces side by side.
const CUBE_READER: &str = "
@group(0) @binding(0) var cube: texture_cube<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var atlas: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = textureDimensions(cube).x;
    let face = id.x / n;
    if face >= 6u || id.y >= n {
        return;
    }
    let sc = (f32(id.x % n) + 0.5) / f32(n) * 2.0 - 1.0;
    let tc = (f32(id.y) + 0.5) / f32(n) * 2.0 - 1.0;
    var d: vec3<f32>;
    switch face {
        case 0u: { d = vec3<f32>(1.0, -tc, -sc); }
        case 1u: { d = vec3<f32>(-1.0, -tc, sc); }
        case 2u: { d = vec3<f32>(sc, 1.0, tc); }
        case 3u: { d = vec3<f32>(sc, -1.0, -tc); }
        case 4u: { d = vec3<f32>(sc, -tc, 1.0); }
        default: { d = vec3<f32>(-sc, -tc, -1.0); }
    }
    textureStore(atlas, id.xy, textureSampleLevel(cube, nearest, d, 0.0));
}
";

/// The six faces of a cube `texture` as a cube sampler sees them (wgpu's GL backend cannot copy a
/// cube map out), in the order of `CubeFace::ALL`, rows top first.
fn read_cube(ctx: &GpuContext, texture: &wgpu::Texture) -> Vec<Image<f32>> {
    let n = texture.width();
    let device = &ctx.device;
    let atlas = map_texture(
        ctx,
        (6 * n, n, 1),
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("envmap test cube reader"),
        source: wgpu::ShaderSource::Wgsl(CUBE_READER.into()),
    });
    let compute = wgpu::ShaderStages::COMPUTE;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("envmap test cube reader"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: compute,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::Cube,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: compute,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering),
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: compute,
                ty: wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format: wgpu::TextureFormat::Rgba32Float,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
                count: None,
            },
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("envmap test cube reader"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("envmap test cube reader"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("envmap test nearest"),
        ..Default::default()
    });
    let cube_view = texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::Cube),
        ..Default::default()
    });
    let atlas_view = atlas.create_view(&Default::default());
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("envmap test cube reader"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&cube_view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&sampler),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&atlas_view),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups((6 * n).div_ceil(8), n.div_ceil(8), 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let all = read_layer(ctx, &atlas, 0);
    (0..6)
        .map(|face| Image {
            width: n,
            height: n,
            pixels: all
                .pixels
                .chunks_exact(4 * 6 * n as usize)
                .flat_map(|row| row[(4 * face * n) as usize..(4 * (face + 1) * n) as usize].to_vec())
                .collect(),
        })
        .collect()
}

/// The largest difference between `got` and `want`, relative to `floor` or the value if larger,
/// and where.
fn worst_relative(got: &Image<f32>, want: &Image<f32>, floor: f32) -> (f32, usize) {
    assert_eq!((got.width, got.height), (want.width, want.height));
    got.pixels
        .iter()
        .zip(&want.pixels)
        .map(|(g, w)| (g - w).abs() / w.abs().max(floor))
        .enumerate()
        .map(|(k, e)| (e, k))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// The six GPU layers, with the disc (Rgba32Float) and without (Rgba16Float), sampled as a cube
/// at each texel's direction, are `render_cube_faces`' faces texel for texel: both come from the
/// same half-float HDR images and add the same pieces in the same order.
#[test]
fn the_gpu_cube_is_the_cpu_cube() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let sky = street_sky(100.0, 30.0);
    let frame = street_frame(&sky);
    let size = 16;
    let mut pass = EnvironmentMapPass::new(ctx);
    for (format, discs) in [
        (wgpu::TextureFormat::Rgba32Float, SunDiscs::Included),
        (wgpu::TextureFormat::Rgba16Float, SunDiscs::Omitted),
    ] {
        let cpu = renderer.render_cube_faces(ctx, &frame, size, discs).expect("render");
        let target = map_texture(ctx, (size, size, 6), format, TARGET_USAGE);
        pass.render_cube(ctx, renderer, &frame, &target, discs).expect("render");
        let layers = read_cube(ctx, &target);
        let mut peak: f32 = 0.0;
        for face in CubeFace::ALL {
            let got = &layers[face.index()];
            let want = cpu.face(face);
            peak = peak.max(got.pixels.iter().copied().fold(0.0, f32::max));
            let (error, at) = worst_relative(got, want, 1e-6);
            println!("{format:?} {discs:?} {face:?}: worst relative difference {error:e} at {at}");
            // Half-float rounding of the HDR target would be 2⁻¹¹; the paths agree far closer.
            assert!(
                error <= 1e-6,
                "{face:?}: {error} at {at}: {} vs {}",
                got.pixels[at],
                want.pixels[at]
            );
        }
        if discs == SunDiscs::Included {
            assert!(peak > firmament_render::HDR_MAX * 10.0, "the disc: {peak}");
        }
    }
}

/// The GPU's equirectangular map is `render_equirect`'s within f32 resampling (the GPU finds the
/// sample positions in `f32`, the CPU in `f64`), the disc included.
#[test]
fn the_gpu_equirect_is_the_cpu_equirect() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let sky = street_sky(100.0, 30.0);
    let frame = street_frame(&sky);
    let width = 64;
    let cpu = renderer
        .render_equirect(ctx, &frame, width, SunDiscs::Included)
        .expect("render");
    let target = map_texture(
        ctx,
        (width, width / 2, 1),
        wgpu::TextureFormat::Rgba32Float,
        TARGET_USAGE,
    );
    let mut pass = EnvironmentMapPass::new(ctx);
    pass.render_equirect(ctx, renderer, &frame, &target, SunDiscs::Included)
        .expect("render");
    let got = read_layer(ctx, &target, 0);
    let (error, at) = worst_relative(&got, &cpu, 1e-3);
    println!("equirect: worst relative difference {error:e} at {at}");
    assert!(
        error < 1e-4,
        "{error} at {at}: {} vs {}",
        got.pixels[at],
        cpu.pixels[at]
    );
}

/// The GPU map's disc carries the sun's irradiance after the air: the map with the disc less the
/// map without, `Σ ΔL·dω`, against `E·T` (sun 30° up, 128 × 64).
#[test]
fn the_gpu_disc_carries_the_suns_irradiance() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let sky = street_sky(100.0, 30.0);
    let frame = street_frame(&sky);
    let width = 128;
    let mut pass = EnvironmentMapPass::new(ctx);
    let mut map = |discs| {
        let target = map_texture(
            ctx,
            (width, width / 2, 1),
            wgpu::TextureFormat::Rgba32Float,
            TARGET_USAGE,
        );
        pass.render_equirect(ctx, renderer, &frame, &target, discs)
            .expect("render");
        read_layer(ctx, &target, 0)
    };
    let (with, without) = (map(SunDiscs::Included), map(SunDiscs::Omitted));
    let sun = sun_at_eye(&sky.atmosphere, &[], &[], &sky.suns[0], frame.camera.position);
    let want = DVec3::new(sun.irradiance_rgb.r, sun.irradiance_rgb.g, sun.irradiance_rgb.b);
    let got = total_irradiance(&with) - total_irradiance(&without);
    let error = relative(got, want);
    println!("GPU disc: map {got:.1} lux, E·T {want:.1} lux: relative {error:.6}");
    assert!(error.abs().max_element() < 0.01, "{error}");
}

/// A target the pass must refuse: its size (width, height, layers), format and usage, the discs
/// asked for, and words of the rule its message must name.
type BadTarget = (
    (u32, u32, u32),
    wgpu::TextureFormat,
    wgpu::TextureUsages,
    SunDiscs,
    &'static str,
);

/// Targets the pass cannot fill are refused with the rule they break, before anything is drawn.
#[test]
fn bad_targets_are_refused_with_their_rule() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let frame = street_frame(&street_sky(100.0, 30.0));
    let mut pass = EnvironmentMapPass::new(ctx);
    let f16 = wgpu::TextureFormat::Rgba16Float;
    let f32 = wgpu::TextureFormat::Rgba32Float;
    let cube_cases: &[BadTarget] = &[
        (
            (16, 16, 6),
            f16,
            TARGET_USAGE,
            SunDiscs::Included,
            "SunDiscs::Included needs Rgba32Float",
        ),
        (
            (16, 16, 3),
            f32,
            TARGET_USAGE,
            SunDiscs::Omitted,
            "exactly 6 array layers",
        ),
        ((16, 8, 6), f32, TARGET_USAGE, SunDiscs::Omitted, "must be square"),
        (
            (16, 16, 6),
            wgpu::TextureFormat::Rgba8Unorm,
            TARGET_USAGE,
            SunDiscs::Omitted,
            "Rgba16Float or Rgba32Float",
        ),
        (
            (16, 16, 6),
            f32,
            wgpu::TextureUsages::TEXTURE_BINDING,
            SunDiscs::Omitted,
            "COPY_DST",
        ),
    ];
    for &(size, format, usage, discs, rule) in cube_cases {
        let target = map_texture(ctx, size, format, usage);
        let error = pass
            .render_cube(ctx, renderer, &frame, &target, discs)
            .expect_err("refused");
        let message = error.to_string();
        assert!(matches!(error, RenderError::EnvironmentMapTarget(_)), "{message}");
        assert!(message.contains(rule), "{size:?} {format:?}: {message}");
    }
    for (size, rule) in [
        ((64, 64, 1), "half of it"),
        ((64, 32, 6), "exactly 1 layer"),
        ((2, 1, 1), "at least 4"),
    ] {
        let target = map_texture(ctx, size, f32, TARGET_USAGE);
        let error = pass
            .render_equirect(ctx, renderer, &frame, &target, SunDiscs::Omitted)
            .expect_err("refused");
        assert!(error.to_string().contains(rule), "{size:?}: {error}");
    }
}
