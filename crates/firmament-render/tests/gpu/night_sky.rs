//! The night-sky pass on the GPU against the f64 core, in linear HDR float: a star's light summed
//! over its footprint (radiance × each pixel's exact solid angle) against its colour and its
//! centroid against the core's projection; stars behind an object or behind the camera draw
//! nothing; the Moon at first quarter pixel by pixel against the f64 Lommel–Seeliger radiance
//! along each pixel's view ray, lit on the side of the Sun, over the illuminated fraction of the
//! disc; the Moon in the Earth's shadow likewise; and the whole sky of a real night.

use crate::support;

use std::sync::Arc;

use firmament_core::astro::moon::{moon_view, next_phase};
use firmament_core::astro::{CivilDateTime, Instant};
use firmament_core::atmosphere::planet_shadow::{PlanetShadow, ShadowSettings};
use firmament_core::atmosphere::presets;
use firmament_core::camera::viewport::{Viewport, project_zero_to_one};
use firmament_core::classic::lighting::Material;
use firmament_core::classic::mesh::Mesh;
use firmament_core::classic::scene::{ObjectLayer, SceneObject};
use firmament_core::color::LinearRgb;
use firmament_core::display::{DisplaySettings, Exposure, ToneCurve};
use firmament_core::frame::Sky;
use firmament_core::sky::night::{MoonDisc, MoonShadow, NightLayer, StarPoint};
use firmament_core::{Camera, Frame};
use firmament_render::FrameTargets;
use firmament_render::gpu_types::MoonDraw;
use firmament_render::headless::Image;
use firmament_render::passes::NightSkyPass;
use firmament_render::readback::{decode_f16, read_texture};
use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, DVec4};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

/// At the origin looking down −z, 45° (a pixel is ~0.3 mrad).
fn camera() -> Camera {
    crate::support::origin_camera_45(WIDTH, HEIGHT)
}

fn frame(camera: Camera, night: NightLayer, objects: Vec<SceneObject>) -> Frame {
    Frame {
        camera,
        sky: Sky::Clear(LinearRgb::new(0.0, 0.0, 0.0)),
        display: DisplaySettings {
            exposure: Exposure::multiplier(1.0),
            tone_curve: ToneCurve::None,
            ..DisplaySettings::default()
        },
        objects: ObjectLayer {
            objects,
            ..ObjectLayer::default()
        },
        flares: Default::default(),
        night,
    }
}

fn render(frame: &Frame) -> Image<f32> {
    let mut gpu = support::gpu();
    let support::Gpu { ctx, renderer } = &mut *gpu;
    renderer.render_hdr(ctx, frame, WIDTH, HEIGHT).expect("render")
}

fn rgb(image: &Image<f32>, x: u32, y: u32) -> DVec3 {
    let p = image.pixel(x, y).expect("inside");
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// NDC of a point given in pixel coordinates (x right, y down from the top-left corner).
fn ndc_of(px: DVec2) -> DVec2 {
    DVec2::new(
        px.x / f64::from(WIDTH) * 2.0 - 1.0,
        1.0 - px.y / f64::from(HEIGHT) * 2.0,
    )
}

/// The exact solid angle of pixel (x, y), steradians: the rectangle it covers on the image plane
/// at distance 1 (tan coordinates u, v), ∬ du dv / (1 + u² + v²)^{3/2}.
fn pixel_solid_angle(camera: &Camera, x: u32, y: u32) -> f64 {
    let tan_y = (0.5 * camera.fov_y).tan();
    let tan_x = tan_y * camera.aspect;
    let f = |u: f64, v: f64| (u * v / (1.0 + u * u + v * v).sqrt()).atan();
    let a = ndc_of(DVec2::new(f64::from(x), f64::from(y)));
    let b = ndc_of(DVec2::new(f64::from(x + 1), f64::from(y + 1)));
    let (u0, u1) = (a.x * tan_x, b.x * tan_x);
    let (v0, v1) = (a.y * tan_y, b.y * tan_y);
    (f(u1, v1) - f(u0, v1) - f(u1, v0) + f(u0, v0)).abs()
}

/// Where the core puts a world direction on the image, pixel coordinates (y down).
fn project(camera: &Camera, direction: DVec3) -> Option<DVec2> {
    if direction.dot(camera.forward()) <= 0.0 {
        return None;
    }
    let window = project_zero_to_one(
        camera.position + direction * 100.0,
        &camera.view_matrix(),
        &camera.projection_matrix(),
        &Viewport::new(f64::from(WIDTH), f64::from(HEIGHT)),
    )?;
    Some(DVec2::new(window.x, f64::from(HEIGHT) - window.y))
}

/// The world direction through a point in pixel coordinates.
fn direction_at(camera: &Camera, px: DVec2) -> DVec3 {
    camera.view_direction(ndc_of(px))
}

/// Σ radiance × solid angle over the image, and the energy-weighted centroid (pixel coords).
fn energy_and_centroid(camera: &Camera, image: &Image<f32>) -> (DVec3, DVec2) {
    let (mut energy, mut moment, mut weight) = (DVec3::ZERO, DVec2::ZERO, 0.0);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let e = rgb(image, x, y) * pixel_solid_angle(camera, x, y);
            energy += e;
            moment += DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5) * e.y;
            weight += e.y;
        }
    }
    (energy, moment / weight)
}

