use std::f64::consts::PI;

use glam::DVec3;

use super::*;
use crate::atmosphere::presets;
use crate::geometry::{Ellipsoid, Ray};

fn no_air(_: DVec3) -> Spectrum {
    Spectrum::ONE
}

fn saturn() -> (Rings, DVec3) {
    (
        Rings::saturn(),
        Planet::spheroid(60_268_000.0, 54_364_000.0, 600_000.0).radii,
    )
}

/// A sun 26.7° above the ring plane (Saturn's largest tilt), towards +x.
fn sun() -> DVec3 {
    let elevation = 26.7_f64.to_radians();
    DVec3::new(elevation.cos(), 0.0, elevation.sin())
}

/// The surface point and normal at geodetic `latitude_deg`, `longitude_deg` from the sun's azimuth.
fn ground(radii: DVec3, latitude_deg: f64, longitude_deg: f64) -> (DVec3, DVec3) {
    let n = geodetic_normal(latitude_deg.to_radians(), longitude_deg.to_radians());
    (radii * radii * n / (radii * n).length(), n)
}

fn relative(a: Spectrum, b: Spectrum) -> f64 {
    (a - b).abs().max_element() / b.max_element()
}

#[test]
fn a_uniform_annulus_seen_from_its_axis_gives_the_closed_form() {
    // E = πL(cos²θ₁ − cos²θ₂), θ the angles of the annulus's edges from the axis; the point
    // above the plane faces it.
    let (inner, outer, z) = (2.0, 5.0, 3.0);
    let light = integrate_over_annuli(
        &[(inner, outer)],
        DVec3::new(0.0, 0.0, z),
        DVec3::NEG_Z,
        |_| None,
        |_, _| Spectrum::ONE,
    );
    let cos2 = |r: f64| z * z / (r * r + z * z);
    let exact = PI * (cos2(inner) - cos2(outer));
    assert!((light.x / exact - 1.0).abs() < 1e-6, "{} vs {exact}", light.x);
    // Half of it beyond a dark half-turn.
    let half = integrate_over_annuli(
        &[(inner, outer)],
        DVec3::new(0.0, 0.0, z),
        DVec3::NEG_Z,
        |_| Some((1.0, PI)),
        |_, _| Spectrum::ONE,
    );
    assert!((half.x / exact - 0.5).abs() < 1e-6, "{}", half.x / exact);
}

/// The same integral by brute force: a midpoint grid over every band, each cell seen when it is
/// above `n`'s horizon and lit when the ray from it towards the sun misses the ellipsoid.
fn brute_force(rings: &Rings, radii: DVec3, p: DVec3, n: DVec3, sun: DVec3) -> Spectrum {
    let globe = Ellipsoid {
        center: DVec3::ZERO,
        radii,
    };
    let (radial, angular) = (120, 1440);
    let mut e = Spectrum::ZERO;
    for band in &rings.bands {
        let dr = (band.outer_m - band.inner_m) / radial as f64;
        for i in 0..radial {
            let r = band.inner_m + (i as f64 + 0.5) * dr;
            for k in 0..angular {
                let phi = (k as f64 + 0.5) * 2.0 * PI / angular as f64;
                let x = DVec3::new(r * phi.cos(), r * phi.sin(), 0.0);
                let to_ring = x - p;
                let d = to_ring.length();
                let cos_p = n.dot(to_ring) / d;
                let ray = Ray::new(x, sun).unwrap();
                if cos_p <= 0.0 || globe.intersect(&ray).is_some_and(|h| h.far > 0.0) {
                    continue;
                }
                let area = r * dr * 2.0 * PI / angular as f64;
                e +=
                    rings.radiance(r, to_ring / d, sun, Spectrum::ONE, true) * (cos_p * p.z.abs() / d / (d * d) * area);
            }
        }
    }
    e
}

#[test]
fn saturn_s_ringshine_agrees_with_a_brute_force_sum() {
    let (rings, radii) = saturn();
    // North (under the lit face) and south (the far face), on the night side, at dusk and by day.
    for (latitude, longitude) in [(40.0, 180.0), (25.0, 120.0), (-35.0, 170.0), (60.0, 90.0), (30.0, 0.0)] {
        let (p, n) = ground(radii, latitude, longitude);
        let light = rings.light_on_ground(radii, p, n, sun(), no_air);
        let reference = brute_force(&rings, radii, p, n, sun());
        let error = relative(light, reference);
        println!(
            "latitude {latitude}°, longitude {longitude}°: {:.4e} vs {:.4e} ({:.3} %)",
            light.y,
            reference.y,
            100.0 * error,
        );
        assert!(reference.max_element() > 0.0);
        assert!(error < 5e-3, "latitude {latitude}, longitude {longitude}: {error}");
    }
}

