//! The stars of the night sky: a real catalogue of the naked-eye stars, their colours and the
//! light each gives.
//!
//! # The catalogue
//! Every Hipparcos star with V ≤ 6.5 (8867 stars; *The Hipparcos and Tycho Catalogues*, ESA
//! SP-1200, 1997: Johnson V and B−V of the main catalogue, ICRS positions at epoch J1991.25).
//! The data come from the `star-catalog` crate (Gavin J Stark, MIT OR Apache-2.0), whose
//! `hipp_bright` feature carries the Hipparcos stars to V = 8; `build.rs` extracts the naked-eye
//! ones at build time into a 28-byte-a-star table embedded here. Proper motion is not applied:
//! the largest among these stars (Arcturus, 2.3″ a year) moves it 20″ from 1991.25 to 2000, far
//! below what a sky render can show. Positions are taken as J2000.0 mean equatorial; precess
//! them to the date with [`super::sidereal::j2000_to_horizon_matrix`].
//!
//! # Brightness
//! A star of V magnitude m gives `E = 10^(−0.4 (m + 13.99))` lux on a surface facing it above the
//! atmosphere: V = 0 is 2.54·10⁻⁶ lux (the V zero point of Allen's *Astrophysical Quantities*;
//! Schaefer 1993, "Astronomy and the limits of vision", *Vistas in Astronomy* 36, 311).
//!
//! # Colour
//! B−V → effective temperature by Ballesteros (2012, *EPL* 97, 34008):
//! `T = 4600 K (1/(0.92 (B−V) + 1.7) + 1/(0.92 (B−V) + 0.62))`, then a black body of that
//! temperature through the model's spectral conversion
//! ([`crate::atmosphere::star::blackbody_spectrum`] and
//! [`crate::atmosphere::spectrum::SpectralConversion`], the ones the physical sky's suns use),
//! normalised to luminance 1.

use std::sync::OnceLock;

use glam::DVec3;

use super::sidereal::equatorial_unit_vector;
use crate::atmosphere::spectrum::{SpectralConversion, Wavelengths};
use crate::atmosphere::star::blackbody_spectrum;
use crate::color::LinearRgb;

/// The catalogue table written by `build.rs`: per star RA, Dec (f64 radians), V, B−V (f32) and
/// the Hipparcos number (u32), little-endian, brightest first.
static CATALOGUE_BYTES: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/bright_stars.bin"));

/// Bytes per star in [`CATALOGUE_BYTES`].
const RECORD_BYTES: usize = 28;

/// The faintest V magnitude in [`catalogue`].
pub const LIMITING_MAGNITUDE: f64 = 6.5;

/// One star.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Star {
    /// Right ascension, radians (ICRS ≈ J2000.0 mean equator and equinox).
    pub ra_rad: f64,
    /// Declination, radians (ICRS ≈ J2000.0).
    pub dec_rad: f64,
    /// Johnson V magnitude.
    pub v_mag: f64,
    /// Johnson B−V colour index, magnitudes.
    pub b_minus_v: f64,
    /// Hipparcos catalogue number.
    pub hip: u32,
}

impl Star {
    /// The unit vector towards the star in the J2000.0 equatorial frame (`x` to the equinox, `z`
    /// to the north celestial pole).
    pub fn unit_vector(&self) -> DVec3 {
        equatorial_unit_vector(self.ra_rad, self.dec_rad)
    }

    /// Illuminance from the star at the top of the atmosphere, lux ([`star_illuminance_lux`]).
    pub fn illuminance_lux(&self) -> f64 {
        star_illuminance_lux(self.v_mag)
    }

    /// The star's colour, linear sRGB of luminance 1 ([`star_color`]).
    pub fn color(&self) -> LinearRgb {
        star_color(self.b_minus_v)
    }

    /// The star's proper name, if it is one of the [`NAMED_STARS`].
    pub fn name(&self) -> Option<&'static str> {
        NAMED_STARS
            .iter()
            .find(|(_, hip)| *hip == self.hip)
            .map(|(name, _)| *name)
    }
}

