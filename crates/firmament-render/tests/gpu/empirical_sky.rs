//! GPU tests of the seed's atmosphere model (`EmpiricalSkyPass`, `shaders/empirical_sky.wgsl`)
//! against its f64 port (`firmament_core::atmosphere::empirical::EmpiricalAtmosphere::color`):
//! every pixel of small images, compared in linear float.
//!
//! The GPU's HDR target is half float (11-bit mantissa, relative rounding up to 2⁻¹¹ ≈ 4.9e-4),
//! so each pixel's difference is that rounding plus f32's own error. Measured on llvmpipe: worst
//! pixel 9.4e-4, median 2.5e-4 to 4.1e-4 (relative to the pixel's largest channel), in every
//! view below, the far camera's included.

use crate::support::{Gpu, direction, gpu};

use firmament_core::atmosphere::Planet;
use firmament_core::atmosphere::empirical::{EmpiricalAtmosphere, EmpiricalStar};
use firmament_core::display::DisplaySettings;
use firmament_core::frame::{EMPIRICAL_DEFAULT_LUMINANCE, EmpiricalSky, Sky};
use firmament_core::{Camera, Frame};
use glam::{DVec2, DVec3};

const AU: f64 = firmament_core::atmosphere::presets::ASTRONOMICAL_UNIT;
const SUN_RADIUS: f64 = 6.957e8;
const WIDTH: u32 = 32;
const HEIGHT: u32 = 24;

/// Largest relative difference (largest channel difference over the largest reference channel,
/// or over 1e-3 of the luminance for near-black pixels) allowed per pixel.
const TOLERANCE: f64 = 1.5e-3;

/// The empirical model with `preset`'s values, posed so the world is ENU at (`latitude`,
/// `longitude`) degrees, lit by stars towards the given world directions (planet frame positions
/// 1 AU away).
fn posed_sky(preset: EmpiricalAtmosphere, latitude: f64, longitude: f64, suns: &[(DVec3, f64, DVec3)]) -> EmpiricalSky {
    let planet = Planet::spheroid(preset.equatorial_radius, preset.polar_radius, preset.height)
        .posed_at(latitude.to_radians(), longitude.to_radians());
    let stars = suns
        .iter()
        .map(|&(direction, radius, color)| {
            let d = planet.direction_to_planet_frame(direction.normalize());
            EmpiricalStar::at(d * AU, radius, color)
        })
        .collect();
    EmpiricalSky {
        atmosphere: preset,
        center: planet.center,
        orientation: planet.orientation,
        stars,
        luminance: EMPIRICAL_DEFAULT_LUMINANCE,
    }
}

fn camera(position: DVec3, target: DVec3, fov_y: f64) -> Camera {
    let camera = Camera::looking_at(position, target, DVec3::Z)
        .or_else(|| Camera::looking_at(position, target, DVec3::Y))
        .expect("a view direction");
    Camera {
        fov_y,
        aspect: f64::from(WIDTH) / f64::from(HEIGHT),
        ..camera
    }
}

/// Worst and median relative difference over every pixel, and the worst pixel.
struct Comparison {
    worst: f64,
    median: f64,
    at: (u32, u32),
    lit: usize,
}

fn compare(gpu: &mut Gpu, name: &str, sky: &EmpiricalSky, camera: Camera) -> Comparison {
    let frame = Frame::new(camera, Sky::Empirical(sky.clone()));
    let Gpu { ctx, renderer } = gpu;
    let image = renderer.render_hdr(ctx, &frame, WIDTH, HEIGHT).expect("render");
    let mut differences = Vec::new();
    let mut worst = (0.0, (0, 0));
    let mut lit = 0;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let ndc = DVec2::new(
                (f64::from(x) + 0.5) / f64::from(WIDTH) * 2.0 - 1.0,
                1.0 - (f64::from(y) + 0.5) / f64::from(HEIGHT) * 2.0,
            );
            let (rgb, _) = sky.color(camera.position, camera.view_direction(ndc));
            let p = image.pixel(x, y).expect("inside");
            let gpu_rgb = DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])) / sky.luminance;
            let scale = rgb.max_element().max(1e-3);
            let d = (gpu_rgb - rgb).abs().max_element() / scale;
            assert!(gpu_rgb.is_finite(), "{name}: pixel ({x}, {y}) is {gpu_rgb}");
            if rgb.max_element() > 1e-3 {
                lit += 1;
            }
            if d > worst.0 {
                worst = (d, (x, y));
            }
            differences.push(d);
        }
    }
    differences.sort_by(f64::total_cmp);
    let c = Comparison {
        worst: worst.0,
        median: differences[differences.len() / 2],
        at: worst.1,
        lit,
    };
    eprintln!(
        "{name}: worst relative difference {:.2e} at {:?}, median {:.2e}, {} of {} pixels lit",
        c.worst,
        c.at,
        c.median,
        c.lit,
        WIDTH * HEIGHT
    );
    c
}

