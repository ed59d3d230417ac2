//! The night sky of a frame at a real instant: the stars and the Moon of
//! [`firmament_core::sky::night`] over `[planet]`'s place, in the units of the frame's sky.
//!
//! - **Physical atmosphere** (cd/m²): a star's light is its illuminance in lux
//!   (`units_per_lux = 1`), dimmed per channel by the reference transmittance from the camera
//!   towards it — tabulated against the angle from the camera's vertical (the air is the same
//!   all round it) whenever the air or the camera's place changed, zero where the ground is in
//!   the way. The daylit sky then hides
//!   the stars by itself, as it does in a real sky: a magnitude-0 star adds about one cd/m² to a
//!   pixel, the day sky thousands.
//! - **Gradient and seed skies** (display units, not radiance): the same light (a magnitude-0
//!   star is about one display unit on one pixel of a 1280×720, 60° view), dimmed by a standard
//!   extinction of 0.2 magnitudes per airmass (Kasten & Young 1989's airmass) or, for the seed,
//!   by its own 8-step extinction, and faded out by daylight as the sun rises from −12° to −2°
//!   (these skies do not add up light physically). The Moon, whose surface would be thousands of
//!   display units, is scaled so a full moon's surface shows [`MOON_DISPLAY_RADIANCE`].
//! - **Clear** skies draw no night sky.

use std::sync::{Arc, Mutex};

use firmament_core::Camera;
use firmament_core::astro::Instant;
use firmament_core::astro::moon::{MOON_RADIUS_KM, moon_view};
use firmament_core::astro::spa::refraction_deg;
use firmament_core::atmosphere::eclipse::MAX_ECLIPSERS;
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::atmosphere::{Atmosphere, Eclipser, Spectrum, Sun, presets};
use firmament_core::frame::{AtmosphereSky, EmpiricalSky, MAX_SUNS, Sky};
use firmament_core::sky::night::{HORIZON_CUTOFF_DEG, NightLayer};
use glam::{DMat3, DVec3};

use super::lunar_eclipse::{LunarEclipse, lunar_eclipse};
use crate::model::Scene;

/// Face-on radiance of the lit Moon in display units for the gradient and seed skies: bright,
/// but inside the tone curve.
pub const MOON_DISPLAY_RADIANCE: f64 = 1.5;

/// Extinction in the visual band for the gradient sky, magnitudes per airmass (a clear site).
const EXTINCTION_MAG_PER_AIRMASS: f64 = 0.2;

/// Elevations (degrees above the camera's horizontal) at which the atmosphere's transmittance is
/// tabulated: dense near the horizon, where it changes fast.
fn table_elevations() -> Vec<f64> {
    let low = (0..48).map(|i| -2.0 + 0.25 * f64::from(i));
    let high = (0..=80).map(|i| 10.0 + f64::from(i));
    low.chain(high).collect()
}

/// Linear interpolation in a table sampled at `xs` (ascending).
fn interpolate(xs: &[f64], ys: &[DVec3], x: f64) -> DVec3 {
    let i = xs.partition_point(|&v| v <= x);
    match i {
        0 => ys[0],
        i if i >= xs.len() => ys[ys.len() - 1],
        i => {
            let t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
            ys[i - 1].lerp(ys[i], t)
        }
    }
}

/// The last table [`atmosphere_transmittance`] built: the atmosphere, the camera in the planet
/// frame and the table. A time-lapse or the viewer asks for the same one frame after frame, and
/// each costs 129 adaptive quadratures (about 20 ms, most of building a frame; docs/PERFORMANCE.md).
#[allow(
    clippy::type_complexity,
    reason = "a one-entry cache; a named type would say no more"
)]
static LAST_TABLE: Mutex<Option<(Atmosphere, DVec3, Arc<[DVec3]>)>> = Mutex::new(None);

