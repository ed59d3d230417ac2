//! Occluders in the reference against closed forms: shadows on the ground, a light shaft's
//! missing light, and a view ray that ends on a box. Metre-sized shapes in an East-North-Up world
//! frame on the Earth's surface, 6.4e6 m from where the reference integrates.

use std::f64::consts::{FRAC_PI_4, SQRT_2};

use glam::{DQuat, DVec3};

use super::*;
use crate::atmosphere::presets;

fn relative(a: Spectrum, b: Spectrum) -> f64 {
    ((a - b) / b).abs().max_element()
}

/// The Earth preset posed East-North-Up at 45° N, the sun at the zenith there, few panels and
/// paths (these tests look at the deterministic parts, and at differences on one grid).
fn noon() -> Reference {
    let mut earth = presets::earth();
    earth.planet = earth.planet.posed_at(45f64.to_radians(), 0.0);
    let settings = ReferenceSettings {
        view_steps: 512,
        paths: 16,
        ..Default::default()
    };
    Reference::new(earth.clone(), &[presets::earth_sun(DVec3::Z)], settings)
}

/// A 1 m ball 3 m over the origin hides the zenith sun from the ground under it, to the
/// centimetre, and changes nothing a step beside its shadow.
#[test]
fn a_ball_shadows_the_ground_under_it() {
    let bare = noon();
    let ball = Occluder::Sphere {
        center: DVec3::new(0.0, 0.0, 3.0),
        radius: 1.0,
    };
    let shaded = bare.clone().with_occluders(&[ball]);
    let direct = |reference: &Reference, x: f64| reference.ground_irradiance(DVec3::new(x, 0.0, 0.0)).direct;
    assert!(direct(&bare, 0.0).min_element() > 0.0);
    assert_eq!(direct(&shaded, 0.0), Spectrum::ZERO);
    assert_eq!(direct(&shaded, 0.99), Spectrum::ZERO);
    for x in [1.01, 5.0] {
        assert!(relative(direct(&shaded, x), direct(&bare, x)) < 1e-12, "x = {x}");
    }
}

/// A horizontal view ray 1.7 m up passes under a slab 50 m up over x ∈ [10, 20] m, wide in y,
/// with the sun at the zenith. The slab removes exactly the single scattering of the shadowed
/// 10 m: near the ground that is `10 m · σ_s·P(ν = 0) · E · T_sun · T_view(15 m)` (the integrand
/// is constant to ~1e-4 over the 10 m, and its midpoint value is exact to second order).
#[test]
fn a_slab_s_shadow_removes_its_shaft_of_light() {
    let bare = noon();
    let slab = Occluder::Box {
        center: DVec3::new(15.0, 0.0, 50.0),
        half_extents: DVec3::new(5.0, 500.0, 0.5),
        orientation: DQuat::IDENTITY,
    };
    let shaded = bare.clone().with_occluders(&[slab]);
    let view = Ray::new(DVec3::new(0.0, 0.0, 1.7), DVec3::X).unwrap();
    let (lit, lit_transmittance) = bare.single_scattering_before(&view, f64::INFINITY);
    let (shadowed, transmittance) = shaded.single_scattering_before(&view, f64::INFINITY);
    assert!(
        relative(transmittance, lit_transmittance) < 1e-12,
        "the slab is not on the view ray"
    );

    let atmosphere = bare.atmosphere();
    let (planet, medium) = (&atmosphere.planet, &atmosphere.medium);
    let sun = presets::earth_sun(DVec3::Z);
    // Over 15 m the ray rises 15²/2R ≈ 2e-5 m above the curved ground: 1.7 m it is.
    let coefficients = medium.at(1.7);
    let middle = planet.to_planet_frame(view.at(15.0));
    let towards_sun = planet.direction_to_planet_frame(DVec3::Z);
    let want = medium.scattering_phase(&coefficients, 0.0)
        * sun.irradiance
        * bare.transmittance_to_space(middle, towards_sun)
        * (-coefficients.extinction * 15.0).exp()
        * 10.0;
    let missing = lit - shadowed;
    assert!(relative(missing, want) < 1e-4, "{missing} vs {want}");
}