fn assert_close(c: &Comparison, name: &str, min_lit: usize) {
    assert!(c.lit >= min_lit, "{name}: only {} pixels lit", c.lit);
    assert!(
        c.worst < TOLERANCE,
        "{name}: worst relative difference {:.3e} at {:?} (tolerance {TOLERANCE:e})",
        c.worst,
        c.at
    );
}

#[test]
fn orbit_view_of_the_globe_and_its_limb_matches_the_f64_port() {
    let mut gpu = gpu();
    // 12 000 km above 20° N, the Sun on the horizon there: the half-lit globe, limb and space.
    let sky = posed_sky(
        EmpiricalAtmosphere::seed_earth(),
        20.0,
        0.0,
        &[(direction(240.0, 0.0), SUN_RADIUS, DVec3::splat(10.0))],
    );
    let position = DVec3::new(0.0, 0.0, 1.2e7);
    let cam = camera(position, DVec3::new(0.0, 1.0, 0.0), 50f64.to_radians());
    let c = compare(&mut gpu, "orbit, one star", &sky, cam);
    assert_close(&c, "orbit, one star", 200);
    // From 1000 km, looking along the limb with two stars.
    let sky = posed_sky(
        EmpiricalAtmosphere::seed_earth(),
        -10.0,
        30.0,
        &[
            (direction(90.0, 20.0), SUN_RADIUS, DVec3::new(10.0, 9.5, 9.0)),
            (direction(200.0, -30.0), 3.0 * SUN_RADIUS, DVec3::new(10.0, 4.0, 2.0)),
        ],
    );
    let position = DVec3::new(0.0, 0.0, 1.0e6);
    let cam = camera(position, position + direction(90.0, -25.0), 60f64.to_radians());
    let c = compare(&mut gpu, "limb from 1000 km, two stars", &sky, cam);
    assert_close(&c, "limb from 1000 km, two stars", 200);
}

#[test]
fn ground_views_match_the_f64_port() {
    let mut gpu = gpu();
    // From 1.7 m, looking at the Sun 10° up with a large (5°) disc in view: disc pixels start at
    // the star's colour (alpha 1) and are normalised.
    let sun = direction(250.0, 10.0);
    let sky = posed_sky(
        EmpiricalAtmosphere::seed_earth(),
        45.0,
        0.0,
        &[(sun, AU * 5f64.to_radians().sin(), DVec3::new(10.0, 9.0, 7.0))],
    );
    let position = DVec3::new(0.0, 0.0, 1.7);
    let on_disc = sky.color(position, sun);
    assert_eq!(on_disc.1, 1.0, "the Sun's disc is on the view axis");
    let cam = camera(position, position + direction(250.0, 12.0), 70f64.to_radians());
    let c = compare(&mut gpu, "Earth ground, one star", &sky, cam);
    assert_close(&c, "Earth ground, one star", 300);
    // Mars, two suns, one below the horizon (the light_dir[0] quirk counts it with star 0's
    // direction).
    let sky = posed_sky(
        EmpiricalAtmosphere::seed_mars(),
        0.0,
        0.0,
        &[
            (direction(180.0, 40.0), SUN_RADIUS, DVec3::splat(10.0)),
            (direction(0.0, -5.0), SUN_RADIUS, DVec3::new(10.0, 6.0, 3.0)),
        ],
    );
    let position = DVec3::new(0.0, 0.0, 100.0);
    let cam = camera(position, position + direction(170.0, 20.0), 90f64.to_radians());
    let c = compare(&mut gpu, "Mars ground, two stars", &sky, cam);
    assert_close(&c, "Mars ground, two stars", 300);
}

#[test]
fn the_limb_from_25_au_matches_the_f64_port() {
    let mut gpu = gpu();
    // A far camera: rays start at their closest approach to the planet (the f32 camera position
    // would be off by hundreds of kilometres). The planet fills the narrow view.
    let sky = posed_sky(
        EmpiricalAtmosphere::seed_earth(),
        0.0,
        0.0,
        &[(direction(90.0, 10.0), SUN_RADIUS, DVec3::splat(10.0))],
    );
    let center = sky.center;
    let position = center + DVec3::new(-3.0e5, -25.0 * AU, 2.0e5);
    let half_angle = 1.3 * (sky.atmosphere.top().radii.max_element()) / (25.0 * AU);
    let cam = camera(position, center, 2.0 * half_angle);
    let c = compare(&mut gpu, "25 AU", &sky, cam);
    assert_close(&c, "25 AU", 200);
}

#[test]
fn invalid_parameters_draw_nothing() {
    let mut gpu = gpu();
    let mut sky = posed_sky(EmpiricalAtmosphere::seed_earth(), 0.0, 0.0, &[]);
    sky.atmosphere.view_depth = 0.0;
    let frame = Frame {
        camera: camera(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 1.0, 2.0), 1.0),
        sky: Sky::Empirical(sky),
        display: DisplaySettings::default(),
        objects: Default::default(),
        flares: Default::default(),
        night: Default::default(),
    };
    let Gpu { ctx, renderer } = &mut *gpu;
    let image = renderer.render_hdr(ctx, &frame, 4, 3).expect("render");
    assert!(image.pixels.chunks_exact(4).all(|p| p[..3] == [0.0; 3]));
}
