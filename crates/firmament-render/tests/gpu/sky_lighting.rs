//! GPU tests of the sky lighting for users' own materials (`AtmospherePass::sky_lighting_buffer`,
//! read by `shaders::FIRMAMENT_LIGHTING_WGSL`): the spherical-harmonic sky irradiance against the
//! f64 reference path tracer and against the GPU's own sky, the suns' colours against the
//! reference transmittance, and a user's shader that includes the WGSL file.

use crate::support::{Gpu, direction, gpu};

use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::atmosphere::{Atmosphere, Planet, Sun, presets};
use firmament_core::classic::sky_light::SkyLight;
use firmament_core::color::LinearRgb;
use firmament_core::envmap::{CubeFace, cube_direction, cube_texel_solid_angle};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::{Camera, Frame};
use firmament_render::GpuContext;
use firmament_render::envmap::SunDiscs;
use firmament_render::gpu_types::SkyLightingGpu;
use firmament_render::gpu_types::sky_lighting::{SKY_SH_COEFFICIENTS, sh_basis, sh_irradiance};
use firmament_render::passes::AtmospherePass;
use firmament_render::passes::atmosphere::sky_lighting_layout_entry;
use firmament_render::readback::read_buffer;
use firmament_render::shaders::firmament_lighting_wgsl;
use glam::DVec3;

/// Bruneton's 6360 km sphere with the `earth` medium, posed so the world is ENU at
/// (`latitude`, `longitude`) — so the planet frame is not the world frame.
fn earth_sphere(latitude: f64, longitude: f64) -> Atmosphere {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0).posed_at(latitude.to_radians(), longitude.to_radians());
    atmosphere
}

/// The Sun at (`azimuth`, `elevation`) degrees.
fn sun(azimuth: f64, elevation: f64) -> Sun {
    presets::earth_sun(direction(azimuth, elevation))
}

/// A camera at `position` looking along `view` with a 90° square field of view (a cube face).
fn camera(position: DVec3, view: DVec3) -> Camera {
    let camera = Camera::looking_at(position, position + view, DVec3::Z)
        .or_else(|| Camera::looking_at(position, position + view, DVec3::Y))
        .expect("a view direction");
    Camera {
        fov_y: std::f64::consts::FRAC_PI_2,
        aspect: 1.0,
        ..camera
    }
}

/// The camera 1.7 m above the ground, looking north.
fn street_camera() -> Camera {
    camera(DVec3::new(0.0, 0.0, 1.7), DVec3::Y)
}

/// The lighting buffer after one frame of `sky` seen by `camera`.
fn lighting(ctx: &GpuContext, pass: &mut AtmospherePass, sky: &AtmosphereSky, camera: &Camera) -> SkyLightingGpu {
    pass.prepare(&ctx.queue, sky, camera);
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    pass.record_luts(&mut encoder);
    ctx.queue.submit([encoder.finish()]);
    let size = std::mem::size_of::<SkyLightingGpu>() as u64;
    let bytes = read_buffer(ctx, pass.sky_lighting_buffer(), size).expect("readback");
    SkyLightingGpu::from_bytes(&bytes).expect("the whole buffer")
}

fn rgb(c: LinearRgb) -> DVec3 {
    DVec3::new(c.r, c.g, c.b)
}

/// Relative difference of two colours: the largest channel difference over the largest channel.
fn relative_difference(got: DVec3, want: DVec3) -> f64 {
    (got - want).abs().max_element() / want.abs().max_element().max(1e-30)
}

/// Monte Carlo paths of each of the two reference estimates (two seeds) of the sky irradiance.
const REFERENCE_PATHS: usize = 65_536;

/// The largest relative difference of one channel.
fn channel_difference(got: DVec3, want: DVec3) -> f64 {
    ((got - want).abs() / want.abs().max(DVec3::splat(1e-30))).max_element()
}

