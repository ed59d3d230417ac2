//! GPU test of the cloud density field: `cloud_density` and `cloud_density_with_coverage` of
//! `shaders/clouds/density.wgsl`, fed `CloudsGpu::new`'s uniforms, against the core's `f64`
//! `CloudLayer::density_at_altitude` and `density_with_coverage` at the same points and altitudes
//! — every kind, several seeds and drifts (none, an hour's and a day's wind, a radian), on an
//! Earth-sized sphere and on the WGS 84 ellipsoid, with points at ground level.
//!
//! The shader is handed each point rounded to `f32` and the core that rounded point, so both
//! evaluate the same field at the same place. The shader never rounds the pattern point `R·p`
//! (it keeps it as exact products plus a small rest, see its header) and splits it into lattice
//! cells exactly, so no lattice boundary can fall differently; what is left is `f32` rounding in
//! the rest (~1e-4 m), in the noise and in the profile. The field is continuous everywhere (zero
//! at its shells and at the edges of covered columns; the uniform slab gets the same `h` on both
//! sides), so that rounding moves a value by ~1e-5 of the layer's density at most (llvmpipe:
//! median 3e-8, worst 1.5e-5). Asserted: 99 % of the points within 1e-4 of `density_per_m`,
//! every point within 1e-3.

use crate::support::gpu;

use firmament_core::atmosphere::Planet;
use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer, MAX_CLOUD_LAYERS, wind_drift};
use firmament_render::gpu_types::CloudsGpu;
use firmament_render::readback::read_buffer;
use firmament_render::shaders::CLOUD_DENSITY;
use glam::Vec3;

/// The kernel: for point `i`, `points[2i] = (p, h)` and `points[2i + 1] = (layer, coverage,
/// evaluation, …)`; a negative coverage means the layer's own (`cloud_density`); evaluation 1
/// asks for the average over columns at `h` (`cloud_mean_density_with_coverage`, `p` unused), 2
/// for the layer's tabulated average at its own coverage (`cloud_mean_density`), 3 for the share
/// of rays crossing `h` metres along the ground that meet cloud (`cloud_cover_seen`).
const KERNEL: &str = r"
@group(0) @binding(0) var<uniform> clouds: CloudsGpu;
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> densities: array<f32>;

@compute @workgroup_size(64)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&densities) {
        return;
    }
    let point = points[2u * i];
    let extra = points[2u * i + 1u];
    let layer = clouds.layers[min(u32(extra.x), MAX_CLOUD_LAYERS - 1u)];
    if extra.z > 2.5 {
        densities[i] = cloud_cover_seen(layer, extra.y, point.w);
    } else if extra.z > 1.5 {
        densities[i] = cloud_mean_density(layer, point.w);
    } else if extra.z > 0.5 {
        densities[i] = cloud_mean_density_with_coverage(layer, point.w, select(extra.y, layer.coverage.x, extra.y < 0.0));
    } else if extra.y < 0.0 {
        densities[i] = cloud_density(layer, point.xyz, point.w);
    } else {
        densities[i] = cloud_density_with_coverage(layer, point.xyz, point.w, extra.y);
    }
}
";

/// One evaluation: the point (`f32`), its altitude, its layer and the coverage given (`None`:
/// the layer's own); or the average over the layer's columns at that altitude.
struct Sample {
    p: Vec3,
    h: f32,
    layer: usize,
    coverage: Option<f32>,
    evaluation: Evaluation,
}

/// What the kernel evaluates at a sample.
#[derive(Clone, Copy, PartialEq)]
enum Evaluation {
    /// The field at the point.
    Field,
    /// The average over the columns at its altitude, computed.
    Average,
    /// The same at the layer's own coverage, from its tabulated profile.
    Profile,
    /// The share of rays meeting cloud from afar, `h` the crossing along the ground.
    Cover,
}

/// A uniform number in [0, 1) for sample `i`, stream `k` (a fixed sequence).
fn uniform(i: u32, k: u32) -> f64 {
    let mut x = i.wrapping_mul(0x9e37_79b9) ^ k.wrapping_mul(0x85eb_ca6b) ^ 0x1234_5678;
    for _ in 0..3 {
        x ^= x >> 16;
        x = x.wrapping_mul(0x7feb_352d);
        x ^= x >> 15;
        x = x.wrapping_mul(0x846c_a68b);
        x ^= x >> 16;
    }
    f64::from(x) / 4_294_967_296.0
}

