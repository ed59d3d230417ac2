use std::f64::consts::PI;

use glam::{DQuat, DVec3};

use super::*;
use crate::atmosphere::body::tests::sun;
use crate::atmosphere::body::{BodySurface, Reflectance};
use crate::atmosphere::eclipse::visible_fraction;
use crate::atmosphere::presets;
use crate::frame::AtmosphereSky;

/// A ball of radius `radius` 10⁹ m from a planet without light of its own (geometric albedo 0).
fn ball(reflectance: Reflectance, radius: f64) -> (Body, Planet) {
    let mut planet = Planet::sphere(6_371_000.0, 100_000.0);
    planet.geometric_albedo = 0.0;
    let body = Body {
        center: DVec3::new(1.0e9, 0.0, 0.0),
        radii: DVec3::splat(radius),
        orientation: DQuat::IDENTITY,
        albedo: Spectrum::new(0.1, 0.2, 0.3),
        reflectance,
        surface: BodySurface::Uniform,
        planet_shadow: None,
        air: None,
    };
    (body, planet)
}

/// The disc-integrated phase laws (brightness at phase angle `alpha` over that at 0): a Lambert
/// sphere's (Russell 1916, ApJ 43, 173), a Lommel–Seeliger sphere's
/// `1 − sin(α/2)·tan(α/2)·ln(cot(α/4))` (Hapke 2012, §9.4, no opposition effect) and the Moon's
/// measured curve (Krisciunas & Schaefer 1991, eq. 9).
fn phase_law(reflectance: Reflectance, alpha: f64) -> f64 {
    match reflectance {
        Reflectance::Lambert => (alpha.sin() + (PI - alpha) * alpha.cos()) / PI,
        Reflectance::LommelSeeliger => {
            if alpha == 0.0 {
                1.0
            } else {
                1.0 - (alpha / 2.0).sin() * (alpha / 2.0).tan() * (1.0 / (alpha / 4.0).tan()).ln()
            }
        }
        Reflectance::Lunar => {
            let phi = alpha.to_degrees();
            10f64.powf(-0.4 * (0.026 * phi + 4e-9 * phi.powi(4)))
        }
    }
}

/// The light of a ball seen 10⁴ radii away (where the near side's being nearer adds 10⁻⁴) at phase angles from full to a thin crescent follows
/// the closed-form phase laws and the Moon's measured one, their geometric albedos 2A/3 (Lambert)
/// and A (Lommel–Seeliger, the Moon).
#[test]
fn a_balls_light_follows_its_phase_law() {
    let radius = 1.0e6;
    // The sun lights the ball across the planet's line of sight, out of its shadow.
    let s = sun(DVec3::Z);
    let laws = [
        (Reflectance::Lambert, 2.0 / 3.0),
        (Reflectance::LommelSeeliger, 1.0),
        (Reflectance::Lunar, 1.0),
    ];
    for (reflectance, albedo_ratio) in laws {
        let (body, planet) = ball(reflectance, radius);
        for alpha_deg in [0.0f64, 30.0, 60.0, 90.0, 120.0, 150.0] {
            let alpha = alpha_deg.to_radians();
            let towards_viewer = DVec3::new(0.0, alpha.sin(), alpha.cos());
            let q = body.center + towards_viewer * (1.0e4 * radius);
            let got = cast_irradiance(q, 0, &[s], &planet, None, std::slice::from_ref(&body));
            let expected = s.irradiance * body.albedo * (albedo_ratio * phase_law(reflectance, alpha) / 1.0e8);
            let error = ((got - expected) / (s.irradiance * body.albedo * (albedo_ratio / 1.0e8))).abs();
            assert!(
                error.max_element() < 1e-3,
                "{reflectance:?} at {alpha_deg}°: {got:?} vs {expected:?}"
            );
        }
    }
}

/// A body sends nothing to a point inside it, and none of the light of a sun that comes from it.
#[test]
fn a_body_sends_none_of_its_own_light() {
    let (body, planet) = ball(Reflectance::Lambert, 1.0e6);
    let s = sun(DVec3::Z);
    let inside = cast_irradiance(body.center, 0, &[s], &planet, None, std::slice::from_ref(&body));
    assert_eq!(inside, Spectrum::ZERO);
    let own = Sun {
        from_body: Some(0),
        disc: false,
        ..sun(DVec3::X)
    };
    let q = body.center - DVec3::X * 1.0e8;
    let lit_by_own = cast_irradiance(q, 0, &[own], &planet, None, std::slice::from_ref(&body));
    assert_eq!(lit_by_own, Spectrum::ZERO);
}

/// The sky adds each body's light as a disc-less sun towards it that the body does not hide:
/// from the planet the Moon, full and at its mean distance, gives its geometric albedo's share.
#[test]
fn the_sky_carries_a_bodys_light_as_a_sun_it_does_not_hide() {
    let mut atmosphere = presets::earth();
    atmosphere.planet.geometric_albedo = 0.0;
    let distance = 384_400_000.0;
    let mut sky = AtmosphereSky {
        atmosphere,
        suns: vec![sun(DVec3::new(0.0, -1.0, 0.0))],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    // Full: the Moon opposite the sun, just off the planet's shadow (2° out of line).
    let towards = DVec3::new(0.0, 2f64.to_radians().cos(), 2f64.to_radians().sin());
    let center = sky.atmosphere.planet.center;
    let mut moon = Body::moon(center + towards * distance);
    moon.surface = BodySurface::Uniform;
    sky.add_body(moon.clone());
    let eye = center + DVec3::new(0.0, 0.0, 6_371_000.0 + 10.0);
    sky.add_body_lights(eye, |_| true);
    sky.validate().expect("a valid sky");
    assert_eq!(sky.suns.len(), 2);
    // Again: the light is replaced, not added twice.
    let once = sky.suns.clone();
    sky.add_body_lights(eye, |_| true);
    assert_eq!(sky.suns, once);
    let light = sky.suns[1];
    assert_eq!(light.from_body, Some(0));
    assert!(!light.disc);
    let to_moon = moon.center - eye;
    assert!(light.direction.angle_between(to_moon) < 1e-7);
    assert!((light.angular_radius - (moon.mean_radius() / to_moon.length()).asin()).abs() < 1e-15);
    // A·E·(R/d)²·Φ(α) at a phase angle of ~2°, within the 2R/d ≈ 1 % by which
    // the near side's being nearer brightens it.
    let alpha = sky.suns[0].direction.angle_between(-to_moon);
    let full = sky.suns[0].irradiance * moon.albedo * (moon.mean_radius() / to_moon.length()).powi(2);
    let expected = full * phase_law(Reflectance::Lunar, alpha);
    let error = ((light.irradiance - expected) / full).abs().max_element();
    assert!(error < 1.2e-2, "{:?} vs {expected:?}", light.irradiance);
    // The Moon hides its own light from nowhere; it still hides (most of) a sun behind it.
    let eclipsers = [moon.eclipser()];
    let behind = moon.center + to_moon.normalize() * 1.0e7;
    let seen_from_behind = visible_fraction(behind, &light, &eclipsers);
    assert_eq!(seen_from_behind, 1.0);
    let sun_behind = Sun {
        direction: to_moon.normalize(),
        ..sky.suns[0]
    };
    assert!(visible_fraction(eye, &sun_behind, &eclipsers) < 0.1);
}