/// The share of a star's light the footprint gives each pixel, in f64: the pixels whose
/// centres lie within 2.5 px of `center` along each axis, a Gaussian of σ = 0.6 px at their
/// centres, normalised over them. `(x, y, weight)`, pixels possibly outside the image.
fn footprint(center: DVec2) -> Vec<(i64, i64, f64)> {
    let sigma: f64 = 0.6;
    let first = (center - 3.0).ceil() + 0.5;
    let g = |x: f64| (-0.5 * x * x / (sigma * sigma)).exp();
    let sum = |c: f64, f: f64| (0..5).map(|j| g(f + f64::from(j) - c)).sum::<f64>();
    let (sx, sy) = (sum(center.x, first.x), sum(center.y, first.y));
    let mut out = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            let p = first + DVec2::new(f64::from(i), f64::from(j));
            let w = g(p.x - center.x) * g(p.y - center.y) / (sx * sy);
            out.push(((p.x - 0.5) as i64, (p.y - 0.5) as i64, w));
        }
    }
    out
}

fn star_layer(stars: Vec<StarPoint>) -> NightLayer {
    NightLayer { stars, moon: None }
}

#[test]
fn a_star_s_light_sums_to_its_colour_at_its_projected_position() {
    let color = DVec3::new(1e-3, 2e-3, 5e-4);
    // Near the centre at sub-pixel offsets, and towards a corner where pixels subtend ~40 % less.
    for (camera, at) in [
        (camera(), DVec2::new(81.3, 57.8)),
        (camera(), DVec2::new(40.5, 30.0)),
        (camera(), DVec2::new(147.77, 108.21)),
        (
            Camera {
                far: None,
                orientation: DQuat::from_rotation_y(0.4) * DQuat::from_rotation_x(0.2),
                ..camera()
            },
            DVec2::new(12.62, 100.49),
        ),
    ] {
        let direction = direction_at(&camera, at);
        let image = render(&frame(camera, star_layer(vec![StarPoint { direction, color }]), vec![]));
        let (energy, centroid) = energy_and_centroid(&camera, &image);
        let expected_at = project(&camera, direction).expect("in front");
        let error = ((energy - color) / color).abs().max_element();
        let offset = (centroid - expected_at).length();
        println!(
            "star at {at}: Σ L·Ω = {:.5e} {:.5e} {:.5e} (colour {color}), worst channel {:.3} %; \
             centroid {centroid:.4}, core projection {expected_at:.4}, {offset:.4} px apart",
            energy.x,
            energy.y,
            energy.z,
            error * 100.0
        );
        assert!(error < 0.01, "energy {energy} vs {color}");
        assert!(offset < 0.1, "centroid {centroid} vs {expected_at}");
        // And the per-pixel shares are the footprint's.
        for (x, y, w) in footprint(expected_at) {
            let got = rgb(&image, x as u32, y as u32).y * pixel_solid_angle(&camera, x as u32, y as u32);
            assert!(
                (got - w * color.y).abs() <= 0.01 * w * color.y + 1e-4 * color.y,
                "pixel ({x}, {y}): {got} vs {}",
                w * color.y
            );
        }
    }
}

