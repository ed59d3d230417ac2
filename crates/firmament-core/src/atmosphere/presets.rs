//! Atmosphere and sun presets, each with its sources.

use glam::DVec3;

use crate::atmosphere::medium::{
    Absorber, Constituents, Density, DensityLayer, DensityProfile, DensityTable, Medium, Mie, Phase, Rayleigh,
};
use crate::atmosphere::spectrum::{Spectrum, Wavelengths};
use crate::atmosphere::{Atmosphere, Planet, Sun};

mod titan;
mod venus;

pub use titan::{titan, titan_sun};
pub use venus::{VENUS_SEMI_MAJOR_AXIS_AU, venus, venus_sun};

/// WGS84 equatorial radius, m (NIMA TR8350.2, 2000).
pub const WGS84_EQUATORIAL_RADIUS: f64 = 6_378_137.0;
/// WGS84 polar radius, m (`a·(1 − f)`, `1/f = 298.257223563`).
pub const WGS84_POLAR_RADIUS: f64 = 6_356_752.314_245_18;
/// Earth's geometric albedo, 0.434 (NASA Earth Fact Sheet, Williams 2024): the light it casts
/// on the Moon ([`Planet::geometric_albedo`]).
pub const EARTH_GEOMETRIC_ALBEDO: f64 = 0.434;
/// Mars' geometric albedo, 0.170 (NASA Mars Fact Sheet, Williams 2024).
pub const MARS_GEOMETRIC_ALBEDO: f64 = 0.170;
/// Saturn's visual geometric albedo, 0.47 (NASA Saturn Fact Sheet).
pub const SATURN_GEOMETRIC_ALBEDO: f64 = 0.47;
/// One astronomical unit, m (IAU 2012 Resolution B2).
pub const ASTRONOMICAL_UNIT: f64 = 149_597_870_700.0;

/// Earth: the constants Bruneton ("Precomputed Atmospheric Scattering: a New Implementation",
/// 2017, `demo.cc`) and Hillaire ("A Scalable and Production Ready Sky and Atmosphere Rendering
/// Technique", EGSR 2020) share, on the WGS84 ellipsoid instead of their 6360 km sphere:
/// - Rayleigh scattering (5.802, 13.558, 33.100)·10⁻⁶ m⁻¹ at 680/550/440 nm, scale height 8 km;
/// - Mie scattering 3.996·10⁻⁶ m⁻¹ and extinction 4.440·10⁻⁶ m⁻¹ (single-scattering albedo 0.9),
///   scale height 1.2 km, Cornette–Shanks phase with g = 0.8;
/// - ozone absorption (0.650, 1.881, 0.085)·10⁻⁶ m⁻¹ (Bruneton's cross-sections from Gorshelev
///   et al. 2014 / Serdyuchenko et al. 2014 at 300 Dobson units) in a tent from 10 km to a peak
///   at 25 km and back to 0 at 40 km;
/// - top of the atmosphere 60 km above the surface, ground albedo 0.1.
pub fn earth() -> Atmosphere {
    Atmosphere {
        planet: Planet::spheroid(WGS84_EQUATORIAL_RADIUS, WGS84_POLAR_RADIUS, 60_000.0)
            .with_geometric_albedo(EARTH_GEOMETRIC_ALBEDO),
        medium: Medium::from_constituents(
            &Constituents {
                rayleigh: Rayleigh {
                    scattering: Spectrum::new(5.802e-6, 13.558e-6, 33.100e-6),
                    density: DensityProfile::single(DensityLayer::exponential(8_000.0)),
                },
                mie: Mie {
                    scattering: Spectrum::splat(3.996e-6),
                    extinction: Spectrum::splat(4.440e-6),
                    density: DensityProfile::single(DensityLayer::exponential(1_200.0)),
                    phase: Phase::CornetteShanks { g: 0.8 },
                },
                absorber: Absorber {
                    absorption: Spectrum::new(0.650e-6, 1.881e-6, 0.085e-6),
                    density: DensityProfile::tent(10_000.0, 25_000.0, 40_000.0),
                },
            },
            Spectrum::splat(0.1),
        ),
        wavelengths: Wavelengths::default(),
    }
}

