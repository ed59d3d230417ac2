//! Titan: 1.47 bar of nitrogen and methane under an orange, forward-scattering, absorbing haze
//! of optical depth ~8, as the Huygens probe saw it in January 2005.
//!
//! Where a number was read decides how it is cited: a paper's own abstract or record is cited
//! plainly; "as transcribed in `file`" means it was read in a file of the public repository
//! `Nicholaswogan/SolarSystemExploration` (`input/Titan/`), not in the paper, and is still to be
//! checked against it; "derived" means worked out here from the cited numbers; "estimate" means no
//! measurement pins it. docs/ATMOSPHERE.md, "Venus and Titan", has the terms as tables.

use glam::DVec3;

use super::venus::N2_CROSS_SECTION;
use super::{density_table, table_integral};
use crate::atmosphere::medium::{Medium, MediumTerm, Phase, PhaseTable};
use crate::atmosphere::spectrum::{Spectrum, Wavelengths};
use crate::atmosphere::{Atmosphere, Planet, Sun};

/// Titan's mean radius, m (Zebker et al., "Size and shape of Saturn's moon Titan", Science 324,
/// 921, 2009: 2574.73 ± 0.09 km).
const RADIUS: f64 = 2_574_700.0;

/// Top of the model atmosphere above the surface, m: the gas is 1.3·10⁻⁷ of its surface density
/// there and the haze above 500 km has a vertical optical depth of ~4·10⁻⁴ at 550 nm. An estimate.
const ATMOSPHERE_HEIGHT: f64 = 600_000.0;

/// CH₄'s Rayleigh cross-sections at 680/550/440 nm, m², derived from Sneep & Ubachs' formula
/// (JQSRT 92, 293, 2005) with their CH₄ refractive index `(n − 1)·10⁸ = 46662 + 4.02·10⁻⁶ ν²` (ν
/// in cm⁻¹) and King factor 1, as printed in public codes. N₂'s are Venus' (`venus.rs`).
const CH4_CROSS_SECTION: [f64; 3] = [5.387e-31, 1.283e-30, 3.231e-30];

/// The gas' number density relative to the surface's, by altitude (m): the recommended density
/// of the Titan engineering model of Waite et al. (2013; the model file in Wogan's repository,
/// whose publication was not checked), normalised at 0 km — derived.
const GAS_PROFILE: [(f64, f64); 22] = [
    (0.0, 1.0),
    (5_000.0, 0.8185),
    (10_000.0, 0.6532),
    (15_000.0, 0.5162),
    (20_000.0, 0.4033),
    (25_000.0, 0.3107),
    (30_000.0, 0.2356),
    (40_000.0, 0.1267),
    (50_000.0, 0.06561),
    (60_000.0, 0.03059),
    (70_000.0, 0.0143),
    (80_000.0, 0.009098),
    (100_000.0, 0.00429),
    (120_000.0, 0.002245),
    (140_000.0, 0.001238),
    (160_000.0, 7.139e-4),
    (200_000.0, 2.614e-4),
    (250_000.0, 8.347e-5),
    (300_000.0, 2.984e-5),
    (400_000.0, 4.594e-6),
    (500_000.0, 7.544e-7),
    (600_000.0, 1.299e-7),
];

/// CH₄'s number density relative to the surface's, by altitude (m): the same model's density
/// times its CH₄ mole fraction (5.65 % at the surface, 1.48 % in the stratosphere: Niemann et al.,
/// JGR 115, E12006, 2010, through Hörst 2017), normalised at 0 km — derived.
const METHANE_PROFILE: [(f64, f64); 15] = [
    (0.0, 1.0),
    (5_000.0, 0.7925),
    (10_000.0, 0.4688),
    (15_000.0, 0.264),
    (20_000.0, 0.165),
    (25_000.0, 0.1058),
    (30_000.0, 0.07105),
    (40_000.0, 0.03352),
    (50_000.0, 0.01713),
    (60_000.0, 0.007985),
    (80_000.0, 0.002375),
    (100_000.0, 0.00112),
    (150_000.0, 2.446e-4),
    (200_000.0, 6.82e-5),
    (300_000.0, 7.8e-6),
];

