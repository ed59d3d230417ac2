//! GPU tests of the bodies beside the planet (`atmosphere/bodies.wgsl`) against closed forms and
//! the f64 core (`firmament_core::atmosphere::body`, `eclipse`): a body's radiance by its
//! reflectance law under an air too thin to matter, the planet's penumbra on it, which of the
//! planet and a body hides the other, and a body seen from 1 AU and from 100 AU.

use crate::support::{centre_radiance, far_view_difference, gpu};

use firmament_core::atmosphere::body::maria::{MARIA, albedo_factor};
use firmament_core::atmosphere::body::phase::lunar_phase_factor;
use firmament_core::atmosphere::body::{Body, BodySurface, MOON_ALBEDO, MOON_RADIUS_M, Reflectance, sunlight_share};
use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer};
use firmament_core::atmosphere::planet_shadow::{PlanetShadow, ShadowSettings};
use firmament_core::atmosphere::{Planet, Spectrum, presets};
use firmament_core::frame::AtmosphereSky;
use glam::{DQuat, DVec3};

const EARTH_RADIUS_M: f64 = 6_360_000.0;

/// Earth's air a million times thinner on Bruneton's sphere (the world ENU at 0°, 0°: the
/// planet's centre at (0, 0, −R)), one sun from world direction `sun`, and `bodies`.
pub(crate) fn airless_with(sun: DVec3, bodies: Vec<Body>) -> AtmosphereSky {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(EARTH_RADIUS_M, 60_000.0).posed_at(0.0, 0.0);
    for term in &mut atmosphere.medium.terms {
        term.scattering *= 1e-6;
        term.absorption *= 1e-6;
    }
    let mut sky = AtmosphereSky {
        atmosphere,
        suns: vec![presets::earth_sun(sun)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    for body in bodies {
        sky.add_body(body);
    }
    sky.validate().expect("a valid sky");
    sky
}

/// The Moon without its maria or its phase factor: its albedo 0.12 everywhere, Lommel–Seeliger.
fn plain_moon(center: DVec3) -> Body {
    Body {
        surface: BodySurface::Uniform,
        reflectance: Reflectance::LommelSeeliger,
        ..Body::moon(center)
    }
}

pub(crate) fn planet_center() -> DVec3 {
    DVec3::new(0.0, 0.0, -EARTH_RADIUS_M)
}

/// A plain Moon 384 400 km behind the planet from a sun along +x, its centre `off_axis_m` from the
/// shadow's axis, and an eye sunward of it and off the axis (so it sees the face towards the
/// planet without looking through it): the Moon's centre, the eye, the sky.
fn moon_behind_the_planet(off_axis_m: f64) -> (DVec3, DVec3, AtmosphereSky) {
    let moon_center = planet_center() + DVec3::new(-384_400_000.0, 0.0, off_axis_m);
    let eye = moon_center + DVec3::new(20_000_000.0, 0.0, 30_000_000.0);
    (moon_center, eye, airless_with(DVec3::X, vec![plain_moon(moon_center)]))
}

/// Spectral radiance as the GPU's linear sRGB.
pub(crate) fn as_srgb(sky: &AtmosphereSky, radiance: Spectrum) -> DVec3 {
    let c = sky.atmosphere.spectral_conversion().linear_srgb(radiance);
    DVec3::new(c.r, c.g, c.b)
}

/// The radiance of a ball of `radius` at `center` (normal albedo `albedo`, law `law`) at its
/// point with outward normal `n`, seen from `eye`, lit by `sun` unshadowed: the law's closed form.
fn closed_form(
    sky: &AtmosphereSky,
    center: DVec3,
    radius: f64,
    n: DVec3,
    eye: DVec3,
    albedo: f64,
    law: Reflectance,
) -> DVec3 {
    let sun = &sky.suns[0];
    let p = center + n * radius;
    let mu0 = n.dot(sun.direction);
    let mu = n.dot((eye - p).normalize());
    let factor = match law {
        Reflectance::Lambert => mu0,
        Reflectance::LommelSeeliger => 2.0 * mu0 / (mu0 + mu),
        Reflectance::Lunar => 2.0 * mu0 / (mu0 + mu) * lunar_phase_factor(sun.direction.angle_between(eye - p)),
    };
    as_srgb(sky, sun.irradiance * (albedo / std::f64::consts::PI * factor))
}

fn relative(got: DVec3, want: DVec3) -> f64 {
    ((got - want) / want).abs().max_element()
}

/// A Lommel–Seeliger Moon, a Lambert ball and the Moon with its phase factor 384 400 km out, seen
/// from 60 000 km at points from the sub-solar point to near the limb and the terminator: the GPU
/// within 1 % of the laws' closed forms (`(A/π)·E·μ₀`, `(A/π)·E·2μ₀/(μ₀ + μ)` and that times the
/// core's `lunar_phase_factor`).
#[test]
fn a_body_sends_back_what_its_reflectance_law_says() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.3, -0.2, 0.5).normalize();
    let moon_center = planet_center() + DVec3::new(384_400_000.0, 0.0, 0.0);
    let ball_center = planet_center() + DVec3::new(0.0, 384_400_000.0, 0.0);
    let ball = Body {
        center: ball_center,
        radii: DVec3::splat(1_000_000.0),
        orientation: DQuat::from_rotation_y(0.3),
        albedo: Spectrum::splat(0.4),
        reflectance: Reflectance::Lambert,
        surface: BodySurface::Uniform,
        planet_shadow: None,
        air: None,
    };
    let lunar_center = planet_center() + DVec3::new(0.0, 0.0, 384_400_000.0);
    let lunar = Body {
        reflectance: Reflectance::Lunar,
        ..plain_moon(lunar_center)
    };
    let sky = airless_with(sun, vec![plain_moon(moon_center), ball.clone(), lunar]);
    let cases = [
        (moon_center, MOON_RADIUS_M, 0.12, Reflectance::LommelSeeliger),
        (ball_center, 1_000_000.0, 0.4, Reflectance::Lambert),
        (lunar_center, MOON_RADIUS_M, 0.12, Reflectance::Lunar),
    ];
    for (center, radius, albedo, law) in cases {
        // The eye 60 000 km out, 40° from the sun about the body.
        let axis = sun.cross(DVec3::Z).normalize();
        let to_eye = DQuat::from_axis_angle(axis, 40f64.to_radians()) * sun;
        let eye = center + to_eye * 60_000_000.0;
        // Normals towards the sun, half-way to the eye, near the limb, near the terminator.
        let limb = DQuat::from_axis_angle(axis, -75f64.to_radians()) * to_eye;
        let terminator = DQuat::from_axis_angle(axis, 80f64.to_radians()) * sun;
        let half_way = (sun + to_eye).normalize();
        for n in [sun, half_way, limb, terminator] {
            let target = center + n * radius;
            let got = centre_radiance(&mut gpu, &sky, eye, target - eye);
            let want = closed_form(&sky, center, radius, n, eye, albedo, law);
            println!("{law:?} n·s {:.3}: gpu {got:.2} closed form {want:.2}", n.dot(sun));
            assert!(relative(got, want) < 0.01, "{law:?} at n {n}: {got} vs {want}");
        }
    }
}

