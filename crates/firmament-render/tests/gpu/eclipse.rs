//! GPU tests of eclipses (`atmosphere/eclipse.wgsl`) against the f64 core: the eclipsed
//! fraction itself, and the sky under a partial and a total eclipse against the reference
//! integrator, whose path tracer lights every scattering event by the sun its own point sees.

use crate::support::{Gpu, centre_radiance, direction, gpu, street_sky};

use firmament_core::atmosphere::Eclipser;
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::frame::AtmosphereSky;
use firmament_core::geometry::Ray;
use glam::{DQuat, DVec3};

/// The Moon's mean radius, m.
const MOON_RADIUS_M: f64 = 1.7374e6;

const EYE: DVec3 = DVec3::new(0.0, 0.0, 1.7);

/// A street sky with the sun 60° up in the south and the Moon 360 000 km out, `offset` radians
/// from the sun's centre as the eye sees it (towards the east).
fn eclipsed_sky(offset: f64) -> AtmosphereSky {
    eclipsed_sky_at(60.0, offset)
}

/// [`eclipsed_sky`] with the sun `elevation` degrees up.
fn eclipsed_sky_at(elevation: f64, offset: f64) -> AtmosphereSky {
    let mut sky = street_sky(180.0, elevation);
    let towards_sun = sky.suns[0].direction;
    let turned = DQuat::from_axis_angle(towards_sun.cross(DVec3::X).normalize(), offset) * towards_sun;
    sky.eclipsers = vec![Eclipser {
        center: EYE + turned * 3.6e8,
        radius_m: MOON_RADIUS_M,
    }];
    sky
}

/// The GPU against the reference (`paths` paths) for views at each (azimuth, elevation): the
/// relative errors of the largest channel.
fn compare(gpu: &mut Gpu, sky: &AtmosphereSky, views: &[(f64, f64)], paths: usize) -> Vec<f64> {
    let settings = ReferenceSettings {
        paths,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings).with_eclipsers(&sky.eclipsers);
    let conversion = sky.atmosphere.spectral_conversion();
    views
        .iter()
        .map(|&(azimuth, elevation)| {
            let view = direction(azimuth, elevation);
            let g = centre_radiance(gpu, sky, EYE, view);
            let parts = reference.radiance(&Ray {
                origin: EYE,
                direction: view,
            });
            let rgb = conversion.linear_srgb(parts.scattered());
            let r = DVec3::new(rgb.r, rgb.g, rgb.b);
            let error = (g - r).abs().max_element() / r.abs().max_element().max(1e-30);
            println!(
                "azimuth {azimuth:5.1} elevation {elevation:5.1}: gpu {g:.5} reference {r:.5} relative {error:.4}"
            );
            error
        })
        .collect()
}

const VIEWS: [(f64, f64); 8] = [
    (0.0, 90.0),
    (180.0, 40.0),
    (90.0, 30.0),
    (0.0, 20.0),
    (180.0, 3.0),
    (270.0, 3.0),
    (0.0, 3.0),
    (90.0, -10.0),
];

/// Half the sun hidden at the eye (the Moon 0.0045 rad off its centre): the air all round is
/// eclipsed alike, and the GPU's sky is within 2 % of the reference's (measured 1.3 % worst, the
/// ground; 0.4 % median) and darker than the clear sky by about the share hidden.
#[test]
fn a_partial_eclipse_dims_the_sky_as_the_reference_does() {
    let mut gpu = gpu();
    let sky = eclipsed_sky(0.0045);
    let visible = Reference::new(sky.atmosphere.clone(), &sky.suns, ReferenceSettings::default())
        .with_eclipsers(&sky.eclipsers)
        .sun_visible_fraction(EYE, 0);
    assert!((0.4..0.7).contains(&visible), "{visible}");
    let zenith = direction(0.0, 90.0);
    let clear = centre_radiance(&mut gpu, &street_sky(180.0, 60.0), EYE, zenith);
    let eclipsed = centre_radiance(&mut gpu, &sky, EYE, zenith);
    let ratio = eclipsed.z / clear.z;
    assert!(
        (ratio - visible).abs() < 0.05,
        "the zenith keeps {ratio:.3}, the sun {visible:.3}"
    );
    let errors = compare(&mut gpu, &sky, &VIEWS, 4096);
    let worst = errors.iter().copied().fold(0.0, f64::max);
    assert!(worst < 0.02, "worst {worst:.4}: {errors:.4?}");
}

