//! The Moon: position, phase, apparent size and brightness.
//!
//! - **Position**: Meeus, *Astronomical Algorithms* (2nd ed., 1998), ch. 47 — the truncated
//!   ELP-2000/82 theory with tables 47.A and 47.B in full (in `moon_terms.rs`); about 10″ in
//!   longitude and 4″ in latitude, geocentric, mean equinox of date. The apparent position adds
//!   the nutation in longitude and uses the true obliquity ([`Nutation`]).
//! - **Topocentric position**: the observer's geocentric position from Meeus ch. 11 (the IAU 1976
//!   ellipsoid), subtracted from the Moon's geocentric vector — the rigorous parallax correction
//!   of Meeus ch. 40 in vector form. The Moon moves by up to ~1° between geocentre and observer.
//! - **Sun** (needed for the phase): Meeus ch. 25's low-accuracy solar coordinates (0.01°), which
//!   moves a computed new or full moon by at most ~1.5 min.
//! - **Phase**: Meeus ch. 48 — geocentric elongation ψ and phase angle i from the two position
//!   vectors (eqs. 48.2–48.3), illuminated fraction k = (1 + cos i)/2 (eq. 48.1), position angle
//!   of the bright limb χ (eq. 48.5). New, first quarter, full and last quarter moon are when the
//!   difference of the apparent ecliptic longitudes, Moon minus Sun, is 0°, 90°, 180° and 270°
//!   (Meeus ch. 49's definition); [`next_phase`] finds them by Newton's method.
//! - **Brightness**: the Moon's V magnitude `−12.73 + 0.026|φ| + 4·10⁻⁹ φ⁴` (φ the phase angle
//!   in degrees; Allen, *Astrophysical Quantities* 3rd ed. 1973, as fitted by Krisciunas &
//!   Schaefer 1991, *PASP* 103, 1033, eq. 9), valid at the mean distances, scaled here by the
//!   inverse squares of the Earth–Moon and Sun–Moon distances, and made an illuminance with
//!   [`star_illuminance_lux`] (`E = 10^(−0.4 (V + 13.99))` lux). It leaves out the opposition
//!   surge within ~7° of full moon (the Moon is then up to ~35 % brighter).
//!
//! # Drawing the Moon
//! [`MoonView::sun_direction`] is the direction of the Sun seen from the Moon's centre in the
//! observer's East-North-Up frame. Shading a sphere at [`MoonView::direction`] with a light from
//! that direction reproduces the phase (the lit fraction of the disc is k) and the orientation of
//! the terminator (the bright limb faces the position angle χ) with nothing else to compute.

use glam::DVec3;

use crate::atmosphere::body::phase::lunar_phase_magnitude;

use super::moon_terms::{LATITUDE, LONGITUDE_DISTANCE};
use super::sidereal::{
    Nutation, equatorial_to_horizon_matrix, equatorial_unit_vector, greenwich_apparent_sidereal_time,
    local_sidereal_time, normalize_radians, ra_dec_of,
};
use super::stars::star_illuminance_lux;
use super::time::Instant;

/// The Moon's mean radius, km (IAU Working Group on Cartographic Coordinates, 1737.4 km).
pub const MOON_RADIUS_KM: f64 = 1737.4;

/// The Earth's equatorial radius used by Meeus (IAU 1976), km.
pub const EARTH_EQUATORIAL_RADIUS_KM: f64 = 6378.14;

/// The Earth's polar-to-equatorial axis ratio b/a of the IAU 1976 ellipsoid (Meeus ch. 11).
const EARTH_AXIS_RATIO: f64 = 0.996_647_19;

/// The astronomical unit, km (IAU 2012).
pub const ASTRONOMICAL_UNIT_KM: f64 = 149_597_870.7;

/// The Moon's mean distance, km, at which its magnitude formula holds.
pub const MEAN_MOON_DISTANCE_KM: f64 = 384_400.0;

/// The Moon's mean synodic month, days (Meeus ch. 49).
pub const SYNODIC_MONTH_DAYS: f64 = 29.530_588_861;

/// A geocentric ecliptic position: longitude and latitude (radians) and distance (km).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EclipticPosition {
    /// Ecliptic longitude, radians in [0, 2π).
    pub longitude: f64,
    /// Ecliptic latitude, radians.
    pub latitude: f64,
    /// Distance from the Earth's centre, km.
    pub distance_km: f64,
}

