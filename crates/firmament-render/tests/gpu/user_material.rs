//! GPU test of a user's material that includes both WGSL files for users' shaders
//! (`firmament_lighting_wgsl` and `firmament_aerial_perspective_wgsl`): a white Lambertian
//! surface at a known normal and distance must come out as
//! `1/π · (Σ E·T_sun · max(n·l, 0) + E_sky(n)) · T + S`, its lighting exactly what the read-back
//! lighting buffer gives in `f64`, and T and S as the `f64` reference integrator's
//! (`Reference::radiance_before`, as in `aerial_perspective.rs`).

use crate::support::{direction, gpu, sky_reference, street_sky};

use firmament_core::Camera;
use firmament_core::geometry::Ray;
use firmament_render::SkyLightingGpu;
use firmament_render::passes::AtmospherePass;
use firmament_render::passes::atmosphere::{aerial_perspective_layout_entries, sky_lighting_layout_entry};
use firmament_render::readback::read_buffer;
use firmament_render::shaders::{firmament_aerial_perspective_wgsl, firmament_lighting_wgsl};
use glam::DVec3;

/// A camera at `position` looking along `view`, with a narrow field of view.
fn camera(position: DVec3, view: DVec3) -> Camera {
    let camera = Camera::looking_at(position, position + view, DVec3::Z).expect("a view direction");
    Camera {
        fov_y: 0.5_f64.to_radians(),
        aspect: 1.0,
        ..camera
    }
}

/// The user's shader: for each surface (normal, distance) of `surfaces`, seen at the centre of
/// the screen, a white Lambertian material's radiance, then that radiance through the air, the
/// air's scattered light alone (black surface) and its transmittance.
const USER_SHADER: &str = r"
struct Surface {
    normal: vec4<f32>, // xyz unit world normal; w = distance from the camera (m)
}

@group(0) @binding(6) var<storage, read> surfaces: array<Surface>;
@group(0) @binding(7) var<storage, read_write> results: array<vec4<f32>>;

@compute @workgroup_size(1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let surface = surfaces[id.x];
    let n = surface.normal.xyz;
    let ndc = vec2<f32>(0.0, 0.0);
    let albedo = vec3<f32>(1.0);
    var e = firmament_sky_irradiance(n);
    for (var i = 0u; i < firmament_sun_count(); i++) {
        e += firmament_sun_color(i) * max(dot(n, firmament_sun_direction(i)), 0.0);
    }
    let lit = albedo / 3.14159265 * e;
    let air = firmament_aerial_perspective(ndc, surface.normal.w);
    results[4u * id.x] = vec4<f32>(lit, 0.0);
    results[4u * id.x + 1u] = vec4<f32>(firmament_apply_aerial_perspective(lit, ndc, surface.normal.w), 0.0);
    results[4u * id.x + 2u] = vec4<f32>(firmament_apply_aerial_perspective(vec3<f32>(0.0), ndc, surface.normal.w), 0.0);
    results[4u * id.x + 3u] = vec4<f32>(air.transmittance, 0.0);
}
";

fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn rgb(v: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

#[test]
fn a_white_lambertian_surface_is_lit_and_fogged_as_the_reference() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let device = &ctx.device;
    let sky = street_sky(90.0, 25.0);
    let reference = sky_reference(&sky, 4096);
    let conversion = sky.atmosphere.spectral_conversion();
    let pass = AtmospherePass::new(device);

    // The user's pipeline: firmament's lighting at binding 0, its aerial perspective at 1 … 5,
    // the user's own buffers at 6 and 7, all in group 0.
    let source = format!(
        "{}\n{}\n{USER_SHADER}",
        firmament_lighting_wgsl(0, 0),
        firmament_aerial_perspective_wgsl(0, 1)
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("test user material"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let mut entries = vec![sky_lighting_layout_entry(0)];
    entries.extend(aerial_perspective_layout_entries(1));
    entries.extend([storage_entry(6, true), storage_entry(7, false)]);
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("test user material layout"),
        entries: &entries,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("test user material"),
        layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("test user material"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        })),
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let normals_per_case = 3;
    let surfaces = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test surfaces"),
        size: (normals_per_case * 16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let results_size = (normals_per_case * 4 * 16) as u64;
    let results = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test results"),
        size: results_size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut bind_entries = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: pass.sky_lighting_buffer().as_entire_binding(),
    }];
    bind_entries.extend(pass.aerial_perspective_bindings().bind_group_entries(1));
    bind_entries.extend([
        wgpu::BindGroupEntry {
            binding: 6,
            resource: surfaces.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 7,
            resource: results.as_entire_binding(),
        },
    ]);
    // One bind group for every frame: the pass's buffers and textures are its own for life.
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("test user material"),
        layout: &layout,
        entries: &bind_entries,
    });

    let mut pass = pass;
    let (mut worst_lighting, mut worst_s, mut worst_t, mut worst_total) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for (height, view_elevation) in [(2.0, 1.0), (3_000.0, -3.0)] {
        for (azimuth, distance) in [(0.0, 700.0), (60.0, 5_000.0), (270.0, 20_000.0)] {
            let eye = DVec3::Z * height;
            let view = direction(azimuth, view_elevation);
            let camera = camera(eye, view);
            // Up, facing the camera, and facing the sun's side.
            let normals = [DVec3::Z, -view, direction(90.0, 10.0)];
            let input: Vec<[f32; 4]> = normals
                .iter()
                .map(|n| [n.x as f32, n.y as f32, n.z as f32, distance as f32])
                .collect();
            pass.prepare(&ctx.queue, &sky, &camera);
            ctx.queue.write_buffer(&surfaces, 0, bytemuck::cast_slice(&input));
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
            // The frame's lighting and volume, then the user's work.
            pass.record_luts(&mut encoder);
            pass.record_aerial_perspective_volume(&mut encoder);
            {
                let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
                compute.set_pipeline(&pipeline);
                compute.set_bind_group(0, &bind_group, &[]);
                compute.dispatch_workgroups(normals_per_case as u32, 1, 1);
            }
            ctx.queue.submit([encoder.finish()]);
            let bytes = read_buffer(ctx, &results, results_size).expect("readback");
            let got: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
            let size = std::mem::size_of::<SkyLightingGpu>() as u64;
            let lighting =
                SkyLightingGpu::from_bytes(&read_buffer(ctx, pass.sky_lighting_buffer(), size).expect("readback"))
                    .expect("the whole buffer");

            let want = reference.radiance_before(
                &Ray {
                    origin: eye,
                    direction: view,
                },
                distance,
            );
            let s = conversion.linear_srgb(want.scattered());
            let want_s = DVec3::new(s.r, s.g, s.b);
            let want_t = want.transmittance;
            let want_t = DVec3::new(want_t.x, want_t.y, want_t.z);
            for (k, n) in normals.iter().enumerate() {
                let mut e = lighting.sky_irradiance(*n);
                for i in 0..lighting.sun_count() {
                    e += lighting.sun_color(i) * n.dot(lighting.sun_direction(i)).max(0.0);
                }
                let want_lit = e / std::f64::consts::PI;
                let lit = rgb(got[4 * k]);
                let total = rgb(got[4 * k + 1]);
                let scattered = rgb(got[4 * k + 2]);
                let transmittance = rgb(got[4 * k + 3]);
                let want_total = want_lit * want_t + want_s;
                let lighting_error = (lit - want_lit).abs().max_element() / want_lit.max_element();
                let s_error = (scattered - want_s).abs().max_element() / want_s.max_element();
                let t_error = (transmittance - want_t).abs().max_element();
                let total_error = (total - want_total).abs().max_element() / want_total.max_element();
                // The function's own pieces agree: colour · T + S.
                let pieces = lit * transmittance + scattered;
                assert!(
                    (total - pieces).abs().max_element() <= 1e-5 * total.max_element(),
                    "apply {total} vs pieces {pieces}"
                );
                println!(
                    "h {height} m, view ({azimuth}°, {view_elevation}°), {distance} m, n {n:.2}: \
                     out {total:.2} vs {want_total:.2} ({:.2} %); lit {lit:.2} (f64 {:.1e}); \
                     S {scattered:.2} vs {want_s:.2} ({:.2} %); T {transmittance:.4} vs {want_t:.4}",
                    100.0 * total_error,
                    lighting_error,
                    100.0 * s_error
                );
                worst_lighting = worst_lighting.max(lighting_error);
                worst_s = worst_s.max(s_error);
                worst_t = worst_t.max(t_error);
                worst_total = worst_total.max(total_error);
            }
        }
    }
    println!(
        "worst: surface radiance {:.2} %, lighting vs f64 on the buffer {worst_lighting:.1e}, \
         scattered light {:.2} %, transmittance {worst_t:.4} absolute",
        100.0 * worst_total,
        100.0 * worst_s
    );
    assert!(worst_lighting < 1e-5, "lighting off by {worst_lighting:e}");
    // aerial_perspective.rs's budgets: 6 % for the scattered light (the multiple-scattering
    // model's error), 3·10⁻³ for the transmittance; the total inherits them.
    assert!(worst_s < 0.06, "scattered light off by {:.1} %", 100.0 * worst_s);
    assert!(worst_t < 3e-3, "transmittance off by {worst_t}");
    assert!(
        worst_total < 0.06,
        "surface radiance off by {:.1} %",
        100.0 * worst_total
    );
}
