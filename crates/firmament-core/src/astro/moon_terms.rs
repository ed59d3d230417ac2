//! The periodic terms of the Moon's geocentric longitude, distance and latitude: Meeus,
//! *Astronomical Algorithms* (2nd ed., 1998), tables 47.A and 47.B, the truncated ELP-2000/82
//! theory of Chapront-Touzé & Chapront. Published data, transcribed in full.
//!
//! Each term has the multiples of the arguments D (the Moon's mean elongation), M (the Sun's mean
//! anomaly), M′ (the Moon's mean anomaly) and F (the Moon's argument of latitude), then its
//! coefficients. Terms with M are multiplied by E (or E² for 2M) at use, E being the Earth's
//! orbital eccentricity factor (Meeus eq. 47.6).

/// One term of table 47.A: multiples of (D, M, M′, F), the coefficient of sin(argument) in Σl
/// (10⁻⁶ degree) and of cos(argument) in Σr (10⁻³ km).
#[derive(Debug, Clone, Copy)]
pub(super) struct LongitudeDistanceTerm {
    /// Multiples of D, M, M′ and F.
    pub(super) multiples: [i8; 4],
    /// Coefficient of the sine in Σl, 10⁻⁶ degree.
    pub(super) longitude: i32,
    /// Coefficient of the cosine in Σr, 10⁻³ km.
    pub(super) distance: i32,
}

/// One term of table 47.B: multiples of (D, M, M′, F) and the coefficient of sin(argument) in Σb
/// (10⁻⁶ degree).
#[derive(Debug, Clone, Copy)]
pub(super) struct LatitudeTerm {
    /// Multiples of D, M, M′ and F.
    pub(super) multiples: [i8; 4],
    /// Coefficient of the sine in Σb, 10⁻⁶ degree.
    pub(super) latitude: i32,
}

/// Shorthand for a table 47.A row.
const fn lr(d: i8, m: i8, mp: i8, f: i8, longitude: i32, distance: i32) -> LongitudeDistanceTerm {
    LongitudeDistanceTerm {
        multiples: [d, m, mp, f],
        longitude,
        distance,
    }
}

/// Shorthand for a table 47.B row.
const fn b(d: i8, m: i8, mp: i8, f: i8, latitude: i32) -> LatitudeTerm {
    LatitudeTerm {
        multiples: [d, m, mp, f],
        latitude,
    }
}

/// Table 47.A: the 60 terms of the longitude (Σl) and distance (Σr).
#[rustfmt::skip]
pub(super) const LONGITUDE_DISTANCE: [LongitudeDistanceTerm; 60] = [
    lr(0, 0, 1, 0, 6288774, -20905355),
    lr(2, 0, -1, 0, 1274027, -3699111),
    lr(2, 0, 0, 0, 658314, -2955968),
    lr(0, 0, 2, 0, 213618, -569925),
    lr(0, 1, 0, 0, -185116, 48888),
    lr(0, 0, 0, 2, -114332, -3149),
    lr(2, 0, -2, 0, 58793, 246158),
    lr(2, -1, -1, 0, 57066, -152138),
    lr(2, 0, 1, 0, 53322, -170733),
    lr(2, -1, 0, 0, 45758, -204586),
    lr(0, 1, -1, 0, -40923, -129620),
    lr(1, 0, 0, 0, -34720, 108743),
    lr(0, 1, 1, 0, -30383, 104755),
    lr(2, 0, 0, -2, 15327, 10321),
    lr(0, 0, 1, 2, -12528, 0),
    lr(0, 0, 1, -2, 10980, 79661),
    lr(4, 0, -1, 0, 10675, -34782),
    lr(0, 0, 3, 0, 10034, -23210),
    lr(4, 0, -2, 0, 8548, -21636),
    lr(2, 1, -1, 0, -7888, 24208),
    lr(2, 1, 0, 0, -6766, 30824),
    lr(1, 0, -1, 0, -5163, -8379),
    lr(1, 1, 0, 0, 4987, -16675),
    lr(2, -1, 1, 0, 4036, -12831),
    lr(2, 0, 2, 0, 3994, -10445),
    lr(4, 0, 0, 0, 3861, -11650),
    lr(2, 0, -3, 0, 3665, 14403),
    lr(0, 1, -2, 0, -2689, -7003),
    lr(2, 0, -1, 2, -2602, 0),
    lr(2, -1, -2, 0, 2390, 10056),
    lr(1, 0, 1, 0, -2348, 6322),
    lr(2, -2, 0, 0, 2236, -9884),
    lr(0, 1, 2, 0, -2120, 5751),
    lr(0, 2, 0, 0, -2069, 0),
    lr(2, -2, -1, 0, 2048, -4950),
    lr(2, 0, 1, -2, -1773, 4130),
    lr(2, 0, 0, 2, -1595, 0),
    lr(4, -1, -1, 0, 1215, -3958),
    lr(0, 0, 2, 2, -1110, 0),
    lr(3, 0, -1, 0, -892, 3258),
    lr(2, 1, 1, 0, -810, 2616),
    lr(4, -1, -2, 0, 759, -1897),
    lr(0, 2, -1, 0, -713, -2117),
    lr(2, 2, -1, 0, -700, 2354),
    lr(2, 1, -2, 0, 691, 0),
    lr(2, -1, 0, -2, 596, 0),
    lr(4, 0, 1, 0, 549, -1423),
    lr(0, 0, 4, 0, 537, -1117),
    lr(4, -1, 0, 0, 520, -1571),
    lr(1, 0, -2, 0, -487, -1739),
    lr(2, 1, 0, -2, -399, 0),
    lr(0, 0, 2, -2, -381, -4421),
    lr(1, 1, 1, 0, 351, 0),
    lr(3, 0, -2, 0, -340, 0),
    lr(4, 0, -3, 0, 330, 0),
    lr(2, -1, 2, 0, 327, 0),
    lr(0, 2, 1, 0, -323, 1165),
    lr(1, 1, -1, 0, 299, 0),
    lr(2, 0, 3, 0, 294, 0),
    lr(2, 0, -1, -2, 0, 8752),
];

