//! GPU test of the classic lighting pass against the f64 statement of the GL equations:
//! every pixel inside the silhouette is recomputed on the CPU from the same mesh (ray-triangle
//! barycentrics give the perspective-correct interpolation the rasterizer does).

mod support;

use firmament_core::classic::fog::{Fog, FogCoordinate, FogMode};
use firmament_core::classic::lighting::{Light, LightModel, Lighting, Material, SpecularModel};
use firmament_core::projection::perspective_reverse_z;
use firmament_render::gpu_types::{ClassicFrameUniforms, ClassicShading};
use firmament_render::passes::{ClassicMeshPass, GpuMesh};
use firmament_render::readback::read_texture;
use firmament_render::{Backend, FrameTargets, GpuContext};
use glam::{DMat3, DMat4, DVec3, DVec4};

/// A latitude-longitude sphere of radius 1 (only the test's own geometry; not GLTools').
fn uv_sphere(slices: u32, stacks: u32) -> (Vec<DVec3>, Vec<u32>) {
    let mut positions = Vec::new();
    for i in 0..=stacks {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(stacks);
        for j in 0..=slices {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(slices);
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ));
        }
    }
    let mut indices = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let a = i * (slices + 1) + j;
            let b = a + slices + 1;
            // Counter-clockwise seen from outside.
            indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    (positions, indices)
}

