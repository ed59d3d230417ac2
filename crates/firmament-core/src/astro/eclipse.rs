//! Solar eclipses seen from one place: where the Moon stands against the Sun, and the local
//! circumstances (the four contacts and the maximum).
//!
//! - **Positions**: the Sun's topocentric geometric direction from NREL's SPA ([`solar_position`],
//!   no refraction) and the Moon's from [`moon_view`] (Meeus ch. 47 with the rigorous parallax),
//!   both in the observer's East-North-Up frame.
//! - **Radii**: the conventions of NASA's eclipse predictions (Espenak & Meeus, *Five Millennium
//!   Canon of Solar Eclipses*, NASA/TP-2006-214141, §1.3): the Sun's semi-diameter 959.63″ at
//!   1 AU ([`SUN_RADIUS_KM`]) and the Moon's `k = 0.272 281` Earth radii for the umbral contacts
//!   (second and third; its mean radius, `k = 0.272 507 6`, for the first and fourth). So the
//!   contacts compare with NASA's published times (see the tests: Dallas, 2024-04-08).
//! - **Contacts**: first and fourth where the discs touch outside, second and third where the
//!   Moon's disc touches the Sun's inside (total: the Moon larger; annular: the Sun larger); each
//!   found by bisection to 0.01 s between samples a minute apart, the maximum (least separation)
//!   by golden-section search.
//!
//! The atmosphere's eclipse (how much sunlight each point of the air receives) is
//! [`crate::atmosphere::eclipse`]; this module only says where the bodies stand.

use glam::DVec3;

use super::moon::{ASTRONOMICAL_UNIT_KM, moon_view};
use super::spa::{SpaInput, solar_position};
use super::time::Instant;

/// The Sun's radius that gives its semi-diameter of 959.63″ at 1 AU, km (NASA's eclipse
/// predictions; the IAU's nominal radius is 695 700 km).
pub const SUN_RADIUS_KM: f64 = 695_990.0;

/// The Earth's equatorial radius the lunar radius ratios multiply, km (WGS84).
const EARTH_RADIUS_KM: f64 = 6378.137;

/// The Moon's radius for the first and fourth contacts, km (`k = 0.272 507 6`).
pub const MOON_RADIUS_PENUMBRAL_KM: f64 = 0.272_507_6 * EARTH_RADIUS_KM;

/// The Moon's radius for the second and third contacts, km (`k = 0.272 281`: the valleys of its
/// limb, whose last beads of sunlight end totality).
pub const MOON_RADIUS_UMBRAL_KM: f64 = 0.272_281 * EARTH_RADIUS_KM;

/// The Sun and the Moon seen from one place at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolarEclipseView {
    /// Unit East-North-Up direction to the Sun's centre (topocentric, geometric).
    pub sun_direction: DVec3,
    /// Unit East-North-Up direction to the Moon's centre (topocentric, geometric).
    pub moon_direction: DVec3,
    /// Distance to the Moon's centre, km.
    pub moon_distance_km: f64,
    /// Angle between the two centres, radians.
    pub separation: f64,
    /// The Sun's angular radius, radians.
    pub sun_radius: f64,
    /// The Moon's angular radius for the first and fourth contacts, radians.
    pub moon_radius: f64,
    /// The Moon's angular radius for the second and third contacts, radians.
    pub moon_radius_umbral: f64,
}

impl SolarEclipseView {
    /// The eclipse's magnitude: the fraction of the Sun's diameter the Moon covers (> 1 in
    /// totality), 0 when the discs are apart.
    pub fn magnitude(&self) -> f64 {
        ((self.sun_radius + self.moon_radius - self.separation) / (2.0 * self.sun_radius)).max(0.0)
    }
}