/// The layers of one batch: every kind, with seeds and drifts, one at ground level.
fn layers(planet: &Planet, seed: u32) -> Vec<CloudLayer> {
    let reference = planet.surface_point(0.6, -1.3);
    let hour = 3_600.0;
    let with = |kind, bottom, top, coverage, density, k: u32, wind: [f64; 2], seconds: f64| CloudLayer {
        seed: seed + k,
        wind_mps: wind,
        drift: wind_drift(planet, reference, wind, seconds),
        ..CloudLayer::new(bottom, top, coverage, density, kind)
    };
    let radian = planet.radii.x / 20.0;
    vec![
        with(CloudKind::Cumulus, 1_000.0, 3_000.0, 0.5, 0.05, 0, [0.0, 0.0], 0.0),
        with(
            CloudKind::Stratocumulus,
            1_500.0,
            2_500.0,
            0.7,
            0.02,
            1,
            [12.0, -4.0],
            hour,
        ),
        with(CloudKind::Stratus, 0.0, 600.0, 0.9, 0.03, 2, [0.0, 0.0], 0.0),
        with(
            CloudKind::Altostratus,
            3_000.0,
            5_000.0,
            0.8,
            0.01,
            3,
            [30.0, 0.0],
            24.0 * hour,
        ),
        with(CloudKind::Cirrus, 8_000.0, 9_500.0, 0.5, 1e-3, 4, [0.0, 20.0], radian),
        with(CloudKind::Uniform, 0.0, 2_000.0, 0.3, 0.04, 5, [5.0, 5.0], hour),
        with(CloudKind::Cumulus, 0.0, 2_500.0, 0.8, 0.08, 6, [-8.0, 3.0], 6.0 * hour),
        with(
            CloudKind::Stratocumulus,
            500.0,
            1_500.0,
            0.4,
            0.05,
            7,
            [20.0, 20.0],
            radian,
        ),
    ]
}

/// Samples of the layers: mostly inside clouds (where the field is not simply 0), some outside,
/// some at ground level, some with a coverage given (the coverage-map path).
fn samples(planet: &Planet, layers: &[CloudLayer], per_layer: u32) -> Vec<Sample> {
    let mut samples = Vec::new();
    for (index, layer) in layers.iter().enumerate() {
        let (mut inside, mut outside, mut i) = (0, 0, 0);
        while inside + outside < per_layer && i < 200 * per_layer {
            i += 1;
            let n = index as u32 * 1_000_000 + i;
            // Around a spot of the planet (so the layers' own clusters are seen), 400 km across.
            let latitude = 0.6 + (uniform(n, 0) - 0.5) * 0.06;
            let longitude = -1.3 + (uniform(n, 1) - 0.5) * 0.06;
            let ground = uniform(n, 2) < 0.1 && layer.bottom_m == 0.0;
            let h = if ground {
                0.0
            } else {
                layer.bottom_m + (uniform(n, 3) * 1.1 - 0.05) * (layer.top_m - layer.bottom_m)
            };
            let up = firmament_core::atmosphere::planet::geodetic_normal(latitude, longitude);
            let p = (planet.surface_point(latitude, longitude) + up * h).as_vec3();
            // The altitude of the rounded point, as the march would compute it (but exact).
            let h = if ground {
                0.0
            } else {
                planet.altitude(p.as_dvec3()) as f32
            };
            let coverage = (index % 3 == 1).then(|| (uniform(n, 4) * layer.coverage) as f32);
            let sample = Sample {
                p,
                h,
                layer: index,
                coverage,
                evaluation: Evaluation::Field,
            };
            let d = reference(layers, &sample);
            if d > 0.0 && inside < per_layer * 3 / 4 {
                inside += 1;
                samples.push(sample);
            } else if d == 0.0 && outside < per_layer / 4 {
                outside += 1;
                samples.push(sample);
            }
        }
    }
    samples
}