/// The haze below 30 km, relative density by altitude (m): uniform, with a 4 km ramp centred on
/// 30 km (the column is 30 km).
const LOW_HAZE_PROFILE: [(f64, f64); 3] = [(0.0, 1.0), (28_000.0, 1.0), (32_000.0, 0.0)];

/// The haze between 30 and 80 km, relative density by altitude (m): uniform, ramps centred on
/// the edges and complementary to the terms below and above (the column is 50 km).
const MIDDLE_HAZE_PROFILE: [(f64, f64); 5] = [
    (0.0, 0.0),
    (28_000.0, 0.0),
    (32_000.0, 1.0),
    (78_000.0, 1.0),
    (82_000.0, 0.0),
];

/// The haze above 80 km, relative density by altitude (m): exponential with a 65 km scale height
/// up to ~140 km and 45 km above (Doose et al., "Vertical structure and optical properties of
/// Titan's aerosols from radiance measurements made inside and outside the atmosphere", Icarus 270,
/// 355, 2016; Bazzon et al., A&A 572, A6, 2014, eqs. A.11–A.13, read through a third party) —
/// derived.
const HIGH_HAZE_PROFILE: [(f64, f64); 17] = [
    (0.0, 0.0),
    (78_000.0, 0.0),
    (82_000.0, 0.94),
    (90_000.0, 0.8574),
    (100_000.0, 0.7351),
    (110_000.0, 0.6303),
    (120_000.0, 0.5404),
    (140_000.0, 0.3973),
    (160_000.0, 0.2547),
    (180_000.0, 0.1633),
    (200_000.0, 0.1047),
    (250_000.0, 0.03447),
    (300_000.0, 0.01135),
    (350_000.0, 0.003736),
    (400_000.0, 0.00123),
    (500_000.0, 1.333e-4),
    (600_000.0, 1.44e-5),
];

/// The haze's phase function at 599.9 nm, (scattering angle °, value): Tomasko et al., "A model
/// of Titan's aerosols based on measurements made inside the atmosphere", PSS 56, 669 (2008),
/// Table 1a, as transcribed in `Tomasko2008_PhaseFunction.txt` (4π-normalised; normalised again on
/// load). A strong forward peak, P(0°) ≈ 360, backscatter P(180°) ≈ 0.21, mean cosine 0.78.
const HAZE_PHASE: [(f64, f64); 30] = [
    (0.0, 362.8),
    (1.0, 325.1),
    (2.0, 239.9),
    (3.0, 156.7),
    (4.0, 99.13),
    (5.0, 64.74),
    (6.0, 44.54),
    (7.0, 32.2),
    (8.0, 24.26),
    (10.0, 14.5),
    (15.0, 7.413),
    (20.0, 4.414),
    (30.0, 1.857),
    (40.0, 0.9414),
    (50.0, 0.5495),
    (60.0, 0.3582),
    (70.0, 0.2564),
    (80.0, 0.1996),
    (90.0, 0.1679),
    (100.0, 0.1515),
    (110.0, 0.1454),
    (120.0, 0.1466),
    (130.0, 0.1534),
    (140.0, 0.1643),
    (150.0, 0.1774),
    (160.0, 0.1902),
    (170.0, 0.1998),
    (175.0, 0.204),
    (178.0, 0.2079),
    (180.0, 0.2092),
];

/// One region of Tomasko et al. 2008's haze: vertical optical depth `coefficient·λ^−exponent`
/// (λ in nm), single-scattering albedo at 680/550/440 nm, and the profile it is spread over.
struct HazeRegion {
    name: &'static str,
    coefficient: f64,
    exponent: f64,
    albedo: [f64; 3],
    profile: &'static [(f64, f64)],
}

