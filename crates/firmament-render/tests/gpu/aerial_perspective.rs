//! GPU tests of the aerial-perspective volume against the f64 reference
//! (`Reference::radiance_before`: the air in front of an opaque surface), in linear float.

use crate::support::{clear_targets, direction, gpu, sky_reference, street_sky};

use firmament_core::Camera;
use firmament_core::frame::AtmosphereSky;
use firmament_core::geometry::Ray;
use firmament_render::passes::AtmospherePass;
use firmament_render::readback::{decode_f16, read_texture};
use firmament_render::{FrameTargets, GpuContext};
use glam::{DVec3, DVec4};

/// The reversed-Z depth-buffer value of a point at view depth `depth` metres.
fn depth_value(camera: &Camera, depth: f64) -> f32 {
    let clip = camera.projection_matrix() * DVec4::new(0.0, 0.0, -depth, 1.0);
    (clip.z / clip.w) as f32
}

/// What the aerial-perspective pass makes of a wall of linear-sRGB radiance `wall` at view depth
/// `depth` filling a `width`×`height` image: every pixel, row by row (the two full-screen draws
/// callers' passes get).
fn wall_pixels(
    ctx: &GpuContext,
    pass: &mut AtmospherePass,
    sky: &AtmosphereSky,
    camera: &Camera,
    size: (u32, u32),
    wall: f64,
    depth: f64,
) -> Vec<DVec3> {
    applied_to_wall(ctx, pass, sky, camera, size, wall, depth, false)
}

/// [`wall_pixels`] by the draws or, with `compute`, by the compute pass of the renderer's own
/// targets.
#[allow(clippy::too_many_arguments, reason = "a test helper: the wall's whole description")]
fn applied_to_wall(
    ctx: &GpuContext,
    pass: &mut AtmospherePass,
    sky: &AtmosphereSky,
    camera: &Camera,
    (width, height): (u32, u32),
    wall: f64,
    depth: f64,
    compute: bool,
) -> Vec<DVec3> {
    let targets = FrameTargets::new(&ctx.device, width, height);
    pass.prepare(&ctx.queue, sky, camera);
    pass.bind_depth(&ctx.device, &targets.depth_view);
    pass.bind_sky_target(&ctx.device, &targets.hdr, &targets.depth_view);
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    pass.record_luts(&mut encoder);
    let color = wgpu::Color {
        r: wall,
        g: wall,
        b: wall,
        a: 1.0,
    };
    clear_targets(&mut encoder, &targets, color, depth_value(camera, depth));
    if compute {
        assert!(
            pass.record_aerial_perspective_on_target(&mut encoder),
            "a target is bound"
        );
    } else {
        pass.record_aerial_perspective(&mut encoder, &targets.hdr_view);
    }
    ctx.queue.submit([encoder.finish()]);
    let texels = decode_f16(&read_texture(ctx, &targets.hdr).expect("readback"));
    texels
        .chunks_exact(4)
        .map(|t| DVec3::new(f64::from(t[0]), f64::from(t[1]), f64::from(t[2])))
        .collect()
}

/// The mean of [`wall_pixels`] over a 2×2 image.
fn apply_to_wall(
    ctx: &GpuContext,
    pass: &mut AtmospherePass,
    sky: &AtmosphereSky,
    camera: &Camera,
    wall: f64,
    depth: f64,
) -> DVec3 {
    wall_pixels(ctx, pass, sky, camera, (2, 2), wall, depth)
        .into_iter()
        .sum::<DVec3>()
        / 4.0
}

/// A camera at `position` looking along `view`, with a narrow field of view.
fn camera(position: DVec3, view: DVec3) -> Camera {
    let camera = Camera::looking_at(position, position + view, DVec3::Z).expect("a view direction");
    Camera {
        fov_y: 0.5_f64.to_radians(),
        aspect: 1.0,
        ..camera
    }
}

/// Radiance of the wall that shows the transmittance, cd/m² (well inside half-float range).
const BRIGHT_WALL: f64 = 30_000.0;

