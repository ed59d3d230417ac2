//! Venus: a CO₂ atmosphere of 92 bar under a sulphuric-acid cloud deck of optical depth ~26.
//!
//! Where a number was read decides how it is cited: a paper's own abstract or record is cited
//! plainly; "as transcribed in `file`" means it was read in a file of the public repository
//! `Nicholaswogan/SolarSystemExploration` (`input/Venus/`), not in the paper, and is still to be
//! checked against it; "derived" means worked out here from the cited numbers; "estimate" means no
//! measurement pins it. docs/ATMOSPHERE.md, "Venus and Titan", has the terms as tables.

use glam::DVec3;

use super::{density_table, table_integral};
use crate::atmosphere::medium::{Medium, MediumTerm, Phase};
use crate::atmosphere::spectrum::{Spectrum, Wavelengths};
use crate::atmosphere::{Atmosphere, Planet, Sun};

/// Venus' mean distance from the Sun, AU (NASA Venus Fact Sheet, Williams 2024: 108.21·10⁶ km).
pub const VENUS_SEMI_MAJOR_AXIS_AU: f64 = 0.723_332;

/// Venus' mean radius, m (NASA Venus Fact Sheet; Archinal et al., "Report of the IAU Working
/// Group on Cartographic Coordinates and Rotational Elements: 2015", Celest. Mech. Dyn. Astr. 130,
/// 2018: 6051.8 km).
const RADIUS: f64 = 6_051_800.0;

/// Top of the model atmosphere above the surface, m: where the VIRA tables end (Seiff et al.
/// 1985, below); the haze reaches ~100–110 km (Titov et al. 2018). An estimate.
const ATMOSPHERE_HEIGHT: f64 = 100_000.0;

/// Rayleigh cross-sections at 680/550/440 nm, m², derived from the formula of Sneep & Ubachs,
/// "Direct measurement of the Rayleigh scattering cross section in various gases", JQSRT 92, 293
/// (2005) — with Bideau-Mehu et al. (Opt. Commun. 9, 432, 1973)'s CO₂ refractive index and
/// King factor `1.1364 + 25.3·10⁻¹² ν²` (ν in cm⁻¹) as Sneep & Ubachs print them, and the N₂
/// values of Peck & Khanna (JOSA 56, 1059, 1966) and Bates (PSS 32, 785, 1984) as public codes
/// print them (both transcribed, not read in the papers). He et al. (ACP 21, 14927, 2021)
/// validate the formula for CO₂ to ≲ 1 % over 307–725 nm.
const CO2_CROSS_SECTION: [f64; 3] = [4.895e-31, 1.164e-30, 2.923e-30];
/// N₂, as [`CO2_CROSS_SECTION`], m².
pub(super) const N2_CROSS_SECTION: [f64; 3] = [1.958e-31, 4.635e-31, 1.156e-30];

/// The gas' number density relative to the surface's, by altitude (m): VIRA's pressure over
/// temperature (Seiff et al., "Models of the structure of the atmosphere of Venus from the surface
/// to 100 kilometers altitude", Adv. Space Res. 5(11), 3, 1985; the 45° table as transcribed in
/// `venus_seiff1985.txt`), normalised at 0 km — derived.
const GAS_PROFILE: [(f64, f64); 22] = [
    (0.0, 1.0),
    (5_000.0, 0.7637),
    (10_000.0, 0.5748),
    (15_000.0, 0.4249),
    (20_000.0, 0.3096),
    (25_000.0, 0.2211),
    (30_000.0, 0.1539),
    (35_000.0, 0.1038),
    (40_000.0, 0.06716),
    (45_000.0, 0.04117),
    (50_000.0, 0.02413),
    (55_000.0, 0.01392),
    (60_000.0, 0.007215),
    (64_000.0, 0.003635),
    (68_000.0, 0.00175),
    (72_000.0, 8.17e-4),
    (76_000.0, 3.74e-4),
    (80_000.0, 1.69e-4),
    (84_000.0, 7.19e-5),
    (88_000.0, 2.86e-5),
    (90_000.0, 1.75e-5),
    (100_000.0, 1.27e-6),
];

/// The upper haze, relative density by altitude (m): 1 at 70 km falling with a ~4 km scale
/// height to 90 km, over Titov et al. 2018's 70–90 km (below) — derived.
const UPPER_HAZE_PROFILE: [(f64, f64); 8] = [
    (0.0, 0.0),
    (69_500.0, 0.0),
    (70_000.0, 1.0),
    (75_000.0, 0.287),
    (80_000.0, 0.048),
    (85_000.0, 0.0081),
    (90_000.0, 0.001_35),
    (100_000.0, 0.0),
];