/// An equatorial position: right ascension and declination (radians, equator and equinox of date)
/// and distance (km).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EquatorialPosition {
    /// Right ascension, radians in [0, 2π).
    pub ra: f64,
    /// Declination, radians.
    pub dec: f64,
    /// Distance, km.
    pub distance_km: f64,
}

impl EquatorialPosition {
    /// The position as a vector in km (`x` to the equinox, `z` to the north celestial pole).
    pub fn vector_km(&self) -> DVec3 {
        equatorial_unit_vector(self.ra, self.dec) * self.distance_km
    }

    /// The position of a vector in km.
    pub fn from_vector_km(vector: DVec3) -> Self {
        let (ra, dec) = ra_dec_of(vector);
        Self {
            ra,
            dec,
            distance_km: vector.length(),
        }
    }
}

/// The fundamental arguments of Meeus ch. 47 in degrees, at `t` Julian centuries of TT since
/// J2000.0: L′ (the Moon's mean longitude), D, M, M′, F (eqs. 47.1–47.5).
fn fundamental_arguments(t: f64) -> [f64; 5] {
    let t2 = t * t;
    let t3 = t2 * t;
    let t4 = t3 * t;
    [
        218.316_447_7 + 481_267.881_234_21 * t - 0.001_578_6 * t2 + t3 / 538_841.0 - t4 / 65_194_000.0,
        297.850_192_1 + 445_267.111_403_4 * t - 0.001_881_9 * t2 + t3 / 545_868.0 - t4 / 113_065_000.0,
        357.529_109_2 + 35_999.050_290_9 * t - 0.000_153_6 * t2 + t3 / 24_490_000.0,
        134.963_396_4 + 477_198.867_505_5 * t + 0.008_741_4 * t2 + t3 / 69_699.0 - t4 / 14_712_000.0,
        93.272_095_0 + 483_202.017_523_3 * t - 0.003_653_9 * t2 - t3 / 3_526_000.0 + t4 / 863_310_000.0,
    ]
}

/// The Moon's geocentric ecliptic longitude, latitude and distance, referred to the mean equinox
/// of date (Meeus ch. 47; ≈10″ in longitude, 4″ in latitude), at the instant's dynamical time.
pub fn moon_geocentric_ecliptic(instant: &Instant) -> EclipticPosition {
    let t = instant.centuries_tt();
    let [l_prime, d, m, m_prime, f] = fundamental_arguments(t);
    let (l_prime, d, m, m_prime, f) = (
        l_prime.to_radians(),
        d.to_radians(),
        m.to_radians(),
        m_prime.to_radians(),
        f.to_radians(),
    );
    let a1 = (119.75 + 131.849 * t).to_radians();
    let a2 = (53.09 + 479_264.290 * t).to_radians();
    let a3 = (313.45 + 481_266.484 * t).to_radians();
    // Eccentricity factor of the Earth's orbit (eq. 47.6).
    let e = 1.0 - 0.002_516 * t - 0.000_007_4 * t * t;
    let e_factor = |multiple_of_m: i8| match multiple_of_m.unsigned_abs() {
        0 => 1.0,
        1 => e,
        _ => e * e,
    };
    let argument =
        |k: [i8; 4]| f64::from(k[0]) * d + f64::from(k[1]) * m + f64::from(k[2]) * m_prime + f64::from(k[3]) * f;

    let (mut sum_l, mut sum_r) = (0.0, 0.0);
    for term in &LONGITUDE_DISTANCE {
        let (sin, cos) = argument(term.multiples).sin_cos();
        let factor = e_factor(term.multiples[1]);
        sum_l += f64::from(term.longitude) * factor * sin;
        sum_r += f64::from(term.distance) * factor * cos;
    }
    let mut sum_b: f64 = LATITUDE
        .iter()
        .map(|term| f64::from(term.latitude) * e_factor(term.multiples[1]) * argument(term.multiples).sin())
        .sum();
    // Additive terms: Venus (A₁), Jupiter (A₂) and the flattening of the Earth (L′ − F, L′).
    sum_l += 3958.0 * a1.sin() + 1962.0 * (l_prime - f).sin() + 318.0 * a2.sin();
    sum_b += -2235.0 * l_prime.sin()
        + 382.0 * a3.sin()
        + 175.0 * (a1 - f).sin()
        + 175.0 * (a1 + f).sin()
        + 127.0 * (l_prime - m_prime).sin()
        - 115.0 * (l_prime + m_prime).sin();

    EclipticPosition {
        longitude: normalize_radians(l_prime + (sum_l * 1e-6).to_radians()),
        latitude: (sum_b * 1e-6).to_radians(),
        distance_km: 385_000.56 + sum_r / 1000.0,
    }
}