/// Table 47.B: the 60 terms of the latitude (Σb).
#[rustfmt::skip]
pub(super) const LATITUDE: [LatitudeTerm; 60] = [
    b(0, 0, 0, 1, 5128122),
    b(0, 0, 1, 1, 280602),
    b(0, 0, 1, -1, 277693),
    b(2, 0, 0, -1, 173237),
    b(2, 0, -1, 1, 55413),
    b(2, 0, -1, -1, 46271),
    b(2, 0, 0, 1, 32573),
    b(0, 0, 2, 1, 17198),
    b(2, 0, 1, -1, 9266),
    b(0, 0, 2, -1, 8822),
    b(2, -1, 0, -1, 8216),
    b(2, 0, -2, -1, 4324),
    b(2, 0, 1, 1, 4200),
    b(2, 1, 0, -1, -3359),
    b(2, -1, -1, 1, 2463),
    b(2, -1, 0, 1, 2211),
    b(2, -1, -1, -1, 2065),
    b(0, 1, -1, -1, -1870),
    b(4, 0, -1, -1, 1828),
    b(0, 1, 0, 1, -1794),
    b(0, 0, 0, 3, -1749),
    b(0, 1, -1, 1, -1565),
    b(1, 0, 0, 1, -1491),
    b(0, 1, 1, 1, -1475),
    b(0, 1, 1, -1, -1410),
    b(0, 1, 0, -1, -1344),
    b(1, 0, 0, -1, -1335),
    b(0, 0, 3, 1, 1107),
    b(4, 0, 0, -1, 1021),
    b(4, 0, -1, 1, 833),
    b(0, 0, 1, -3, 777),
    b(4, 0, -2, 1, 671),
    b(2, 0, 0, -3, 607),
    b(2, 0, 2, -1, 596),
    b(2, -1, 1, -1, 491),
    b(2, 0, -2, 1, -451),
    b(0, 0, 3, -1, 439),
    b(2, 0, 2, 1, 422),
    b(2, 0, -3, -1, 421),
    b(2, 1, -1, 1, -366),
    b(2, 1, 0, 1, -351),
    b(4, 0, 0, 1, 331),
    b(2, -1, 1, 1, 315),
    b(2, -2, 0, -1, 302),
    b(0, 0, 1, 3, -283),
    b(2, 1, 1, -1, -229),
    b(1, 1, 0, -1, 223),
    b(1, 1, 0, 1, 223),
    b(0, 1, -2, -1, -220),
    b(2, 1, -1, -1, -220),
    b(1, 0, 1, 1, -185),
    b(2, -1, -2, -1, 181),
    b(0, 1, 2, 1, -177),
    b(4, 0, -2, -1, 176),
    b(4, -1, -1, -1, 166),
    b(1, 0, 1, -1, -164),
    b(4, 0, 1, -1, 132),
    b(1, 0, -1, -1, -119),
    b(4, -1, 0, -1, 115),
    b(2, -2, 0, 1, 107),
];