/// The same slab's shadow splits the view ray exactly, for the zenith sun and for a sun 53° up
/// behind the slab: the light before the shadow, plus what arrives from beyond it through the air
/// up to there — the bare reference along three rays. For the low sun the shadow is cast from the
/// slab's underside and top edges 47.8–48.8 m up, so it lies 0.75 × that farther along.
#[test]
fn a_slab_s_shadow_splits_the_view_ray() {
    let slab = Occluder::Box {
        center: DVec3::new(15.0, 0.0, 50.0),
        half_extents: DVec3::new(5.0, 500.0, 0.5),
        orientation: DQuat::IDENTITY,
    };
    let view = Ray::new(DVec3::new(0.0, 0.0, 1.7), DVec3::X).unwrap();
    for (towards_sun, start, end) in [
        (DVec3::Z, 10.0, 20.0),
        (DVec3::new(-0.6, 0.0, 0.8), 10.0 + 0.75 * 47.8, 20.0 + 0.75 * 48.8),
    ] {
        let bare = Reference::new(
            noon().atmosphere,
            &[presets::earth_sun(towards_sun)],
            ReferenceSettings {
                view_steps: 256,
                paths: 16,
                ..Default::default()
            },
        );
        let shadowed = bare
            .clone()
            .with_occluders(&[slab])
            .single_scattering_before(&view, f64::INFINITY)
            .0;
        let (before, _) = bare.single_scattering_before(&view, start);
        let (_, through) = bare.single_scattering_before(&view, end);
        let (beyond, _) = bare.single_scattering_before(&Ray::new(view.at(end), DVec3::X).unwrap(), f64::INFINITY);
        let split = before + through * beyond;
        assert!(relative(shadowed, split) < 1e-9, "{towards_sun}: {shadowed} vs {split}");
        let lit = bare.single_scattering_before(&view, f64::INFINITY).0;
        // The shaft is a few 1e-5 of the horizon's light in the red, but not nothing.
        assert!(
            ((lit - shadowed) / lit).min_element() > 1e-5,
            "{towards_sun}: {lit} {shadowed}"
        );
    }
}

/// A view ray aimed at the ground 170 m ahead meets a cube turned 45° about the vertical first,
/// at its near edge, `(30 − √2)·√(1 + 10⁻⁴)` m along it: the ray ends there like
/// [`Reference::radiance_before`] a black surface.
#[test]
fn a_view_ray_ends_on_a_box() {
    let bare = noon();
    let cube = Occluder::Box {
        center: DVec3::new(30.0, 0.0, 1.4),
        half_extents: DVec3::ONE,
        orientation: DQuat::from_rotation_z(FRAC_PI_4),
    };
    let shaded = bare.clone().with_occluders(&[cube]);
    let eye = DVec3::new(0.0, 0.0, 1.7);
    let view = Ray::new(eye, DVec3::new(1.0, 0.0, -0.01)).unwrap();
    let hit = (30.0 - SQRT_2) * (1.0 + 1e-4f64).sqrt();

    let open = bare.radiance(&view);
    assert!(open.ground.min_element() > 0.0 && open.transmittance == Spectrum::ZERO);
    let blocked = shaded.radiance(&view);
    assert_eq!(blocked.ground, Spectrum::ZERO);
    assert_eq!(blocked.sun_discs, Spectrum::ZERO);
    let planet = &bare.atmosphere().planet;
    let depth = bare.optical_depth(planet.to_planet_frame(eye), planet.to_planet_frame(view.at(hit)));
    assert!(relative(blocked.transmittance, (-depth).exp()) < 1e-9);
    let surface = bare.radiance_before(&view, hit);
    assert!(relative(blocked.single, surface.single) < 1e-9);
    assert_eq!(
        shaded.single_scattering_before(&view, f64::INFINITY),
        (blocked.single, blocked.transmittance)
    );
    // A nearer `distance` still wins.
    let (_, near) = shaded.single_scattering_before(&view, 5.0);
    assert!(relative(near, bare.single_scattering_before(&view, 5.0).1) < 1e-12);
}

/// Looking straight up at the sun through a ball hides its disc and leaves only the unlit air
/// under the ball; from inside the ball nothing is seen at all.
#[test]
fn a_ball_hides_the_sun_s_disc() {
    let bare = noon();
    let ball = Occluder::Sphere {
        center: DVec3::new(0.0, 0.0, 3.0),
        radius: 1.0,
    };
    let shaded = bare.clone().with_occluders(&[ball]);
    let up = Ray::new(DVec3::new(0.0, 0.0, 0.5), DVec3::Z).unwrap();
    assert!(bare.radiance(&up).sun_discs.min_element() > 0.0);
    let blocked = shaded.radiance(&up);
    assert_eq!(blocked.sun_discs, Spectrum::ZERO);
    // The 1.5 m of air below the ball lie in its shadow.
    assert_eq!(blocked.single, Spectrum::ZERO);
    let (_, transmittance) = bare.single_scattering_before(&up, 1.5);
    assert!(relative(blocked.transmittance, transmittance) < 1e-12);
    let inside = Ray::new(DVec3::new(0.0, 0.0, 3.0), DVec3::X).unwrap();
    assert_eq!(
        shaded.single_scattering_before(&inside, f64::INFINITY),
        (Spectrum::ZERO, Spectrum::ONE)
    );
}
