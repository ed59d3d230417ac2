//! The shadow against closed forms: the eclipse of the sun by an airless planet, the refraction
//! of a grazing ray, the conservation of the light bent into the shadow; and a lunar eclipse's
//! colour and depth against what is observed.

use super::*;
use crate::atmosphere::eclipse::hidden_fraction;
use crate::atmosphere::presets;

/// The Moon's mean distance, metres.
const MOON_DISTANCE_M: f64 = 3.844e8;

fn earth() -> Atmosphere {
    presets::earth()
}

fn sun() -> Sun {
    presets::earth_sun(DVec3::Z)
}

#[test]
fn an_airless_planet_eclipses_the_sun_as_two_discs_do() {
    let atmosphere = earth();
    let height = atmosphere.planet.atmosphere_height;
    let settings = ShadowSettings {
        refractivity: 0.0,
        cloud_top_m: height,
        clear_fraction: 0.0,
        ..ShadowSettings::default()
    };
    let sun = sun();
    let shadow = PlanetShadow::new(&atmosphere, &sun, MOON_DISTANCE_M, &settings);
    let top = atmosphere.planet.mean_radius() + height;
    let image = MOON_DISTANCE_M * sun.angular_radius;
    for (k, light) in shadow.light.iter().enumerate() {
        let rho = k as f64 * shadow.step_m;
        let want = 1.0 - hidden_fraction(rho / image, top / image, sun.limb_darkening);
        assert!((light.y - want).abs() < 2e-3, "{rho} m: {} vs {want}", light.y);
    }
}

#[test]
fn a_grazing_ray_bends_by_twice_the_horizontal_refraction() {
    let atmosphere = earth();
    let settings = ShadowSettings {
        cloud_top_m: 0.0,
        ..ShadowSettings::default()
    };
    let rays = Rays::new(&atmosphere, 1.0, &settings);
    let bend = rays.impact[0] - rays.landing[0];
    let arcmin = bend.to_degrees() * 60.0;
    // The astronomical refraction at the horizon is 34.5′ (Bennett's formula at 0°: 34.5′).
    assert!((arcmin / 69.0 - 1.0).abs() < 0.05, "{arcmin}′");
}

#[test]
fn the_light_bent_into_the_shadow_is_the_light_that_crossed_the_air() {
    let atmosphere = earth();
    let rays = Rays::new(&atmosphere, MOON_DISTANCE_M, &ShadowSettings::default());
    // In: ∫ T(h)·2πb db over the impact parameters; out: ∫ E₁(q)·2πq dq over the refracted
    // light's landing places (the straight sunlight beyond the top left out).
    let mut entering = Spectrum::ZERO;
    for i in 1..rays.impact.len() {
        let db = rays.impact[i] - rays.impact[i - 1];
        let b = 0.5 * (rays.impact[i] + rays.impact[i - 1]);
        entering += (rays.transmittance[i] + rays.transmittance[i - 1]) * 0.5 * (2.0 * PI * b * db);
    }
    let reach = rays.landing.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let n = 400_000;
    let dq = reach / n as f64;
    let mut landed = Spectrum::ZERO;
    for i in 0..n {
        let q = (i as f64 + 0.5) * dq;
        let refracted = rays.landing_at(q, q) + rays.landing_at(-q, q);
        landed += refracted * (2.0 * PI * q * dq);
    }
    let ratio = landed / entering;
    assert!((ratio - Spectrum::ONE).abs().max_element() < 2e-3, "{ratio}");
}

#[test]
fn the_eclipsed_moon_is_dim_and_red() {
    let atmosphere = earth();
    let sun = sun();
    let shadow = PlanetShadow::new(&atmosphere, &sun, MOON_DISTANCE_M, &ShadowSettings::default());
    // The geometric umbra's radius at the Moon: R − D·(α − R/D) ≈ 4600 km.
    let radius = atmosphere.planet.mean_radius();
    let umbra = radius - MOON_DISTANCE_M * sun.angular_radius;
    for rho in [0.0, 0.3 * umbra, 0.7 * umbra] {
        let light = shadow.at(rho);
        println!(
            "{:.0} km: {:.3e} {:.3e} {:.3e}",
            rho / 1000.0,
            light.x,
            light.y,
            light.z
        );
        // Observed totality: the Moon 10–15 magnitudes below full (Danjon L 1–3), red.
        assert!(light.y > 1e-6 && light.y < 1e-3, "{rho}: {light}");
        assert!(light.x > 3.0 * light.z, "{rho}: {light}");
    }
    // Full sunlight beyond the penumbra, and the penumbra between.
    assert_eq!(shadow.at(shadow.reach_m() * 1.01), Spectrum::ONE);
    let edge = shadow.at(radius);
    assert!(edge.y > 0.2 && edge.y < 0.8, "{edge}");
}
