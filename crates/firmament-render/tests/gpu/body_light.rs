//! A body's light on the planet (moonlight from the Moon as a body): the sun the sky carries for
//! it is not hidden by the body it comes from, and does not light that body.

use crate::bodies::airless_with;
use crate::support::{centre_radiance, gpu};
use firmament_core::atmosphere::body::{Body, BodySurface, Reflectance};
use firmament_core::atmosphere::presets;
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

fn relative(got: DVec3, want: DVec3) -> f64 {
    ((got - want) / want).abs().max_element()
}

/// The Moon without its maria, its centre 384 400 km from the planet's towards `towards`.
fn moon(sky: &AtmosphereSky, towards: DVec3) -> Body {
    Body {
        surface: BodySurface::Uniform,
        reflectance: Reflectance::LommelSeeliger,
        ..Body::moon(sky.atmosphere.planet.center + towards.normalize() * 384_400_000.0)
    }
}

/// A full Moon high in a night sky over Earth's air: the ground and the sky lit by its light are
/// what the same light gives as a plain disc-less sun with no body in the way (within 1 %), where
/// the body would otherwise cover its own light exactly and put it out.
#[test]
fn a_bodys_light_is_not_hidden_by_the_body() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.0, -0.8, -0.6).normalize();
    let mut sky = airless_with(sun, Vec::new());
    // Earth's air, not the thinned one.
    sky.atmosphere.medium = presets::earth().medium;
    // Opposite the sun, 3° off the planet's shadow.
    let towards = DVec3::new(0.0, 0.8, 0.6 + 3f64.to_radians());
    sky.add_body(moon(&sky, towards));
    let eye = DVec3::new(0.0, 0.0, 2.0);
    sky.add_body_lights(eye, |_| true);
    sky.validate().expect("a valid sky");
    assert_eq!(sky.suns.len(), 2, "the Moon's light");
    let mut plain = sky.clone();
    plain.bodies.clear();
    plain.eclipsers.clear();
    plain.suns[1].from_body = None;
    let views = [
        ("the ground", DVec3::new(0.2, 0.3, -1.0)),
        ("the sky", DVec3::new(0.6, 0.2, 0.3)),
        ("the aureole", towards.normalize() + DVec3::new(0.05, 0.0, 0.0)),
    ];
    for (name, view) in views {
        let got = centre_radiance(&mut gpu, &sky, eye, view);
        let want = centre_radiance(&mut gpu, &plain, eye, view);
        println!("{name}: with the body {got:?}, plain sun {want:?}");
        assert!(want.min_element() > 0.0, "{name}: lit");
        assert!(relative(got, want) < 0.01, "{name}: {got} vs {want}");
    }
}

/// A body lit by its own light alone stays black (no planet-shine), while a second body beside
/// it is lit by it.
#[test]
fn a_body_is_not_lit_by_its_own_light() {
    let mut gpu = gpu();
    let sun = DVec3::new(0.0, 1.0, 0.2).normalize();
    let sky = airless_with(sun, Vec::new());
    let first = moon(&sky, DVec3::X);
    let second = Body {
        center: first.center + DVec3::new(0.0, 0.0, 20_000_000.0),
        ..first.clone()
    };
    let mut sky = airless_with(sun, vec![first.clone(), second.clone()]);
    sky.atmosphere.planet.geometric_albedo = 0.0;
    // Its light as seen from the second body, alone in the sky.
    let at = second.center - DVec3::Z * 2.0 * second.mean_radius();
    sky.add_body_lights(at, |_| true);
    let own = sky
        .suns
        .iter()
        .copied()
        .find(|s| s.from_body == Some(0))
        .expect("the first body's light");
    sky.suns = vec![own];
    let eye = first.center + DVec3::new(-30_000_000.0, 0.0, 10_000_000.0);
    let first_seen = centre_radiance(&mut gpu, &sky, eye, first.center - eye);
    let second_seen = centre_radiance(&mut gpu, &sky, eye, second.center - DVec3::Z * 1.5e6 - eye);
    println!("the first body {first_seen:?}, the second {second_seen:?}");
    assert_eq!(first_seen, DVec3::ZERO, "a body lit by its own light");
    assert!(second_seen.min_element() > 0.0, "the other body, lit by it");
}
