//! Sidereal time, nutation, precession, and the change from equatorial to horizon coordinates.
//!
//! - **Greenwich mean sidereal time**: the IAU 1982 expression (Aoki et al. 1982, *A&A* 105, 359)
//!   in the form of Meeus, *Astronomical Algorithms* (2nd ed., 1998), eq. 12.4, with the Julian
//!   Date in UT.
//! - **Nutation**: Meeus ch. 22's short series (the four largest terms of the IAU 1980 theory),
//!   good to 0.5″ in Δψ and 0.1″ in Δε; the mean obliquity by the IAU expression of Meeus
//!   eq. 22.2 (Lieske et al. 1977; 1″ over 2000 years around J2000).
//! - **Apparent sidereal time**: GMST plus the equation of the equinoxes Δψ·cos ε (Meeus ch. 12).
//! - **Precession** of J2000.0 coordinates to the mean equinox of date: the rigorous method of
//!   Meeus ch. 21 (IAU 1976 angles ζ, z, θ, eq. 21.3 with the starting epoch J2000.0).
//!
//! All angles here are radians. Equatorial unit vectors have `x` towards the equinox, `z` towards
//! the celestial north pole; horizon vectors are East-North-Up, as everywhere in firmament.

use std::f64::consts::TAU;

use glam::{DMat3, DVec3};

use super::time::{Instant, J2000};

/// One arcsecond in radians.
pub const ARCSECOND: f64 = std::f64::consts::PI / (180.0 * 3600.0);

/// The angle reduced to [0, 2π) radians.
pub fn normalize_radians(angle: f64) -> f64 {
    let r = angle.rem_euclid(TAU);
    // rem_euclid may return TAU itself for tiny negative inputs.
    if r >= TAU { 0.0 } else { r }
}

/// Nutation in longitude and obliquity, and the mean obliquity of the ecliptic, for one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nutation {
    /// Nutation in longitude Δψ, radians.
    pub longitude: f64,
    /// Nutation in obliquity Δε, radians.
    pub obliquity: f64,
    /// Mean obliquity of the ecliptic ε₀, radians (Meeus eq. 22.2).
    pub mean_obliquity: f64,
}

impl Nutation {
    /// Meeus ch. 22's low-precision nutation (0.5″ in Δψ, 0.1″ in Δε) and eq. 22.2's mean
    /// obliquity, at the instant's dynamical time.
    pub fn low_precision(instant: &Instant) -> Self {
        let t = instant.centuries_tt();
        // Longitude of the Moon's ascending node, the mean longitudes of the Sun and the Moon.
        let omega = (125.04452 - 1934.136261 * t + 0.0020708 * t * t + t * t * t / 450_000.0).to_radians();
        let sun = (280.4665 + 36_000.769_8 * t).to_radians();
        let moon = (218.3165 + 481_267.881_3 * t).to_radians();
        let longitude =
            -17.20 * omega.sin() - 1.32 * (2.0 * sun).sin() - 0.23 * (2.0 * moon).sin() + 0.21 * (2.0 * omega).sin();
        let obliquity =
            9.20 * omega.cos() + 0.57 * (2.0 * sun).cos() + 0.10 * (2.0 * moon).cos() - 0.09 * (2.0 * omega).cos();
        Self {
            longitude: longitude * ARCSECOND,
            obliquity: obliquity * ARCSECOND,
            mean_obliquity: mean_obliquity(t),
        }
    }

    /// True obliquity of the ecliptic ε = ε₀ + Δε, radians.
    pub fn true_obliquity(&self) -> f64 {
        self.mean_obliquity + self.obliquity
    }

    /// The equation of the equinoxes Δψ·cos ε, radians: apparent minus mean sidereal time.
    pub fn equation_of_the_equinoxes(&self) -> f64 {
        self.longitude * self.true_obliquity().cos()
    }

    /// The rotation from mean equatorial coordinates of date to true (nutated) equatorial
    /// coordinates of date: `R₁(−ε) R₃(−Δψ) R₁(ε₀)` (Explanatory Supplement to the Astronomical
    /// Almanac, 1992, §3.222).
    pub fn matrix(&self) -> DMat3 {
        DMat3::from_rotation_x(self.true_obliquity())
            * DMat3::from_rotation_z(self.longitude)
            * DMat3::from_rotation_x(-self.mean_obliquity)
    }
}