/// The Sun seen from Earth, towards `direction` (world frame): spectral irradiance
/// (1.474, 1.8504, 1.91198) W·m⁻²·nm⁻¹ at 680/550/440 nm (Bruneton 2017's values from the ASTM
/// G-173 extraterrestrial spectrum), angular radius 0.004675 rad, limb darkening 0.6.
pub fn earth_sun(direction: DVec3) -> Sun {
    Sun {
        direction: direction.normalize_or_zero(),
        angular_radius: 0.004675,
        irradiance: Spectrum::new(1.474, 1.8504, 1.91198),
        limb_darkening: 0.6,
        disc: true,
        from_body: None,
    }
}

/// Mars' mean distance from the Sun, AU (NASA Mars Fact Sheet, Williams 2024).
pub const MARS_SEMI_MAJOR_AXIS_AU: f64 = 1.52366;

/// Mars in a clear season, from published measurements:
/// - shape: equatorial radius 3396.19 km, polar 3376.20 km (Archinal et al., "Report of the IAU
///   Working Group on Cartographic Coordinates and Rotational Elements: 2015", Celest. Mech. Dyn.
///   Astr. 130, 2018);
/// - CO₂ Rayleigh scattering: Earth's air coefficients scaled by Mars' surface number density
///   (610 Pa at 210 K: 2.1·10²³ m⁻³ against 2.55·10²⁵) and CO₂'s 2.45× larger cross-section
///   (Sneep & Ubachs, JQSRT 92, 2005), scale height 11.1 km (NASA Mars Fact Sheet);
/// - dust: visible optical depth 0.5 (Lemmon et al., Icarus 251, 2015, MER typical clear-season
///   values) mixed with the gas' 11.1 km scale height; single-scattering albedo 0.974 / 0.954 /
///   0.887 at 680/550/440 nm and Henyey–Greenstein g = 0.63 (Wolff et al., JGR 114, 2009; Tomasko
///   et al., JGR 104, 1999) — the absorption in blue makes the butterscotch day sky and the blue
///   sunset;
/// - no ozone to speak of; top of the atmosphere 80 km; ground albedo 0.25 (Bond albedo).
pub fn mars() -> Atmosphere {
    let number_density_ratio = 2.1e23 / 2.55e25;
    let co2_cross_section_ratio = 2.45;
    let rayleigh = Spectrum::new(5.802e-6, 13.558e-6, 33.100e-6) * number_density_ratio * co2_cross_section_ratio;
    let dust_extinction = 0.5 / 11_100.0;
    let albedo = Spectrum::new(0.974, 0.954, 0.887);
    Atmosphere {
        planet: Planet::spheroid(3_396_190.0, 3_376_200.0, 80_000.0).with_geometric_albedo(MARS_GEOMETRIC_ALBEDO),
        medium: Medium::from_constituents(
            &Constituents {
                rayleigh: Rayleigh {
                    scattering: rayleigh,
                    density: DensityProfile::single(DensityLayer::exponential(11_100.0)),
                },
                mie: Mie {
                    scattering: albedo * dust_extinction,
                    extinction: Spectrum::splat(dust_extinction),
                    density: DensityProfile::single(DensityLayer::exponential(11_100.0)),
                    phase: Phase::HenyeyGreenstein { g: 0.63 },
                },
                absorber: Absorber {
                    absorption: Spectrum::ZERO,
                    density: DensityProfile::single(DensityLayer::EMPTY),
                },
            },
            Spectrum::splat(0.25),
        ),
        wavelengths: Wavelengths::default(),
    }
}

/// The Sun seen from Mars: Earth's solar irradiance divided by Mars' mean distance squared, and
/// the angular radius divided by that distance.
pub fn mars_sun(direction: DVec3) -> Sun {
    sun_at(direction, MARS_SEMI_MAJOR_AXIS_AU)
}

/// The Sun towards `direction` from `au` astronomical units: Earth's solar irradiance divided
/// by `au²`, its angular radius by `au`.
fn sun_at(direction: DVec3, au: f64) -> Sun {
    let earth = earth_sun(direction);
    Sun {
        irradiance: earth.irradiance / (au * au),
        angular_radius: earth.angular_radius / au,
        ..earth
    }
}

/// Saturn's mean distance from the Sun, AU (NASA Saturn Fact Sheet, Williams 2024:
/// 1433.53·10⁶ km).
pub const SATURN_SEMI_MAJOR_AXIS_AU: f64 = 9.5826;