/// Totality at the eye (the Moon in line with the sun; its shadow ~55 km across the air): the sky
/// overhead falls to ~1/2000 of the clear sky's and the horizon glows with the light of the air
/// outside the shadow. Overhead all the reference's light is scattered in from outside the
/// shadow (orders ≥ 2); the GPU takes it from the visible fraction averaged around each point,
/// a model whose one reach was fitted here (docs/ATMOSPHERE.md, "Eclipses"): the horizon within
/// 10 % and the sky overhead within 20 % of the reference (measured 7 % and 12 %).
#[test]
fn a_total_eclipse_darkens_the_sky_but_not_the_horizon() {
    let mut gpu = gpu();
    let sky = eclipsed_sky(0.0);
    let zenith = direction(0.0, 90.0);
    let clear = centre_radiance(&mut gpu, &street_sky(180.0, 60.0), EYE, zenith);
    let settings = ReferenceSettings {
        paths: 4096,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings).with_eclipsers(&sky.eclipsers);
    assert_eq!(reference.sun_visible_fraction(EYE, 0), 0.0);
    let horizon: Vec<(f64, f64)> = VIEWS.iter().copied().filter(|v| v.1 == 3.0).collect();
    let errors = compare(&mut gpu, &sky, &horizon, 4096);
    let worst = errors.iter().copied().fold(0.0, f64::max);
    assert!(worst < 0.1, "horizon worst {worst:.4}: {errors:.4?}");
    let conversion = sky.atmosphere.spectral_conversion();
    for (azimuth, elevation) in [(0.0, 90.0), (180.0, 40.0)] {
        let view = direction(azimuth, elevation);
        let g = centre_radiance(&mut gpu, &sky, EYE, view);
        let parts = reference.radiance(&Ray {
            origin: EYE,
            direction: view,
        });
        let r = conversion.linear_srgb(parts.scattered()).b;
        println!(
            "overhead ({azimuth}, {elevation}): gpu {:.4}, reference {r:.4}, clear zenith {:.1}",
            g.z, clear.z
        );
        assert!(r > 0.0 && r < 2e-3 * clear.z, "reference {r}");
        assert!((g.z / r - 1.0).abs() < 0.2, "the GPU {} against the reference {r}", g.z);
    }
    // The sun's disc is gone: looking at it shows the dark sky.
    let at_sun = centre_radiance(&mut gpu, &sky, EYE, sky.suns[0].direction);
    assert!(at_sun.max_element() < 1e-3 * clear.z, "{at_sun}");
    // The corona through the air, against the reference's (Baumbach's law, the disc term there):
    // the GPU's is within 1 %, what is left the sky the GPU leaves out in the shadow.
    let sun = sky.suns[0];
    let axis = sun.direction.cross(DVec3::Z).normalize();
    for radii in [1.5, 2.0, 4.0] {
        let view = DQuat::from_axis_angle(axis, radii * sun.angular_radius) * sun.direction;
        let g = centre_radiance(&mut gpu, &sky, EYE, view);
        let parts = reference.radiance(&Ray {
            origin: EYE,
            direction: view,
        });
        let rgb = |s| {
            let c = conversion.linear_srgb(s);
            DVec3::new(c.r, c.g, c.b)
        };
        let (corona, sky_light) = (rgb(parts.sun_discs), rgb(parts.scattered()));
        println!("{radii} radii out: gpu {g:.3}, reference corona {corona:.3} and sky {sky_light:.3}");
        assert!(corona.z > 1.0, "{corona}");
        let off = (g - corona).abs().max_element();
        assert!(off <= 0.01 * corona.max_element() + sky_light.max_element(), "{off}");
    }
}

/// Held out from the fit of the umbra's model (docs/ATMOSPHERE.md, "Eclipses"): totality with the
/// sun 30° up. The horizon within 10 % of the reference (measured 3 %), the sky overhead and 40°
/// up both ways within 40 % (measured 31–37 % dark; black before the model).
#[test]
fn the_umbra_s_sky_is_lit_by_the_air_around_it() {
    let mut gpu = gpu();
    let sky = eclipsed_sky_at(30.0, 0.0);
    let sky_views = [(0.0, 90.0), (180.0, 40.0), (0.0, 40.0)];
    let errors = compare(&mut gpu, &sky, &sky_views, 4096);
    assert!(errors.iter().all(|&e| e < 0.4), "the sky: {errors:.4?}");
    let errors = compare(&mut gpu, &sky, &[(90.0, 3.0), (180.0, 3.0)], 4096);
    assert!(errors.iter().all(|&e| e < 0.1), "the horizon: {errors:.4?}");
}