/// The physical sky's transmittance from the camera at `eye` (world frame) towards a world
/// direction, per linear sRGB channel of sunlight (relative to sunlight above the air).
fn atmosphere_transmittance(sky: &AtmosphereSky, eye: DVec3) -> impl Fn(DVec3) -> DVec3 {
    let atmosphere = &sky.atmosphere;
    let planet = &atmosphere.planet;
    let at = planet.to_planet_frame(eye);
    let up = planet.up(at);
    let side = up.any_orthonormal_vector();
    let xs = table_elevations();
    let mut last = LAST_TABLE.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let ys = match &*last {
        Some((medium, place, ys)) if medium == atmosphere && *place == at => Arc::clone(ys),
        _ => {
            let reference = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
            let conversion = atmosphere.spectral_conversion();
            let sunlight = firmament_core::atmosphere::presets::earth_sun(DVec3::Z).irradiance;
            let space = conversion.linear_srgb(sunlight);
            let ys: Arc<[DVec3]> = xs
                .iter()
                .map(|e| {
                    let (s, c) = e.to_radians().sin_cos();
                    let t = reference.transmittance_to_space(at, up * s + side * c);
                    let seen = conversion.linear_srgb(sunlight * t);
                    DVec3::new(seen.r / space.r, seen.g / space.g, seen.b / space.b).max(DVec3::ZERO)
                })
                .collect();
            *last = Some((atmosphere.clone(), at, Arc::clone(&ys)));
            ys
        }
    };
    drop(last);
    let planet = *planet;
    move |world: DVec3| {
        let d = planet.direction_to_planet_frame(world.normalize()).normalize();
        interpolate(&xs, &ys, d.dot(up).clamp(-1.0, 1.0).asin().to_degrees())
    }
}

/// Kasten & Young (1989)'s relative airmass at elevation `e` degrees (finite down to −0.5°).
fn airmass(e: f64) -> f64 {
    let e = e.max(-0.5);
    1.0 / (e.to_radians().sin() + 0.50572 * (e + 6.07995).powf(-1.6364))
}