/// Rayleigh scattering cross-section of molecular hydrogen at `nm` nanometres, m²: Dalgarno &
/// Williams, "Rayleigh Scattering by Molecular Hydrogen", ApJ 136, 690 (1962),
/// `σ = 8.14·10⁻¹³/λ⁴ + 1.28·10⁻⁶/λ⁶ + 1.61/λ⁸` cm² with λ in ångströms.
pub fn h2_rayleigh_cross_section(nm: f64) -> f64 {
    let angstrom = nm * 10.0;
    let l2 = angstrom * angstrom;
    let cm2 = 8.14e-13 / (l2 * l2) + 1.28e-6 / (l2 * l2 * l2) + 1.61 / (l2 * l2 * l2 * l2);
    cm2 * 1e-4
}

/// Saturn above its visible cloud deck, the surface being the 1-bar level:
/// - shape: equatorial radius 60268 km, polar 54364 km at 1 bar, flattening 0.098 (Archinal et
///   al., "Report of the IAU Working Group on Cartographic Coordinates and Rotational Elements:
///   2015", Celest. Mech. Dyn. Astr. 130, 2018; NASA Saturn Fact Sheet);
/// - H₂ Rayleigh scattering: the number density at 1 bar and 134 K (NASA Saturn Fact Sheet),
///   `n = p/(k_B·T) = 5.41·10²⁵ m⁻³`, times the H₂ mole fraction 0.963 (same sheet) and
///   [`h2_rayleigh_cross_section`] — (2.05, 4.88, 12.28)·10⁻⁶ m⁻¹ at 680/550/440 nm; helium
///   (3.25 %, polarisability a quarter of H₂'s) would add under 0.3 % and is left out; scale
///   height 59.5 km (NASA Saturn Fact Sheet);
/// - no aerosols or absorbing gas: the upper-tropospheric haze and methane bands are left out;
/// - top of the atmosphere 600 km above the 1-bar level (about ten scale heights);
/// - ground albedo (0.55, 0.45, 0.30) at 680/550/440 nm: a stand-in for the ammonia cloud deck,
///   near Saturn's visual geometric albedo 0.47 (NASA Saturn Fact Sheet) and reddened towards
///   the blue as the globe's spectrum is (Mallama & Pavlov, "The Geometric Magnitude and Albedo
///   for the Globe of Saturn", arXiv:1701.00256, 2017, from Karkoschka, Icarus 133, 1998);
///   approximate, not a measured Lambert albedo.
pub fn saturn() -> Atmosphere {
    // Boltzmann constant, J/K (SI 2019, exact).
    const BOLTZMANN: f64 = 1.380_649e-23;
    let wavelengths = Wavelengths::default();
    let h2_number_density = 0.963 * 1.0e5 / (BOLTZMANN * 134.0);
    let rayleigh = Spectrum::from_array(
        wavelengths
            .0
            .map(|nm| h2_number_density * h2_rayleigh_cross_section(nm)),
    );
    Atmosphere {
        planet: Planet::spheroid(60_268_000.0, 54_364_000.0, 600_000.0).with_geometric_albedo(SATURN_GEOMETRIC_ALBEDO),
        medium: Medium::from_constituents(
            &Constituents {
                rayleigh: Rayleigh {
                    scattering: rayleigh,
                    density: DensityProfile::single(DensityLayer::exponential(59_500.0)),
                },
                mie: Mie {
                    scattering: Spectrum::ZERO,
                    extinction: Spectrum::ZERO,
                    density: DensityProfile::single(DensityLayer::EMPTY),
                    phase: Phase::HenyeyGreenstein { g: 0.0 },
                },
                absorber: Absorber {
                    absorption: Spectrum::ZERO,
                    density: DensityProfile::single(DensityLayer::EMPTY),
                },
            },
            Spectrum::new(0.55, 0.45, 0.30),
        ),
        wavelengths,
    }
}

/// The Sun seen from Saturn: Earth's solar irradiance divided by Saturn's mean distance squared
/// (about 1/91.8), and the angular radius divided by that distance.
pub fn saturn_sun(direction: DVec3) -> Sun {
    sun_at(direction, SATURN_SEMI_MAJOR_AXIS_AU)
}