/// The Sun and the Moon at `instant` from geodetic `latitude_deg`, `longitude_deg` (east
/// positive) and `height_m` above the ellipsoid.
pub fn solar_eclipse_view(instant: &Instant, latitude_deg: f64, longitude_deg: f64, height_m: f64) -> SolarEclipseView {
    let sun = solar_position(&SpaInput {
        elevation_m: height_m,
        ..SpaInput::new(*instant, latitude_deg, longitude_deg)
    });
    let moon = moon_view(instant, latitude_deg, longitude_deg, height_m);
    let sun_direction = sun.direction_enu(false);
    let moon_distance_km = moon.equatorial.distance_km;
    let separation = moon
        .direction
        .cross(sun_direction)
        .length()
        .atan2(moon.direction.dot(sun_direction));
    let sun_distance_km = sun.geocentric.radius_au * ASTRONOMICAL_UNIT_KM;
    SolarEclipseView {
        sun_direction,
        moon_direction: moon.direction,
        moon_distance_km,
        separation,
        sun_radius: (SUN_RADIUS_KM / sun_distance_km).asin(),
        moon_radius: (MOON_RADIUS_PENUMBRAL_KM / moon_distance_km).asin(),
        moon_radius_umbral: (MOON_RADIUS_UMBRAL_KM / moon_distance_km).asin(),
    }
}

/// A solar eclipse as one place sees it. Instants keep the ΔT of the search's start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalCircumstances {
    /// First contact: the partial eclipse begins.
    pub first_contact: Instant,
    /// Second contact: totality or annularity begins (`None` for a partial eclipse here).
    pub second_contact: Option<Instant>,
    /// The least separation of the centres.
    pub maximum: Instant,
    /// Third contact: totality or annularity ends.
    pub third_contact: Option<Instant>,
    /// Fourth contact: the partial eclipse ends.
    pub fourth_contact: Instant,
    /// The Sun and the Moon at the maximum.
    pub at_maximum: SolarEclipseView,
}

/// The solar eclipse seen from `latitude_deg`, `longitude_deg`, `height_m` whose maximum lies
/// within `hours` of `around`, or `None` when the discs do not meet there then (a Sun below the
/// horizon is not checked: the contacts are geometric).
pub fn local_circumstances(
    around: &Instant,
    hours: f64,
    latitude_deg: f64,
    longitude_deg: f64,
    height_m: f64,
) -> Option<LocalCircumstances> {
    let view = |t: f64| solar_eclipse_view(&around.plus_seconds(t), latitude_deg, longitude_deg, height_m);
    let span = hours * 3600.0;
    // The separation changes by ~0.5″/s: minute samples find its least, golden sections refine it.
    let step = 60.0;
    let samples = (2.0 * span / step).ceil() as usize;
    let (mut best, mut best_separation) = (-span, f64::INFINITY);
    for i in 0..=samples {
        let t = -span + step * i as f64;
        let separation = view(t).separation;
        if separation < best_separation {
            (best, best_separation) = (t, separation);
        }
    }
    let maximum = golden_minimum(|t| view(t).separation, best - step, best + step);
    let at_maximum = view(maximum);
    let outer = |v: &SolarEclipseView| v.separation - (v.sun_radius + v.moon_radius);
    if outer(&at_maximum) >= 0.0 {
        return None;
    }
    let inner = |v: &SolarEclipseView| v.separation - (v.moon_radius_umbral - v.sun_radius).abs();
    let contact = |f: &dyn Fn(&SolarEclipseView) -> f64, forward: bool| -> Option<f64> {
        let direction = if forward { 1.0 } else { -1.0 };
        let mut inside = maximum;
        for k in 1..=(span / step).ceil() as usize {
            let t = maximum + direction * step * k as f64;
            if f(&view(t)) >= 0.0 {
                return Some(bisect(|t| f(&view(t)), inside, t));
            }
            inside = t;
        }
        None
    };
    let at = |t: f64| around.plus_seconds(t);
    let central = inner(&at_maximum) < 0.0;
    Some(LocalCircumstances {
        first_contact: at(contact(&outer, false)?),
        second_contact: if central { contact(&inner, false).map(at) } else { None },
        maximum: at(maximum),
        third_contact: if central { contact(&inner, true).map(at) } else { None },
        fourth_contact: at(contact(&outer, true)?),
        at_maximum,
    })
}