/// (a) The irradiance of the up normal on the ground from the spherical harmonics (evaluated in
/// f64 on the read-back coefficients) against the reference path tracer's sky irradiance on a
/// horizontal surface, both in linear sRGB (lux). The reference is the mean of two seeds, its
/// noise half their difference. Printed apart: the exact cosine integral of the sky the GPU
/// draws (a cube map) against the reference — the sky-view LUT's own error —, and the harmonics
/// against that integral — bands 0–2's error, the cosine lobe they represent leaking a little of
/// the lit ground below the horizon into an upward normal.
#[test]
fn sky_irradiance_on_the_ground_matches_the_reference() {
    let mut gpu = gpu();
    let mut pass = AtmospherePass::new(&gpu.ctx.device);
    let camera = street_camera();
    let (mut worst, mut worst_channel): (f64, f64) = (0.0, 0.0);
    for elevation in [60.0, 20.0, 3.0] {
        let atmosphere = earth_sphere(0.0, 0.0);
        let sky = AtmosphereSky {
            atmosphere: atmosphere.clone(),
            suns: vec![Sun {
                disc: false,
                from_body: None,
                ..sun(90.0, elevation)
            }],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let got = lighting(&gpu.ctx, &mut pass, &sky, &camera).sky_irradiance(DVec3::Z);
        let conversion = atmosphere.spectral_conversion();
        let reference = |seed| {
            let settings = ReferenceSettings {
                paths: REFERENCE_PATHS,
                seed,
                ..ReferenceSettings::default()
            };
            let irradiance = Reference::new(atmosphere.clone(), &sky.suns, settings).ground_irradiance(camera.position);
            rgb(conversion.linear_srgb(irradiance.sky))
        };
        let (a, b) = (reference(ReferenceSettings::default().seed), reference(7));
        let want = 0.5 * (a + b);
        let noise = 0.5 * relative_difference(a, b);
        let exact = cube_irradiance(&render_cube(&mut gpu, &sky, camera.position), DVec3::Z);
        let error = relative_difference(got, want);
        let channel_error = channel_difference(got, want);
        println!(
            "sun {elevation:4.1}° up: sky irradiance gpu {got:.1} reference {want:.1} lux (noise ±{:.2} %): \
             error {:.2} % of the largest channel, {:.2} % per channel; of which the sky drawn {:+.2} % {:+.2} % {:+.2} %, \
             bands 0-2 {:+.2} % {:+.2} % {:+.2} %",
            100.0 * noise,
            100.0 * error,
            100.0 * channel_error,
            100.0 * (exact.x / want.x - 1.0),
            100.0 * (exact.y / want.y - 1.0),
            100.0 * (exact.z / want.z - 1.0),
            100.0 * (got.x / exact.x - 1.0),
            100.0 * (got.y / exact.y - 1.0),
            100.0 * (got.z / exact.z - 1.0),
        );
        worst = worst.max(error);
        worst_channel = worst_channel.max(channel_error);
    }
    println!(
        "worst {:.2} % of the largest channel, {:.2} % per channel",
        100.0 * worst,
        100.0 * worst_channel
    );
    // Measured 5.7 % and 8.5 % (sun 3° up): the sky the sky-view LUT draws is within 1.4 % of
    // the reference (docs/ATMOSPHERE.md), bands 0-2 add 0.3-9 % (red most: the lit ground's
    // light leaks into the band-limited cosine lobe), the reference's noise is ±1 %. The budget
    // was 5 % and 7 % while the sky ran 1-4 % low and cancelled part of the bands' excess, and
    // 6 % and 8 % until the reference's sky irradiance took the same random numbers at every
    // point (its 3° value moved by 0.9 %, within its noise).
    assert!(worst < 0.06, "worst {:.2} % of the largest channel", 100.0 * worst);
    assert!(worst_channel < 0.09, "worst {:.2} % per channel", 100.0 * worst_channel);
}

/// (c) Each sun's colour at the camera, `E·T`, against the reference transmittance
/// (`SkyLight::sun_colors`, which is `E·T/π`), and its world direction.
#[test]
fn sun_colors_match_the_reference() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let mut pass = AtmospherePass::new(&ctx.device);
    let camera = street_camera();
    let mut worst: f64 = 0.0;
    for (latitude, elevation) in [(0.0, 60.0), (0.0, 20.0), (0.0, 3.0), (45.0, 20.0)] {
        let sky = AtmosphereSky {
            atmosphere: earth_sphere(latitude, 30.0),
            suns: vec![sun(120.0, elevation), sun(250.0, 40.0)],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let got = lighting(ctx, &mut pass, &sky, &camera);
        assert_eq!(got.sun_count(), 2);
        let light = SkyLight::new(&sky);
        for (i, want) in light.sun_colors(camera.position).iter().enumerate() {
            let want = want.truncate() * std::f64::consts::PI;
            let error = relative_difference(got.sun_color(i), want);
            let direction_error = (got.sun_direction(i) - sky.suns[i].direction).length();
            println!(
                "latitude {latitude}°, sun {i} ({elevation}° up): E·T gpu {:.1} reference {want:.1} lux, error {:.3} %, \
                 direction off by {direction_error:.1e}",
                got.sun_color(i),
                100.0 * error
            );
            assert!(direction_error < 1e-6, "sun {i} direction {}", got.sun_direction(i));
            worst = worst.max(error);
        }
        assert_eq!(got.suns[2..], [Default::default(); 6][..], "unused suns are zero");
    }
    println!("worst {:.3} %", 100.0 * worst);
    assert!(worst < 0.01, "worst {:.2} %", 100.0 * worst);
}

/// Cube-face pixels per side for the sky the projection is checked against.
const FACE: u32 = 128;

/// One pixel of a cube map: its world direction, solid angle and linear sRGB radiance (cd/m²).
struct CubePixel {
    direction: DVec3,
    solid_angle: f64,
    radiance: DVec3,
}

/// The GPU's own sky around `position`: its cube faces (`render_cube_faces`, no sun discs),
/// each texel with its direction and exact solid angle.
fn render_cube(gpu: &mut Gpu, sky: &AtmosphereSky, position: DVec3) -> Vec<CubePixel> {
    let Gpu { ctx, renderer } = gpu;
    let frame = Frame::new(camera(position, DVec3::Y), Sky::Atmosphere(sky.clone()));
    let cube = renderer
        .render_cube_faces(ctx, &frame, FACE, SunDiscs::Omitted)
        .expect("render");
    let mut pixels = Vec::new();
    for face in CubeFace::ALL {
        let image = cube.face(face);
        for y in 0..FACE {
            for x in 0..FACE {
                let p = image.pixel(x, y).expect("inside");
                pixels.push(CubePixel {
                    direction: cube_direction(face, f64::from(x) + 0.5, f64::from(y) + 0.5, FACE),
                    solid_angle: cube_texel_solid_angle(x, y, FACE),
                    radiance: DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])),
                });
            }
        }
    }
    let total: f64 = pixels.iter().map(|p| p.solid_angle).sum();
    assert!((total / (4.0 * std::f64::consts::PI) - 1.0).abs() < 1e-9, "{total} sr");
    pixels
}