/// A black sphere of radius 4 m at (0, 0, −20).
fn occluder() -> SceneObject {
    let mesh = Arc::new(Mesh::glt_sphere(4.0, 64, 32).expect("valid sphere"));
    let black = Material {
        diffuse: DVec4::new(0.0, 0.0, 0.0, 1.0),
        ..Material::default()
    };
    SceneObject::new(mesh, DMat4::from_translation(DVec3::new(0.0, 0.0, -20.0)), black)
}

#[test]
fn stars_behind_an_object_or_the_camera_draw_nothing() {
    let camera = camera();
    let color = DVec3::splat(1e-3);
    let hidden = StarPoint {
        direction: DVec3::new(0.05, 0.02, -1.0).normalize(),
        color,
    };
    let total = |image: &Image<f32>| {
        image
            .pixels
            .chunks_exact(4)
            .map(|p| f64::from(p[0] + p[1] + p[2]))
            .sum::<f64>()
    };
    // Seen without the sphere...
    let open = render(&frame(camera, star_layer(vec![hidden]), vec![]));
    assert!(total(&open) > 0.0);
    // ...nothing with it.
    let covered = render(&frame(camera, star_layer(vec![hidden]), vec![occluder()]));
    println!(
        "star behind a sphere: image sum {} (without the sphere {:.4})",
        total(&covered),
        total(&open)
    );
    assert_eq!(total(&covered), 0.0);
    // Behind the camera, malformed, dark: nothing; an empty layer: nothing.
    let odd = vec![
        StarPoint {
            direction: DVec3::new(0.0, 0.0, 1.0),
            color,
        },
        StarPoint {
            direction: DVec3::NAN,
            color,
        },
        StarPoint {
            direction: DVec3::NEG_Z,
            color: DVec3::new(f64::NAN, 1.0, 1.0),
        },
    ];
    assert_eq!(total(&render(&frame(camera, star_layer(odd), vec![]))), 0.0);
    assert_eq!(total(&render(&frame(camera, NightLayer::default(), vec![]))), 0.0);
}

fn utc(y: i32, mo: u32, d: u32, h: u32, mi: u32) -> Instant {
    Instant::from_civil(&CivilDateTime::utc(y, mo, d, h, mi, 0.0), None).expect("valid date")
}

/// The f64 average of the 4 × 4 rays the pass takes over pixel (x, y): a regular grid at ±1/8
/// and ±3/8 of a pixel from its centre.
fn moon_pixel_average(camera: &Camera, moon: &MoonDisc, x: u32, y: u32) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for j in 0..4 {
        for i in 0..4 {
            let o = (DVec2::new(f64::from(i), f64::from(j)) + 0.5) * 0.25 - 0.5;
            let px = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5) + o;
            sum += moon.radiance_along(direction_at(camera, px)).unwrap_or(DVec3::ZERO);
        }
    }
    sum / 16.0
}

/// A camera looking at `moon` with a field of view `fov_radii` Moon radii high, rolled so the
/// terminator is not along a pixel row.
fn moon_camera(moon: &MoonDisc, fov_radii: f64) -> Camera {
    let mut camera = Camera::looking_at(DVec3::ZERO, moon.direction, DVec3::Z).expect("camera");
    camera.orientation = (camera.orientation * DQuat::from_rotation_z(0.5)).normalize();
    camera.fov_y = fov_radii * moon.angular_radius;
    camera.aspect = f64::from(WIDTH) / f64::from(HEIGHT);
    camera
}

fn moon_layer(moon: MoonDisc) -> NightLayer {
    NightLayer {
        stars: vec![],
        moon: Some(moon),
    }
}