/// The upper cloud, 56.5–70 km, relative density by altitude (m); each edge is a 500 m ramp
/// centred on it, so the column is the layer's thickness (13.5 km).
const UPPER_CLOUD_PROFILE: [(f64, f64); 5] = [
    (0.0, 0.0),
    (56_250.0, 0.0),
    (56_750.0, 1.0),
    (69_750.0, 1.0),
    (70_250.0, 0.0),
];

/// The middle (50.5–56.5 km) and lower (47.5–50.5 km) clouds as one term, relative density by
/// altitude (m): 2 in the lower cloud, which is as thick in optical depth in half the height, 1
/// in the middle; ramps centred on the edges, so the column is 2·3 km + 6 km = 12 km.
const MIDDLE_LOWER_CLOUD_PROFILE: [(f64, f64); 7] = [
    (0.0, 0.0),
    (47_250.0, 0.0),
    (47_750.0, 2.0),
    (50_450.0, 2.0),
    (50_550.0, 1.0),
    (56_250.0, 1.0),
    (56_750.0, 0.0),
];

/// The lower haze, 31–47.5 km, relative density by altitude (m), ramps centred on the edges
/// (column 16.5 km).
const LOWER_HAZE_PROFILE: [(f64, f64); 5] = [
    (0.0, 0.0),
    (30_750.0, 0.0),
    (31_250.0, 1.0),
    (47_250.0, 1.0),
    (47_750.0, 0.0),
];

/// The unknown UV absorber, relative density by altitude (m): the "low" mixing-ratio profile of
/// Haus et al. (2015; "Radiative energy balance of Venus based on improved models of the middle and
/// lower atmosphere", Icarus 272, 178, 2016) as transcribed in `venus_haus_uv.cld`, times the
/// gas density, normalised at its peak — derived.
const UV_ABSORBER_PROFILE: [(f64, f64); 13] = [
    (0.0, 0.0),
    (48_400.0, 0.0),
    (52_400.0, 0.008),
    (54_400.0, 0.034),
    (56_400.0, 0.232),
    (58_500.0, 0.996),
    (62_500.0, 1.0),
    (64_500.0, 0.612),
    (66_500.0, 0.098),
    (68_500.0, 0.014),
    (70_500.0, 0.0016),
    (78_600.0, 8e-4),
    (80_600.0, 0.0),
];