/// The Sun's geocentric ecliptic longitude (geometric, mean equinox of date; latitude taken as 0)
/// and distance, by Meeus ch. 25's low-accuracy method (0.01°).
pub fn sun_geocentric_ecliptic(instant: &Instant) -> EclipticPosition {
    let t = instant.centuries_tt();
    let l0 = 280.466_46 + 36_000.769_83 * t + 0.000_303_2 * t * t;
    let m = (357.529_11 + 35_999.050_29 * t - 0.000_153_7 * t * t).to_radians();
    let e = 0.016_708_634 - 0.000_042_037 * t - 0.000_000_126_7 * t * t;
    let center = (1.914_602 - 0.004_817 * t - 0.000_014 * t * t) * m.sin()
        + (0.019_993 - 0.000_101 * t) * (2.0 * m).sin()
        + 0.000_289 * (3.0 * m).sin();
    let true_anomaly = m + center.to_radians();
    let radius_au = 1.000_001_018 * (1.0 - e * e) / (1.0 + e * true_anomaly.cos());
    EclipticPosition {
        longitude: normalize_radians((l0 + center).to_radians()),
        latitude: 0.0,
        distance_km: radius_au * ASTRONOMICAL_UNIT_KM,
    }
}

/// The Moon's apparent geocentric ecliptic position: [`moon_geocentric_ecliptic`] plus the
/// nutation in longitude (Meeus ch. 47; the Moon's aberration, < 1″, is left out as Meeus does).
pub fn moon_apparent_ecliptic(instant: &Instant, nutation: &Nutation) -> EclipticPosition {
    let mut position = moon_geocentric_ecliptic(instant);
    position.longitude = normalize_radians(position.longitude + nutation.longitude);
    position
}

/// The Sun's apparent geocentric ecliptic position: [`sun_geocentric_ecliptic`] plus the
/// nutation in longitude and the annual aberration −20.4898″/R (Meeus eq. 25.10).
pub fn sun_apparent_ecliptic(instant: &Instant, nutation: &Nutation) -> EclipticPosition {
    let mut position = sun_geocentric_ecliptic(instant);
    let radius_au = position.distance_km / ASTRONOMICAL_UNIT_KM;
    let aberration = (-20.4898 / 3600.0 / radius_au).to_radians();
    position.longitude = normalize_radians(position.longitude + nutation.longitude + aberration);
    position
}

/// An apparent ecliptic position (true equinox of date) to equatorial coordinates with the true
/// obliquity.
fn to_equatorial(position: &EclipticPosition, nutation: &Nutation) -> EquatorialPosition {
    let (ra, dec) =
        super::sidereal::ecliptic_to_equatorial(position.longitude, position.latitude, nutation.true_obliquity());
    EquatorialPosition {
        ra,
        dec,
        distance_km: position.distance_km,
    }
}

/// The Moon's apparent geocentric right ascension, declination and distance (true equator and
/// equinox of date).
pub fn moon_apparent_equatorial(instant: &Instant, nutation: &Nutation) -> EquatorialPosition {
    to_equatorial(&moon_apparent_ecliptic(instant, nutation), nutation)
}

/// The Sun's apparent geocentric right ascension, declination and distance (true equator and
/// equinox of date), to Meeus ch. 25's low accuracy (0.01°).
pub fn sun_apparent_equatorial(instant: &Instant, nutation: &Nutation) -> EquatorialPosition {
    to_equatorial(&sun_apparent_ecliptic(instant, nutation), nutation)
}

/// The observer's geocentric position in km, equatorial coordinates of date, at geodetic latitude
/// `latitude_rad`, height `height_m` above the ellipsoid and local sidereal time `lst_rad`
/// (Meeus ch. 11: ρ sin φ′ and ρ cos φ′ on the IAU 1976 ellipsoid).
pub fn observer_geocentric_km(latitude_rad: f64, height_m: f64, lst_rad: f64) -> DVec3 {
    let u = (EARTH_AXIS_RATIO * latitude_rad.tan()).atan();
    let h = height_m / (EARTH_EQUATORIAL_RADIUS_KM * 1000.0);
    let rho_sin = EARTH_AXIS_RATIO * u.sin() + h * latitude_rad.sin();
    let rho_cos = u.cos() + h * latitude_rad.cos();
    let (sin_lst, cos_lst) = lst_rad.sin_cos();
    DVec3::new(rho_cos * cos_lst, rho_cos * sin_lst, rho_sin) * EARTH_EQUATORIAL_RADIUS_KM
}