/// A Moon in the planet's penumbra, sun low behind the planet: a point where the planet hides
/// part of the sun shows the unshadowed closed form times the core's visible fraction of the
/// limb-darkened sun (firmament_core::atmosphere::eclipse), within 1 %; a point in the umbra
/// is dark.
#[test]
fn the_planet_s_penumbra_dims_a_body_as_the_eclipse_model_says() {
    let mut gpu = gpu();
    // Along the shadow, the umbra's radius is R − d·(α_sun·…): about 4 700 km here, and the
    // penumbra reaches to about 8 000 km. The Moon's centre 6 400 km off the axis.
    let (moon_center, eye, sky) = moon_behind_the_planet(6_400_000.0);
    let planet = &sky.atmosphere.planet;
    let globe = firmament_core::atmosphere::Eclipser {
        center: planet.center,
        radius_m: EARTH_RADIUS_M,
    };
    let mut seen_partial = false;
    for n in [
        DVec3::new(1.0, 0.0, 0.6),
        DVec3::new(1.0, 0.0, 0.1),
        DVec3::new(1.0, 0.0, 1.2),
    ] {
        let n = n.normalize();
        let p = moon_center + n * MOON_RADIUS_M;
        let share = globe.visible_fraction(p, &sky.suns[0]);
        seen_partial |= share > 0.05 && share < 0.95;
        let lit = closed_form(
            &sky,
            moon_center,
            MOON_RADIUS_M,
            n,
            eye,
            0.12,
            Reflectance::LommelSeeliger,
        );
        let want = lit * share;
        let got = centre_radiance(&mut gpu, &sky, eye, p - eye);
        println!("share {share:.4}: gpu {got:.3} want {want:.3}");
        // Within 1 % of the full light (the share's own f32 error near the umbra is absolute).
        assert!(
            (got - want).abs().max_element() < 0.01 * lit.max_element(),
            "share {share}: {got} vs {want}"
        );
    }
    assert!(seen_partial, "no point of the test lay in the penumbra");
}

