use glam::DQuat;

use super::*;
use crate::atmosphere::body::tests::sun;
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
    let segment = body.air_along(&ray, f64::INFINITY, &suns, |_, _| Spectrum::ONE);
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
        body.air_along(&miss, f64::INFINITY, &suns, |_, _| Spectrum::ONE),
        AirSegment::CLEAR
    );
    let towards = Ray::new(body.center - DVec3::X * 1e8, DVec3::X).unwrap();
    assert_eq!(
        body.air_along(&towards, 1e7, &suns, |_, _| Spectrum::ONE),
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