/// A density table of a preset's constant `(altitude m, density)` pairs, `name` naming it; every
/// preset's tables are checked by the test `presets_are_valid`.
fn density_table(name: &str, pairs: &[(f64, f64)]) -> Density {
    Density::Table(DensityTable::new(name, pairs).expect("a preset's density table is valid"))
}

/// The integral of a table of `(altitude m, density)` pairs, linear between them: the column it
/// spreads a term over, m.
fn table_integral(pairs: &[(f64, f64)]) -> f64 {
    pairs
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::MediumTerm;

    #[test]
    fn presets_are_valid() {
        // Venus' and Titan's tables are made (`expect`) when their presets are.
        for atmosphere in [earth(), mars(), saturn(), venus(), titan()] {
            atmosphere.validate().unwrap();
        }
        for sun in [earth_sun, mars_sun, saturn_sun, venus_sun, titan_sun] {
            sun(DVec3::Z).validate().unwrap();
        }
        assert!((earth().planet.flattening() - 1.0 / 298.257_223_563).abs() < 1e-12);
    }

    #[test]
    fn saturn_matches_its_sources() {
        let saturn = saturn();
        // Flattening 0.098 (NASA Saturn Fact Sheet: 0.09796).
        assert!((saturn.planet.flattening() - 0.09796).abs() < 1e-4);
        // H₂ cross-section at 550 nm from Dalgarno & Williams, worked by hand: 9.38e-32 m².
        assert!((h2_rayleigh_cross_section(550.0) / 9.377e-32 - 1.0).abs() < 1e-3);
        // Rayleigh coefficients as documented, and blue-heavy like any Rayleigh atmosphere.
        let rayleigh = saturn.medium.terms[0].scattering;
        for (got, want) in rayleigh.to_array().into_iter().zip([2.051e-6, 4.881e-6, 12.28e-6]) {
            assert!((got / want - 1.0).abs() < 5e-3, "{rayleigh}");
        }
        // Vertical optical depth above 1 bar at 550 nm: σ·H ≈ 0.290.
        assert!((rayleigh.y * 59_500.0 - 0.290).abs() < 2e-3);
        // The Sun at 9.58 AU: irradiance 1/91.8 of Earth's.
        let ratio = earth_sun(DVec3::Z).irradiance.y / saturn_sun(DVec3::Z).irradiance.y;
        assert!((ratio - 91.83).abs() < 0.01, "{ratio}");
    }

    /// The vertical optical depth of `terms` from the ground to `top` metres: the extinction of
    /// [`Medium::at`] by the midpoint rule in 1 m steps.
    fn vertical_optical_depth(terms: &[MediumTerm], top: f64) -> Spectrum {
        let medium = Medium {
            terms: terms.to_vec(),
            ground_albedo: Spectrum::ZERO,
        };
        let steps = top as usize;
        (0..steps)
            .map(|i| medium.at(i as f64 + 0.5).extinction)
            .sum::<Spectrum>()
            * (top / steps as f64)
    }

    fn within(got: Spectrum, want: [f64; 3], tolerance: f64) -> bool {
        got.to_array()
            .iter()
            .zip(want)
            .all(|(g, w)| (g / w - 1.0).abs() <= tolerance)
    }

    #[test]
    fn venus_matches_its_sources() {
        let venus = venus();
        let top = venus.planet.atmosphere_height;
        assert_eq!(venus.planet.radii, DVec3::splat(6_051_800.0));
        assert_eq!(top, 100_000.0);
        let terms = &venus.medium.terms;
        assert_eq!(terms.len(), 6);
        // The gas: the column of VIRA (Seiff et al. 1985) times CO₂'s cross-section, τ_R = 6.9 /
        // 16.4 / 41.2 from 1.44·10³¹ m⁻² (the research note's hydrostatic column).
        let gas = vertical_optical_depth(&terms[..1], top);
        assert!(within(gas, [6.9, 16.4, 41.2], 0.03), "{gas}");
        // Its surface coefficient, an extinction length of ~1 km at 550 nm.
        assert!(within(terms[0].scattering, [4.35e-4, 1.034e-3, 2.60e-3], 0.005));
        // Cloud and haze: Titov et al. 2018's layer midpoints 0.6 + 7 + 9 + 9 and Crisp's 0.24,
        // grey.
        let clouds = vertical_optical_depth(&terms[1..5], top);
        assert!(within(clouds, [25.84; 3], 0.03), "{clouds}");
        for (term, tau) in terms[1..5].iter().zip([0.6, 7.0, 18.0, 0.24]) {
            let one = vertical_optical_depth(std::slice::from_ref(term), top);
            assert!(within(one, [tau; 3], 0.01), "{one} against {tau}");
            assert_eq!(term.absorption, Spectrum::ZERO);
        }
        // Nothing of the cloud below 30.5 km or above 100 km; the lower cloud twice as dense as
        // the middle one.
        let local = |h: f64| {
            Medium {
                terms: terms[1..5].to_vec(),
                ground_albedo: Spectrum::ZERO,
            }
            .at(h)
        };
        assert_eq!(local(30_000.0).extinction, Spectrum::ZERO);
        assert!((local(49_000.0).extinction.y / local(53_000.0).extinction.y - 2.0).abs() < 1e-12);
        // The UV absorber: 0.015 / 0.026 / 0.067 (Haus et al.'s profile and cross-section).
        let uv = vertical_optical_depth(&terms[5..], top);
        assert!(within(uv, [0.015, 0.026, 0.067], 0.03), "{uv}");
        // The Sun at 0.723 AU: 1.911 times Earth's irradiance, a disc 0.737° across.
        let ratio = venus_sun(DVec3::Z).irradiance.y / earth_sun(DVec3::Z).irradiance.y;
        assert!((ratio - 1.9113).abs() < 1e-3, "{ratio}");
        assert!((2.0 * venus_sun(DVec3::Z).angular_radius.to_degrees() - 0.7406).abs() < 1e-3);
    }

    #[test]
    fn titan_matches_its_sources() {
        let titan = titan();
        let top = titan.planet.atmosphere_height;
        assert_eq!(titan.planet.radii, DVec3::splat(2_574_700.0));
        assert_eq!(top, 600_000.0);
        let terms = &titan.medium.terms;
        assert_eq!(terms.len(), 5);
        // The haze: Tomasko et al. 2008's three-region fit, 5.59 / 8.11 / 12.17 in all.
        let haze = vertical_optical_depth(&terms[2..], top);
        assert!(within(haze, [5.59, 8.11, 12.17], 0.03), "{haze}");
        // Region by region: 1.12 / 1.37 / 1.70 below 30 km, 2.07 / 2.79 / 3.83 at 30–80 km,
        // 2.40 / 3.94 / 6.64 above.
        for (term, tau) in terms[2..]
            .iter()
            .zip([[1.12, 1.37, 1.70], [2.07, 2.79, 3.83], [2.40, 3.94, 6.64]])
        {
            let one = vertical_optical_depth(std::slice::from_ref(term), top);
            assert!(within(one, tau, 0.01), "{one} against {tau:?}");
        }
        // Its single-scattering albedo above 80 km, and the phase function's mean cosine (0.783
        // from Tomasko et al.'s table at 599.9 nm).
        let albedo = terms[4].scattering / terms[4].extinction();
        assert!(within(albedo, [0.957, 0.933, 0.869], 1e-9), "{albedo}");
        assert!((terms[2].phase.g() - 0.783).abs() < 0.01, "{}", terms[2].phase.g());
        // The gas: the hydrostatic column p/(μ·m_u·g) = 2.39·10³⁰ m⁻² at 1467 hPa (Fulchignoni et
        // al. 2005) times the N₂–CH₄ cross-section.
        let gas = vertical_optical_depth(&terms[..1], top);
        assert!(within(gas, [0.51, 1.22, 3.04], 0.05), "{gas}");
        // Methane at 680 nm: 0.0965 per km-amagat (Karkoschka 1998) over ~3.2 km-amagat, 0.31.
        let methane = vertical_optical_depth(&terms[1..2], top);
        assert!((methane.x / 0.31 - 1.0).abs() < 0.07, "{methane}");
        assert_eq!([methane.y, methane.z], [0.0, 0.0]);
        // The Sun at Saturn's distance: 1/91.8 of Earth's irradiance.
        let ratio = earth_sun(DVec3::Z).irradiance.y / titan_sun(DVec3::Z).irradiance.y;
        assert!((ratio - 91.83).abs() < 0.01, "{ratio}");
    }
}