/// The root of `f` between `inside` (f < 0) and `outside` (f ≥ 0), to 0.01 s.
fn bisect(f: impl Fn(f64) -> f64, mut inside: f64, mut outside: f64) -> f64 {
    while (outside - inside).abs() > 0.01 {
        let middle = 0.5 * (inside + outside);
        if f(middle) < 0.0 {
            inside = middle;
        } else {
            outside = middle;
        }
    }
    0.5 * (inside + outside)
}

/// The least of a unimodal `f` on [a, b], to 0.01 s.
fn golden_minimum(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    while b - a > 0.01 {
        let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
        if f(c) < f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::CivilDateTime;

    /// Dallas City Hall (32.7763° N, 96.7969° W, 140 m), 2024-04-08: NASA's local circumstances
    /// (Espenak, as in NASA's Eclipse Explorer and Jubier's map) give totality from 18:40:43 to
    /// 18:44:34 UT, 3 min 51 s.
    const DALLAS: (f64, f64, f64) = (32.7763, -96.7969, 140.0);

    fn utc(hour: u32, minute: u32, second: f64) -> Instant {
        Instant::from_civil(&CivilDateTime::utc(2024, 4, 8, hour, minute, second), None).expect("a valid date")
    }

    fn seconds_between(a: &Instant, b: &Instant) -> f64 {
        (a.jd - b.jd) * 86_400.0
    }

    #[test]
    fn totality_in_dallas_matches_nasa_within_five_seconds() {
        let (lat, lon, h) = DALLAS;
        let local = local_circumstances(&utc(18, 42, 0.0), 3.0, lat, lon, h).expect("an eclipse");
        let second = local.second_contact.expect("total");
        let third = local.third_contact.expect("total");
        let nasa_second = utc(18, 40, 43.0);
        let nasa_third = utc(18, 44, 34.0);
        assert!(
            seconds_between(&second, &nasa_second).abs() < 5.0,
            "C2 {}",
            seconds_between(&second, &nasa_second)
        );
        assert!(
            seconds_between(&third, &nasa_third).abs() < 5.0,
            "C3 {}",
            seconds_between(&third, &nasa_third)
        );
        let duration = seconds_between(&third, &second);
        assert!((duration - 231.0).abs() < 5.0, "duration {duration} s");
        // The partial phases: NASA gives 17:23 and 20:02 UT to the minute.
        assert!(seconds_between(&local.first_contact, &utc(17, 23, 0.0)).abs() < 60.0);
        assert!(seconds_between(&local.fourth_contact, &utc(20, 2, 0.0)).abs() < 60.0);
    }

    /// At NASA's mid-totality the centres stand as far apart as NASA's duration says: with the
    /// centres moving apart at `v` along a straight line, a chord of `v·T` through a circle of
    /// radius `ρ_moon − ρ_sun` lies `√((ρ_moon − ρ_sun)² − (v·T/2)²)` from the centre (Dallas is
    /// ~40 km off the central line, so not zero).
    #[test]
    fn the_centres_at_mid_totality_stand_where_nasa_puts_them() {
        let (lat, lon, h) = DALLAS;
        let middle = utc(18, 42, 38.5);
        let view = solar_eclipse_view(&middle, lat, lon, h);
        let later = solar_eclipse_view(&middle.plus_seconds(1.0), lat, lon, h);
        let earlier = solar_eclipse_view(&middle.plus_seconds(-1.0), lat, lon, h);
        let relative = |v: &SolarEclipseView| v.moon_direction - v.sun_direction;
        let speed = (relative(&later) - relative(&earlier)).length() / 2.0;
        let radius = view.moon_radius_umbral - view.sun_radius;
        let half_chord = speed * 231.0 / 2.0;
        let nasa = (radius * radius - half_chord * half_chord).sqrt();
        let arcsec = (view.separation - nasa).to_degrees() * 3600.0;
        assert!(arcsec.abs() < 10.0, "{arcsec}″ from NASA's");
        assert!(view.magnitude() > 1.0);
    }

    #[test]
    fn no_eclipse_a_week_later() {
        let (lat, lon, h) = DALLAS;
        let later = utc(18, 42, 0.0).plus_seconds(7.0 * 86_400.0);
        assert!(local_circumstances(&later, 3.0, lat, lon, h).is_none());
    }
}