#[test]
fn the_quarter_moon_matches_lommel_seeliger_pixel_by_pixel() {
    let quarter = next_phase(&utc(2025, 3, 1, 0, 0), 90.0);
    let view = moon_view(&quarter, 48.1, 11.6, 520.0);
    let moon = MoonDisc::from_view(&view, DMat3::IDENTITY, 1.0, DVec3::new(0.9, 0.8, 0.6));
    // The Moon fills half the image height (a radius of 30 pixels).
    let camera = moon_camera(&moon, 4.0);
    let image = render(&frame(camera, moon_layer(moon), vec![]));
    let scale = moon.radiance.max_element();
    let (mut disc, mut lit, mut interior) = (0u32, 0u32, 0u32);
    let (mut worst_ray, mut worst_average): (f64, f64) = (0.0, 0.0);
    let mut lit_sum = DVec2::ZERO;
    let mut energy = DVec3::ZERO;
    // Relative error with a floor of 1e-4 of the peak (f16 and f32 rounding near the terminator).
    let relative = |got: DVec3, expected: DVec3| {
        ((got - expected).abs() / (expected.abs() + DVec3::splat(1e-4 * scale))).max_element()
    };
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let px = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            let ray = direction_at(&camera, px);
            let got = rgb(&image, x, y);
            energy += got * pixel_solid_angle(&camera, x, y);
            // What the pixel shows: the average over its 16 rays, everywhere (rim included).
            let average = moon_pixel_average(&camera, &moon, x, y);
            let error = relative(got, average);
            worst_average = worst_average.max(error);
            assert!(error < 0.01, "({x}, {y}): {got} vs the f64 average {average}");
            let from_centre = ray.angle_between(moon.direction) / moon.angular_radius;
            if from_centre > 1.0 {
                continue;
            }
            disc += 1;
            if got.y > 0.0 {
                lit += 1;
                lit_sum += px;
            }
            // Interior pixels wholly on one side of the terminator: the radiance along the
            // pixel's own view ray.
            let corners_lit = [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)].map(|(dx, dy)| {
                let corner = direction_at(&camera, px + DVec2::new(dx, dy));
                moon.radiance_along(corner).is_some_and(|l| l.y > 0.0)
            });
            if from_centre > 0.95 || corners_lit.iter().any(|&c| c != corners_lit[0]) {
                continue;
            }
            let expected = moon.radiance_along(ray).expect("on the disc");
            let error = relative(got, expected);
            worst_ray = worst_ray.max(error);
            interior += 1;
            assert!(error < 0.01, "({x}, {y}): {got} vs {expected} along its view ray");
        }
    }
    let share = f64::from(lit) / f64::from(disc);
    let k = view.phase.illuminated_fraction;
    // The bright side faces the Sun: the lit pixels' centroid lies from the disc's centre along
    // the Sun's direction projected on the image.
    let centre = project(&camera, moon.direction).expect("in front");
    let s = moon.sun_direction - moon.direction * moon.sun_direction.dot(moon.direction);
    let towards_sun = DVec2::new(s.dot(camera.right()), -s.dot(camera.up())).normalize();
    let towards_lit = (lit_sum / f64::from(lit) - centre).normalize();
    let angle = towards_lit.angle_to(towards_sun).to_degrees();
    let light = moon.illuminance();
    let energy_error = ((energy - light) / light).abs().max_element();
    println!(
        "quarter moon (phase angle {:.2}°, radius 30 px): {interior} interior pixels within {:.3} % \
         of the radiance along their view ray, every pixel within {:.3} % of the f64 average of its \
         16 rays (1e-4 of the peak added); lit share {share:.4} vs k = {k:.4}; bright side {angle:.2}° \
         from the Sun's direction; Σ L·Ω {:.5e} vs illuminance {:.5e} lx (green), {:.3} %",
        moon.phase_angle().to_degrees(),
        worst_ray * 100.0,
        worst_average * 100.0,
        energy.y,
        light.y,
        energy_error * 100.0
    );
    assert!(interior > 1000, "{interior}");
    assert!((share - k).abs() < 0.03, "{share} vs {k}");
    assert!(angle.abs() < 3.0, "{angle}°");
    assert!(energy_error < 0.01, "{energy} vs {light}");
}