/// Möller–Trumbore: (t, u, v) of the ray from the origin along `d` through triangle (a, b, c).
fn hit(d: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = -a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

fn sum(primary: DVec4, secondary: DVec4) -> DVec3 {
    (primary.truncate() + secondary.truncate()).clamp(DVec3::ZERO, DVec3::ONE)
}

#[test]
fn classic_lighting_matches_the_gl_equations_per_pixel() {
    let ctx = GpuContext::headless(Backend::Auto).unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    let (size, w) = (72u32, 72.0);
    let (positions, indices) = uv_sphere(26, 13);
    let mesh = GpuMesh::new(&ctx.device, &positions, &positions, &indices).expect("valid mesh");
    let pass = ClassicMeshPass::new(&ctx.device);
    let targets = FrameTargets::new(&ctx.device, size, size);
    // The SuperBible scene: the sphere 4 units in front of a 35° camera, turned a little.
    let model_view =
        DMat4::from_translation(DVec3::new(0.0, 0.0, -4.0)) * DMat4::from_rotation_x(0.4) * DMat4::from_rotation_y(0.3);
    let projection = perspective_reverse_z(35f64.to_radians(), 1.0, 1.0, 100.0);
    let normal_matrix = DMat3::from_mat4(model_view).inverse().transpose();

    let superbible_light = Light {
        position: DVec4::new(-100.0, 100.0, 100.0, 1.0),
        ..Light::gl_default(0)
    };
    let blue = Material {
        ambient: DVec4::new(0.1, 0.1, 0.1, 1.0),
        diffuse: DVec4::new(0.0, 0.0, 1.0, 1.0),
        specular: DVec4::ONE,
        emission: DVec4::new(0.0, 0.0, 0.0, 1.0),
        shininess: 128.0,
    };
    let spot = Light {
        position: DVec4::new(2.0, 1.0, 0.0, 1.0),
        diffuse: DVec4::new(1.0, 0.5, 0.2, 1.0),
        specular: DVec4::new(0.3, 1.0, 0.3, 1.0),
        spot_direction: DVec3::new(-2.0, -1.0, -4.0),
        spot_cutoff: 25.0,
        spot_exponent: 4.0,
        linear_attenuation: 0.1,
        quadratic_attenuation: 0.02,
        ..Light::gl_default(1)
    };
    let lights_a = [superbible_light];
    let lights_b = [superbible_light, spot];
    let superbible_model = LightModel {
        ambient: DVec4::ONE,
        ..LightModel::default()
    };
    let spot_model = LightModel {
        local_viewer: true,
        separate_specular: true,
        ..LightModel::default()
    };
    let linear_fog = Fog {
        mode: FogMode::Linear { start: 3.2, end: 4.8 },
        coordinate: FogCoordinate::EyePlaneDepth,
        color: DVec4::new(0.7, 0.6, 0.5, 1.0),
    };
    let exp2_fog = Fog {
        mode: FogMode::Exp2 { density: 0.3 },
        coordinate: FogCoordinate::EyeDistance,
        color: DVec4::new(0.2, 0.9, 0.3, 1.0),
    };
    let cases = [
        (
            "superbible gouraud",
            &lights_a[..],
            superbible_model,
            SpecularModel::Blinn,
            ClassicShading::Gouraud,
            None,
        ),
        (
            "superbible phong",
            &lights_a[..],
            superbible_model,
            SpecularModel::Blinn,
            ClassicShading::Phong,
            None,
        ),
        (
            "spot, local viewer, separate specular",
            &lights_b[..],
            spot_model,
            SpecularModel::Phong,
            ClassicShading::Phong,
            None,
        ),
        (
            "spot gouraud",
            &lights_b[..],
            LightModel::default(),
            SpecularModel::Blinn,
            ClassicShading::Gouraud,
            None,
        ),
        (
            "linear fog, eye-plane depth",
            &lights_a[..],
            superbible_model,
            SpecularModel::Blinn,
            ClassicShading::Phong,
            Some(linear_fog),
        ),
        (
            "exp2 fog, eye distance",
            &lights_b[..],
            spot_model,
            SpecularModel::Blinn,
            ClassicShading::Gouraud,
            Some(exp2_fog),
        ),
    ];
    let eye_vertices: Vec<DVec3> = positions.iter().map(|p| model_view.transform_point3(*p)).collect();
    let eye_normals: Vec<DVec3> = positions.iter().map(|n| (normal_matrix * *n).normalize()).collect();
    let inverse_projection = projection.inverse();

    for (name, lights, model, specular, shading, fog) in cases {
        let lighting = Lighting {
            lights,
            model,
            front: blue,
            back: Material::default(),
            specular,
        };
        pass.prepare(
            &ctx.queue,
            &ClassicFrameUniforms::new(&lighting, &model_view, &projection, shading, fog.as_ref()),
        );
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
        support::clear_targets(&mut encoder, &targets, wgpu::Color::TRANSPARENT, 0.0);
        pass.record(&mut encoder, &targets.hdr_view, &targets.depth_view, &mesh);
        ctx.queue.submit([encoder.finish()]);
        let bytes = read_texture(&ctx, &targets.hdr).expect("readback");
        let px: Vec<f32> = bytes
            .chunks_exact(2)
            .map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32())
            .collect();
        let at = |x: u32, y: u32| {
            let i = ((y * size + x) * 4) as usize;
            [px[i], px[i + 1], px[i + 2], px[i + 3]]
        };

        let (mut checked, mut worst) = (0, 0.0f64);
        for y in 1..size - 1 {
            for x in 1..size - 1 {
                // Silhouette pixels (any neighbour uncovered) are excluded, as the issue allows.
                // Coverage is alpha > 0.5: an interpolated alpha of 1 need not stay exactly 1.
                let interior = (0..9).all(|k| at(x + k % 3 - 1, y + k / 3 - 1)[3] > 0.5);
                if !interior {
                    continue;
                }
                let ndc = DVec4::new(
                    (f64::from(x) + 0.5) / w * 2.0 - 1.0,
                    1.0 - (f64::from(y) + 0.5) / w * 2.0,
                    1.0,
                    1.0,
                );
                let p = inverse_projection * ndc;
                let d = (p.truncate() / p.w).normalize();
                let nearest = indices
                    .chunks_exact(3)
                    .filter_map(|t| {
                        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
                        hit(d, eye_vertices[a], eye_vertices[b], eye_vertices[c]).map(|h| (h, [a, b, c]))
                    })
                    .min_by(|a, b| a.0.0.total_cmp(&b.0.0));
                let Some(((t, u, v), [a, b, c])) = nearest else {
                    panic!("{name}: covered pixel ({x}, {y}) misses the mesh")
                };
                let weights = [1.0 - u - v, u, v];
                let expected = match shading {
                    ClassicShading::Phong => {
                        let n = eye_normals[a] * weights[0] + eye_normals[b] * weights[1] + eye_normals[c] * weights[2];
                        let lit = lighting.shade(d * t, n, true);
                        sum(lit.primary, lit.secondary)
                    }
                    ClassicShading::Gouraud => {
                        let lit = [a, b, c].map(|i| lighting.shade(eye_vertices[i], eye_normals[i], true));
                        let primary =
                            lit[0].primary * weights[0] + lit[1].primary * weights[1] + lit[2].primary * weights[2];
                        let secondary = lit[0].secondary * weights[0]
                            + lit[1].secondary * weights[1]
                            + lit[2].secondary * weights[2];
                        sum(primary, secondary)
                    }
                };
                // GL computes the fog coordinate per vertex, interpolates it, and fogs per fragment.
                let expected = match fog {
                    None => expected,
                    Some(fog) => {
                        let coord: f64 = [a, b, c]
                            .iter()
                            .zip(weights)
                            .map(|(&i, w)| fog.coordinate.of(eye_vertices[i]) * w)
                            .sum();
                        fog.mode.apply(expected.extend(1.0), fog.color, coord).truncate()
                    }
                };
                let got = at(x, y);
                let err = (DVec3::new(f64::from(got[0]), f64::from(got[1]), f64::from(got[2])) - expected)
                    .abs()
                    .max_element();
                worst = worst.max(err);
                assert!(
                    err < 1.0 / 255.0,
                    "{name}: pixel ({x}, {y}) is {got:?}, the GL equations give {expected}"
                );
                checked += 1;
            }
        }
        assert!(checked > 1000, "{name}: only {checked} interior pixels");
        eprintln!("{name}: {checked} pixels, worst {worst:.2e}");
    }
}
