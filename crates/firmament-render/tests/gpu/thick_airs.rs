//! Venus's and Titan's thick airs on the GPU against the f64 reference (issue 30, part 3): 23
//! views each — the sky from the ground with the Sun 60° and 20° up, and the globe from orbit
//! (the sunlit disc, its limb, the terminator).
//!
//! The reference needs many paths there (a path from Venus's ground wanders for thousands of
//! events before it finds sunlit air), so its values are stored in `data/thick_airs.txt`, made by
//! the ignored `write_the_thick_air_references` with the paths each line states, and one view of
//! each air is recomputed here with fewer paths to check that the stored values are still the
//! reference's (`the_stored_thick_air_references_are_the_reference_s`).

use std::fmt::Write as _;

use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::atmosphere::{Atmosphere, Spectrum, Sun, presets};
use firmament_core::frame::AtmosphereSky;
use firmament_core::geometry::Ray;
use glam::DVec3;

use crate::support::{centre_radiance, direction, gpu};

/// The stored references: one line per view.
const STORED: &str = include_str!("data/thick_airs.txt");

/// An air, its sun, and the height of its orbit views, metres.
struct Body {
    name: &'static str,
    atmosphere: fn() -> Atmosphere,
    sun: fn(DVec3) -> Sun,
    orbit: f64,
    /// Reference paths per view for the stored values.
    paths: usize,
    /// The budget for the median of the views' errors (docs/ATMOSPHERE.md, "Thick airs").
    median_budget: f64,
}

const BODIES: [Body; 2] = [
    Body {
        name: "venus",
        atmosphere: presets::venus,
        sun: presets::venus_sun,
        orbit: 300_000.0,
        paths: 32_768,
        median_budget: 0.07,
    },
    Body {
        name: "titan",
        atmosphere: presets::titan,
        sun: presets::titan_sun,
        orbit: 1_000_000.0,
        paths: 65_536,
        median_budget: 0.07,
    },
];

/// A view: the sun's elevation, the eye's altitude (m) and the view's azimuth from the sun's and
/// elevation, degrees.
#[derive(Debug, Clone, Copy)]
struct View {
    sun_elevation: f64,
    altitude: f64,
    azimuth: f64,
    elevation: f64,
}

/// The 23 views of `body`: from 1 m above the ground the zenith and, towards the sun, across and
/// away from it, 45°, 10° and 2° up (Sun 60° and 20° up); from orbit straight down with the Sun
/// 60° up and at the horizon (the terminator), and at the sunlit limb.
fn views(body: &Body) -> Vec<View> {
    let mut views = Vec::new();
    for sun_elevation in [60.0, 20.0] {
        views.push(View {
            sun_elevation,
            altitude: 1.0,
            azimuth: 0.0,
            elevation: 90.0,
        });
        for elevation in [45.0, 10.0, 2.0] {
            for azimuth in [0.0, 90.0, 180.0] {
                views.push(View {
                    sun_elevation,
                    altitude: 1.0,
                    azimuth,
                    elevation,
                });
            }
        }
    }
    let radius = (body.atmosphere)().planet.radii.x;
    // Just above the limb's dip: the bright edge of the disc.
    let limb = -(radius / (radius + body.orbit)).acos().to_degrees() + 1.0;
    for (sun_elevation, elevation) in [(60.0, -90.0), (0.0, -90.0), (60.0, limb)] {
        views.push(View {
            sun_elevation,
            altitude: body.orbit,
            azimuth: 0.0,
            elevation,
        });
    }
    views
}

/// `body`'s air posed so the world is East-North-Up at (0°, 0°), the Sun towards north.
fn sky(body: &Body, sun_elevation: f64) -> AtmosphereSky {
    let mut atmosphere = (body.atmosphere)();
    atmosphere.planet = atmosphere.planet.posed_at(0.0, 0.0);
    AtmosphereSky {
        atmosphere,
        suns: vec![(body.sun)(direction(0.0, sun_elevation))],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    }
}

fn eye(view: &View) -> DVec3 {
    DVec3::new(0.0, 0.0, view.altitude)
}

/// The reference's scattered radiance (W·m⁻²·sr⁻¹·nm⁻¹) along `view` and its standard error.
fn reference_radiance(body: &Body, view: &View, paths: usize) -> (Spectrum, Spectrum) {
    let sky = sky(body, view.sun_elevation);
    let settings = ReferenceSettings {
        paths,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings);
    let parts = reference.radiance(&Ray {
        origin: eye(view),
        direction: direction(view.azimuth, view.elevation),
    });
    (parts.scattered(), parts.multiple.standard_error)
}

/// A stored line: body, sun elevation, altitude, azimuth, elevation, paths, radiance (3),
/// standard error (3).
struct Stored {
    body: String,
    view: [f64; 4],
    radiance: Spectrum,
    error: Spectrum,
}

fn stored() -> Vec<Stored> {
    STORED
        .lines()
        .filter(|line| !line.starts_with('#') && !line.trim().is_empty())
        .map(|line| {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let number = |i: usize| -> f64 { fields[i].parse().expect("a number in data/thick_airs.txt") };
            Stored {
                body: fields[0].to_owned(),
                view: [number(1), number(2), number(3), number(4)],
                radiance: Spectrum::new(number(6), number(7), number(8)),
                error: Spectrum::new(number(9), number(10), number(11)),
            }
        })
        .collect()
}