/// Proper names (IAU Working Group on Star Names) of landmark stars — the 50 or so brightest and
/// the Pole Star and the Plough's — with their Hipparcos numbers.
pub const NAMED_STARS: &[(&str, u32)] = &[
    ("Sirius", 32349),
    ("Canopus", 30438),
    ("Rigil Kentaurus", 71683),
    ("Arcturus", 69673),
    ("Vega", 91262),
    ("Capella", 24608),
    ("Rigel", 24436),
    ("Procyon", 37279),
    ("Achernar", 7588),
    ("Betelgeuse", 27989),
    ("Hadar", 68702),
    ("Altair", 97649),
    ("Acrux", 60718),
    ("Aldebaran", 21421),
    ("Spica", 65474),
    ("Antares", 80763),
    ("Pollux", 37826),
    ("Fomalhaut", 113368),
    ("Deneb", 102098),
    ("Mimosa", 62434),
    ("Toliman", 71681),
    ("Regulus", 49669),
    ("Adhara", 33579),
    ("Castor", 36850),
    ("Gacrux", 61084),
    ("Shaula", 85927),
    ("Bellatrix", 25336),
    ("Elnath", 25428),
    ("Miaplacidus", 45238),
    ("Alnilam", 26311),
    ("Alnair", 109268),
    ("Alnitak", 26727),
    ("Alioth", 62956),
    ("Mirfak", 15863),
    ("Kaus Australis", 90185),
    ("Dubhe", 54061),
    ("Wezen", 34444),
    ("Alkaid", 67301),
    ("Sargas", 86228),
    ("Avior", 41037),
    ("Menkalinan", 28360),
    ("Atria", 82273),
    ("Alhena", 31681),
    ("Peacock", 100751),
    ("Polaris", 11767),
    ("Hamal", 9884),
    ("Diphda", 3419),
    ("Kochab", 72607),
    ("Alpheratz", 677),
    ("Saiph", 27366),
    ("Rasalhague", 86032),
    ("Algol", 14576),
    ("Denebola", 57632),
    ("Mizar", 65378),
    ("Schedar", 3179),
    ("Mintaka", 25930),
    ("Caph", 746),
    ("Merak", 53910),
    ("Phecda", 58001),
    ("Megrez", 59774),
];

/// Reads one little-endian field of `N` bytes at `offset` of a record.
fn field<const N: usize>(record: &[u8], offset: usize) -> [u8; N] {
    let mut out = [0; N];
    out.copy_from_slice(&record[offset..offset + N]);
    out
}

/// The naked-eye stars (V ≤ 6.5, Hipparcos), brightest first; decoded once.
pub fn catalogue() -> &'static [Star] {
    static CATALOGUE: OnceLock<Vec<Star>> = OnceLock::new();
    CATALOGUE.get_or_init(|| {
        CATALOGUE_BYTES
            .chunks_exact(RECORD_BYTES)
            .map(|r| Star {
                ra_rad: f64::from_le_bytes(field(r, 0)),
                dec_rad: f64::from_le_bytes(field(r, 8)),
                // Hipparcos gives V to 0.01 and B−V to 0.001 mag: undo the f32 rounding noise.
                v_mag: (f64::from(f32::from_le_bytes(field(r, 16))) * 100.0).round() / 100.0,
                b_minus_v: (f64::from(f32::from_le_bytes(field(r, 20))) * 1000.0).round() / 1000.0,
                hip: u32::from_le_bytes(field(r, 24)),
            })
            .collect()
    })
}

/// The catalogue star with this proper name ([`NAMED_STARS`], case-insensitive).
pub fn named_star(name: &str) -> Option<&'static Star> {
    let (_, hip) = NAMED_STARS.iter().find(|(n, _)| n.eq_ignore_ascii_case(name))?;
    catalogue().iter().find(|s| s.hip == *hip)
}

/// Illuminance at the top of the atmosphere, lux, from a point source of V magnitude `v_mag`:
/// `10^(−0.4 (V + 13.99))` (V = 0 gives 2.54·10⁻⁶ lux; Allen's *Astrophysical Quantities*).
pub fn star_illuminance_lux(v_mag: f64) -> f64 {
    10_f64.powf(-0.4 * (v_mag + 13.99))
}