/// The topocentric position of a body from its geocentric one, for an observer at geodetic
/// latitude `latitude_rad`, height `height_m` and local (apparent) sidereal time `lst_rad`: the
/// rigorous parallax correction (Meeus ch. 40) as a difference of vectors.
pub fn topocentric(
    geocentric: &EquatorialPosition,
    latitude_rad: f64,
    height_m: f64,
    lst_rad: f64,
) -> EquatorialPosition {
    EquatorialPosition::from_vector_km(geocentric.vector_km() - observer_geocentric_km(latitude_rad, height_m, lst_rad))
}

/// The Moon's angular radius (semi-diameter), radians, at `distance_km` from the observer.
pub fn moon_angular_radius(distance_km: f64) -> f64 {
    (MOON_RADIUS_KM / distance_km).clamp(-1.0, 1.0).asin()
}

/// The Moon's phase as seen from one place (geocentric or topocentric).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoonPhase {
    /// Elongation ψ: the angle between the Sun and the Moon seen from the observer, radians in
    /// [0, π] (Meeus eq. 48.2).
    pub elongation: f64,
    /// Phase angle i: the angle between the Sun and the observer seen from the Moon, radians in
    /// [0, π] (Meeus eq. 48.3); 0 at full moon.
    pub phase_angle: f64,
    /// Illuminated fraction of the disc, k = (1 + cos i)/2, in [0, 1] (Meeus eq. 48.1).
    pub illuminated_fraction: f64,
    /// Position angle of the midpoint of the bright limb, χ, radians in [0, 2π), measured from
    /// the direction of the north celestial pole towards the east (Meeus eq. 48.5).
    pub bright_limb_angle: f64,
    /// Apparent ecliptic longitude of the Moon minus that of the Sun, radians in [0, 2π): 0 at
    /// new moon, π/2 at first quarter, π at full moon, 3π/2 at last quarter; grows with the
    /// Moon's age.
    pub longitude_elongation: f64,
}

impl MoonPhase {
    /// The phase from apparent equatorial positions of the Moon and the Sun (same frame, seen
    /// from the same place) and the true obliquity (for [`MoonPhase::longitude_elongation`]).
    pub fn from_positions(moon: &EquatorialPosition, sun: &EquatorialPosition, true_obliquity: f64) -> Self {
        let moon_v = moon.vector_km();
        let sun_v = sun.vector_km();
        let elongation = moon_v.angle_between(sun_v);
        // Seen from the Moon: towards the Sun and towards the observer.
        let phase_angle = (sun_v - moon_v).angle_between(-moon_v);
        let delta_ra = sun.ra - moon.ra;
        let bright_limb_angle = normalize_radians(
            (sun.dec.cos() * delta_ra.sin())
                .atan2(sun.dec.sin() * moon.dec.cos() - sun.dec.cos() * moon.dec.sin() * delta_ra.cos()),
        );
        let to_ecliptic = glam::DMat3::from_rotation_x(-true_obliquity);
        let (moon_lon, _) = ra_dec_of(to_ecliptic * moon_v);
        let (sun_lon, _) = ra_dec_of(to_ecliptic * sun_v);
        Self {
            elongation,
            phase_angle,
            illuminated_fraction: (1.0 + phase_angle.cos()) / 2.0,
            bright_limb_angle,
            longitude_elongation: normalize_radians(moon_lon - sun_lon),
        }
    }

    /// The Moon's V magnitude at this phase, at the mean Earth–Moon distance and 1 AU from the
    /// Sun (Allen 1973 via Krisciunas & Schaefer 1991, eq. 9).
    pub fn magnitude_at_mean_distance(&self) -> f64 {
        -12.73 + lunar_phase_magnitude(self.phase_angle)
    }
}

/// The Moon's geocentric phase at an instant (Meeus ch. 48, with the low-precision nutation).
pub fn moon_phase(instant: &Instant) -> MoonPhase {
    let nutation = Nutation::low_precision(instant);
    let moon = moon_apparent_equatorial(instant, &nutation);
    let sun = sun_apparent_equatorial(instant, &nutation);
    MoonPhase::from_positions(&moon, &sun, nutation.true_obliquity())
}