/// Venus at low latitudes, from published measurements (the tags: see the module's head):
/// - shape: a sphere of radius 6 051 800 m (NASA Venus Fact Sheet; Archinal et al. 2018, Celest.
///   Mech. Dyn. Astr. 130); top of the atmosphere 100 km above the surface (where the VIRA tables
///   end; an estimate);
/// - gas, 96.5 % CO₂ and 3.5 % N₂ (von Zahn et al. 1983, read through a third party): Rayleigh
///   scattering `n₀·σ` with `n₀ = p/(k_B·T) = 9.07·10²⁶ m⁻³` at VIRA's 92.10 bar and 735.3 K at
///   0 km (Seiff et al., Adv. Space Res. 5(11), 3, 1985, as transcribed in `venus_seiff1985.txt`)
///   and the cross-sections of Sneep & Ubachs' formula (JQSRT 92, 293, 2005) — (0.435, 1.034,
///   2.60)·10⁻³ m⁻¹ at 680/550/440 nm, derived; density VIRA's p/T by altitude, derived; vertical
///   optical depth 7.0 / 16.6 / 41.7 (an extinction length of ~1 km at the surface);
/// - four grey cloud and haze terms of H₂SO₄ drops, scattering without absorbing (pure 75 %
///   H₂SO₄ has ω = 1.0000 in the visible in the Mie tables transcribed in `venus_h2so4_m*.mie`,
///   and its extinction varies ≤ 5 % over 440–680 nm — derived), with vertical optical depths
///   the midpoints of Titov et al., "Clouds and hazes of Venus", Space Sci. Rev. 214, 126 (2018),
///   Table 1 (from Esposito et al. 1983 and Knollenberg & Hunten 1980; read through a third-party
///   note) at 0.63 µm: upper haze 70–90 km τ 0.6 (0.2–1.0), upper cloud 56.5–70 km τ 7 (6–8),
///   middle cloud 50.5–56.5 km τ 9 (8–10) with the lower cloud 47.5–50.5 km τ 9 (6–12), and the
///   lower haze 31–47.5 km τ 0.24 (Crisp, "Radiative forcing of the Venus mesosphere: I. Solar
///   fluxes and heating rates", Icarus 67, 484, 1986, as transcribed in `crisp_1986.cld`, with
///   pressure turned to altitude by VIRA — derived): 25.8 in all (Crisp's model gives 31, other
///   estimates 20–50). Each term's coefficient is its optical depth over its profile's column,
///   m⁻¹. Henyey–Greenstein phase functions with g 0.72, 0.73, 0.785 and 0.73: Mie asymmetry of
///   the drop modes (the tables in `venus_h2so4_m*.mie`) weighted by each layer's modes at
///   550 nm — derived;
/// - the unknown UV absorber of the upper cloud (Titov et al. 2018): absorption (1.84, 3.23,
///   8.29)·10⁻⁶ m⁻¹ at its peak at 58.5–62.5 km, vertical optical depth 0.015 / 0.026 / 0.067,
///   integrated from the mixing ratio and the fitted cross-section of Haus et al. (2015; Icarus
///   272, 178, 2016) as transcribed in `venus_haus_uv.cld` and `haus_uv_xsec_low.dat` — derived;
///   Hansen & Hovenier ("Interpretation of the polarization of Venus", J. Atmos. Sci. 31, 1137,
///   1974)'s single-scattering albedo fit, as transcribed by Bailey et al., gives 0.018 / 0.026
///   / 0.125 over a τ-25 cloud;
/// - ground albedo 0.10 grey: dark basalt "without significant color" in the visible (Pieters et
///   al., "The color of the surface of Venus", Science 234, 1379, 1986); the value is an
///   estimate.
///
/// About 2.6 % of the sunlight reaching the top of the atmosphere reaches the ground in the
/// global mean (Titov et al., "Radiation in the atmosphere of Venus", AGU Geophys. Monogr. 176,
/// 2007), reddened by the gas; the cloud deck hides the Sun's disc from the ground.
pub fn venus() -> Atmosphere {
    // Boltzmann constant, J/K (SI 2019, exact).
    const BOLTZMANN: f64 = 1.380_649e-23;
    let surface_number_density = 92.10e5 / (BOLTZMANN * 735.3);
    let gas_cross_section: [f64; 3] =
        std::array::from_fn(|i| 0.965 * CO2_CROSS_SECTION[i] + 0.035 * N2_CROSS_SECTION[i]);
    let gas = Spectrum::from_array(gas_cross_section) * surface_number_density;
    // A grey cloud term of vertical optical depth `tau` spread over `profile`.
    let cloud = |tau: f64, profile: &[(f64, f64)], name: &str, g: f64| MediumTerm {
        scattering: Spectrum::splat(tau / table_integral(profile)),
        absorption: Spectrum::ZERO,
        density: density_table(name, profile),
        phase: Phase::HenyeyGreenstein { g },
    };
    Atmosphere {
        // Geometric albedo 0.689 (NASA Venus Fact Sheet, Williams 2024): the light it casts on bodies.
        planet: Planet::sphere(RADIUS, ATMOSPHERE_HEIGHT).with_geometric_albedo(0.689),
        medium: Medium {
            terms: vec![
                MediumTerm {
                    scattering: gas,
                    absorption: Spectrum::ZERO,
                    density: density_table("venus gas", &GAS_PROFILE),
                    phase: Phase::Rayleigh,
                },
                cloud(0.6, &UPPER_HAZE_PROFILE, "venus upper haze", 0.72),
                cloud(7.0, &UPPER_CLOUD_PROFILE, "venus upper cloud", 0.73),
                cloud(18.0, &MIDDLE_LOWER_CLOUD_PROFILE, "venus middle and lower cloud", 0.785),
                cloud(0.24, &LOWER_HAZE_PROFILE, "venus lower haze", 0.73),
                MediumTerm {
                    scattering: Spectrum::ZERO,
                    absorption: Spectrum::new(1.84e-6, 3.23e-6, 8.29e-6),
                    density: density_table("venus UV absorber", &UV_ABSORBER_PROFILE),
                    phase: Phase::Rayleigh,
                },
            ],
            ground_albedo: Spectrum::splat(0.10),
        },
        wavelengths: Wavelengths::default(),
    }
}

/// The Sun seen from Venus: Earth's solar irradiance divided by Venus' mean distance squared
/// (1.911 times Earth's), and the angular radius divided by that distance.
pub fn venus_sun(direction: DVec3) -> Sun {
    super::sun_at(direction, VENUS_SEMI_MAJOR_AXIS_AU)
}