/// The core's density at a sample.
fn reference(layers: &[CloudLayer], s: &Sample) -> f64 {
    let layer = &layers[s.layer];
    let (p, h) = (s.p.as_dvec3(), f64::from(s.h));
    if s.evaluation == Evaluation::Cover {
        return layer.cover_seen(s.coverage.map_or(layer.coverage, f64::from), h);
    }
    if s.evaluation != Evaluation::Field {
        let coverage = s.coverage.map_or(layer.coverage, f64::from);
        return layer.mean_density_with_coverage(h, coverage);
    }
    match s.coverage {
        Some(c) => layer.density_with_coverage(p, h, f64::from(c)),
        None => layer.density_at_altitude(p, h),
    }
}

/// The shader's densities at `samples` of `layers` over `planet`.
fn evaluate(layers: &[CloudLayer], planet: &Planet, samples: &[Sample]) -> Vec<f32> {
    assert!(layers.len() <= MAX_CLOUD_LAYERS);
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let source = format!("{}\n{KERNEL}", CLOUD_DENSITY.source());
    let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("test cloud density"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("test cloud density layout"),
        entries: &[
            entry(0, wgpu::BufferBindingType::Uniform),
            entry(1, wgpu::BufferBindingType::Storage { read_only: true }),
            entry(2, wgpu::BufferBindingType::Storage { read_only: false }),
        ],
    });
    let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("test cloud density pipeline"),
        layout: Some(&ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("test cloud density pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        })),
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let buffer = |label, contents: &[u8], usage| {
        let b = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: contents.len() as u64,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&b, 0, contents);
        b
    };
    let uniforms = CloudsGpu::new(layers, planet);
    let clouds = buffer(
        "test clouds",
        bytemuck::bytes_of(&uniforms),
        wgpu::BufferUsages::UNIFORM,
    );
    let points: Vec<[f32; 4]> = samples
        .iter()
        .flat_map(|s| {
            [
                [s.p.x, s.p.y, s.p.z, s.h],
                [
                    s.layer as f32,
                    s.coverage.unwrap_or(-1.0),
                    f32::from(s.evaluation as u8),
                    0.0,
                ],
            ]
        })
        .collect();
    let points = buffer(
        "test cloud points",
        bytemuck::cast_slice(&points),
        wgpu::BufferUsages::STORAGE,
    );
    let size = (samples.len() * 4) as u64;
    let densities = buffer(
        "test cloud densities",
        &vec![0; samples.len() * 4],
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    );
    let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("test cloud density bind group"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: clouds.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: points.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: densities.as_entire_binding(),
            },
        ],
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups((samples.len() as u32).div_ceil(64), 1, 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let bytes = read_buffer(ctx, &densities, size).expect("readback");
    bytemuck::cast_slice::<u8, f32>(&bytes).to_vec()
}

#[test]
fn the_shader_evaluates_the_cores_density_field() {
    let planets = [
        ("Earth-sized sphere", Planet::sphere(6_371_000.0, 100_000.0)),
        (
            "WGS 84 ellipsoid",
            Planet::spheroid(6_378_137.0, 6_356_752.314, 100_000.0),
        ),
    ];
    let mut report = String::new();
    for (batch, (name, planet)) in planets.iter().enumerate() {
        let layers = layers(planet, 10 * batch as u32 + 1);
        let samples = samples(planet, &layers, 300);
        let got = evaluate(&layers, planet, &samples);
        let mut errors: Vec<(f64, usize)> = samples
            .iter()
            .zip(&got)
            .enumerate()
            .map(|(i, (s, &g))| {
                let scale = layers[s.layer].density_per_m;
                ((f64::from(g) - reference(&layers, s)).abs() / scale, i)
            })
            .collect();
        let inside = samples.iter().filter(|s| reference(&layers, s) > 0.0).count();
        errors.sort_by(|a, b| a.0.total_cmp(&b.0));
        let within = errors.iter().filter(|(e, _)| *e <= 1e-4).count();
        let (worst, at) = errors[errors.len() - 1];
        let s = &samples[at];
        report += &format!(
            "{name}: {} points ({inside} in cloud), {within} within 1e-4 of density_per_m, median {:.1e}, \
             99th percentile {:.1e}, worst {worst:.1e} ({:?}, h = {} m, gpu {} vs cpu {})\n",
            samples.len(),
            errors[errors.len() / 2].0,
            errors[errors.len() * 99 / 100].0,
            layers[s.layer].kind,
            s.h,
            got[at],
            reference(&layers, s),
        );
        assert!(inside * 2 > samples.len(), "{report}");
        assert!(within * 100 >= samples.len() * 99, "{report}");
        assert!(worst <= 1e-3, "{report}");
        // Every layer is seen in cloud, and ground level too.
        for index in 0..layers.len() {
            assert!(
                samples.iter().any(|s| s.layer == index && reference(&layers, s) > 0.0),
                "layer {index} of {name} never in cloud"
            );
        }
        assert!(samples.iter().any(|s| s.h == 0.0 && reference(&layers, s) > 0.0));
    }
    println!("{report}");
}