#[test]
fn aerial_perspective_matches_the_reference() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = street_sky(90.0, 25.0);
    let reference = sky_reference(&sky, 4096);
    let conversion = sky.atmosphere.spectral_conversion();
    let mut pass = AtmospherePass::new(&ctx.device);
    let mut worst = (0.0_f64, 0.0_f64);
    // From 2 m and from a 3 km mountain, views level, up and down the slope, walls near and far.
    for (height, view_elevation) in [(2.0, 1.0), (2.0, 4.0), (3_000.0, -3.0)] {
        for (azimuth, distance) in [(0.0, 700.0), (60.0, 4_000.0), (180.0, 15_000.0), (270.0, 40_000.0)] {
            let eye = DVec3::Z * height;
            let view = direction(azimuth, view_elevation);
            let camera = camera(eye, view);
            let scattered = apply_to_wall(ctx, &mut pass, &sky, &camera, 0.0, distance);
            // A bright wall, so the half-float target resolves its product with T finely.
            let transmitted =
                (apply_to_wall(ctx, &mut pass, &sky, &camera, BRIGHT_WALL, distance) - scattered) / BRIGHT_WALL;
            let want = reference.radiance_before(
                &Ray {
                    origin: eye,
                    direction: view,
                },
                distance,
            );
            let want_scattered = conversion.linear_srgb(want.scattered());
            let want_scattered = DVec3::new(want_scattered.r, want_scattered.g, want_scattered.b);
            let want_transmitted = DVec3::new(want.transmittance.x, want.transmittance.y, want.transmittance.z);
            let scattering_error = (scattered - want_scattered).abs().max_element() / want_scattered.max_element();
            let transmittance_error = (transmitted - want_transmitted).abs().max_element();
            println!(
                "h {height} m, view ({azimuth}°, {view_elevation}°), wall at {distance} m: \
                 S {scattered:.4} vs {want_scattered:.4} ({:.2} %), T {transmitted:.4} vs {want_transmitted:.4}",
                100.0 * scattering_error
            );
            worst = (worst.0.max(scattering_error), worst.1.max(transmittance_error));
        }
    }
    println!(
        "worst: scattered light {:.2} %, transmittance {:.4} absolute",
        100.0 * worst.0,
        worst.1
    );
    // Measured worst 4.1 %: the multiple-scattering model's error (docs/ATMOSPHERE.md);
    // single scattering and the transmittance are exact to the quadrature.
    assert!(worst.0 < 0.06, "scattered light off by {:.1} %", 100.0 * worst.0);
    assert!(worst.1 < 3e-3, "transmittance off by {}", worst.1);
}

/// A wide view from the street (60°, 32 froxel rows 1.9° apart) with geometry on the ground
/// kilometres away, just under the horizon: its pixels lie between a froxel row above the
/// horizon and one below it, whose ray meets the ground ~100 m out. Their air must still be the
/// air in front of the geometry. (Columns used to stop at the ground: the row below then held
/// 100 m of air, and filtering halved the light in front of geometry 2 km away — 49–57 % low.)
#[test]
fn geometry_at_the_horizon_of_a_wide_view_gets_its_air() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = street_sky(90.0, 25.0);
    let reference = sky_reference(&sky, 4096);
    let conversion = sky.atmosphere.spectral_conversion();
    let mut pass = AtmospherePass::new(&ctx.device);
    let eye = DVec3::Z * 2.0;
    // 8×8 pixels over 60°: row 4's centre (ndc y = −1/8) looks 4.13° below the axis, so a
    // camera pitched 4.10° up sees 0.03° below the horizon there, on a froxel-row boundary.
    let (width, height) = (8_u32, 8_u32);
    let ndc_y = -0.125_f64;
    let below_axis = (ndc_y.abs() * 30_f64.to_radians().tan()).atan().to_degrees();
    let view = direction(0.0, below_axis - 0.03);
    let camera = Camera::looking_at(eye, eye + view, DVec3::Z)
        .expect("a view direction")
        .with_fov_y(60_f64.to_radians());
    let camera = Camera { aspect: 1.0, ..camera };
    let mut worst = 0.0_f64;
    for depth in [700.0, 2_000.0, 3_000.0] {
        let pixels = wall_pixels(ctx, &mut pass, &sky, &camera, (width, height), 0.0, depth);
        for (row, column) in [(3_u32, 3_u32), (4, 3), (4, 4)] {
            let ndc = glam::DVec2::new(
                (f64::from(column) + 0.5) / f64::from(width) * 2.0 - 1.0,
                1.0 - (f64::from(row) + 0.5) / f64::from(height) * 2.0,
            );
            let ray = camera.view_direction(ndc);
            let along = depth / ray.dot(camera.forward());
            assert!(eye.z + ray.z * along > 0.0, "the wall's point is above the ground");
            let want = reference.radiance_before(
                &Ray {
                    origin: eye,
                    direction: ray,
                },
                along,
            );
            let want = conversion.linear_srgb(want.scattered());
            let want = DVec3::new(want.r, want.g, want.b);
            let got = pixels[(row * width + column) as usize];
            let error = (got - want).abs().max_element() / want.max_element();
            println!(
                "wall at {depth} m, pixel ({column}, {row}), elevation {:.2}°: S {got:.3} vs {want:.3} ({:.2} %)",
                ray.z.asin().to_degrees(),
                100.0 * error
            );
            worst = worst.max(error);
        }
    }
    println!("worst {:.2} %", 100.0 * worst);
    assert!(worst < 0.06, "scattered light off by {:.1} %", 100.0 * worst);
}

