//! GPU tests of the environment maps (`firmament_render::envmap`): the sun-less map's sky
//! irradiance on the ground against the `f64` reference path tracer, the disc's irradiance
//! against the sun's after the air, and where the sun lands in both layouts.

use std::f64::consts::TAU;

use crate::support::{Gpu, direction, gpu, street_sky};

use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::envmap::{CubeFace, cube_position, equirect_position, sun_at_eye};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::{Camera, Frame};
use firmament_render::envmap::SunDiscs;
use firmament_render::headless::Image;
use glam::DVec3;

/// The camera 1.7 m above the ground (its orientation does not matter to a map).
fn street_frame(sky: &AtmosphereSky) -> Frame {
    let camera = Camera::from_heading_pitch(DVec3::new(0.0, 0.0, 1.7), 0.3, 0.1);
    Frame::new(camera, Sky::Atmosphere(sky.clone()))
}

/// An equirectangular map's irradiance on an upward normal: `∫ L·cos θ dω` over the upper
/// hemisphere, each pixel weighted by its exact `∫ cos θ dω` (`(2π/W)·(sin² θ₁ − sin² θ₀)/2`).
fn upper_irradiance(map: &Image<f32>) -> DVec3 {
    let (w, h) = (map.width, map.height);
    let theta = |j: u32| std::f64::consts::PI * f64::from(j) / f64::from(h);
    (0..h / 2)
        .map(|j| {
            let weight = TAU / f64::from(w) * 0.5 * (theta(j + 1).sin().powi(2) - theta(j).sin().powi(2));
            (0..w)
                .map(|i| {
                    let p = map.pixel(i, j).expect("inside");
                    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
                })
                .sum::<DVec3>()
                * weight
        })
        .sum()
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
        let got = upper_irradiance(&map);
        let conversion = sky.atmosphere.spectral_conversion();
        let reference = |seed| {
            let settings = ReferenceSettings {
                paths: REFERENCE_PATHS,
                seed,
                ..ReferenceSettings::default()
            };
            let e = Reference::new(sky.atmosphere, &sky.suns, settings).ground_irradiance(frame.camera.position);
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
    let sun = sun_at_eye(&sky.atmosphere, &[], &sky.suns[0], frame.camera.position);
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