/// Mean obliquity of the ecliptic ε₀ in radians for `t` Julian centuries of TT since J2000.0
/// (Meeus eq. 22.2, the IAU expression of Lieske et al. 1977).
pub fn mean_obliquity(t: f64) -> f64 {
    let arcsec = 84_381.448 - 46.8150 * t - 0.000_59 * t * t + 0.001_813 * t * t * t;
    arcsec * ARCSECOND
}

/// Greenwich mean sidereal time in radians, [0, 2π), by the IAU 1982 expression (Meeus eq. 12.4)
/// at the instant's UT.
pub fn greenwich_mean_sidereal_time(instant: &Instant) -> f64 {
    let days = instant.jd - J2000;
    let t = days / 36_525.0;
    // Split the large daily term to keep f64 precision: 360.98564736629 = 360 + 0.98564736629.
    let degrees = 280.460_618_37 + 0.985_647_366_29 * days + 360.0 * days.fract() + 0.000_387_933 * t * t
        - t * t * t / 38_710_000.0;
    normalize_radians(degrees.to_radians())
}

/// Greenwich apparent sidereal time in radians, [0, 2π): GMST plus the equation of the equinoxes
/// (Meeus ch. 12) from the given nutation.
pub fn greenwich_apparent_sidereal_time(instant: &Instant, nutation: &Nutation) -> f64 {
    normalize_radians(greenwich_mean_sidereal_time(instant) + nutation.equation_of_the_equinoxes())
}

/// Local sidereal time in radians, [0, 2π), from a Greenwich sidereal time (mean or apparent) and
/// the longitude, radians east of Greenwich (west negative).
pub fn local_sidereal_time(greenwich_rad: f64, longitude_east_rad: f64) -> f64 {
    normalize_radians(greenwich_rad + longitude_east_rad)
}

/// Local apparent sidereal time in radians, [0, 2π), at a longitude (radians, east positive),
/// with [`Nutation::low_precision`].
pub fn local_apparent_sidereal_time(instant: &Instant, longitude_east_rad: f64) -> f64 {
    let nutation = Nutation::low_precision(instant);
    local_sidereal_time(greenwich_apparent_sidereal_time(instant, &nutation), longitude_east_rad)
}

/// The unit vector of right ascension `ra_rad` and declination `dec_rad` (radians) in its
/// equatorial frame (`x` to the equinox, `z` to the north celestial pole).
pub fn equatorial_unit_vector(ra_rad: f64, dec_rad: f64) -> DVec3 {
    let (sin_ra, cos_ra) = ra_rad.sin_cos();
    let (sin_dec, cos_dec) = dec_rad.sin_cos();
    DVec3::new(cos_dec * cos_ra, cos_dec * sin_ra, sin_dec)
}

/// Right ascension in [0, 2π) and declination in [−π/2, π/2], radians, of an equatorial vector
/// (of any non-zero length).
pub fn ra_dec_of(vector: DVec3) -> (f64, f64) {
    let ra = normalize_radians(vector.y.atan2(vector.x));
    let dec = vector.z.atan2(vector.x.hypot(vector.y));
    (ra, dec)
}

/// The rotation from equatorial coordinates of date to the local East-North-Up frame, for the
/// local sidereal time `lst_rad` and the geodetic latitude `latitude_rad`. Multiply an equatorial
/// unit vector by it to get the horizon direction (the same as [`equatorial_to_horizon`]).
pub fn equatorial_to_horizon_matrix(lst_rad: f64, latitude_rad: f64) -> DMat3 {
    let (sin_lat, cos_lat) = latitude_rad.sin_cos();
    // Hour-angle frame: x towards the meridian's equator point (H = 0), y towards H = −6 h (east).
    let to_hour_angle = DMat3::from_rotation_z(-lst_rad);
    // Rows east = (0, 1, 0), north = (−sin φ, 0, cos φ), up = (cos φ, 0, sin φ).
    let to_enu = DMat3::from_cols(
        DVec3::new(0.0, -sin_lat, cos_lat),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, cos_lat, sin_lat),
    );
    to_enu * to_hour_angle
}