/// The three regions of Tomasko et al. 2008's fit (PSS 56, 669; the coefficients as transcribed in
/// two independent codes, Ádámkovics's and Wogan's, and through a third party in Bazzon et al.
/// 2014, App. A.4), with their single-scattering albedos from Tomasko et al. 2008, Table 2, as
/// transcribed in `Tomasko2008_w0.txt`, interpolated to the model wavelengths; above 80 km the
/// optical-depth-weighted mean of the 80 km and 144 km values — derived.
const HAZE: [HazeRegion; 3] = [
    HazeRegion {
        name: "titan haze below 30 km",
        coefficient: 627.0,
        exponent: 0.9706,
        albedo: [0.970, 0.956, 0.929],
        profile: &LOW_HAZE_PROFILE,
    },
    HazeRegion {
        name: "titan haze 30-80 km",
        coefficient: 2.029e4,
        exponent: 1.409,
        albedo: [0.990, 0.967, 0.928],
        profile: &MIDDLE_HAZE_PROFILE,
    },
    HazeRegion {
        name: "titan haze above 80 km",
        coefficient: 1.012e7,
        exponent: 2.339,
        albedo: [0.957, 0.933, 0.869],
        profile: &HIGH_HAZE_PROFILE,
    },
];

/// Titan at the Huygens landing site (10° S, January 2005), from published measurements (the
/// tags: see the module's head):
/// - shape: a sphere of radius 2 574 700 m (Zebker et al., Science 324, 921, 2009); top of the
///   atmosphere 600 km above the surface (an estimate);
/// - gas, 94.35 % N₂ and 5.65 % CH₄ at the surface (Niemann et al., JGR 115, E12006, 2010, read
///   through Hörst, "Titan's atmosphere and climate", JGR Planets 122, 432, 2017): Rayleigh
///   scattering `n₀·σ` with `n₀ = p/(k_B·T) = 1.135·10²⁶ m⁻³` at 1467 hPa and 93.65 K
///   (Fulchignoni et al., "In situ measurements of the physical characteristics of Titan's
///   environment", Nature 438, 785, 2005) and the cross-sections of Sneep & Ubachs' formula
///   (JQSRT 92, 293, 2005) — (2.44, 5.78, 14.4)·10⁻⁵ m⁻¹ at 680/550/440 nm, derived; density by
///   the Titan engineering model of Waite et al. 2013 (as transcribed in Wogan's repository),
///   derived; vertical optical depth 0.50 / 1.18 / 2.96 (the hydrostatic column, 2.39·10³⁰ m⁻²,
///   gives 0.51 / 1.22 / 3.04);
/// - CH₄ absorption at 680 nm only: Karkoschka ("Methane, ammonia, and temperature measurements
///   of the Jovian planets and Titan from CCD-spectrophotometry", Icarus 133, 134, 1998)'s
///   coefficient 0.0965 (km-amagat)⁻¹ averaged over 680 ± 25 nm (read through a third party)
///   times the CH₄ density, 2.3·10⁻⁵ m⁻¹ at the surface, vertical optical depth 0.29 — derived;
///   the weak bands at 550 and 440 nm are left out (not quantified);
/// - three haze terms, the regions of Tomasko et al. 2008 (PSS 56, 669): vertical optical depth
///   `627.0·λ^−0.9706` below 30 km, `2.029·10⁴·λ^−1.409` at 30–80 km and `1.012·10⁷·λ^−2.339`
///   above (λ in nm) — 5.59 / 8.11 / 12.17 in all at 680/550/440 nm — each spread over its
///   profile (uniform below 80 km, exponential above: Doose et al., Icarus 270, 355, 2016), with
///   single-scattering albedos 0.970 / 0.956 / 0.929, 0.990 / 0.967 / 0.928 and 0.957 / 0.933 /
///   0.869 (Tomasko et al. 2008, Table 2, as transcribed) and the phase function of their
///   Table 1a at 599.9 nm (as transcribed) for all three; the blue is the least certain channel
///   (DISR constrains ω and the phase function poorly below 490 nm: García Muñoz et al., Nature
///   Astron. 1, 0114, 2017, read through a third party);
/// - ground albedo 0.20 / 0.15 / 0.10 at 680/550/440 nm: the red slope Schröder & Keller ("The
///   reflectance spectrum of Titan's surface at the Huygens landing site determined by the
///   Descent Imager/Spectral Radiometer", PSS 56, 753, 2008) report, scaled to the 0.2 at 938 nm
///   Bazzon et al. 2014 assume — an estimate.
///
/// About 12 % of the sunlight reaching the top of the atmosphere is absorbed at the ground in the
/// global mean (Tomasko et al., "Heat balance in Titan's atmosphere", PSS 56, 648, 2008, Fig. 3,
/// as transcribed in `Tomasko2008Solar.txt` — derived).
pub fn titan() -> Atmosphere {
    // Boltzmann constant, J/K (SI 2019, exact); Loschmidt's number at 273.15 K and 101.325 kPa,
    // m⁻³ (CODATA 2018), the amagat.
    const BOLTZMANN: f64 = 1.380_649e-23;
    const LOSCHMIDT: f64 = 2.686_780_1e25;
    const METHANE_FRACTION: f64 = 0.0565;
    let wavelengths = Wavelengths::default();
    let surface_number_density = 1467.0e2 / (BOLTZMANN * 93.65);
    let gas_cross_section: [f64; 3] = std::array::from_fn(|i| {
        (1.0 - METHANE_FRACTION) * N2_CROSS_SECTION[i] + METHANE_FRACTION * CH4_CROSS_SECTION[i]
    });
    // Karkoschka's 0.0965 per km-amagat, per metre at the surface's CH₄ density.
    let methane_absorption = 0.0965e-3 * METHANE_FRACTION * surface_number_density / LOSCHMIDT;
    let phase = Phase::Table(PhaseTable::new("titan haze phase", &HAZE_PHASE).expect("titan haze phase is valid"));
    let haze = HAZE.iter().map(|region| {
        let extinction = Spectrum::from_array(
            wavelengths
                .0
                .map(|nm| region.coefficient * nm.powf(-region.exponent) / table_integral(region.profile)),
        );
        let albedo = Spectrum::from_array(region.albedo);
        MediumTerm {
            scattering: extinction * albedo,
            absorption: extinction * (Spectrum::ONE - albedo),
            density: density_table(region.name, region.profile),
            phase: phase.clone(),
        }
    });
    let mut terms = vec![
        MediumTerm {
            scattering: Spectrum::from_array(gas_cross_section) * surface_number_density,
            absorption: Spectrum::ZERO,
            density: density_table("titan gas", &GAS_PROFILE),
            phase: Phase::Rayleigh,
        },
        MediumTerm {
            scattering: Spectrum::ZERO,
            absorption: Spectrum::new(methane_absorption, 0.0, 0.0),
            density: density_table("titan methane", &METHANE_PROFILE),
            phase: Phase::Rayleigh,
        },
    ];
    terms.extend(haze);
    Atmosphere {
        // Geometric albedo 0.22 (NASA Saturnian Satellite Fact Sheet): the light it casts on bodies.
        planet: Planet::sphere(RADIUS, ATMOSPHERE_HEIGHT).with_geometric_albedo(0.22),
        medium: Medium {
            terms,
            ground_albedo: Spectrum::new(0.20, 0.15, 0.10),
        },
        wavelengths,
    }
}

/// The Sun seen from Titan, which orbits Saturn: Earth's solar irradiance divided by Saturn's
/// mean distance squared (about 1/91.8), and the angular radius divided by that distance.
pub fn titan_sun(direction: DVec3) -> Sun {
    super::saturn_sun(direction)
}