/// The spherical-harmonic projection of a cube map, in f64.
fn project(pixels: &[CubePixel]) -> [DVec3; SKY_SH_COEFFICIENTS] {
    let mut sh = [DVec3::ZERO; SKY_SH_COEFFICIENTS];
    for p in pixels {
        for (c, basis) in sh.iter_mut().zip(sh_basis(p.direction)) {
            *c += p.radiance * (basis * p.solid_angle);
        }
    }
    sh
}

/// The exact irradiance of a cube map on unit normal `n`: `∫ L·max(n·ω, 0) dω`.
fn cube_irradiance(pixels: &[CubePixel], n: DVec3) -> DVec3 {
    pixels
        .iter()
        .map(|p| p.radiance * (p.direction.dot(n).max(0.0) * p.solid_angle))
        .sum()
}

/// Unit normals to compare irradiance on: the axes and the cube's diagonals.
fn normals() -> Vec<DVec3> {
    let mut normals = vec![DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z];
    for x in [-1.0, 1.0] {
        for y in [-1.0, 1.0] {
            for z in [-1.0, 1.0] {
                normals.push(DVec3::new(x, y, z).normalize());
            }
        }
    }
    normals
}

/// (b) The GPU's projection against an f64 projection of the sky the GPU draws (same LUT, same
/// conversion): the irradiance on 14 normals, relative to the largest.
#[test]
fn the_projection_matches_the_sky_the_gpu_draws() {
    let mut gpu = gpu();
    let mut pass = AtmospherePass::new(&gpu.ctx.device);
    let no_disc = |s: Sun| Sun { disc: false, ..s };
    let cases = [
        (
            "street at 45° N, suns 35° and 12° up",
            earth_sphere(45.0, 30.0),
            vec![no_disc(sun(100.0, 35.0)), no_disc(sun(230.0, 12.0))],
            DVec3::new(0.0, 0.0, 1.7),
        ),
        (
            "mountain, sun 4° up",
            earth_sphere(0.0, 0.0),
            vec![no_disc(sun(300.0, 4.0))],
            DVec3::new(0.0, 0.0, 3_000.0),
        ),
        (
            "orbit 400 km up, sun 30° up",
            earth_sphere(0.0, 0.0),
            vec![no_disc(sun(90.0, 30.0))],
            DVec3::new(0.0, 0.0, 400_000.0),
        ),
    ];
    let mut worst: f64 = 0.0;
    for (name, atmosphere, suns, position) in cases {
        let sky = AtmosphereSky {
            atmosphere: atmosphere.clone(),
            suns,
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let got = lighting(&gpu.ctx, &mut pass, &sky, &camera(position, DVec3::Y)).sky_sh();
        let want = project(&render_cube(&mut gpu, &sky, position));
        let irradiance: Vec<(DVec3, DVec3)> = normals()
            .into_iter()
            .map(|n| (sh_irradiance(&got, n), sh_irradiance(&want, n)))
            .collect();
        let scale = irradiance.iter().map(|(_, w)| w.max_element()).fold(0.0, f64::max);
        let error = irradiance
            .iter()
            .map(|(g, w)| (*g - *w).abs().max_element() / scale)
            .fold(0.0, f64::max);
        println!(
            "{name}: irradiance up {:.1} vs {:.1}, down {:.1} vs {:.1} lux; worst of 14 normals {:.3} % of the largest",
            irradiance[4].0,
            irradiance[4].1,
            irradiance[5].0,
            irradiance[5].1,
            100.0 * error
        );
        worst = worst.max(error);
    }
    println!("worst {:.3} %", 100.0 * worst);
    assert!(worst < 0.01, "worst {:.2} %", 100.0 * worst);
}

/// A user's compute shader that includes `firmament_lighting_wgsl` (its buffer at group 0,
/// binding 0, laid out by `sky_lighting_layout_entry`) reads what the Rust side reads.
#[test]
fn a_user_shader_reads_the_lighting() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let mut pass = AtmospherePass::new(&ctx.device);
    let sky = AtmosphereSky {
        atmosphere: earth_sphere(45.0, 30.0),
        suns: vec![sun(120.0, 25.0), sun(250.0, 8.0)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    let expected = lighting(ctx, &mut pass, &sky, &street_camera());
    let normals = normals();
    let user = r"
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;

const NORMALS: u32 = 14u;

@compute @workgroup_size(1)
fn cs_main() {
    for (var i = 0u; i < NORMALS; i++) {
        let n = results[i].xyz;
        results[NORMALS + i] = vec4<f32>(firmament_sky_irradiance(n), 0.0);
        results[2u * NORMALS + i] = vec4<f32>(firmament_irradiance(n), 0.0);
    }
    for (var i = 0u; i < firmament_sun_count(); i++) {
        results[3u * NORMALS + 2u * i] = vec4<f32>(firmament_sun_direction(i), f32(firmament_sun_count()));
        results[3u * NORMALS + 2u * i + 1u] = vec4<f32>(firmament_sun_color(i), 0.0);
    }
}
";
    let source = format!("{}\n{user}", firmament_lighting_wgsl(0, 0));
    let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("test user shader"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("test user layout"),
        entries: &[
            sky_lighting_layout_entry(0),
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    });
    let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("test user pipeline"),
        layout: Some(&ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("test user pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        })),
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let slots = 3 * normals.len() + 2 * firmament_core::frame::MAX_SUNS;
    let mut input = vec![[0.0f32; 4]; slots];
    for (slot, n) in input.iter_mut().zip(&normals) {
        *slot = [n.x as f32, n.y as f32, n.z as f32, 0.0];
    }
    let results = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test user results"),
        size: (slots * 16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    ctx.queue.write_buffer(&results, 0, bytemuck::cast_slice(&input));
    let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("test user bind group"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: pass.sky_lighting_buffer().as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: results.as_entire_binding(),
            },
        ],
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    {
        let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        compute.set_pipeline(&pipeline);
        compute.set_bind_group(0, &bind_group, &[]);
        compute.dispatch_workgroups(1, 1, 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let bytes = read_buffer(ctx, &results, (slots * 16) as u64).expect("readback");
    let got: Vec<DVec3> = bytemuck::cast_slice::<u8, [f32; 4]>(&bytes)
        .iter()
        .map(|v| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .collect();
    let close = |got: DVec3, want: DVec3, scale: f64, what: &str| {
        assert!(
            (got - want).abs().max_element() <= 1e-5 * scale,
            "{what}: shader {got} vs rust {want}"
        );
    };
    let scale = normals
        .iter()
        .map(|n| expected.sky_irradiance(*n).max_element())
        .fold(0.0, f64::max);
    let count = expected.sun_count();
    assert_eq!(count, 2);
    for (i, n) in normals.iter().enumerate() {
        close(
            got[normals.len() + i],
            expected.sky_irradiance(*n),
            scale,
            "sky irradiance",
        );
        let mut all = expected.sky_irradiance(*n);
        for s in 0..count {
            all += expected.sun_color(s) * n.dot(expected.sun_direction(s)).max(0.0);
        }
        close(got[2 * normals.len() + i], all, all.max_element(), "irradiance");
    }
    for s in 0..count {
        let base = 3 * normals.len() + 2 * s;
        close(got[base], expected.sun_direction(s), 1.0, "sun direction");
        assert_eq!(bytemuck::cast_slice::<u8, [f32; 4]>(&bytes)[base][3], count as f32);
        close(
            got[base + 1],
            expected.sun_color(s),
            expected.sun_color(s).max_element(),
            "sun colour",
        );
    }
}

/// Without suns everything is zero, also after a lit frame.
#[test]
fn no_suns_give_no_light() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let mut pass = AtmospherePass::new(&ctx.device);
    let lit = AtmosphereSky {
        atmosphere: earth_sphere(0.0, 0.0),
        suns: vec![sun(0.0, 30.0)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    let camera = street_camera();
    assert_eq!(lighting(ctx, &mut pass, &lit, &camera).sun_count(), 1);
    let dark = AtmosphereSky {
        suns: vec![],
        ..lit.clone()
    };
    assert_eq!(lighting(ctx, &mut pass, &dark, &camera), SkyLightingGpu::default());
}

/// From beyond `FAR_CAMERA_RADII` top radii the sky gives no light; the sun still does, through
/// no air.
#[test]
fn a_far_camera_gets_sunlight_only() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let mut pass = AtmospherePass::new(&ctx.device);
    let sky = AtmosphereSky {
        atmosphere: earth_sphere(0.0, 0.0),
        suns: vec![sun(90.0, 30.0)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    let au = 1.495_978_707e11;
    let got = lighting(ctx, &mut pass, &sky, &camera(DVec3::new(0.0, 0.0, au), DVec3::Y));
    assert_eq!(got.sky_sh, [[0.0; 4]; SKY_SH_COEFFICIENTS]);
    let outside = rgb(sky.atmosphere.spectral_conversion().linear_srgb(sky.suns[0].irradiance));
    println!("E from 1 AU: {} vs {outside} lux", got.sun_color(0));
    assert!(relative_difference(got.sun_color(0), outside) < 1e-5);
}