/// A lunar eclipse on the Moon as a body: inside the umbra it takes the light the core's shadow
/// profile gives (Earth's real air refracting sunlight into the shadow,
/// `firmament_core::atmosphere::planet_shadow`), the GPU within 2 % of the f64 core's
/// `Body::radiance` with `sunlight_share` at points from the umbra's core to its edge — and red.
#[test]
fn the_moon_in_the_umbra_is_lit_red_by_the_planet_s_air() {
    let mut gpu = gpu();
    // The Moon's centre 2 000 km off the shadow's axis: the points lie 1 400 to 3 500 km from
    // it, inside the umbra (about 4 600 km out).
    let (moon_center, eye, mut sky) = moon_behind_the_planet(2_000_000.0);
    // The profile of Earth's real air (the sky's own is a million times thinner).
    let mut earth = presets::earth();
    earth.planet = sky.atmosphere.planet;
    sky.light_bodies_in_planet_shadow(|_, s, d| PlanetShadow::new(&earth, s, d, &ShadowSettings::default()));
    assert!(sky.bodies[0].planet_shadow.is_some(), "the Moon stands in the shadow");
    let planet = sky.atmosphere.planet;
    let local = sky.bodies[0].to_planet_frame(&planet);
    let suns: Vec<_> = sky
        .suns
        .iter()
        .map(|s| firmament_core::atmosphere::Sun {
            direction: planet.direction_to_planet_frame(s.direction),
            ..*s
        })
        .collect();
    for n in [
        DVec3::new(1.0, 0.0, -0.4),
        DVec3::new(1.0, 0.0, 0.2),
        DVec3::new(1.0, 0.6, 0.9),
    ] {
        let p = moon_center + n.normalize() * MOON_RADIUS_M;
        assert!(n.dot(eye - p) > 0.0, "the eye sees the point");
        let p_local = planet.to_planet_frame(p);
        let to_viewer = planet.direction_to_planet_frame((eye - p).normalize());
        let bodies = std::slice::from_ref(&local);
        let radiance = local.radiance(p_local, to_viewer, &suns, |s| {
            sunlight_share(p_local, &suns, s, &planet, None, bodies, 0)
        }) + local.planetshine_radiance(p_local, to_viewer, &suns, &planet);
        let want = as_srgb(&sky, radiance);
        let got = centre_radiance(&mut gpu, &sky, eye, p - eye);
        let full = closed_form(
            &sky,
            moon_center,
            MOON_RADIUS_M,
            n.normalize(),
            eye,
            0.12,
            Reflectance::Lambert,
        );
        println!(
            "n {n}: gpu {got:.5} core {want:.5} ({:.2e} of full sunlight)",
            want.x / full.x
        );
        assert!(relative(got, want) < 0.02, "at n {n}: {got} vs {want}");
        assert!(want.x > 2.0 * want.z && want.x < 0.01 * full.x, "dim and red: {want}");
    }
}