/// How much of the night sky shows in a display-unit sky with the sun at `sun_elevation`
/// (degrees): none from −2° up, all from −12° down, smooth between.
fn darkness(sun_elevation: f64) -> f64 {
    let t = ((-2.0 - sun_elevation) / 10.0).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The empirical sky's own extinction from `eye` towards a world direction.
fn empirical_transmittance(sky: &EmpiricalSky, eye: DVec3) -> impl Fn(DVec3) -> DVec3 {
    let at = sky.to_planet_frame(eye);
    let to_planet = sky.orientation.normalize().inverse();
    move |world: DVec3| sky.atmosphere.star_transmittance(at, to_planet * world)
}

/// The frame's night sky at `instant` for `camera` over `sky` (see the module docs): empty when
/// the scene draws neither stars nor the Moon.
pub(crate) fn night_layer(scene: &Scene, instant: &Instant, camera: &Camera, sky: &Sky) -> NightLayer {
    let t = &scene.time;
    if !t.stars && !t.moon {
        return NightLayer::default();
    }
    let limit = if t.stars { t.star_limit } else { f64::NEG_INFINITY };
    let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
    let height = camera.position.z.max(0.0);
    let build = |units: f64, transmittance: &dyn Fn(DVec3) -> DVec3| {
        NightLayer::at(instant, lat, lon, height, DMat3::IDENTITY, units, limit, transmittance)
    };
    let mut layer = match sky {
        Sky::Atmosphere(sky) => build(1.0, &atmosphere_transmittance(sky, camera.position)),
        Sky::Gradient(state) => {
            let dark = darkness(state.sun.direction.normalize().z.asin().to_degrees());
            if dark <= 0.0 {
                return NightLayer::default();
            }
            let extinction = move |d: DVec3| {
                let e = d.normalize().z.clamp(-1.0, 1.0).asin().to_degrees();
                if e < 0.0 {
                    return DVec3::ZERO;
                }
                DVec3::splat(dark * 10f64.powf(-0.4 * EXTINCTION_MAG_PER_AIRMASS * airmass(e)))
            };
            scale_moon(build(1.0, &extinction))
        }
        Sky::Empirical(empirical) => {
            let sun_up = empirical.stars.first().map_or(-90.0, |s| {
                let d = empirical.orientation.normalize() * (s.position - empirical.to_planet_frame(camera.position));
                d.normalize().z.clamp(-1.0, 1.0).asin().to_degrees()
            });
            let dark = darkness(sun_up);
            if dark <= 0.0 {
                return NightLayer::default();
            }
            let through = empirical_transmittance(empirical, camera.position);
            scale_moon(build(1.0, &|d: DVec3| through(d) * dark))
        }
        Sky::Clear(_) => return NightLayer::default(),
    };
    if let Sky::Atmosphere(sky) = sky {
        // The bodies hide the stars behind them; the Moon as a body replaces its disc.
        let hidden = |d: DVec3| {
            sky.bodies
                .iter()
                .any(|b| b.eclipser().hides(camera.position, d.normalize()))
        };
        layer.stars.retain(|star| !hidden(star.direction));
        if super::bodies::has_moon(scene) {
            layer.moon = None;
        }
    }
    match &mut layer.moon {
        Some(moon) if t.moon => {
            moon.direction = refracted(scene, instant, moon.direction);
            let air = match sky {
                Sky::Atmosphere(sky) => sky.suns.iter().find(|s| s.disc).map(|sun| (&sky.atmosphere, sun)),
                _ => None,
            };
            moon.shadow = earth_shadow(scene, instant, height, air).map(|e| e.shadow);
        }
        _ => layer.moon = None,
    }
    layer
}

/// The Earth's shadow on the Moon at `instant` (see [`lunar_eclipse`]), through `air` (the
/// physical sky's atmosphere and its first sun with a disc) or else Earth's own.
fn earth_shadow(
    scene: &Scene,
    instant: &Instant,
    height_m: f64,
    air: Option<(&Atmosphere, &Sun)>,
) -> Option<LunarEclipse> {
    let sun_direction = scene.real_sun(instant).ok()?.direction_enu(false);
    let (atmosphere, sun) = match air {
        Some((atmosphere, sun)) => (atmosphere.clone(), *sun),
        None => (presets::earth(), presets::earth_sun(sun_direction)),
    };
    lunar_eclipse(scene, instant, height_m, sun_direction, &atmosphere, &sun)
}

/// A topocentric East-North-Up direction lifted by the refraction of `[time]`'s air at its
/// elevation (SPA's formula, as for the sun): the Moon stands against the Sun as it does in
/// space, and an eclipse's discs line up.
pub(super) fn refracted(scene: &Scene, instant: &Instant, direction: DVec3) -> DVec3 {
    let e0 = direction.z.clamp(-1.0, 1.0).asin();
    let lift = refraction_deg(e0.to_degrees(), &scene.spa_input(instant)).to_radians();
    let horizontal = DVec3::new(direction.x, direction.y, 0.0).normalize_or(DVec3::Y);
    let e = (e0 + lift).min(std::f64::consts::FRAC_PI_2);
    horizontal * e.cos() + DVec3::Z * e.sin()
}

/// How far from a sun, beyond the two discs' radii, the Moon seen from the camera can still
/// eclipse it somewhere in the visible air, radians: its parallax across the ~3500 km of air a
/// camera sees to the horizon from high up is ~0.5°.
const ECLIPSE_MARGIN: f64 = 1.5 * std::f64::consts::PI / 180.0;

/// Whether a Moon seen towards `direction` with angular radius `radius` stands within
/// [`ECLIPSE_MARGIN`] of a sun's disc.
fn eclipses_a_sun(sky: &AtmosphereSky, direction: DVec3, radius: f64) -> bool {
    sky.suns
        .iter()
        .any(|sun| sun.disc && sun.direction.angle_between(direction) < sun.angular_radius + radius + ECLIPSE_MARGIN)
}

/// Adds the Moon as a body that can eclipse the suns, when `time.moon` is on and it stands within
/// [`ECLIPSE_MARGIN`] of a sun's disc: a ball of the Moon's mean radius where the camera sees it
/// (refracted as the sun is), at its topocentric distance.
pub(crate) fn add_eclipsing_moon(scene: &Scene, instant: &Instant, camera: &Camera, sky: &mut AtmosphereSky) {
    if !scene.time.moon || sky.eclipsers.len() >= MAX_ECLIPSERS {
        return;
    }
    let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
    let view = moon_view(instant, lat, lon, camera.position.z.max(0.0));
    let direction = refracted(scene, instant, view.direction);
    if eclipses_a_sun(sky, direction, view.angular_radius) {
        sky.eclipsers.push(Eclipser {
            center: camera.position + direction * (view.equatorial.distance_km * 1000.0),
            radius_m: MOON_RADIUS_KM * 1000.0,
        });
    }
}

/// Adds the Moon to a physical sky's suns as the night's light source, when it is above the
/// horizon and `time.moon` is on: its direction and angular radius from the observer, the Sun's
/// spectrum scaled to the Moon's illuminance at the top of the atmosphere (moonlight is
/// sunlight, slightly reddened by the lunar surface, which is left out), no disc of its own (the
/// night-sky pass shades its phase). The air scatters it and it lights the ground and sky-lit
/// objects like a dim sun. Left out when the sky already has [`MAX_SUNS`] suns.
pub(crate) fn add_moonlight(scene: &Scene, instant: &Instant, camera: &Camera, sky: &mut AtmosphereSky) {
    if !scene.time.moon || sky.suns.len() >= MAX_SUNS {
        return;
    }
    let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
    let mut view = moon_view(instant, lat, lon, camera.position.z.max(0.0));
    view.direction = refracted(scene, instant, view.direction);
    // A Moon that eclipses a sun is new: its lit side faces away.
    if eclipses_a_sun(sky, view.direction, view.angular_radius)
        || view.direction.z < HORIZON_CUTOFF_DEG.to_radians().sin()
        || view.illuminance_lux.is_nan()
        || view.illuminance_lux <= 0.0
    {
        return;
    }
    let sunlight = scene.planet.body.sun(view.direction).irradiance;
    // Luminance of an irradiance spectrum is its illuminance, lux.
    let sun_lux = sky.atmosphere.spectral_conversion().luminance(sunlight);
    if sun_lux.is_nan() || sun_lux <= 0.0 {
        return;
    }
    // In a lunar eclipse the Moon passes on only the sunlight the Earth's shadow leaves it.
    let height = camera.position.z.max(0.0);
    let shade = sky
        .suns
        .iter()
        .find(|s| s.disc)
        .and_then(|sun| earth_shadow(scene, instant, height, Some((&sky.atmosphere, sun))))
        .map_or(Spectrum::ONE, |e| e.mean());
    sky.suns.push(Sun {
        direction: view.direction,
        angular_radius: view.angular_radius,
        irradiance: sunlight * shade * (view.illuminance_lux / sun_lux),
        limb_darkening: 0.0,
        disc: false,
        from_body: None,
    });
}

/// The Moon of a display-unit sky at [`MOON_DISPLAY_RADIANCE`] (its transmittance kept).
fn scale_moon(mut layer: NightLayer) -> NightLayer {
    if let Some(moon) = &mut layer.moon {
        // The radiance of a full moon's surface from the illuminance of a typical full moon
        // (0.27 lux over a disc of 0.259°).
        let full = 0.27 / (std::f64::consts::PI * 0.259f64.to_radians().powi(2));
        moon.radiance *= MOON_DISPLAY_RADIANCE / full;
    }
    layer
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_transmittance_table_follows_the_air_and_the_place() {
        let mut earth = AtmosphereSky {
            atmosphere: firmament_core::atmosphere::presets::earth(),
            suns: vec![],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        // The world is east-north-up at (0°, 0°) on the ground.
        earth.atmosphere.planet = earth.atmosphere.planet.posed_at(0.0, 0.0);
        let mut hazy = earth.clone();
        hazy.atmosphere.medium.terms[1].scattering *= 4.0;
        hazy.atmosphere.medium.terms[1].absorption *= 4.0;
        let eye = DVec3::new(0.0, 0.0, 2.0);
        let towards = DVec3::new(0.3, 0.2, 0.4);
        let clear = atmosphere_transmittance(&earth, eye)(towards);
        let seen_hazy = atmosphere_transmittance(&hazy, eye)(towards);
        let seen_higher = atmosphere_transmittance(&earth, eye * 1000.0)(towards);
        assert!(seen_hazy.max_element() < clear.max_element(), "{seen_hazy} vs {clear}");
        assert!(
            seen_higher.min_element() > clear.min_element(),
            "{seen_higher} vs {clear}"
        );
        // Back to the first: the same table as when it was first built.
        assert_eq!(atmosphere_transmittance(&earth, eye)(towards), clear);
    }

    #[test]
    fn airmass_and_darkness_follow_their_laws() {
        assert!((airmass(90.0) - 1.0).abs() < 1e-3);
        assert!((airmass(30.0) - 2.0).abs() < 0.01);
        assert!(airmass(0.0) > 35.0 && airmass(0.0) < 40.0, "{}", airmass(0.0));
        assert_eq!(darkness(5.0), 0.0);
        assert_eq!(darkness(-12.0), 1.0);
        assert!((darkness(-7.0) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn interpolation_is_linear_and_clamped() {
        let xs = [0.0, 1.0, 3.0];
        let ys = [DVec3::ZERO, DVec3::ONE, DVec3::splat(3.0)];
        assert_eq!(interpolate(&xs, &ys, -1.0), DVec3::ZERO);
        assert_eq!(interpolate(&xs, &ys, 2.0), DVec3::splat(2.0));
        assert_eq!(interpolate(&xs, &ys, 9.0), DVec3::splat(3.0));
    }
}