/// The Moon's V magnitude at phase angle `phase_angle_rad`, `distance_km` from the observer and
/// `sun_distance_km` from the Sun: the phase law of [`MoonPhase::magnitude_at_mean_distance`]
/// plus `5 log₁₀(Δ/384400 km · r/1 AU)` for the inverse-square distances.
pub fn moon_magnitude(phase_angle_rad: f64, distance_km: f64, sun_distance_km: f64) -> f64 {
    -12.73
        + lunar_phase_magnitude(phase_angle_rad)
        + 5.0 * (distance_km / MEAN_MOON_DISTANCE_KM * sun_distance_km / ASTRONOMICAL_UNIT_KM).log10()
}

/// Everything needed to draw the Moon for one observer at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoonView {
    /// Unit East-North-Up direction of the Moon's centre from the observer (topocentric, no
    /// refraction).
    pub direction: DVec3,
    /// Unit East-North-Up direction of the Sun seen from the Moon's centre: light a sphere at
    /// [`MoonView::direction`] from here and the disc shows the right phase and terminator.
    pub sun_direction: DVec3,
    /// Apparent topocentric right ascension, declination and distance (true equator of date).
    pub equatorial: EquatorialPosition,
    /// The Moon's angular radius seen by the observer, radians.
    pub angular_radius: f64,
    /// The phase seen by the observer (topocentric).
    pub phase: MoonPhase,
    /// The Moon's V magnitude at this phase and distance.
    pub magnitude: f64,
    /// Illuminance from the Moon on a surface facing it at the top of the atmosphere, lux.
    pub illuminance_lux: f64,
}

/// The Moon seen at an instant from geodetic latitude `latitude_deg`, longitude `longitude_deg`
/// (east positive) and height `height_m` above the ellipsoid.
pub fn moon_view(instant: &Instant, latitude_deg: f64, longitude_deg: f64, height_m: f64) -> MoonView {
    let latitude = latitude_deg.to_radians();
    let nutation = Nutation::low_precision(instant);
    let lst = local_sidereal_time(
        greenwich_apparent_sidereal_time(instant, &nutation),
        longitude_deg.to_radians(),
    );
    let observer = observer_geocentric_km(latitude, height_m, lst);
    let moon_geo = moon_apparent_equatorial(instant, &nutation).vector_km();
    let sun_geo = sun_apparent_equatorial(instant, &nutation).vector_km();
    let moon = EquatorialPosition::from_vector_km(moon_geo - observer);
    let sun = EquatorialPosition::from_vector_km(sun_geo - observer);
    let to_enu = equatorial_to_horizon_matrix(lst, latitude);
    let phase = MoonPhase::from_positions(&moon, &sun, nutation.true_obliquity());
    let magnitude = moon_magnitude(phase.phase_angle, moon.distance_km, (sun_geo - moon_geo).length());
    MoonView {
        direction: (to_enu * moon.vector_km()).normalize(),
        sun_direction: (to_enu * (sun_geo - moon_geo)).normalize(),
        equatorial: moon,
        angular_radius: moon_angular_radius(moon.distance_km),
        phase,
        magnitude,
        illuminance_lux: star_illuminance_lux(magnitude),
    }
}

/// The first instant after `instant` at which the Moon's [`MoonPhase::longitude_elongation`]
/// equals `target_elongation_deg` (0 new moon, 90 first quarter, 180 full moon, 270 last
/// quarter), found by Newton's method to ~0.1 s; ΔT is kept from `instant`. The result's error
/// against the true phase is that of the positions: ~1 min.
pub fn next_phase(instant: &Instant, target_elongation_deg: f64) -> Instant {
    let elongation_deg = |t: &Instant| moon_phase(t).longitude_elongation.to_degrees();
    // Mean motion of the elongation, degrees per day.
    let mean_rate = 360.0 / SYNODIC_MONTH_DAYS;
    let mut ahead = (target_elongation_deg - elongation_deg(instant)).rem_euclid(360.0);
    if ahead < 1e-9 {
        ahead = 360.0;
    }
    let mut t = instant.plus_seconds(ahead / mean_rate * 86_400.0);
    for _ in 0..20 {
        let error = wrap_degrees(target_elongation_deg - elongation_deg(&t));
        if error.abs() < 1e-6 {
            break;
        }
        // The true rate varies between ~10 and ~15°/day: measure it.
        let probe = t.plus_seconds(600.0);
        let rate = wrap_degrees(elongation_deg(&probe) - elongation_deg(&t)) / (600.0 / 86_400.0);
        let rate = if rate.is_finite() && rate > 5.0 {
            rate
        } else {
            mean_rate
        };
        t = t.plus_seconds(error / rate * 86_400.0);
    }
    t
}