/// The East-North-Up unit vector of a body at right ascension `ra_rad` and declination
/// `dec_rad` (equatorial coordinates of date), seen at local sidereal time `lst_rad` from
/// latitude `latitude_rad` (all radians). Meeus eqs. 13.5–13.6 in vector form: with the hour
/// angle H = LST − α, east = −cos δ sin H, north = cos φ sin δ − sin φ cos δ cos H,
/// up = sin φ sin δ + cos φ cos δ cos H. No refraction.
pub fn equatorial_to_horizon(ra_rad: f64, dec_rad: f64, lst_rad: f64, latitude_rad: f64) -> DVec3 {
    let hour_angle = lst_rad - ra_rad;
    let (sin_h, cos_h) = hour_angle.sin_cos();
    let (sin_dec, cos_dec) = dec_rad.sin_cos();
    let (sin_lat, cos_lat) = latitude_rad.sin_cos();
    DVec3::new(
        -cos_dec * sin_h,
        cos_lat * sin_dec - sin_lat * cos_dec * cos_h,
        sin_lat * sin_dec + cos_lat * cos_dec * cos_h,
    )
}

/// Right ascension and declination (radians, of date) of an East-North-Up direction seen at local
/// sidereal time `lst_rad` from latitude `latitude_rad`: the inverse of [`equatorial_to_horizon`].
pub fn horizon_to_equatorial(enu: DVec3, lst_rad: f64, latitude_rad: f64) -> (f64, f64) {
    ra_dec_of(equatorial_to_horizon_matrix(lst_rad, latitude_rad).transpose() * enu)
}

/// Ecliptic longitude and latitude (radians) to right ascension and declination (radians) for the
/// obliquity `obliquity_rad` (Meeus eqs. 13.3–13.4); right ascension in [0, 2π).
pub fn ecliptic_to_equatorial(longitude_rad: f64, latitude_rad: f64, obliquity_rad: f64) -> (f64, f64) {
    let ecliptic = equatorial_unit_vector(longitude_rad, latitude_rad);
    ra_dec_of(DMat3::from_rotation_x(obliquity_rad) * ecliptic)
}

/// The IAU 1976 precession angles (ζ, z, θ) in radians from J2000.0 to the instant's dynamical
/// time (Meeus eq. 21.3 with T = 0).
pub fn precession_angles(instant: &Instant) -> (f64, f64, f64) {
    let t = instant.centuries_tt();
    let zeta = (2306.2181 + (0.30188 + 0.017998 * t) * t) * t;
    let z = (2306.2181 + (1.09468 + 0.018203 * t) * t) * t;
    let theta = (2004.3109 - (0.42665 + 0.041833 * t) * t) * t;
    (zeta * ARCSECOND, z * ARCSECOND, theta * ARCSECOND)
}

/// The rotation from mean equatorial coordinates of J2000.0 to mean equatorial coordinates of the
/// instant: `R₃(−z) R₂(θ) R₃(−ζ)`, the matrix form of Meeus eq. 21.4.
pub fn precession_matrix_from_j2000(instant: &Instant) -> DMat3 {
    let (zeta, z, theta) = precession_angles(instant);
    DMat3::from_rotation_z(z) * DMat3::from_rotation_y(-theta) * DMat3::from_rotation_z(zeta)
}

/// Precesses J2000.0 mean right ascension and declination (radians) to the mean equinox of the
/// instant, by Meeus's rigorous method (ch. 21, eq. 21.4). Proper motion, if any, is the caller's
/// to apply first.
pub fn precess_from_j2000(ra_rad: f64, dec_rad: f64, instant: &Instant) -> (f64, f64) {
    let (zeta, z, theta) = precession_angles(instant);
    let (sin_dec, cos_dec) = dec_rad.sin_cos();
    let (sin_a, cos_a) = (ra_rad + zeta).sin_cos();
    let (sin_t, cos_t) = theta.sin_cos();
    let a = cos_dec * sin_a;
    let b = cos_t * cos_dec * cos_a - sin_t * sin_dec;
    let c = sin_t * cos_dec * cos_a + cos_t * sin_dec;
    let ra = normalize_radians(a.atan2(b) + z);
    // Near the poles asin loses precision: use the vector's other components.
    let dec = c.atan2(a.hypot(b));
    (ra, dec)
}