/// The Moon's near side, full and face-on: points in Mare Tranquillitatis and Mare Imbrium, on a
/// rim of Mare Serenitatis and in the highlands by Tycho show the Lommel–Seeliger closed form
/// with the core's albedo pattern (firmament_core::atmosphere::body::maria) within 1 %.
#[test]
fn the_moon_shows_its_maria() {
    let mut gpu = gpu();
    let sun = DVec3::new(1.0, 0.3, 0.2).normalize();
    let center = planet_center() + DVec3::new(384_400_000.0, 0.0, 0.0);
    // The near side (the body's +x) towards +x, where the eye is.
    let sky = airless_with(sun, vec![Body::moon(center)]);
    let eye = center + DVec3::X * 60_000_000.0;
    let serenitatis = &MARIA[1];
    let rim = DQuat::from_axis_angle(DVec3::Y, -serenitatis.angular_radius()) * serenitatis.center();
    let tycho = DVec3::new(
        0.72 * 11.2f64.to_radians().cos(),
        -0.72 * 11.2f64.to_radians().sin(),
        -0.686,
    )
    .normalize();
    for (name, n) in [
        ("Tranquillitatis", MARIA[2].center()),
        ("Imbrium", MARIA[0].center()),
        ("Serenitatis' rim", rim),
        ("by Tycho", tycho),
    ] {
        let albedo = MOON_ALBEDO * albedo_factor(n);
        let target = center + n * MOON_RADIUS_M;
        let got = centre_radiance(&mut gpu, &sky, eye, target - eye);
        let want = closed_form(&sky, center, MOON_RADIUS_M, n, eye, albedo, Reflectance::Lunar);
        println!("{name}: albedo {albedo:.4}, gpu {got:.1} closed form {want:.1}");
        assert!(relative(got, want) < 0.01, "{name}: {got} vs {want}");
    }
}

/// Earthshine: the Moon's night side at new Moon, lit by the full Earth alone (geometric albedo
/// 0.434), shows `(A/π)·E·p·(R/d)²·Φ(0)` by the Lommel–Seeliger law with the cosine towards the
/// planet, within 1 %; and nothing without the planet's albedo.
#[test]
fn the_full_earth_lights_the_new_moon_s_night_side() {
    let mut gpu = gpu();
    let sun = DVec3::X;
    let distance = 384_400_000.0;
    let center = planet_center() + DVec3::X * distance;
    let mut sky = airless_with(sun, vec![plain_moon(center)]);
    let eye = center - DVec3::new(60_000_000.0, 0.0, 8_000_000.0);
    let ratio = EARTH_RADIUS_M / (distance - MOON_RADIUS_M);
    for n in [DVec3::NEG_X, DVec3::new(-1.0, 0.3, -0.2).normalize()] {
        let p = center + n * MOON_RADIUS_M;
        let to_planet = (planet_center() - p).normalize();
        let mu0 = n.dot(to_planet);
        let mu = n.dot((eye - p).normalize());
        let irradiance = sky.suns[0].irradiance * (0.434 * ratio * ratio);
        let want = as_srgb(
            &sky,
            irradiance * (0.12 / std::f64::consts::PI * 2.0 * mu0 / (mu0 + mu)),
        );
        sky.atmosphere.planet.geometric_albedo = 0.434;
        let got = centre_radiance(&mut gpu, &sky, eye, p - eye);
        sky.atmosphere.planet.geometric_albedo = 0.0;
        let dark = centre_radiance(&mut gpu, &sky, eye, p - eye);
        println!("n {n:.2}: gpu {got:.4} closed form {want:.4}, without {dark}");
        assert!(relative(got, want) < 0.01, "earthshine at n {n}: {got} vs {want}");
        assert_eq!(dark, DVec3::ZERO, "the night side without planet-shine");
    }
}