fn stored_for<'a>(stored: &'a [Stored], body: &Body, view: &View) -> &'a Stored {
    let key = [view.sun_elevation, view.altitude, view.azimuth, view.elevation];
    stored
        .iter()
        .find(|s| s.body == body.name && s.view.iter().zip(key).all(|(a, b)| (a - b).abs() < 1e-6))
        .unwrap_or_else(|| {
            panic!(
                "no stored reference for {} {view:?}: run write_the_thick_air_references",
                body.name
            )
        })
}

/// Writes `data/thick_airs.txt` (about half an hour on 2 cores):
/// `cargo test --release -p firmament-render --test gpu -- --ignored --nocapture write_the_thick_air_references`.
#[test]
#[ignore = "half an hour: it makes the stored references"]
fn write_the_thick_air_references() {
    let mut text = String::from(
        "# Venus's and Titan's skies from the f64 reference (firmament_core::atmosphere::reference), made by\n\
         # thick_airs.rs's write_the_thick_air_references. Columns: body, sun elevation (deg), eye altitude (m),\n\
         # view azimuth from the sun's (deg), view elevation (deg), paths, scattered radiance at 680/550/440 nm\n\
         # (W/(m^2 sr nm)), its standard error at the same wavelengths.\n",
    );
    for body in &BODIES {
        for view in views(body) {
            let started = std::time::Instant::now();
            let (radiance, error) = reference_radiance(body, &view, body.paths);
            println!(
                "{} {view:?}: {radiance:.4} ± {error:.4} ({:.0?})",
                body.name,
                started.elapsed()
            );
            writeln!(
                text,
                "{} {} {} {} {:.6} {} {:.6e} {:.6e} {:.6e} {:.3e} {:.3e} {:.3e}",
                body.name,
                view.sun_elevation,
                view.altitude,
                view.azimuth,
                view.elevation,
                body.paths,
                radiance.x,
                radiance.y,
                radiance.z,
                error.x,
                error.y,
                error.z
            )
            .expect("a string takes any text");
        }
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gpu/data/thick_airs.txt");
    std::fs::write(&path, text).expect("the data folder is writable");
}

/// The largest channel's difference over the largest channel, in linear sRGB.
fn relative_error(gpu: DVec3, reference: DVec3) -> f64 {
    (gpu - reference).abs().max_element() / reference.max_element()
}

/// The GPU against the stored references at every view, each within [`THICK_VIEW`] plus twice
/// the reference's noise there; prints each and returns the sorted errors.
fn errors(body: &Body) -> Vec<f64> {
    let mut gpu = gpu();
    let mut errors = Vec::new();
    let mut over: Vec<String> = Vec::new();
    let stored = stored();
    for view in views(body) {
        let sky = sky(body, view.sun_elevation);
        let conversion = sky.atmosphere.spectral_conversion();
        let rgb = |s: Spectrum| {
            let c = conversion.linear_srgb(s);
            DVec3::new(c.r, c.g, c.b)
        };
        let stored = stored_for(&stored, body, &view);
        let reference = rgb(stored.radiance);
        let gpu = centre_radiance(&mut gpu, &sky, eye(&view), direction(view.azimuth, view.elevation));
        let error = relative_error(gpu, reference);
        // In the same measure: the largest channel's standard error over the largest channel.
        let noise = stored.error.max_element() / stored.radiance.max_element();
        println!(
            "{} sun {:>4}° eye {:>9} m view {:>5}° {:>6.2}°: gpu {gpu:.4} reference {reference:.4} error {:.1} % (noise {:.1} %)",
            body.name,
            view.sun_elevation,
            view.altitude,
            view.azimuth,
            view.elevation,
            100.0 * error,
            100.0 * noise
        );
        if error >= THICK_VIEW + 2.0 * noise {
            over.push(format!("{} {view:?}: {error} (noise {noise})", body.name));
        }
        errors.push(error);
    }
    assert!(over.is_empty(), "over the budget: {over:#?}");
    errors.sort_by(f64::total_cmp);
    errors
}

/// One view of each air recomputed with fewer paths agrees with the stored value within four
/// standard errors of their difference: the stored references are still the reference's.
#[test]
fn the_stored_thick_air_references_are_the_reference_s() {
    let stored = stored();
    for body in &BODIES {
        let view = views(body)[0];
        let stored = stored_for(&stored, body, &view);
        let (radiance, error) = reference_radiance(body, &view, 8192);
        let spread = (stored.error * stored.error + error * error).map(f64::sqrt);
        let off = ((radiance - stored.radiance).abs() / spread).max_element();
        println!(
            "{} {view:?}: stored {:.4} now {radiance:.4} ± {error:.4}: {off:.1} standard errors",
            body.name, stored.radiance
        );
        assert!(off < 4.0, "{}: {off} standard errors", body.name);
    }
}

/// Venus and Titan against the stored references at 23 views each (`cargo test --release -p
/// firmament-render --test gpu -- --nocapture thick_airs::`): every view within [`THICK_VIEW`]
/// plus twice the reference's noise there, the median within the air's own budget. The measured
/// errors and the budget's reasons are in docs/ATMOSPHERE.md, "Thick airs".
#[test]
fn venus_and_titan_match_the_reference_within_the_thick_air_budget() {
    for body in &BODIES {
        let errors = errors(body);
        let (median, worst) = (errors[errors.len() / 2], errors[errors.len() - 1]);
        println!(
            "{}: median {:.1} %, worst {:.1} %",
            body.name,
            100.0 * median,
            100.0 * worst
        );
        assert!(median < body.median_budget, "{}: median {median}", body.name);
    }
}

/// The thick airs' budget, as the largest channel's error over the largest channel: each view
/// within this plus twice the reference's noise there (docs/ATMOSPHERE.md, "Thick airs").
const THICK_VIEW: f64 = 0.15;