/// A full Moon 1.5 of its radii from the axis of the Earth's shadow (the core's profile through
/// Earth's air, 390 000 km behind it): every pixel within 1 % of the f64 average of its 16 rays
/// (1e-3 of the peak added: the shadow's light spans three decades), and the disc's light within
/// 1 % of the Moon's illuminance with the shadow's mean over its face.
#[test]
fn an_eclipsed_moon_matches_its_shadow_pixel_by_pixel() {
    let view = moon_view(&utc(2025, 3, 14, 6, 59), 19.43, -99.13, 2240.0);
    let mut moon = MoonDisc::from_view(&view, DMat3::IDENTITY, 1.0, DVec3::ONE);
    let profile = PlanetShadow::new(
        &presets::earth(),
        &presets::earth_sun(DVec3::Z),
        3.9e8,
        &ShadowSettings::default(),
    );
    let axis = -moon.sun_direction;
    moon.shadow = Some(MoonShadow {
        axis,
        offset: axis.any_orthonormal_vector() * 1.5,
        step: profile.step_m / 1.7374e6,
        light: std::array::from_fn(|k| profile.light[k]),
    });
    let camera = moon_camera(&moon, 4.0);
    let image = render(&frame(camera, moon_layer(moon), vec![]));
    let peak = (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| moon_pixel_average(&camera, &moon, x, y).max_element())
        .fold(0.0, f64::max);
    let mut energy = DVec3::ZERO;
    let mut worst: f64 = 0.0;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let got = rgb(&image, x, y);
            energy += got * pixel_solid_angle(&camera, x, y);
            let want = moon_pixel_average(&camera, &moon, x, y);
            let error = ((got - want).abs() / (want.abs() + DVec3::splat(1e-3 * peak))).max_element();
            worst = worst.max(error);
            assert!(error < 0.01, "({x}, {y}): {got} vs the f64 average {want}");
        }
    }
    let light = moon.illuminance();
    let energy_error = ((energy - light) / light).abs().max_element();
    println!(
        "eclipsed Moon: every pixel within {:.3} %, Σ L·Ω within {:.3} %",
        worst * 100.0,
        energy_error * 100.0
    );
    // Dim and red: the sunlight's share there is 10⁻⁵ to 10⁻³.
    let full = MoonDisc { shadow: None, ..moon }.illuminance();
    assert!(light.y < 1e-3 * full.y && light.x > 2.0 * light.z, "{light} of {full}");
    assert!(energy_error < 0.01, "{energy} vs {light}");
}

#[test]
fn the_moon_keeps_its_light_at_any_size() {
    let start = utc(2025, 3, 1, 0, 0);
    for (what, instant) in [
        ("full", next_phase(&start, 180.0)),
        ("crescent", start.plus_seconds(4.0 * 86_400.0)),
    ] {
        let view = moon_view(&instant, -33.9, 18.4, 0.0);
        let moon = MoonDisc::from_view(&view, DMat3::IDENTITY, 1.0, DVec3::ONE);
        let light = moon.illuminance();
        // Radius 30, 6, 3, 2.1 and 1.5 pixels: discs, then a star.
        for (fov_radii, disc) in [(4.0, true), (20.0, true), (40.0, true), (57.0, true), (80.0, false)] {
            let camera = moon_camera(&moon, fov_radii);
            let (image, _, draw) = render_pass(&camera, &moon_layer(moon));
            assert_eq!(draw == MoonDraw::Disc, disc, "{what}, {fov_radii}: {draw:?}");
            let (energy, _) = energy_and_centroid(&camera, &image);
            let error = ((energy - light) / light).abs().max_element();
            println!(
                "{what} moon, radius {:.1} px ({}): Σ L·Ω / illuminance = {:.4}",
                f64::from(HEIGHT) / fov_radii,
                if disc { "disc" } else { "star" },
                energy.y / light.y
            );
            assert!(error < 0.02, "{what}, {fov_radii}: {energy} vs {light}");
        }
    }
}

/// Renders `layer` with the pass alone (cleared black, depth at the far plane): the HDR image, how
/// many stars the pass drew and how it drew the Moon.
fn render_pass(camera: &Camera, layer: &NightLayer) -> (Image<f32>, u32, MoonDraw) {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let mut pass = NightSkyPass::new(&ctx.device);
    let targets = FrameTargets::new(&ctx.device, WIDTH, HEIGHT);
    pass.prepare(&ctx.device, &ctx.queue, layer, camera, (WIDTH, HEIGHT));
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("gpu_night_sky"),
    });
    support::clear_targets(&mut encoder, &targets, wgpu::Color::TRANSPARENT, 0.0);
    pass.record(&mut encoder, &targets.hdr_view, &targets.depth_view);
    ctx.queue.submit([encoder.finish()]);
    let pixels = decode_f16(&read_texture(ctx, &targets.hdr).expect("readback"));
    (
        Image {
            width: WIDTH,
            height: HEIGHT,
            pixels,
        },
        pass.star_count(),
        pass.moon(),
    )
}

