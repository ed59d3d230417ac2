//! The medium's terms as the GPU reads them (`MediumTerm` and the tables of `AtmosphereParams`
//! in `shaders/atmosphere/bindings.wgsl`; read by `coefficients_at` and `scattering_phase` in
//! `atmosphere/common.wgsl`).
//!
//! Analytic profiles and phase functions go as their parameters. Tables are resampled: a density
//! table at [`DENSITY_TABLE_SAMPLES`] altitudes evenly spread from the ground to the top of the
//! atmosphere, a phase table at [`PHASE_TABLE_SAMPLES`] scattering angles evenly spread from 0°
//! to 180°; the GPU interpolates linearly between them.

use bytemuck::{Pod, Zeroable};
use firmament_core::atmosphere::medium::{Density, DensityLayer, DensityProfile, MAX_TERMS, MediumTerm, Phase};
use firmament_core::atmosphere::{Medium, Spectrum};

use super::codes;

/// The most terms the GPU reads (`MAX_MEDIUM_TERMS` in `bindings.wgsl`).
pub const MAX_MEDIUM_TERMS: usize = MAX_TERMS;
/// Altitudes a density table is resampled at, ground to top.
pub const DENSITY_TABLE_SAMPLES: usize = 128;
/// Scattering angles a phase table is resampled at, 0° to 180°.
pub const PHASE_TABLE_SAMPLES: usize = 256;

/// The largest share f of a term's scattering that multiple scattering sends straight on: the
/// delta-M forward peak (Wiscombe 1977) is a₅, the first Legendre coefficient past the four bands
/// the LUTs hold, but no more than this.
///
/// Delta-M assumes the light the peak scatters hardly changes over the peak's width. That holds
/// for Mars's dust, whose sky is smooth, but not for Earth's haze near the horizon, where a view
/// gets its forward-scattered light from half a lobe of bright sky and half a lobe of dark
/// ground; capping f at about half of Earth's a₅ keeps both within budget. The measurements and
/// what no single cap fits: docs/ATMOSPHERE.md, "Mie's forward peak (delta-M)" and "Not yet done".
pub const MIE_FORWARD_PEAK_MAX: f64 = 0.19;

/// The vertical scattering optical depth (at any model wavelength) from which an air is thick:
/// the orders of multiple scattering after the last marched one are solved by discrete
/// ordinates (`atmosphere/multiscattering_ordinates.wgsl`) rather than summed as a geometric series, and
/// the multiple-scattering LUTs span only the air that scatters ([`THICK_AIR_LUT_TOP_DEPTH`]).
/// Venus's 68 and Titan's 14 (at 440 nm) are thick; Earth's 0.27, Mars's 0.49 and Saturn's 0.73
/// are not, and render as before (docs/ATMOSPHERE.md, "Thick airs").
pub const THICK_AIR_DEPTH: f64 = 2.0;

/// In a thick air the multiple-scattering and sky-irradiance LUTs reach up to where the air
/// above scatters this vertical optical depth, not to the top: Titan's LUTs reach 385 km of its
/// 600 (its lowest 80 km, the haze, had four of the 32 rows), Venus's 83 km of 100.
pub const THICK_AIR_LUT_TOP_DEPTH: f64 = 0.01;

/// Whether `medium` up to `top` metres is a thick air ([`THICK_AIR_DEPTH`]).
pub fn is_thick_air(medium: &Medium, top: f64) -> bool {
    medium.vertical_scattering_depth(0.0, top).max_element() >= THICK_AIR_DEPTH
}

/// The height, metres, the multiple-scattering and sky-irradiance LUTs span for `medium` up to
/// `top`: `top` itself but in a thick air ([`THICK_AIR_LUT_TOP_DEPTH`]).
pub fn multiscattering_lut_height(medium: &Medium, top: f64, thick: bool) -> f64 {
    if thick {
        medium.altitude_of_scattering_depth(top, THICK_AIR_LUT_TOP_DEPTH).max(1.0)
    } else {
        top
    }
}

/// Rows of the multiple-scattering and sky-irradiance LUTs (`LUT_ROWS` in
/// `atmosphere/common.wgsl`).
pub const LUT_ROWS: usize = 32;

/// The share of evenly spread rows in a thick air's rows ([`multiscattering_lut_rows`]): it keeps
/// every row at least a tenth of the even spacing above the one below, even across air that
/// scatters nothing.
const EVEN_ROW_SHARE: f64 = 0.1;

