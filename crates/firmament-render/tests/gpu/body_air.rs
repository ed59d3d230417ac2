//! GPU tests of a body's own air (`atmosphere/body_air.wgsl`, `body_air_medium.wgsl`) against
//! the f64 core's fine march (`firmament_core::atmosphere::body::air`, itself checked against
//! closed forms and the path tracer): the light an Earth-like air scatters, once and more, over
//! the day side's limb, past the terminator and in front of the ground, and the ground lit
//! through it and by its sky.

use crate::bodies::{airless_with, as_srgb, planet_center};
use crate::support::{centre_radiance, gpu};

use firmament_core::atmosphere::body::{Body, BodyAir, BodySurface, Reflectance, shadows_share, sunlight_share};
use firmament_core::atmosphere::{Spectrum, Sun, presets};
use firmament_core::frame::AtmosphereSky;
use firmament_core::geometry::Ray;
use glam::{DQuat, DVec3};

const RADIUS_M: f64 = 6_371_000.0;

/// The core's radiance along the world-frame ray from `eye` along `d`: the body's air in front
/// of its lit ground (or of nothing), in linear sRGB.
fn core_radiance(sky: &AtmosphereSky, eye: DVec3, d: DVec3) -> DVec3 {
    let planet = sky.atmosphere.planet;
    let body = sky.bodies[0].to_planet_frame(&planet);
    let bodies = std::slice::from_ref(&body);
    let suns: Vec<Sun> = sky
        .suns
        .iter()
        .map(|s| Sun {
            direction: planet.direction_to_planet_frame(s.direction),
            ..*s
        })
        .collect();
    let ray = Ray::new(planet.to_planet_frame(eye), planet.direction_to_planet_frame(d)).expect("a ray");
    let tables = body.air_light();
    let shadows = |x: DVec3, s: usize| shadows_share(x, &suns, s, &planet, None, bodies, 0);
    let air = body.air_along(&ray, f64::INFINITY, &suns, shadows, tables.as_ref());
    let ground = body.hit(&ray).map_or(Spectrum::ZERO, |t| {
        let p = ray.at(t);
        let direct = body.radiance(p, -ray.direction, &suns, |s| {
            sunlight_share(p, &suns, s, &planet, None, bodies, 0)
        });
        let sky = tables.as_ref().map_or(Spectrum::ZERO, |tables| {
            body.skylight_radiance(p, -ray.direction, &suns, tables, |s| shadows(p, s))
        });
        direct + sky + body.planetshine_radiance(p, -ray.direction, &suns, &planet)
    });
    as_srgb(sky, air.radiance + air.transmittance * ground)
}

/// An Earth-sized Lambert ball with Earth's air, 384 400 km from a planet too thin to matter,
/// the sun 90° from the planet seen from it, the eye 60 000 km out at 60° from the sun: the GPU
/// within 2 % (of the brightest channel) of the core on the ground through the air (by day and,
/// lit by its sky alone, past the terminator), over the sunlit limb at 2, 15 and 40 km, at the
/// terminator and past it.
#[test]
fn a_body_s_air_scatters_what_the_core_s_march_gives() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.0, 0.0, 1.0);
    let center = planet_center() + DVec3::new(384_400_000.0, 0.0, 0.0);
    let world = Body {
        center,
        radii: DVec3::splat(RADIUS_M),
        orientation: DQuat::IDENTITY,
        albedo: Spectrum::splat(0.3),
        reflectance: Reflectance::Lambert,
        surface: BodySurface::Uniform,
        planet_shadow: None,
        air: BodyAir::from_atmosphere(&presets::earth()),
    };
    let sky = airless_with(sun, vec![world]);
    let to_eye = DQuat::from_rotation_y(60f64.to_radians()) * sun;
    let eye = center + to_eye * 60_000_000.0;
    let distance = eye.distance(center);
    // Rays passing `impact` metres from the centre, on the side `side` (unit, across the view).
    let grazing = |impact: f64, side: DVec3| {
        let across = (side - to_eye * side.dot(to_eye)).normalize();
        let sin = impact / distance;
        -to_eye * (1.0 - sin * sin).sqrt() + across * sin
    };
    let towards_sun = sun;
    // Across the view 5° past the terminator: the ground there is dark, the air above it lit.
    let twilight = DVec3::Y * 5f64.to_radians().cos() - sun * 5f64.to_radians().sin();
    // The ground 3° past the terminator on the side facing the eye: lit by the sky alone.
    let towards_eye = (to_eye - sun * sun.dot(to_eye)).normalize();
    let dusk = towards_eye * 3f64.to_radians().cos() - sun * 3f64.to_radians().sin();
    let cases = [
        (
            "ground 3° past the terminator",
            (center + dusk * RADIUS_M - eye).normalize(),
        ),
        (
            "ground half-way to the sun",
            (center + (sun + to_eye).normalize() * RADIUS_M - eye).normalize(),
        ),
        ("sunlit limb, 2 km up", grazing(RADIUS_M + 2_000.0, towards_sun)),
        ("sunlit limb, 15 km up", grazing(RADIUS_M + 15_000.0, towards_sun)),
        ("sunlit limb, 40 km up", grazing(RADIUS_M + 40_000.0, towards_sun)),
        (
            "the limb across the view, 8 km up",
            grazing(RADIUS_M + 8_000.0, DVec3::Y),
        ),
        (
            "the limb 5° past the terminator, 20 km up",
            grazing(RADIUS_M + 20_000.0, twilight),
        ),
    ];
    for (name, d) in cases {
        let want = core_radiance(&sky, eye, d);
        let got = centre_radiance(&mut gpu, &sky, eye, d);
        println!("{name}: gpu {got:.5} core {want:.5}");
        assert!(want.max_element() > 0.0, "{name}: the core sees light");
        let error = (got - want).abs().max_element() / want.max_element();
        assert!(error < 0.02, "{name}: {got} vs {want} ({:.2} %)", 100.0 * error);
    }
}