/// Depth between the planet and a body: a body behind the planet does not show through it (the
/// pixel is the planet's, as without the body), and one in front of it hides the planet and its
/// clouds (the pixel is the body's closed form).
#[test]
fn the_planet_and_a_body_hide_each_other_by_distance() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.0, -0.6, 0.8).normalize();
    let eye = planet_center() + DVec3::new(0.0, 0.0, 40_000_000.0);
    let towards_planet = planet_center() - eye;
    // Behind: on the far side of the planet, on the line of sight.
    let behind = Body::moon(planet_center() - DVec3::Z * 100_000_000.0);
    let bare = airless_with(sun, Vec::new());
    let with_behind = airless_with(sun, vec![behind]);
    let planet_only = centre_radiance(&mut gpu, &bare, eye, towards_planet);
    let through = centre_radiance(&mut gpu, &with_behind, eye, towards_planet);
    assert!(planet_only.max_element() > 0.0, "the lit planet shows: {planet_only}");
    assert!(
        (through - planet_only).abs().max_element() <= 1e-4 * planet_only.max_element(),
        "a body behind the planet showed through it: {through} vs {planet_only}"
    );
    // In front: between the eye and the planet.
    let front_center = planet_center() + DVec3::Z * 20_000_000.0;
    let with_front = airless_with(sun, vec![plain_moon(front_center)]);
    let got = centre_radiance(&mut gpu, &with_front, eye, towards_planet);
    let want = closed_form(
        &with_front,
        front_center,
        MOON_RADIUS_M,
        DVec3::Z,
        eye,
        0.12,
        Reflectance::LommelSeeliger,
    );
    assert!(
        relative(got, want) < 0.01,
        "a body in front of the planet: {got} vs {want}"
    );
    // The planet's clouds do not show over a body in front of them.
    let mut cloudy = with_front.clone();
    cloudy.clouds = vec![CloudLayer::new(1_000.0, 3_000.0, 1.0, 0.05, CloudKind::Uniform)];
    let over_clouds = centre_radiance(&mut gpu, &cloudy, eye, towards_planet);
    assert!(
        relative(over_clouds, want) < 0.01,
        "a body in front of the clouds: {over_clouds} vs {want}"
    );
    let bare_clouds = airless_with(sun, Vec::new());
    let mut bare_cloudy = bare_clouds.clone();
    bare_cloudy.clouds = cloudy.clouds.clone();
    let clouds_alone = centre_radiance(&mut gpu, &bare_cloudy, eye, towards_planet);
    assert!(
        clouds_alone.max_element() > 2.0 * planet_only.max_element(),
        "the clouds show: {clouds_alone}"
    );
}

/// The planet with a moon beside it seen from 1 AU and from 100 AU: the same picture within
/// 1/255 of its brightest pixel (issue 28's precision check).
#[test]
fn a_body_seen_from_100_au_is_the_one_seen_from_1_au() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.4, 0.5, 0.77).normalize();
    let moon = Body::moon(planet_center() + DVec3::new(14_000_000.0, 0.0, 0.0));
    let sky = airless_with(sun, vec![moon]);
    let (worst, lit) = far_view_difference(&mut gpu, &sky, DVec3::new(0.1, 0.2, 1.0).normalize(), 18_000_000.0, 96);
    println!("worst {worst:.5} of the brightest, {lit} lit pixels");
    assert!(lit > 20, "too little of the scene lit: {lit}");
    assert!(worst < 1.0 / 255.0, "1 AU vs 100 AU: {worst}");
}
