//! The eclipse quadrature against two independent computations: the area of the lens two
//! circles share (closed form, uniform disc) and an integral over the sun's rows (each row's
//! covered chord integrated in closed form, the rows by the midpoint rule), with the same
//! limb-darkening law, in f64.

use super::*;
use crate::atmosphere::Spectrum;

/// The area two circles of radii 1 and `k` with centres `d` apart share.
fn lens_area(d: f64, k: f64) -> f64 {
    if d >= 1.0 + k {
        return 0.0;
    }
    if d <= (1.0 - k).abs() {
        return PI * k.min(1.0).powi(2);
    }
    let alpha = ((d * d + 1.0 - k * k) / (2.0 * d)).acos();
    let beta = ((d * d + k * k - 1.0) / (2.0 * d * k)).acos();
    let kite = ((-d + k + 1.0) * (d + k - 1.0) * (d - k + 1.0) * (d + k + 1.0)).sqrt();
    alpha + k * k * beta - 0.5 * kite
}

/// ∫ sqrt(s² − x²) dx from 0 to x (|x| ≤ s).
fn circle_integral(s: f64, x: f64) -> f64 {
    let x = x.clamp(-s, s);
    if s <= 0.0 {
        return 0.0;
    }
    0.5 * (x * (s * s - x * x).max(0.0).sqrt() + s * s * (x / s).clamp(-1.0, 1.0).asin())
}

/// The hidden fraction by rows: for each row y of the sun, the chord inside both discs, with
/// `I = 1 − u + u·sqrt(1 − x² − y²)` integrated along it in closed form.
fn hidden_by_rows(d: f64, k: f64, u: f64) -> f64 {
    let rows = 400_000;
    let mut hidden = 0.0;
    for i in 0..rows {
        let y = -1.0 + (i as f64 + 0.5) * 2.0 / rows as f64;
        if y.abs() >= k {
            continue;
        }
        let s = (1.0 - y * y).sqrt();
        let b = (k * k - y * y).sqrt();
        let (x0, x1) = ((d - b).max(-s), (d + b).min(s));
        if x1 <= x0 {
            continue;
        }
        hidden += (1.0 - u) * (x1 - x0) + u * (circle_integral(s, x1) - circle_integral(s, x0));
    }
    hidden * 2.0 / rows as f64 / (PI * (1.0 - u / 3.0))
}

/// Partial (the body's edge across the sun), annular (inside it) and total (covering it) cases,
/// small and large bodies.
const CASES: [(f64, f64); 14] = [
    (0.0, 0.5),
    (0.2, 0.5),
    (0.5, 0.5),
    (1.2, 0.5),
    (1.45, 0.5),
    (0.3, 0.95),
    (0.04, 0.97),
    (0.5, 1.0),
    (1.0, 1.0),
    (1.9, 1.0),
    (0.03, 1.05),
    (0.5, 1.06),
    (2.0, 3.0),
    (3.5, 3.0),
];

#[test]
fn a_uniform_disc_hides_the_lens_area() {
    for (d, k) in CASES {
        let exact = lens_area(d, k) / PI;
        let quadrature = hidden_fraction(d, k, 0.0);
        assert!(
            (quadrature - exact).abs() < 1e-7,
            "d {d} k {k}: {quadrature} vs {exact}"
        );
    }
}

#[test]
fn a_limb_darkened_disc_matches_the_row_integral() {
    for u in [0.0, 0.6, 1.0] {
        for (d, k) in CASES {
            let rows = hidden_by_rows(d, k, u);
            let quadrature = hidden_fraction(d, k, u);
            assert!(
                (quadrature - rows).abs() < 1e-6,
                "u {u} d {d} k {k}: {quadrature} vs {rows}"
            );
        }
    }
    // Limb darkening makes a central body hide more than its area, a grazing one less.
    assert!(hidden_fraction(0.0, 0.5, 0.6) > 0.25);
    assert!(hidden_fraction(1.3, 0.5, 0.6) < lens_area(1.3, 0.5) / PI);
}

#[test]
fn totality_and_clear_sky_are_exact() {
    assert_eq!(hidden_fraction(0.0, 1.0, 0.6), 1.0);
    assert_eq!(hidden_fraction(0.04, 1.05, 0.6), 1.0);
    assert_eq!(hidden_fraction(1.5, 0.5, 0.6), 0.0);
    assert_eq!(hidden_fraction(0.3, 0.0, 0.6), 0.0);
}

fn sun_towards(direction: DVec3) -> Sun {
    Sun {
        direction,
        angular_radius: 0.004_65,
        irradiance: Spectrum::ONE,
        limb_darkening: 0.6,
        disc: true,
        from_body: None,
    }
}

#[test]
fn the_moon_hides_the_sun_from_inside_its_shadow_only() {
    let sun = sun_towards(DVec3::Z);
    // The Moon straight towards the sun, 380 000 km out: its angular radius (4.57 mrad) is just
    // under the sun's (4.65 mrad) — an annular eclipse on the axis.
    let moon = Eclipser {
        center: DVec3::new(0.0, 0.0, 3.8e8),
        radius_m: 1.7374e6,
    };
    let on_axis = moon.visible_fraction(DVec3::ZERO, &sun);
    let k: f64 = (1.7374e6f64 / 3.8e8).asin() / 0.004_65;
    assert!((on_axis - (1.0 - hidden_fraction(0.0, k, 0.6))).abs() < 1e-12);
    assert!(on_axis > 0.0 && on_axis < 0.05, "{on_axis}");
    // Nearer, it covers the sun: totality on the axis, partial 1000 km off it, none 5000 km off.
    let near = Eclipser {
        center: DVec3::new(0.0, 0.0, 3.6e8),
        ..moon
    };
    assert_eq!(near.visible_fraction(DVec3::ZERO, &sun), 0.0);
    let partial = near.visible_fraction(DVec3::new(1.0e6, 0.0, 0.0), &sun);
    assert!(partial > 0.1 && partial < 0.9, "{partial}");
    assert_eq!(near.visible_fraction(DVec3::new(5.0e6, 0.0, 0.0), &sun), 1.0);
    // Behind the point, it hides nothing; inside it, everything.
    let behind = Eclipser {
        center: DVec3::new(0.0, 0.0, -3.6e8),
        ..moon
    };
    assert_eq!(behind.visible_fraction(DVec3::ZERO, &sun), 1.0);
    assert_eq!(near.visible_fraction(near.center, &sun), 0.0);
    // Two bodies multiply.
    let both = visible_fraction(DVec3::new(1.0e6, 0.0, 0.0), &sun, &[near, near]);
    assert!((both - partial * partial).abs() < 1e-12);
}

#[test]
fn bad_eclipsers_name_the_rule() {
    let bad = Eclipser {
        center: DVec3::new(f64::NAN, 0.0, 0.0),
        radius_m: 1.0,
    };
    assert!(bad.validate().unwrap_err().to_string().contains("eclipser.center"));
    let flat = Eclipser {
        center: DVec3::ZERO,
        radius_m: 0.0,
    };
    assert!(flat.validate().unwrap_err().to_string().contains("eclipser.radius"));
}