/// The level of detail from afar: the average over a layer's columns at an altitude is the core's
/// (`CloudLayer::mean_density_with_coverage`), for every kind, through each layer and at several
/// coverages, within 1e-5 of `density_per_m` (`f32` sums of the quantile table's 32 intervals);
/// and the layer's tabulated profile, linear between its 32 heights, within 3 % of
/// `density_per_m` of the computed one (its nodes: within 1e-6).
#[test]
fn the_shader_averages_the_columns_as_the_core_does() {
    let planet = Planet::sphere(6_371_000.0, 100_000.0);
    let layers = layers(&planet, 3);
    let mut samples = Vec::new();
    for (index, layer) in layers.iter().enumerate() {
        for k in 0..=124 {
            let h = layer.bottom_m + (f64::from(k) / 124.0 * 1.1 - 0.05) * (layer.top_m - layer.bottom_m);
            for coverage in [None, Some(0.05), Some(0.5), Some(0.95)] {
                samples.push(Sample {
                    p: Vec3::ZERO,
                    h: h as f32,
                    layer: index,
                    coverage,
                    evaluation: Evaluation::Average,
                });
            }
            samples.push(Sample {
                p: Vec3::ZERO,
                h: h as f32,
                layer: index,
                coverage: None,
                evaluation: Evaluation::Profile,
            });
        }
    }
    let got = evaluate(&layers, &planet, &samples);
    let (mut worst_average, mut worst_profile) = (0.0_f64, 0.0_f64);
    let mut positive = 0;
    for (s, &g) in samples.iter().zip(&got) {
        let want = reference(&layers, s);
        positive += usize::from(want > 0.0);
        let error = (f64::from(g) - want).abs() / layers[s.layer].density_per_m;
        match s.evaluation {
            Evaluation::Profile => worst_profile = worst_profile.max(error),
            _ => worst_average = worst_average.max(error),
        }
    }
    println!(
        "{} averages ({positive} positive): computed within {worst_average:.1e}, tabulated within \
         {worst_profile:.1e} of density_per_m",
        samples.len()
    );
    assert!(positive * 2 > samples.len(), "most heights hold cloud on average");
    assert!(
        worst_average <= 1e-5,
        "the shader's averages differ from the core's by {worst_average}"
    );
    assert!(
        worst_profile <= 0.03,
        "the tabulated averages differ from the core's by {worst_profile}"
    );
}

/// The level of detail's share of rays that meet cloud (`cloud_cover_seen`) against the core's
/// `CloudLayer::cover_seen`, for every kind at four coverages and crossings from none to 40 km:
/// within 1e-6 (`f32` powers).
#[test]
fn the_shader_counts_the_columns_a_ray_meets_as_the_core_does() {
    let planet = Planet::sphere(6_371_000.0, 100_000.0);
    let layers = layers(&planet, 3);
    let mut samples = Vec::new();
    for index in 0..layers.len() {
        for k in 0..=40 {
            for coverage in [0.05, 0.3, 0.7, 1.0] {
                samples.push(Sample {
                    p: Vec3::ZERO,
                    h: 1_000.0 * k as f32,
                    layer: index,
                    coverage: Some(coverage),
                    evaluation: Evaluation::Cover,
                });
            }
        }
    }
    let got = evaluate(&layers, &planet, &samples);
    let worst = samples
        .iter()
        .zip(&got)
        .map(|(s, &g)| (f64::from(g) - reference(&layers, s)).abs())
        .fold(0.0, f64::max);
    println!("{} shares of rays meeting cloud: within {worst:.1e}", samples.len());
    assert!(worst <= 1e-6, "the shader's shares differ from the core's by {worst}");
}
