use glam::DQuat;

use super::*;
use crate::atmosphere::body::tests::sun;
use crate::atmosphere::body::{BodySurface, Reflectance};
use crate::atmosphere::medium::{Absorber, DensityLayer, DensityProfile, Mie, Rayleigh};
use crate::atmosphere::{Planet, presets};

const RADIUS: f64 = 3_389_500.0;
const TOP: f64 = 60_000.0;
const SCALE_HEIGHT: f64 = 8_000.0;

/// A ball of Mars's size whose air is molecules alone, `beta` m⁻¹ at the ground.
fn rayleigh_ball(beta: Spectrum) -> Body {
    let exponential = DensityProfile::single(DensityLayer::exponential(SCALE_HEIGHT));
    Body {
        center: DVec3::new(1e9, -2e8, 3e8),
        radii: DVec3::splat(RADIUS),
        orientation: DQuat::from_rotation_y(0.7),
        air: Some(BodyAir {
            constituents: Constituents {
                rayleigh: Rayleigh {
                    scattering: beta,
                    density: exponential,
                },
                mie: Mie {
                    scattering: Spectrum::ZERO,
                    extinction: Spectrum::ZERO,
                    density: exponential,
                    phase: Phase::CornetteShanks { g: 0.8 },
                },
                absorber: Absorber {
                    absorption: Spectrum::ZERO,
                    density: exponential,
                },
            },
            top_altitude_m: TOP,
        }),
        ..Body::moon(DVec3::ZERO)
    }
}

/// The vertical optical depth from altitude `h` to the top of an exponential air: β·H·(e^(−h/H)
/// − e^(−top/H)).
fn depth_above(beta: Spectrum, h: f64) -> Spectrum {
    beta * (SCALE_HEIGHT * ((-h / SCALE_HEIGHT).exp() - (-TOP / SCALE_HEIGHT).exp()))
}

#[test]
fn the_vertical_transmittance_is_the_exponential_air_s_closed_form() {
    let beta = Spectrum::new(5.8e-6, 13.6e-6, 33.1e-6);
    let body = rayleigh_ball(beta);
    let up = DVec3::new(0.3, -0.5, 0.81).normalize();
    for h in [1.0, 5_000.0, 20_000.0] {
        let p = body.center + up * (RADIUS + h);
        let got = body.air_transmittance(p, up);
        let expected = (-depth_above(beta, h)).exp();
        let error = (got / expected - 1.0).abs().max_element();
        assert!(error < 1e-5, "h {h}: {got:?} vs {expected:?}");
    }
    // Towards the body the ray meets it: no light.
    let p = body.center + up * (RADIUS + 1_000.0);
    assert_eq!(body.air_transmittance(p, -up), Spectrum::ZERO);
}

#[test]
fn a_vertical_view_down_the_sun_s_beam_scatters_the_closed_form() {
    // Sun overhead, the view straight down: at altitude h both the sun's and the view's path
    // have the depth τ(h) above h, so L = E·p(−1)·∫ β·ρ(h)·e^(−2τ(h)) dh = E·p(−1)·(1 − e^(−2τ₀))/2.
    let beta = Spectrum::new(5.8e-5, 13.6e-5, 33.1e-5);
    let body = rayleigh_ball(beta);
    let up = DVec3::new(-0.2, 0.9, 0.1).normalize();
    let suns = [sun(up)];
    let ray = Ray::new(body.center + up * (RADIUS + 2.0 * TOP), -up).unwrap();
    let segment = body.air_along(&ray, f64::INFINITY, &suns, |_, _| Spectrum::ONE, None);
    let tau0 = depth_above(beta, 0.0);
    let expected = suns[0].irradiance * (1.0 - (-2.0 * tau0).exp()) * (0.5 * medium::rayleigh_phase(-1.0));
    let error = (segment.radiance / expected - 1.0).abs().max_element();
    assert!(error < 1e-4, "{:?} vs {expected:?}", segment.radiance);
    let through = (segment.transmittance / (-tau0).exp() - 1.0).abs().max_element();
    assert!(through < 1e-5, "{:?}", segment.transmittance);
}

#[test]
fn a_ray_that_misses_the_air_or_ends_before_it_is_clear() {
    let body = rayleigh_ball(Spectrum::splat(1e-5));
    let suns = [sun(DVec3::X)];
    let side = DVec3::Z.cross(DVec3::X);
    let miss = Ray::new(body.center + side * (RADIUS + 2.0 * TOP) - DVec3::X * 1e8, DVec3::X).unwrap();
    assert_eq!(
        body.air_along(&miss, f64::INFINITY, &suns, |_, _| Spectrum::ONE, None),
        AirSegment::CLEAR
    );
    let towards = Ray::new(body.center - DVec3::X * 1e8, DVec3::X).unwrap();
    assert_eq!(
        body.air_along(&towards, 1e7, &suns, |_, _| Spectrum::ONE, None),
        AirSegment::CLEAR
    );
    let airless = Body { air: None, ..body };
    assert_eq!(
        airless.air_transmittance(airless.center + DVec3::X * RADIUS, DVec3::X),
        Spectrum::ONE
    );
}