#[test]
fn a_real_night_renders_every_star_of_its_layer() {
    // Munich, 2025-01-15 22:00 UTC, the sky to the south-east at 40°; frame units mcd/m² (1000
    // per lux) so the faintest stars stay above the half-float target's normal range at 160 px.
    let instant = utc(2025, 1, 15, 22, 0);
    let layer = NightLayer::at(&instant, 48.1, 11.6, 520.0, DMat3::IDENTITY, 1000.0, 6.5, |d: DVec3| {
        DVec3::new(0.8, 0.75, 0.6) * (0.3 + 0.7 * d.z.max(0.0))
    });
    let camera = Camera {
        fov_y: 60f64.to_radians(),
        aspect: f64::from(WIDTH) / f64::from(HEIGHT),
        ..Camera::from_heading_pitch(DVec3::ZERO, 135f64.to_radians(), 40f64.to_radians())
    };
    let (image, drawn, moon_draw) = render_pass(&camera, &layer);
    // The renderer's own path gives the same image.
    let via_renderer = render(&frame(camera, layer.clone(), vec![]));
    let colour = |i: &Image<f32>| -> Vec<f32> { i.pixels.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect() };
    assert_eq!(colour(&via_renderer), colour(&image));
    // Every star with light is uploaded; the GPU clips those out of view.
    assert_eq!(drawn as usize, layer.stars.len());
    // That night the waning gibbous Moon stands in view, ~0.5 px in radius: a star of its light.
    let moon = layer.moon.expect("the Moon is up");
    assert!(matches!(moon_draw, MoonDraw::Point(_)), "{moon_draw:?}");

    // The stars alone (the Moon outshines them 6000 times), footprint by footprint, clipped by
    // the image's edges.
    let stars_only = NightLayer {
        moon: None,
        ..layer.clone()
    };
    let (stars_image, _, _) = render_pass(&camera, &stars_only);
    let inside = |x: i64, y: i64| (0..i64::from(WIDTH)).contains(&x) && (0..i64::from(HEIGHT)).contains(&y);
    let light_in_image = |star: &StarPoint| -> DVec3 {
        project(&camera, star.direction).map_or(DVec3::ZERO, |center| {
            footprint(center)
                .iter()
                .filter(|&&(x, y, _)| inside(x, y))
                .map(|&(_, _, w)| star.color * w)
                .sum()
        })
    };
    let (mut in_view, mut seen) = (0, 0);
    for star in &layer.stars {
        let Some(center) = project(&camera, star.direction) else {
            continue;
        };
        let (x, y) = (center.x.floor() as i64, center.y.floor() as i64);
        if !inside(x, y) {
            continue;
        }
        in_view += 1;
        // The pixel under the star holds at least its own share (neighbours only add).
        let own: f64 = footprint(center)
            .iter()
            .filter(|&&(sx, sy, _)| (sx, sy) == (x, y))
            .map(|&(_, _, w)| w * star.color.y)
            .sum();
        let (x, y) = (x as u32, y as u32);
        if rgb(&stars_image, x, y).y * pixel_solid_angle(&camera, x, y) >= 0.99 * own {
            seen += 1;
        }
    }
    let expected: DVec3 = layer.stars.iter().map(light_in_image).sum();
    let (energy, _) = energy_and_centroid(&camera, &stars_image);
    let error = ((energy - expected) / expected).abs().max_element();
    // The Moon alone, in cd/m² (in mcd/m² its footprint's peak, ~4·10⁵, would pass the half-float
    // target's 65504 and be clamped).
    let moon = MoonDisc {
        radiance: moon.radiance / 1000.0,
        ..moon
    };
    let (moon_image, _, _) = render_pass(&camera, &moon_layer(moon));
    let moon_point = StarPoint {
        direction: moon.direction,
        color: moon.illuminance(),
    };
    let moon_expected = light_in_image(&moon_point);
    let (moon_energy, _) = energy_and_centroid(&camera, &moon_image);
    let moon_error = ((moon_energy - moon_expected) / moon_expected).abs().max_element();
    println!(
        "real night: {} stars in the layer (V < 6.5, above −1°), all uploaded; {in_view} in view, \
         {seen} of them lit where they should be; Σ L·Ω = {:.5e} vs footprints {:.5e} (green), \
         worst channel {:.3} %; the Moon (a star, {:.5e}) within {:.3} %",
        layer.stars.len(),
        energy.y,
        expected.y,
        error * 100.0,
        moon_expected.y,
        moon_error * 100.0
    );
    assert!(in_view > 300, "{in_view}");
    assert_eq!(seen, in_view);
    assert!(error < 0.01, "{energy} vs {expected}");
    assert!(moon_error < 0.01, "{moon_energy} vs {moon_expected}");
}