#[test]
fn the_sky_and_far_geometry_are_left_alone() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = street_sky(90.0, 25.0);
    let mut pass = AtmospherePass::new(&ctx.device);
    let camera = camera(DVec3::Z * 2.0, direction(0.0, 1.0));
    // Depth 0 is the far plane: the sky pass already drew the air there.
    let targets = FrameTargets::new(&ctx.device, 2, 2);
    pass.prepare(&ctx.queue, &sky, &camera);
    pass.bind_depth(&ctx.device, &targets.depth_view);
    pass.bind_sky_target(&ctx.device, &targets.hdr, &targets.depth_view);
    // The draws callers' passes get, and the compute pass of the renderer's own targets.
    for compute in [false, true] {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
        pass.record_luts(&mut encoder);
        let wall = wgpu::Color {
            r: 1.0,
            g: 2.0,
            b: 3.0,
            a: 1.0,
        };
        clear_targets(&mut encoder, &targets, wall, 0.0);
        if compute {
            assert!(pass.record_aerial_perspective_on_target(&mut encoder));
        } else {
            pass.record_aerial_perspective(&mut encoder, &targets.hdr_view);
        }
        ctx.queue.submit([encoder.finish()]);
        let texels = decode_f16(&read_texture(ctx, &targets.hdr).expect("readback"));
        for texel in texels.chunks_exact(4) {
            assert_eq!(texel[..3], [1.0, 2.0, 3.0], "compute: {compute}");
        }
    }
}

/// Across the volume's slices (walls at and between slice centres, 12 m to 15 km) the light
/// grows with distance: no slice is out of step.
#[test]
fn aerial_perspective_grows_with_distance() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = street_sky(90.0, 25.0);
    let mut pass = AtmospherePass::new(&ctx.device);
    let camera = camera(DVec3::Z * 2.0, direction(30.0, 2.0));
    let mut previous = DVec3::ZERO;
    for k in 1..40 {
        let distance = 10.0 * 1.2_f64.powi(k);
        let scattered = apply_to_wall(ctx, &mut pass, &sky, &camera, 0.0, distance);
        assert!(
            scattered.cmpge(previous).all(),
            "{distance} m: {scattered} after {previous}"
        );
        previous = scattered;
    }
}

/// The compute application on the renderer's own targets gives the pixels of the two draws
/// callers' passes get (which the reference tests above measure), over walls near and far.
#[test]
fn the_compute_application_matches_the_draws() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = street_sky(90.0, 25.0);
    let mut pass = AtmospherePass::new(&ctx.device);
    let camera = Camera {
        aspect: 16.0 / 9.0,
        ..camera(DVec3::Z * 2.0, direction(30.0, 3.0)).with_fov_y(60_f64.to_radians())
    };
    for (wall, depth) in [(0.0, 700.0), (50.0, 5_000.0), (2.0, 40_000.0)] {
        let drawn = applied_to_wall(ctx, &mut pass, &sky, &camera, (32, 18), wall, depth, false);
        let computed = applied_to_wall(ctx, &mut pass, &sky, &camera, (32, 18), wall, depth, true);
        let worst = drawn
            .iter()
            .zip(&computed)
            .map(|(a, b)| ((*a - *b).abs() / a.abs().max(DVec3::splat(1e-3))).max_element())
            .fold(0.0, f64::max);
        // The draws round colour · T to half floats before adding S; the pass rounds once.
        assert!(
            worst < 2e-3,
            "wall {wall} at {depth} m: worst relative difference {worst}"
        );
        assert!(
            drawn
                .iter()
                .any(|p| (*p - DVec3::splat(wall)).abs().max_element() > 1e-2),
            "the air changed the wall at {depth} m: the comparison proves something"
        );
    }
}