/// The altitudes, metres, of the [`LUT_ROWS`] rows of a thick air's multiple-scattering and
/// sky-irradiance LUTs, from the ground to `height` ([`multiscattering_lut_height`]) of an air
/// `top` metres high.
///
/// A thick air's light changes most within its first optical depth from the top (where the
/// light scattered once peaks) and from a dark ground, which evenly spread rows step over: the
/// light scattered twice came out dark just below the top, and the solve for the later
/// orders started from it (docs/ATMOSPHERE.md, "Thick airs"). These rows are spread by the
/// vertical scattering depth from the top instead, in cosine steps (fine at both ends, ~π/2 times
/// the mean in the middle, where the light diffuses smoothly), blended with `EVEN_ROW_SHARE`
/// of even steps.
pub fn multiscattering_lut_rows(medium: &Medium, top: f64, height: f64) -> [f64; LUT_ROWS] {
    // The scattering depth from `top` down to each of `STEPS` + 1 altitudes evenly spread over
    // [0, height], at the wavelength that scatters most, by trapezoids.
    const STEPS: usize = 4096;
    let dh = height / STEPS as f64;
    let scattering = |h: f64| medium.at(h).scattering.iter().sum::<Spectrum>().max_element();
    let mut depth = vec![0.0; STEPS + 1];
    depth[STEPS] = medium.vertical_scattering_depth(height, top).max_element();
    for i in (0..STEPS).rev() {
        let (low, high) = (dh * i as f64, dh * (i + 1) as f64);
        depth[i] = depth[i + 1] + 0.5 * (scattering(low) + scattering(high)) * dh;
    }
    let (first, last) = (depth[STEPS], depth[0]);
    // The altitude at depth `d` from the top (depth falls as the index grows).
    let altitude_at = |d: f64| {
        let i = depth.partition_point(|&x| x > d).clamp(1, STEPS);
        let (above, below) = (depth[i], depth[i - 1]);
        let t = if below > above { (below - d) / (below - above) } else { 1.0 };
        dh * ((i - 1) as f64 + t.clamp(0.0, 1.0))
    };
    let last_row = (LUT_ROWS - 1) as f64;
    std::array::from_fn(|y| {
        let even = height * y as f64 / last_row;
        if y == 0 || y == LUT_ROWS - 1 {
            return even;
        }
        let from_top = (LUT_ROWS - 1 - y) as f64 / last_row;
        let d = first + (last - first) * 0.5 * (1.0 - (std::f64::consts::PI * from_top).cos());
        (1.0 - EVEN_ROW_SHARE) * altitude_at(d) + EVEN_ROW_SHARE * even
    })
}

/// Mirrors `DensityProfile` in `shaders/atmosphere/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct DensityProfileUniform {
    /// Layer 0: exp_term, exp_scale (m⁻¹), linear_term (m⁻¹), constant_term.
    pub layer0: [f32; 4],
    /// Layer 1, the same terms.
    pub layer1: [f32; 4],
    /// x = top of layer 0, metres.
    pub width: [f32; 4],
}

impl DensityProfileUniform {
    fn new(profile: &DensityProfile) -> Self {
        let terms = |l: &DensityLayer| {
            [
                l.exp_term as f32,
                l.exp_scale as f32,
                l.linear_term as f32,
                l.constant_term as f32,
            ]
        };
        Self {
            layer0: terms(&profile.layers[0]),
            layer1: terms(&profile.layers[1]),
            width: [profile.layers[0].width as f32, 0.0, 0.0, 0.0],
        }
    }
}

/// Mirrors `MediumTerm` in `shaders/atmosphere/bindings.wgsl`: one term of the medium.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct MediumTermUniform {
    /// rgb: extinction (scattering + absorption) at density 1, m⁻¹; w unused.
    pub extinction: [f32; 4],
    /// rgb: scattering at density 1, m⁻¹; w: the phase function's kind (a `PHASE_*`).
    pub scattering: [f32; 4],
    /// x: `g` (the forward lobe's for two lobes), y: the backward lobe's `g`, z: the forward
    /// lobe's weight; w: the share f of the scattering multiple scattering sends straight on
    /// (a₅, at most [`MIE_FORWARD_PEAK_MAX`], 0 when a₅ < 0; see `Coefficients` in
    /// `atmosphere/common.wgsl`).
    pub phase: [f32; 4],
    /// The phase function's Legendre coefficients a₁ … a₄ (`Phase::legendre_coefficient`).
    pub legendre: [f32; 4],
    /// The profile; all zeros (density 0) for a term whose density is a table.
    pub profile: DensityProfileUniform,
}