#[test]
fn the_rings_send_nothing_edge_on_to_the_sun_or_below_the_horizon() {
    let (rings, radii) = saturn();
    let (p, n) = ground(radii, 40.0, 180.0);
    assert_eq!(rings.light_on_ground(radii, p, n, DVec3::X, no_air), Spectrum::ZERO);
    // At the pole the rings lie below the horizon (their inner edge is 1.24 equatorial radii out).
    let (pole, up) = (DVec3::new(0.0, 0.0, radii.z), DVec3::Z);
    assert_eq!(rings.light_on_ground(radii, pole, up, sun(), no_air), Spectrum::ZERO);
}

#[test]
fn the_table_holds_the_light_at_its_texel_centres_and_turns_with_the_sun() {
    let (rings, radii) = saturn();
    let (width, height) = RING_LIGHT_TABLE_SIZE;
    // The sun at another azimuth: the table is relative to it.
    let turned = DVec3::new(-sun().x * 0.6, sun().x * 0.8, sun().z);
    let air = GroundTransmittance::new(&presets::saturn());
    let table = rings.light_table(radii, turned, &air);
    assert_eq!(table.len(), width * height);
    let (i, j) = (17, 22);
    let azimuth = (i as f64 + 0.5) * 180.0 / width as f64;
    let latitude = row_latitude((j as f64 + 0.5) / height as f64).to_degrees();
    let (p, n) = ground(radii, latitude, azimuth);
    let expected = rings.light_on_ground(radii, p, n, sun(), |view| air.at(n.dot(view)));
    let texel = table[j * width + i];
    assert!(relative(texel, expected) < 1e-9, "{texel} vs {expected}");
    // The air keeps some of it, less in blue.
    let bare = rings.light_on_ground(radii, p, n, sun(), no_air);
    let kept = texel / bare;
    assert!(
        kept.min_element() > 0.0 && kept.max_element() < 1.0 && kept.z < kept.x,
        "{kept}"
    );
}

#[test]
fn the_ground_s_transmittance_follows_the_reference_between_its_nodes() {
    let atmosphere = presets::earth();
    let air = GroundTransmittance::new(&atmosphere);
    let radius = atmosphere.planet.mean_radius();
    let sphere = Atmosphere {
        planet: Planet::sphere(radius, atmosphere.planet.atmosphere_height),
        ..atmosphere
    };
    let reference = Reference::new(sphere, &[], ReferenceSettings::default());
    let ground = DVec3::new(0.0, 0.0, radius + 1e-3);
    for cos in [0.003_f64, 0.02, 0.1, 0.37, 0.8, 1.0] {
        let direction = DVec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
        let want = reference.transmittance_to_space(ground, direction);
        let got = air.at(cos);
        let error = (got - want).abs().max_element() / want.max_element();
        println!("cos θ {cos}: {got:.4} vs {want:.4}");
        assert!(error < 5e-3, "cos θ {cos}: {got} vs {want}");
    }
    assert_eq!(air.at(-0.1), Spectrum::ZERO);
}

#[test]
fn the_table_read_between_its_texels_stays_close_to_the_integral() {
    // Bilinear between texel centres, as the GPU reads it (rings.wgsl), at 400 points spread over
    // the globe; each error against the light there or, where it is faint, 5 % of the brightest.
    let (rings, radii) = saturn();
    let s = DVec3::new(1.0, 0.0, 0.45).normalize();
    let air = GroundTransmittance::new(&presets::saturn());
    let table = rings.light_table(radii, s, &air);
    let (width, height) = RING_LIGHT_TABLE_SIZE;
    let brightest = table.iter().map(|t| t.max_element()).fold(0.0, f64::max);
    let (mut worst, mut sum) = (0.0_f64, 0.0);
    let points = 400;
    for k in 0..points {
        let latitude = -80.0 + 160.0 * ((k * 37 % points) as f64 + 0.5) / points as f64;
        let longitude = 180.0 * ((k * 91 % points) as f64 + 0.5) / points as f64;
        let (p, n) = ground(radii, latitude, longitude);
        let direct = rings.light_on_ground(radii, p, n, s, |view| air.at(n.dot(view)));
        let v = 0.5 + 0.5 * f64::signum(latitude) * (latitude.abs() / 90.0).sqrt();
        let x = (longitude / 180.0 * width as f64 - 0.5).clamp(0.0, width as f64 - 1.0);
        let y = (v * height as f64 - 0.5).clamp(0.0, height as f64 - 1.0);
        let (i, j) = ((x as usize).min(width - 2), (y as usize).min(height - 2));
        let (fx, fy) = (x - i as f64, y - j as f64);
        let at = |i: usize, j: usize| table[j * width + i];
        let read = at(i, j) * (1.0 - fx) * (1.0 - fy)
            + at(i + 1, j) * fx * (1.0 - fy)
            + at(i, j + 1) * (1.0 - fx) * fy
            + at(i + 1, j + 1) * fx * fy;
        let error = (read - direct).abs().max_element() / direct.max_element().max(0.05 * brightest);
        worst = worst.max(error);
        sum += error;
    }
    let mean = sum / points as f64;
    println!(
        "table read between texels: mean {:.2} %, worst {:.2} %",
        100.0 * mean,
        100.0 * worst
    );
    assert!(mean < 0.01 && worst < 0.06, "mean {mean}, worst {worst}");
}