/// Effective temperature, kelvin, of a star of colour index `b_minus_v` (Ballesteros 2012),
/// with B−V clamped to [−0.4, 2.0], the range the formula was fitted on.
pub fn star_temperature_k(b_minus_v: f64) -> f64 {
    let bv = b_minus_v.clamp(-0.4, 2.0);
    4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62))
}

/// The colour of a star of colour index `b_minus_v`: a black body at [`star_temperature_k`]
/// through the model's spectral conversion, linear sRGB scaled to luminance 1
/// (0.2126 r + 0.7152 g + 0.0722 b = 1).
pub fn star_color(b_minus_v: f64) -> LinearRgb {
    static CONVERSION: OnceLock<(Wavelengths, SpectralConversion)> = OnceLock::new();
    let (wavelengths, conversion) = CONVERSION.get_or_init(|| {
        let w = Wavelengths::default();
        (w, SpectralConversion::new(w))
    });
    let spectrum = blackbody_spectrum(star_temperature_k(b_minus_v), *wavelengths);
    conversion
        .linear_srgb(spectrum)
        .scale(1.0 / conversion.luminance(spectrum))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::sidereal::j2000_to_horizon_matrix;
    use crate::astro::{CivilDateTime, Instant};

    #[test]
    fn the_catalogue_holds_the_naked_eye_sky() {
        let stars = catalogue();
        assert_eq!(stars.len(), 8867);
        assert!(stars.windows(2).all(|w| w[0].v_mag <= w[1].v_mag), "brightest first");
        assert!(stars.iter().all(|s| s.v_mag <= LIMITING_MAGNITUDE));
        assert!(stars.iter().all(|s| (0.0..std::f64::consts::TAU).contains(&s.ra_rad)));
        assert!(stars.iter().all(|s| s.dec_rad.abs() <= std::f64::consts::FRAC_PI_2));
        // Carbon stars reach B−V ≈ 3.3 (W Orionis, HIP 23680).
        assert!(stars.iter().all(|s| (-0.5..3.5).contains(&s.b_minus_v)));
        // Sirius leads.
        assert_eq!(stars[0].name(), Some("Sirius"));
    }

    #[test]
    fn star_counts_follow_the_magnitude_law() {
        // log₁₀ N(< m) ≈ 0.51 m + 0.6 over the naked-eye range: a straight-line fit to the
        // observed cumulative star counts (as tabulated in Allen's Astrophysical Quantities).
        // Hipparcos must follow it within 20 %.
        let stars = catalogue();
        for m in [2.0, 4.0, 6.0] {
            let count = stars.iter().filter(|s| s.v_mag < m).count() as f64;
            let law = 10_f64.powf(0.51 * m + 0.6);
            eprintln!("N(V < {m}) = {count}, law {law:.0}, ratio {:.3}", count / law);
            assert!((count / law - 1.0).abs() < 0.2, "N(<{m}) = {count} vs {law}");
        }
    }

    #[test]
    fn landmark_stars_are_where_the_references_put_them() {
        // (name, RA J2000 h m s, Dec J2000 ° ′ ″, V) — SIMBAD/Bright Star Catalogue values.
        let landmarks = [
            ("Polaris", (2.0, 31.0, 49.09), (89.0, 15.0, 50.8), 1.98),
            ("Sirius", (6.0, 45.0, 8.917), (-16.0, 42.0, 58.02), -1.46),
            ("Vega", (18.0, 36.0, 56.336), (38.0, 47.0, 1.28), 0.03),
            ("Arcturus", (14.0, 15.0, 39.672), (19.0, 10.0, 56.67), -0.05),
            ("Betelgeuse", (5.0, 55.0, 10.305), (7.0, 24.0, 25.43), 0.50),
        ];
        for (name, (h, m, s), (d, am, asec), v) in landmarks {
            let star = named_star(name).unwrap_or_else(|| panic!("{name} missing"));
            let ra = ((h + m / 60.0 + s / 3600.0) * 15.0_f64).to_radians();
            let dec = (f64::signum(d) * (d.abs() + am / 60.0 + asec / 3600.0)).to_radians();
            let separation = star.unit_vector().angle_between(equatorial_unit_vector(ra, dec));
            // Epoch 1991.25 vs 2000 and proper motion: Arcturus is the worst, ~20″.
            assert!(
                separation.to_degrees() * 3600.0 < 30.0,
                "{name}: {}″",
                separation.to_degrees() * 3600.0
            );
            assert!((star.v_mag - v).abs() < 0.2, "{name}: V {}", star.v_mag);
        }
        // Every named star is in the catalogue, and brighter than 3.5.
        for (name, _) in NAMED_STARS {
            let star = named_star(name).unwrap_or_else(|| panic!("{name} missing"));
            assert!(star.v_mag < 3.5 && star.name() == Some(name));
        }
        assert!(named_star("polaris").is_some() && named_star("Nowhere").is_none());
    }

    #[test]
    fn polaris_barely_moves_over_a_night() {
        // 45° N, 0° E, 2025-01-15 from 18:00 to 06:00 UTC, every 15 minutes.
        let polaris = named_star("Polaris").expect("Polaris");
        let latitude = 45_f64.to_radians();
        let start = Instant::from_civil(&CivilDateTime::utc(2025, 1, 15, 18, 0, 0.0), None).expect("date");
        let directions: Vec<DVec3> = (0..=48)
            .map(|i| {
                j2000_to_horizon_matrix(&start.plus_seconds(i as f64 * 900.0), latitude, 0.0) * polaris.unit_vector()
            })
            .collect();
        // The true pole: due north at an elevation equal to the latitude.
        let pole = DVec3::new(0.0, latitude.cos(), latitude.sin());
        let mut widest: f64 = 0.0;
        let mut farthest: f64 = 0.0;
        for a in &directions {
            farthest = farthest.max(a.angle_between(pole).to_degrees());
            assert!(a.angle_between(pole).to_degrees() < 1.0);
            for b in &directions {
                widest = widest.max(a.angle_between(*b).to_degrees());
            }
        }
        // Polaris circles the pole at ~0.63° (2025): a ring of 1.3° across at most, over 12 h.
        eprintln!("Polaris: {farthest:.3}° from the pole at most, its directions span {widest:.3}°");
        assert!(widest < 1.35, "{widest}°");
        // Vega, by contrast, swings across the sky.
        let vega = named_star("Vega").expect("Vega");
        let first = directions.len() - 1;
        let vega_at = |i: usize| {
            j2000_to_horizon_matrix(&start.plus_seconds(i as f64 * 900.0), latitude, 0.0) * vega.unit_vector()
        };
        assert!(vega_at(0).angle_between(vega_at(first)).to_degrees() > 60.0);
    }

    #[test]
    fn colours_get_redder_with_b_minus_v() {
        let mut previous = star_color(-0.3);
        for i in 1..=21 {
            let bv = -0.3 + i as f64 * 0.1;
            let c = star_color(bv);
            let luminance = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
            assert!((luminance - 1.0).abs() < 0.01, "B−V {bv}: luminance {luminance}");
            assert!(
                c.r / c.b > previous.r / previous.b,
                "B−V {bv}: {c:?} not redder than {previous:?}"
            );
            previous = c;
        }
        // The Sun (B−V 0.65) is ~5780 K; Vega (0.0) ~9600 K… blue-white; Betelgeuse (1.85) red.
        assert!((star_temperature_k(0.65) - 5778.0).abs() < 50.0);
        let vega = star_color(0.0);
        assert!(vega.b > vega.r);
        let betelgeuse = star_color(1.85);
        assert!(betelgeuse.r > 2.0 * betelgeuse.b);
    }

    #[test]
    fn illuminance_has_the_v_zero_point() {
        assert!((star_illuminance_lux(0.0) / 2.54e-6 - 1.0).abs() < 0.01);
        // Five magnitudes are a factor of 100.
        assert!((star_illuminance_lux(1.0) / star_illuminance_lux(6.0) - 100.0).abs() < 1e-9);
        // The whole catalogue, each star at normal incidence, over the whole sphere: a few
        // 1e-4 lux, Sirius (1e-5 lux) a few percent of it.
        let total: f64 = catalogue().iter().map(Star::illuminance_lux).sum();
        eprintln!("all catalogue stars: {total:.3e} lux");
        assert!((1e-4..4e-4).contains(&total), "{total}");
    }
}