impl MediumTermUniform {
    /// The term as the GPU reads it; in a thick air ([`THICK_AIR_DEPTH`]) delta-M takes the
    /// whole forward peak a₅ rather than at most [`MIE_FORWARD_PEAK_MAX`].
    pub(super) fn new(term: &MediumTerm, thick: bool) -> Self {
        let spectrum = |s: Spectrum, w: u32| [s.x as f32, s.y as f32, s.z as f32, w as f32];
        let profile = match &term.density {
            Density::Profile(p) => DensityProfileUniform::new(p),
            Density::Table(_) => DensityProfileUniform::zeroed(),
        };
        let (phase_kind, lobes) = match &term.phase {
            Phase::Rayleigh => (codes::PHASE_RAYLEIGH, [0.0; 3]),
            Phase::CornetteShanks { g } => (codes::PHASE_CORNETTE_SHANKS, [*g, 0.0, 1.0]),
            Phase::HenyeyGreenstein { g } => (codes::PHASE_HENYEY_GREENSTEIN, [*g, 0.0, 1.0]),
            Phase::DualHenyeyGreenstein(d) => (codes::PHASE_DUAL_HENYEY_GREENSTEIN, [d.g_forward, d.g_back, d.blend]),
            Phase::Table(_) => (codes::PHASE_TABLE, [0.0; 3]),
        };
        let peak_max = if thick { 1.0 } else { MIE_FORWARD_PEAK_MAX };
        let forward_peak = term.phase.legendre_coefficient(5).clamp(0.0, peak_max);
        Self {
            extinction: spectrum(term.extinction(), 0),
            scattering: spectrum(term.scattering, phase_kind),
            phase: [lobes[0] as f32, lobes[1] as f32, lobes[2] as f32, forward_peak as f32],
            legendre: [1, 2, 3, 4].map(|l| term.phase.legendre_coefficient(l) as f32),
            profile,
        }
    }
}

/// The terms of `medium` (the first [`MAX_MEDIUM_TERMS`]), their count, which of them have tables,
/// and the resampled density and phase tables (row `i` for term `i`, four values per vector) of
/// an atmosphere `atmosphere_height` metres high.
pub(super) struct MediumGpu {
    pub(super) terms: [MediumTermUniform; MAX_MEDIUM_TERMS],
    pub(super) count: usize,
    pub(super) table_counts: [u32; 4],
    pub(super) density_table_terms: [[u32; 4]; MAX_MEDIUM_TERMS / 4],
    pub(super) phase_table_terms: [[u32; 4]; MAX_MEDIUM_TERMS / 4],
    pub(super) density_tables: [[f32; 4]; MAX_MEDIUM_TERMS * DENSITY_TABLE_SAMPLES / 4],
    pub(super) phase_tables: [[f32; 4]; MAX_MEDIUM_TERMS * PHASE_TABLE_SAMPLES / 4],
}

impl MediumGpu {
    /// `medium` up to `atmosphere_height` metres; `thick` when it is a thick air
    /// ([`is_thick_air`]).
    pub(super) fn new(medium: &Medium, atmosphere_height: f64, thick: bool) -> Self {
        let mut gpu = Self {
            terms: [MediumTermUniform::zeroed(); MAX_MEDIUM_TERMS],
            count: medium.terms.len().min(MAX_MEDIUM_TERMS),
            table_counts: [0; 4],
            density_table_terms: [[0; 4]; MAX_MEDIUM_TERMS / 4],
            phase_table_terms: [[0; 4]; MAX_MEDIUM_TERMS / 4],
            density_tables: [[0.0; 4]; MAX_MEDIUM_TERMS * DENSITY_TABLE_SAMPLES / 4],
            phase_tables: [[0.0; 4]; MAX_MEDIUM_TERMS * PHASE_TABLE_SAMPLES / 4],
        };
        for (i, term) in medium.terms.iter().take(MAX_MEDIUM_TERMS).enumerate() {
            gpu.terms[i] = MediumTermUniform::new(term, thick);
            if let Density::Table(table) = &term.density {
                list(&mut gpu.density_table_terms, &mut gpu.table_counts[0], i);
                let last = (DENSITY_TABLE_SAMPLES - 1) as f64;
                let row = |k: usize| table.density(atmosphere_height * k as f64 / last);
                write_row(&mut gpu.density_tables, i, DENSITY_TABLE_SAMPLES, row);
            }
            if let Phase::Table(table) = &term.phase {
                list(&mut gpu.phase_table_terms, &mut gpu.table_counts[1], i);
                let last = (PHASE_TABLE_SAMPLES - 1) as f64;
                let row = |k: usize| table.at_angle(std::f64::consts::PI * k as f64 / last);
                write_row(&mut gpu.phase_tables, i, PHASE_TABLE_SAMPLES, row);
            }
        }
        gpu
    }
}