#[test]
fn the_presets_airs_are_constituents_but_venus_s_is_not() {
    let earth = BodyAir::from_atmosphere(&presets::earth()).unwrap();
    assert_eq!(earth.top_altitude_m, 60_000.0);
    earth.validate().unwrap();
    BodyAir::from_atmosphere(&presets::mars()).unwrap().validate().unwrap();
    assert!(BodyAir::from_atmosphere(&presets::venus()).is_none());
}

#[test]
fn bad_airs_name_the_field() {
    let good = BodyAir::from_atmosphere(&presets::earth()).unwrap();
    let field = |air: BodyAir| match air.validate() {
        Err(CoreError::Invalid { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    let mut air = good.clone();
    air.top_altitude_m = 0.0;
    assert_eq!(field(air), "body.air.top_altitude_m");
    let mut air = good.clone();
    air.constituents.mie.extinction = Spectrum::splat(1e-7);
    assert_eq!(field(air), "body.air.mie.extinction");
    let mut air = good.clone();
    air.constituents.rayleigh.scattering.y = f64::NAN;
    assert_eq!(field(air), "body.air.rayleigh.scattering");
    let mut air = good;
    air.constituents.mie.phase = Phase::CornetteShanks { g: 1.0 };
    assert_eq!(field(air), "body.air.mie.phase");
}

#[test]
fn airs_count_in_how_far_apart_bodies_must_be() {
    let planet = Planet::sphere(6_371_000.0, 100_000.0);
    let a = rayleigh_ball(Spectrum::splat(1e-5));
    let mut b = Body { air: None, ..a.clone() };
    // Clear of each other's ground, but inside a's air.
    b.center = a.center + DVec3::X * (2.0 * RADIUS + 0.5 * TOP);
    assert!(super::super::validate_bodies(&[a.clone(), b.clone()], &planet).is_err());
    b.center = a.center + DVec3::X * (2.0 * RADIUS + 2.0 * TOP);
    super::super::validate_bodies(&[a, b], &planet).unwrap();
}

/// An Earth-sized Lambert ball of albedo 0.3 with Earth's air, seen from 60 000 km at 60° from
/// the sun, against the independent path tracer of the same air as the planet's (every order):
/// once-scattered light alone is too dark; with the tables' light scattered more than once and
/// the sky's light on the ground, the ground through the air and the sunlit limb come within
/// the budget (docs/ATMOSPHERE.md, "Bodies", has the figures).
#[test]
fn an_earth_sized_ball_from_space_matches_the_path_tracer() {
    use crate::atmosphere::reference::{Reference, ReferenceSettings};
    let radius = 6_371_000.0;
    let body = Body {
        center: DVec3::ZERO,
        radii: DVec3::splat(radius),
        orientation: DQuat::IDENTITY,
        albedo: Spectrum::splat(0.3),
        reflectance: Reflectance::Lambert,
        surface: BodySurface::Uniform,
        planet_shadow: None,
        air: BodyAir::from_atmosphere(&presets::earth()),
    };
    let tables = body.air_light().expect("an air");
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(radius, 60_000.0);
    atmosphere.medium.ground_albedo = body.albedo;
    let to_sun = DVec3::Z;
    let suns = [sun(to_sun)];
    let settings = ReferenceSettings {
        paths: 16_384,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(atmosphere, &suns, settings);
    let to_eye = DQuat::from_rotation_y(60f64.to_radians()) * to_sun;
    let eye = to_eye * 60_000_000.0;
    let grazing = |impact: f64| {
        let across = (to_sun - to_eye * to_sun.dot(to_eye)).normalize();
        let sin = impact / eye.length();
        -to_eye * (1.0 - sin * sin).sqrt() + across * sin
    };
    let cases = [
        (
            "ground half-way to the sun",
            ((to_sun + to_eye).normalize() * radius - eye).normalize(),
            0.05,
        ),
        ("ground under the eye", -to_eye, 0.05),
        ("sunlit limb, 5 km up", grazing(radius + 5_000.0), 0.1),
        ("sunlit limb, 20 km up", grazing(radius + 20_000.0), 0.1),
    ];
    for (name, d, budget) in cases {
        let ray = Ray::new(eye, d).expect("a ray");
        let radiance = |more: Option<&AirLight>| {
            let air = body.air_along(&ray, f64::INFINITY, &suns, |_, _| Spectrum::ONE, more);
            let ground = body.hit(&ray).map_or(Spectrum::ZERO, |t| {
                let p = ray.at(t);
                let direct = body.radiance(p, -d, &suns, |_| body.air_transmittance(p, to_sun));
                direct
                    + more.map_or(Spectrum::ZERO, |m| {
                        body.skylight_radiance(p, -d, &suns, m, |_| Spectrum::ONE)
                    })
            });
            air.radiance + air.transmittance * ground
        };
        let want = reference.radiance(&ray).scattered();
        let (once, every) = (radiance(None), radiance(Some(&tables)));
        let error = |got: Spectrum| ((got - want).abs() / want).max_element();
        println!(
            "{name}: path tracer {want:.5}, once {once:.5} ({:.1} %), every order {every:.5} ({:.1} %)",
            100.0 * error(once),
            100.0 * error(every)
        );
        assert!(error(every) < budget, "{name}: {every} vs {want}");
        assert!(error(every) < error(once), "{name}: the tables bring it closer");
    }
}