/// An angle in degrees reduced to [−180, 180).
fn wrap_degrees(angle: f64) -> f64 {
    (angle + 180.0).rem_euclid(360.0) - 180.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::CivilDateTime;
    use crate::astro::sidereal::ARCSECOND;

    /// Meeus example 47.a's instant: 1992 April 12, 0h TD (JDE 2448724.5).
    fn example_47a() -> Instant {
        Instant {
            jd: 2_448_724.5,
            delta_t: 0.0,
        }
    }

    #[test]
    fn geocentric_position_matches_meeus_example_47a() {
        let p = moon_geocentric_ecliptic(&example_47a());
        let d_lon = (p.longitude.to_degrees() - 133.162_655) * 3600.0;
        let d_lat = (p.latitude.to_degrees() + 3.229_126) * 3600.0;
        let d_dist = p.distance_km - 368_409.7;
        eprintln!("47.a: Δλ = {d_lon:.4}″, Δβ = {d_lat:.4}″, ΔΔ = {d_dist:.3} km");
        // Meeus prints 6 decimals of a degree (0.0036″) and 0.1 km.
        assert!(d_lon.abs() < 0.01 && d_lat.abs() < 0.01 && d_dist.abs() < 0.06);
    }

    #[test]
    fn apparent_position_matches_meeus_example_47a() {
        let instant = example_47a();
        // With Meeus's own nutation (Δψ = +0.004610°, ε = 23.440636°): exact.
        let exact = Nutation {
            longitude: 0.004_610_f64.to_radians(),
            obliquity: 0.0,
            mean_obliquity: 23.440_636_f64.to_radians(),
        };
        let p = moon_apparent_equatorial(&instant, &exact);
        let d_ra = (p.ra.to_degrees() - 134.688_470) * 3600.0;
        let d_dec = (p.dec.to_degrees() - 13.768_368) * 3600.0;
        eprintln!("47.a apparent, Meeus's nutation: Δα = {d_ra:.4}″, Δδ = {d_dec:.4}″");
        assert!(d_ra.abs() < 0.02 && d_dec.abs() < 0.02);
        // With the low-precision nutation: within its 0.5″.
        let p = moon_apparent_equatorial(&instant, &Nutation::low_precision(&instant));
        let d_ra = (p.ra.to_degrees() - 134.688_470) * 3600.0;
        let d_dec = (p.dec.to_degrees() - 13.768_368) * 3600.0;
        eprintln!("47.a apparent, low-precision nutation: Δα = {d_ra:.4}″, Δδ = {d_dec:.4}″");
        assert!(d_ra.abs() < 1.0 && d_dec.abs() < 1.0);
    }

    #[test]
    fn phase_matches_meeus_example_48a() {
        // 1992 April 12, 0h TD: k = 0.6786, χ = 285.0°; i = 69.0756°, ψ = 110.7929°.
        let phase = moon_phase(&example_47a());
        eprintln!(
            "48.a: k = {:.5}, χ = {:.3}°, i = {:.4}°, ψ = {:.4}°",
            phase.illuminated_fraction,
            phase.bright_limb_angle.to_degrees(),
            phase.phase_angle.to_degrees(),
            phase.elongation.to_degrees()
        );
        assert!((phase.illuminated_fraction - 0.6786).abs() < 5e-4);
        assert!((phase.bright_limb_angle.to_degrees() - 285.0).abs() < 0.1);
        assert!((phase.phase_angle.to_degrees() - 69.0756).abs() < 0.02);
        assert!((phase.elongation.to_degrees() - 110.7929).abs() < 0.02);
        // Waxing gibbous: between first quarter and full moon.
        let age = phase.longitude_elongation.to_degrees();
        assert!((90.0..180.0).contains(&age), "{age}");
    }

    #[test]
    fn topocentric_correction_matches_meeus_example_40a() {
        // Mars, 2003 August 28 3h17m UT from Palomar (φ = 33°21′22″, H = 1706 m,
        // L = 7h47m27s W): α = 22h38m07.25s, δ = −15°46′15.9″, Δ = 0.37276 AU, apparent
        // sidereal time 1h40m45s → α′ = 22h38m08.54s, δ′ = −15°46′30.0″.
        let hours = |h: f64, m: f64, s: f64| ((h + m / 60.0 + s / 3600.0) * 15.0).to_radians();
        let degrees = |d: f64, m: f64, s: f64| (d + m / 60.0 + s / 3600.0).to_radians();
        let geocentric = EquatorialPosition {
            ra: hours(22.0, 38.0, 7.25),
            dec: -degrees(15.0, 46.0, 15.9),
            distance_km: 0.37276 * ASTRONOMICAL_UNIT_KM,
        };
        let lst = hours(1.0, 40.0, 45.0) - hours(7.0, 47.0, 27.0);
        let topo = topocentric(&geocentric, degrees(33.0, 21.0, 22.0), 1706.0, lst);
        let d_ra_s = (topo.ra - hours(22.0, 38.0, 8.54)).to_degrees() / 15.0 * 3600.0;
        let d_dec = (topo.dec + degrees(15.0, 46.0, 30.0)) / ARCSECOND;
        assert!(d_ra_s.abs() < 0.01, "α′ off by {d_ra_s} s");
        assert!(d_dec.abs() < 0.1, "δ′ off by {d_dec}″");
    }

    #[test]
    fn parallax_lowers_the_moon_by_up_to_a_degree() {
        // The horizontal parallax asin(6378/Δ) is ~0.9–1.0°: seen from the surface the Moon is
        // lower than from the geocentre by about that times the cosine of its altitude.
        let instant = Instant::from_civil(&CivilDateTime::utc(2024, 3, 20, 0, 0, 0.0), None).expect("date");
        for (lat, lon) in [(45.0, 0.0), (-30.0, 120.0), (0.0, -60.0), (60.0, 10.0)] {
            let view = moon_view(&instant, lat, lon, 0.0);
            let nutation = Nutation::low_precision(&instant);
            let lst = local_sidereal_time(
                greenwich_apparent_sidereal_time(&instant, &nutation),
                f64::to_radians(lon),
            );
            let geo = moon_apparent_equatorial(&instant, &nutation);
            let geo_dir = equatorial_to_horizon_matrix(lst, f64::to_radians(lat)) * geo.vector_km().normalize();
            let shift = geo_dir.z.asin() - view.direction.z.asin();
            let parallax = (EARTH_EQUATORIAL_RADIUS_KM / geo.distance_km).asin();
            let expected = parallax * geo_dir.z.asin().cos();
            assert!(
                shift > 0.0 && (shift - expected).abs() < 0.03 * parallax,
                "{shift} vs {expected}"
            );
            assert!((view.direction.length() - 1.0).abs() < 1e-12);
            // Semi-diameter ~15–16.8′.
            let s = view.angular_radius.to_degrees() * 60.0;
            assert!((14.5..17.0).contains(&s), "{s}′");
        }
    }

    /// Published times (UTC) of new and full moons, 2024–2026 (eclipse lunations among them).
    const NEW_MOONS: [(i32, u32, u32, u32, u32); 7] = [
        (2024, 1, 11, 11, 57),
        (2024, 4, 8, 18, 21),
        (2024, 10, 2, 18, 49),
        (2025, 3, 29, 10, 58),
        (2025, 9, 21, 19, 54),
        (2026, 2, 17, 12, 1),
        (2026, 8, 12, 17, 37),
    ];
    const FULL_MOONS: [(i32, u32, u32, u32, u32); 6] = [
        (2024, 3, 25, 7, 0),
        (2024, 9, 18, 2, 34),
        (2025, 3, 14, 6, 55),
        (2025, 9, 7, 18, 9),
        (2026, 3, 3, 11, 38),
        (2026, 8, 28, 4, 18),
    ];

    /// Hours between the computed phase, searched from three days before, and the published time.
    fn phase_error_hours(published: (i32, u32, u32, u32, u32), target_deg: f64) -> f64 {
        let (y, mo, d, h, mi) = published;
        let published = Instant::from_civil(&CivilDateTime::utc(y, mo, d, h, mi, 0.0), None).expect("date");
        let found = next_phase(&published.plus_seconds(-3.0 * 86_400.0), target_deg);
        (found.jd - published.jd) * 24.0
    }

    #[test]
    fn new_and_full_moons_match_published_times() {
        let mut worst: f64 = 0.0;
        for (moons, target) in [(&NEW_MOONS[..], 0.0), (&FULL_MOONS[..], 180.0)] {
            for &published in moons {
                let error = phase_error_hours(published, target);
                eprintln!("phase {target:>5}° at {published:?}: {:+.1} min", error * 60.0);
                worst = worst.max(error.abs());
            }
        }
        // The issue asks for half a day; published times are to the minute and our positions
        // good to ~1 min, so anything past a few minutes would be a bug.
        assert!(worst < 12.0, "worst {worst} h");
        assert!(worst < 5.0 / 60.0, "worst {:.1} min", worst * 60.0);
    }

    #[test]
    fn next_phase_moves_forward_and_hits_its_target() {
        let start = Instant::from_civil(&CivilDateTime::utc(2025, 1, 1, 0, 0, 0.0), None).expect("date");
        let mut previous = start;
        for target in [90.0, 180.0, 270.0, 0.0, 90.0] {
            let found = next_phase(&previous, target);
            assert!(found.jd > previous.jd && found.jd - previous.jd < SYNODIC_MONTH_DAYS + 1.0);
            let got = moon_phase(&found).longitude_elongation.to_degrees();
            assert!(wrap_degrees(got - target).abs() < 1e-5, "{got} vs {target}");
            previous = found;
        }
        // Asking again from a phase instant gives the next lunation's.
        let again = next_phase(&previous, 90.0);
        assert!((again.jd - previous.jd - SYNODIC_MONTH_DAYS).abs() < 1.0);
    }

    #[test]
    fn illuminated_fraction_and_brightness_follow_the_phase() {
        let start = Instant::from_civil(&CivilDateTime::utc(2025, 3, 29, 10, 58, 0.0), None).expect("date");
        let full = next_phase(&start, 180.0);
        let quarter = next_phase(&start, 90.0);
        let new = moon_phase(&start);
        assert!(new.illuminated_fraction < 0.01, "{}", new.illuminated_fraction);
        let full_phase = moon_phase(&full);
        assert!(full_phase.illuminated_fraction > 0.99);
        let q = moon_phase(&quarter).illuminated_fraction;
        assert!((q - 0.5).abs() < 0.02, "{q}");
        // Full moon: V ≈ −12.7 at mean distance, ~0.3 lux; a quarter moon is ~10× fainter.
        let m_full = full_phase.magnitude_at_mean_distance();
        assert!((m_full + 12.7).abs() < 0.1, "{m_full}");
        let lux_full = star_illuminance_lux(m_full);
        assert!((0.2..0.4).contains(&lux_full), "{lux_full}");
        let m_quarter = moon_phase(&quarter).magnitude_at_mean_distance();
        let ratio = lux_full / star_illuminance_lux(m_quarter);
        assert!((6.0..15.0).contains(&ratio), "{ratio}");
    }

    #[test]
    fn the_sun_direction_lights_the_visible_phase() {
        // Shading a sphere at the Moon's direction by the Sun direction gives the lit fraction k:
        // the cosine of the angle between the Sun direction and the direction back to the
        // observer is cos i, so (1 + cos i)/2 = k.
        let instant = Instant::from_civil(&CivilDateTime::utc(2025, 6, 3, 21, 0, 0.0), None).expect("date");
        let view = moon_view(&instant, 48.85, 2.35, 35.0);
        let cos_i = view.sun_direction.dot(-view.direction);
        assert!(((1.0 + cos_i) / 2.0 - view.phase.illuminated_fraction).abs() < 1e-9);
        assert!((view.sun_direction.length() - 1.0).abs() < 1e-12);
        // The bright limb faces the Sun: the Sun direction, projected on the sky plane at the
        // Moon, points at position angle χ from celestial north.
        let nutation = Nutation::low_precision(&instant);
        let lst = local_sidereal_time(
            greenwich_apparent_sidereal_time(&instant, &nutation),
            2.35_f64.to_radians(),
        );
        let to_enu = equatorial_to_horizon_matrix(lst, 48.85_f64.to_radians());
        let north_pole = to_enu * DVec3::Z;
        let d = view.direction;
        let north = (north_pole - d * north_pole.dot(d)).normalize();
        let east = north.cross(d); // On the sky (seen from inside), east is left of north.
        let s = view.sun_direction - d * view.sun_direction.dot(d);
        let chi = s.dot(east).atan2(s.dot(north));
        let diff = wrap_degrees((chi - view.phase.bright_limb_angle).to_degrees());
        assert!(diff.abs() < 0.5, "χ from the Sun direction differs by {diff}°");
    }
}