/// The rotation from J2000.0 equatorial unit vectors (a star catalogue's) to the local
/// East-North-Up frame at an instant and place: precession (Meeus ch. 21), nutation
/// ([`Nutation::low_precision`]) and the apparent sidereal time. Aberration (≤ 20.5″) and proper
/// motion are left out. Latitude and longitude in radians, longitude east positive.
pub fn j2000_to_horizon_matrix(instant: &Instant, latitude_rad: f64, longitude_east_rad: f64) -> DMat3 {
    let nutation = Nutation::low_precision(instant);
    let lst = local_sidereal_time(greenwich_apparent_sidereal_time(instant, &nutation), longitude_east_rad);
    equatorial_to_horizon_matrix(lst, latitude_rad) * nutation.matrix() * precession_matrix_from_j2000(instant)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::CivilDateTime;

    /// Hours, minutes and seconds to radians.
    fn hms(h: f64, m: f64, s: f64) -> f64 {
        ((h + m / 60.0 + s / 3600.0) * 15.0).to_radians()
    }

    /// Degrees, arcminutes and arcseconds to radians (sign from `sign`).
    fn dms(sign: f64, d: f64, m: f64, s: f64) -> f64 {
        (sign * (d + m / 60.0 + s / 3600.0)).to_radians()
    }

    /// Radians to seconds of time.
    fn time_seconds(rad: f64) -> f64 {
        rad.to_degrees() / 15.0 * 3600.0
    }

    fn utc(y: i32, mo: u32, d: u32, h: u32, mi: u32, s: f64) -> Instant {
        Instant::from_civil(&CivilDateTime::utc(y, mo, d, h, mi, s), None).expect("valid date")
    }

    #[test]
    fn gmst_matches_meeus_examples_12a_and_12b() {
        // Example 12.a: 1987 April 10, 0h UT → 13h10m46.3668s.
        let a = greenwich_mean_sidereal_time(&utc(1987, 4, 10, 0, 0, 0.0));
        let err_a = time_seconds(a - hms(13.0, 10.0, 46.3668));
        assert!(err_a.abs() < 1e-4, "12.a off by {err_a} s");
        // Example 12.b: 1987 April 10, 19h21m00s UT → 8h34m57.0896s.
        let b = greenwich_mean_sidereal_time(&utc(1987, 4, 10, 19, 21, 0.0));
        let err_b = time_seconds(b - hms(8.0, 34.0, 57.0896));
        assert!(err_b.abs() < 1e-4, "12.b off by {err_b} s");
    }

    #[test]
    fn apparent_sidereal_time_matches_meeus_example_12a() {
        // Example 12.a: Δψ = −3.788″, ε = 23°26′36.85″ → apparent 13h10m46.1351s.
        let instant = utc(1987, 4, 10, 0, 0, 0.0);
        let nutation = Nutation::low_precision(&instant);
        let dpsi = nutation.longitude / ARCSECOND;
        assert!((dpsi + 3.788).abs() < 0.5, "Δψ {dpsi}″");
        let eps = nutation.true_obliquity();
        assert!((eps - dms(1.0, 23.0, 26.0, 36.85)).abs() < 0.5 * ARCSECOND, "ε");
        let gast = greenwich_apparent_sidereal_time(&instant, &nutation);
        let err = time_seconds(gast - hms(13.0, 10.0, 46.1351));
        // 0.5″ in Δψ is 0.03 s of time.
        assert!(err.abs() < 0.035, "apparent sidereal time off by {err} s");
        // With Meeus's own Δψ and ε the equation of the equinoxes is exact.
        let exact = Nutation {
            longitude: -3.788 * ARCSECOND,
            obliquity: 0.0,
            mean_obliquity: dms(1.0, 23.0, 26.0, 36.85),
        };
        let err = time_seconds(greenwich_apparent_sidereal_time(&instant, &exact) - hms(13.0, 10.0, 46.1351));
        assert!(err.abs() < 2e-4, "{err} s");
    }

    #[test]
    fn local_sidereal_time_adds_east_longitude() {
        let gst = 1.0;
        assert!((local_sidereal_time(gst, 0.5) - 1.5).abs() < 1e-15);
        assert!((local_sidereal_time(gst, -2.0) - (TAU - 1.0)).abs() < 1e-12);
    }

    #[test]
    fn horizon_coordinates_match_meeus_example_13b() {
        // Venus from the U.S. Naval Observatory, 1987 April 10 19h21m00s UT: α = 23h09m16.641s,
        // δ = −6°43′11.61″, φ = 38°55′17″ N, L = 77°03′56″ W; apparent sidereal time
        // 8h34m56.853s → A = 68.0337° (from the south, westward), h = 15.1249°.
        let ra = hms(23.0, 9.0, 16.641);
        let dec = dms(-1.0, 6.0, 43.0, 11.61);
        let lat = dms(1.0, 38.0, 55.0, 17.0);
        let lon = dms(-1.0, 77.0, 3.0, 56.0);
        let lst = local_sidereal_time(hms(8.0, 34.0, 56.853), lon);
        let enu = equatorial_to_horizon(ra, dec, lst, lat);
        assert!((enu.length() - 1.0).abs() < 1e-12);
        let altitude = enu.z.asin().to_degrees();
        let azimuth_from_north = enu.x.atan2(enu.y).to_degrees().rem_euclid(360.0);
        // Meeus rounds to 0.0001° from inputs rounded to 1 ms and 0.01″.
        assert!((altitude - 15.1249).abs() < 2e-4, "h = {altitude}");
        assert!(
            (azimuth_from_north - (68.0337 + 180.0)).abs() < 2e-4,
            "A = {azimuth_from_north}"
        );
        // The matrix form and the inverse agree.
        let by_matrix = equatorial_to_horizon_matrix(lst, lat) * equatorial_unit_vector(ra, dec);
        assert!((by_matrix - enu).length() < 1e-12);
        let (ra2, dec2) = horizon_to_equatorial(enu, lst, lat);
        assert!((ra2 - ra).abs() < 1e-12 && (dec2 - dec).abs() < 1e-12);
    }

    #[test]
    fn the_celestial_pole_stays_put_at_every_sidereal_time() {
        let lat = 45_f64.to_radians();
        let reference = equatorial_to_horizon(0.0, std::f64::consts::FRAC_PI_2, 0.0, lat);
        for i in 0..48 {
            let lst = i as f64 / 48.0 * TAU;
            let ra = i as f64 * 0.7;
            let enu = equatorial_to_horizon(ra, std::f64::consts::FRAC_PI_2, lst, lat);
            assert!((enu - reference).length() < 1e-12);
            // Due north, at an elevation equal to the latitude.
            assert!((enu.z.asin() - lat).abs() < 1e-12 && enu.x.abs() < 1e-12 && enu.y > 0.0);
        }
    }

    #[test]
    fn precession_matches_meeus_example_21b() {
        // θ Persei, J2000.0: α₀ = 2h44m11.986s, δ₀ = +49°13′42.48″, proper motion +0.03425 s and
        // −0.0895″ a year; to 2028 Nov 13.19 TD (JDE 2462088.69) → α = 2h46m11.331s,
        // δ = +49°20′54.54″.
        let jde = 2_462_088.69;
        let instant = Instant { jd: jde, delta_t: 0.0 };
        let years = (jde - J2000) / 365.25;
        let ra0 = hms(2.0, 44.0, 11.986 + 0.03425 * years);
        let dec0 = dms(1.0, 49.0, 13.0, 42.48 - 0.0895 * years);
        let (ra, dec) = precess_from_j2000(ra0, dec0, &instant);
        let err_ra = time_seconds(ra - hms(2.0, 46.0, 11.331));
        let err_dec = (dec - dms(1.0, 49.0, 20.0, 54.54)) / ARCSECOND;
        assert!(err_ra.abs() < 2e-3, "α off by {err_ra} s");
        assert!(err_dec.abs() < 0.02, "δ off by {err_dec}″");
        // The matrix form agrees.
        let v = precession_matrix_from_j2000(&instant) * equatorial_unit_vector(ra0, dec0);
        let (ra_m, dec_m) = ra_dec_of(v);
        assert!((ra_m - ra).abs() < 1e-12 && (dec_m - dec).abs() < 1e-12);
    }

    #[test]
    fn nutation_matrix_adds_nutation_in_longitude() {
        let instant = utc(2025, 6, 1, 0, 0, 0.0);
        let n = Nutation::low_precision(&instant);
        let (lambda, beta) = (1.234_f64, 0.1_f64);
        let (ra_mean, dec_mean) = ecliptic_to_equatorial(lambda, beta, n.mean_obliquity);
        let (ra_true, dec_true) = ecliptic_to_equatorial(lambda + n.longitude, beta, n.true_obliquity());
        let v = n.matrix() * equatorial_unit_vector(ra_mean, dec_mean);
        let (ra, dec) = ra_dec_of(v);
        assert!((ra - ra_true).abs() < 1e-12 && (dec - dec_true).abs() < 1e-12);
    }

    #[test]
    fn ecliptic_to_equatorial_matches_meeus_example_13a_inverse() {
        // Pollux (example 13.a): λ = 113.215630°, β = 6.684170°, ε = 23.4392911° →
        // α = 116.328942°, δ = 28.026183°.
        let (ra, dec) = ecliptic_to_equatorial(
            113.215630_f64.to_radians(),
            6.684170_f64.to_radians(),
            23.4392911_f64.to_radians(),
        );
        assert!((ra.to_degrees() - 116.328942).abs() < 2e-6);
        assert!((dec.to_degrees() - 28.026183).abs() < 2e-6);
    }
}