/// Appends term `i` to a list of term indices packed four to a vector, counting it.
fn list(indices: &mut [[u32; 4]], count: &mut u32, i: usize) {
    let at = *count as usize;
    indices[at / 4][at % 4] = i as u32;
    *count += 1;
}

/// Writes `value(k)` for `k < samples` into row `row` of a table packed four to a vector.
fn write_row(table: &mut [[f32; 4]], row: usize, samples: usize, value: impl Fn(usize) -> f64) {
    for k in 0..samples {
        let at = row * samples + k;
        table[at / 4][at % 4] = value(k) as f32;
    }
}

#[cfg(test)]
mod tests {
    use firmament_core::atmosphere::presets;

    use super::*;

    /// Which presets are thick airs, and how high a thick air's multiple-scattering LUTs reach.
    #[test]
    fn venus_and_titan_are_thick_and_the_others_thin() {
        for (name, atmosphere, thick) in [
            ("earth", presets::earth(), false),
            ("mars", presets::mars(), false),
            ("saturn", presets::saturn(), false),
            ("venus", presets::venus(), true),
            ("titan", presets::titan(), true),
        ] {
            let top = atmosphere.planet.atmosphere_height;
            let depth = atmosphere.medium.vertical_scattering_depth(0.0, top);
            let height = multiscattering_lut_height(&atmosphere.medium, top, thick);
            println!("{name}: vertical scattering depth {depth:.3}, LUTs up to {height:.0} m of {top:.0} m");
            assert_eq!(is_thick_air(&atmosphere.medium, top), thick, "{name}");
            if thick {
                // The air above the LUTs scatters THICK_AIR_LUT_TOP_DEPTH.
                let above = atmosphere.medium.vertical_scattering_depth(height, top).max_element();
                assert!((above / THICK_AIR_LUT_TOP_DEPTH - 1.0).abs() < 0.2, "{name}: {above}");
            } else {
                assert_eq!(height, top);
            }
        }
    }

    /// A thick air's LUT rows climb from the ground to the LUTs' top, each at least a tenth of
    /// the even spacing above the one before, and in a uniform slab they follow the cosine steps
    /// in depth that `multiscattering_lut_rows` documents (computed here from the closed form).
    #[test]
    fn a_thick_air_s_lut_rows_climb_in_cosine_steps_of_depth() {
        for (name, atmosphere) in [("venus", presets::venus()), ("titan", presets::titan())] {
            let top = atmosphere.planet.atmosphere_height;
            let height = multiscattering_lut_height(&atmosphere.medium, top, true);
            let rows = multiscattering_lut_rows(&atmosphere.medium, top, height);
            assert_eq!((rows[0], rows[LUT_ROWS - 1]), (0.0, height), "{name}");
            let even = height / (LUT_ROWS - 1) as f64;
            for pair in rows.windows(2) {
                assert!(pair[1] - pair[0] >= 0.099 * even, "{name}: {rows:?}");
            }
        }
        // A slab 10 km high of uniform air scattering 2·10⁻³ m⁻¹ (depth 20): depth from the top
        // d = 20 (1 − h/10 km).
        let mut medium = presets::earth().medium;
        medium.terms.truncate(1);
        medium.terms[0].scattering = Spectrum::splat(2e-3);
        medium.terms[0].density = Density::Profile(DensityProfile::single(DensityLayer::constant()));
        let (top, height) = (10_000.0, 9_995.0);
        let rows = multiscattering_lut_rows(&medium, top, height);
        for (y, h) in rows.iter().enumerate().skip(1).take(LUT_ROWS - 2) {
            let from_top = (LUT_ROWS - 1 - y) as f64 / (LUT_ROWS - 1) as f64;
            let d = 0.01 + (20.0 - 0.01) * 0.5 * (1.0 - (std::f64::consts::PI * from_top).cos());
            let want = 0.9 * top * (1.0 - d / 20.0) + 0.1 * height * y as f64 / (LUT_ROWS - 1) as f64;
            assert!((h - want).abs() < 0.01, "row {y}: {h} vs {want}");
        }
    }
}
