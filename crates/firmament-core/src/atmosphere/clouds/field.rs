//! The density field of a layer, in the spirit of Schneider & Vos, "The real-time volumetric
//! cloudscapes of Horizon Zero Dawn" (SIGGRAPH 2015 Advances in Real-Time Rendering): a 2D
//! coverage field per column, thresholded at the layer's coverage, a vertical profile per kind
//! and 3D detail that erodes the outline and the inside. `shaders/clouds/density.wgsl` mirrors
//! every line in `f32`.
//!
//! # The formula
//! For a point `p` (planet frame, m) at altitude `h` in a layer of shape `S` ([`CloudShape`]),
//! seed `seed`, drift `R` and coverage `c` (the layer's, times its map's there):
//! 1. Outside `bottom ≤ h ≤ top`: 0. Height fraction `x = (h − bottom)/(top − bottom)`.
//! 2. Pattern points: the column's foot `p_c = p − h·p/|p|` (down the radius by the altitude:
//!    on a sphere the surface point under `p`; columns are radial and the pattern wraps the
//!    planet at the surface's scale) and the point itself, both in the pattern frame: `q_c = R
//!    p_c`, `q = R p`.
//! 3. Column field `F(q_c) = clamp(w·(1 − F1²(q_c/cell_w)) + (1 − w)·g, 0, 1)` with Worley's
//!    F1 and `g = ½ + ½n` (or `1 − |n|` for a ridged kind) of three octaves `n` of gradient noise
//!    at `q_c` over the per-axis cells. Threshold `t` = the `1 − c` quantile of `F`
//!    ([`CloudShape::coverage_threshold`]); `c = 0` or `F ≤ t`: 0 (so `c` of the sky's columns
//!    hold cloud). Column strength `s = min((F − t)/(t_core − t), 1)`, 0–1, with `t_core` the
//!    threshold of `c · core_share` ([`CloudShape::core_threshold`]): that share of the covered
//!    columns, the strongest, are cores at full strength.
//! 4. Detail `D(q) = clamp((1 − b)·(½ + ½n_d) + b·max(1 − F1²_d, 0), 0, 1)` at `q/cell_d`
//!    (`n_d`: two octaves of gradient noise), with `b = detail_worley · x`: wisps at the bottom,
//!    billows at the top.
//! 5. The cloud in the column: thickness `H = (h_min + (h_max − h_min)·s(2 − s)) · √(u(2 − u))
//!    · (1 − e_top·(1 − D))` with `u = min(s/dome_edge, 1)`: a parabola in the strength (domed
//!    tops, flat where `s` is full) times a quarter circle (rounded, steep edges), from
//!    `x_bot = anchor − share·H` to `x_top = anchor + (1 − share)·H`.
//! 6. Density `ρ · smooth((x − x_bot)/base_softness) · smooth((x_top − x)/top_softness) ·
//!    (core_min + (1 − core_min)·s) · (1 − e_in·(1 − D))`, `smooth` the cubic smoothstep on
//!    0–1 and `ρ` the layer's `density_per_m`.
//!
//! Every factor of step 6 lies in 0–1, so **the field never exceeds `density_per_m`**: that is
//! the majorant the reference integrator's delta tracking uses. A column with `s > 0` always
//! holds cloud somewhere (`H > 0` as `e_top < 1`), so the covered share of the sky is exactly
//! the share of columns above the threshold. The field is continuous (zero at the layer's
//! bottom and top and at the edges of covered columns), except for [`CloudKind::Uniform`]'s slab.
//!
//! # Precision
//! The `f32` mirror evaluates this field at a given `p` and `h` to ~1e-5 of `density_per_m`
//! (measured by firmament-render's GPU test `cloud_density`): its lattices are this code's
//! exactly (see the `noise` module). What `f32` costs a GPU march is `p`'s own rounding, 0.5 m
//! at the Earth's radius: moving a point by 0.5 m changes the density by < 1e-2 of
//! `density_per_m` at 99 % of points (the 512 m and 1 km features; the test
//! `sensitivity_to_half_a_metre` prints the figures), which is fine for every feature size here
//! (≥ 256 m, the detail's second octave) and would not be below ~50 m cells.

use glam::{DQuat, DVec3};

use super::CloudKind;
use super::noise::{fbm2, fbm3, field_key, salt, worley_squared};
use super::shape::CloudShape;

/// The layer data the field reads.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FieldLayer<'a> {
    pub(crate) bottom_m: f64,
    pub(crate) top_m: f64,
    pub(crate) density_per_m: f64,
    pub(crate) kind: CloudKind,
    pub(crate) seed: u32,
    pub(crate) drift: DQuat,
    pub(crate) shape: Option<&'a CloudShape>,
}

/// The cubic smoothstep of `t` clamped to 0–1.
fn smooth(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The column field `F` at the pattern-frame column foot `q_c` (m), 0–1.
pub(crate) fn column_field(shape: &CloudShape, kind: CloudKind, seed: u32, q_c: DVec3) -> f64 {
    let key = |salt| field_key(seed, kind.code(), salt);
    let mut f = 0.0;
    if shape.worley_weight > 0.0 {
        let cells = worley_squared(q_c * (1.0 / shape.worley_cell_m), key(salt::COLUMN_WORLEY));
        f += shape.worley_weight * (1.0 - cells).clamp(0.0, 1.0);
    }
    if shape.worley_weight < 1.0 {
        let [across, polar] = shape.perlin_cell_m;
        let scale = DVec3::new(1.0 / across, 1.0 / across, 1.0 / polar);
        let keys = [
            key(salt::COLUMN_PERLIN_1),
            key(salt::COLUMN_PERLIN_2),
            key(salt::COLUMN_PERLIN_3),
        ];
        let n = fbm3(q_c * scale, keys);
        let g = (0.5 + 0.5 * n) * (1.0 - shape.ridge) + (1.0 - n.abs()) * shape.ridge;
        f += (1.0 - shape.worley_weight) * g;
    }
    f.clamp(0.0, 1.0)
}

/// The detail `D` at the pattern-frame point `q` (m) and height fraction `x`, 0–1.
fn detail(shape: &CloudShape, kind: CloudKind, seed: u32, q: DVec3, x: f64) -> f64 {
    let key = |salt| field_key(seed, kind.code(), salt);
    let qd = q * (1.0 / shape.detail_cell_m);
    let keys = [key(salt::DETAIL_PERLIN_1), key(salt::DETAIL_PERLIN_2)];
    let wisps = 0.5 + 0.5 * fbm2(qd, keys);
    let b = shape.detail_worley * x;
    let mut d = wisps * (1.0 - b);
    if b > 0.0 {
        d += b * (1.0 - worley_squared(qd, key(salt::DETAIL_WORLEY))).max(0.0);
    }
    d.clamp(0.0, 1.0)
}

/// The extent `(x_bot, x_top)` of the cloud of thickness `thickness` in a column.
fn extent(shape: &CloudShape, thickness: f64) -> (f64, f64) {
    (
        shape.anchor - shape.share_below * thickness,
        shape.anchor + (1.0 - shape.share_below) * thickness,
    )
}

/// The density of `layer` at `p` (planet frame, m), altitude `h` (m), with coverage `coverage`
/// (0–1) there, m⁻¹: the formula of the module docs.
pub(crate) fn density(layer: &FieldLayer<'_>, p: DVec3, h: f64, coverage: f64) -> f64 {
    if !(h >= layer.bottom_m && h <= layer.top_m) {
        return 0.0;
    }
    let Some(shape) = layer.shape.filter(|_| layer.kind != CloudKind::Uniform) else {
        return layer.density_per_m;
    };
    let radius = p.length();
    if radius == 0.0 {
        return 0.0;
    }
    let x = (h - layer.bottom_m) / (layer.top_m - layer.bottom_m);
    let q_c = layer.drift * (p - p * (h / radius));
    if coverage.is_nan() || coverage <= 0.0 {
        return 0.0;
    }
    let f = column_field(shape, layer.kind, layer.seed, q_c);
    let t = shape.coverage_threshold(coverage);
    if f <= t {
        return 0.0;
    }
    let s = ((f - t) / (shape.core_threshold(coverage) - t)).min(1.0);
    let detail = || detail(shape, layer.kind, layer.seed, layer.drift * p, x);
    layer.density_per_m * in_column(shape, s, x, detail)
}

/// Steps 5 and 6 of the formula over `density_per_m`: the density, 0–1, at height fraction `x`
/// of a column of strength `s` (0–1), the detail `d()` asked for only inside the uneroded cloud.
fn in_column(shape: &CloudShape, s: f64, x: f64, d: impl FnOnce() -> f64) -> f64 {
    let u = (s / shape.dome_edge).min(1.0);
    let body = s * (2.0 - s);
    let full = (shape.height_min + (shape.height_max - shape.height_min) * body) * (u * (2.0 - u)).sqrt();
    // Erosion only lowers the thickness, and the extents nest: outside the uneroded cloud, none.
    let (bottom, top) = extent(shape, full);
    if x <= bottom || x >= top {
        return 0.0;
    }
    let d = d();
    let (bottom, top) = extent(shape, full * (1.0 - shape.top_erosion * (1.0 - d)));
    let fall = smooth((x - bottom) / shape.base_softness) * smooth((top - x) / shape.top_softness);
    let core = shape.core_min + (1.0 - shape.core_min) * s;
    fall * core * (1.0 - shape.interior_erosion * (1.0 - d))
}

/// The density of `layer` at altitude `h` (m) averaged over its columns, with coverage
/// `coverage` (0–1), m⁻¹: the field seen from afar, where a pixel spans many columns (the GPU's
/// level of detail, `cloud_mean_density`). The column field follows its kind's distribution —
/// the quantile table, uniform between entries, as the thresholds read it — and each of the
/// table's intervals above the threshold counts with its share of the columns at its middle; the
/// detail is taken at its mean, ½. So the covered share is exactly `coverage`.
pub(crate) fn mean_density(layer: &FieldLayer<'_>, h: f64, coverage: f64) -> f64 {
    if !(h >= layer.bottom_m && h <= layer.top_m) {
        return 0.0;
    }
    let Some(shape) = layer.shape.filter(|_| layer.kind != CloudKind::Uniform) else {
        return layer.density_per_m;
    };
    if coverage.is_nan() || coverage <= 0.0 {
        return 0.0;
    }
    let x = (h - layer.bottom_m) / (layer.top_m - layer.bottom_m);
    let sum: f64 = covered_columns(shape, coverage)
        .map(|(share, s)| share * in_column(shape, s, x, || 0.5))
        .sum();
    layer.density_per_m * sum
}

/// The covered columns as the level of detail weighs them, at coverage `coverage` (0–1): the
/// quantile table's intervals above the threshold (the column field uniform between entries),
/// each as `(share of all columns, strength s at its middle)`.
fn covered_columns(shape: &CloudShape, coverage: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
    let t = shape.coverage_threshold(coverage);
    let t_core = shape.core_threshold(coverage);
    let intervals = (shape.quantiles.len() - 1) as f64;
    shape.quantiles.windows(2).filter_map(move |pair| {
        let (lo, hi) = (pair[0], pair[1]);
        let from = lo.max(t);
        (hi > from).then(|| {
            let share = (hi - from) / (hi - lo) / intervals;
            (share, ((0.5 * (from + hi) - t) / (t_core - t)).min(1.0))
        })
    })
}

/// Steps over a layer's thickness in [`columns_straight_down`]: 16 across the thinnest fade.
const COLUMN_STEPS: u32 = 512;

/// The columns of `layer` with coverage `coverage` (0–1) seen straight down, as
/// [`mean_density`] weighs them (the quantile table's intervals above the threshold, each at its
/// middle, the detail at its mean): their mean optical depth through the layer and their mean
/// transmittance, `(τ̄, mean e^(−τ))`. `(0, 1)` for no cloud; a uniform slab is one column.
pub(crate) fn columns_straight_down(layer: &FieldLayer<'_>, coverage: f64) -> (f64, f64) {
    let thickness = layer.top_m - layer.bottom_m;
    let Some(shape) = layer.shape.filter(|_| layer.kind != CloudKind::Uniform) else {
        let tau = layer.density_per_m * thickness;
        return (tau, (-tau).exp());
    };
    if coverage.is_nan() || coverage <= 0.0 {
        return (0.0, 1.0);
    }
    let dx = 1.0 / f64::from(COLUMN_STEPS);
    let (mut mean_tau, mut transmittance) = (0.0, 1.0);
    for (share, s) in covered_columns(shape, coverage) {
        let depth: f64 = (0..COLUMN_STEPS)
            .map(|k| in_column(shape, s, (f64::from(k) + 0.5) * dx, || 0.5))
            .sum::<f64>()
            * dx
            * layer.density_per_m
            * thickness;
        mean_tau += share * depth;
        transmittance -= share * (1.0 - (-depth).exp());
    }
    (mean_tau, transmittance)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::clouds::CloudLayer;

    /// A point uniformly random on the unit sphere, from two numbers in [0, 1).
    fn direction(u: f64, v: f64) -> DVec3 {
        let z = 2.0 * u - 1.0;
        let phi = std::f64::consts::TAU * v;
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// The mean over columns equals the field averaged over 20 000 random columns of an Earth-sized
    /// sphere (the detail at its mean in both): the quantile table's distribution is the field's.
    #[test]
    fn the_mean_density_is_the_fields_average_over_columns() {
        let radius = 6_371_000.0;
        let kinds = [
            CloudKind::Cumulus,
            CloudKind::Stratocumulus,
            CloudKind::Stratus,
            CloudKind::Altostratus,
            CloudKind::Cirrus,
        ];
        let columns = 20_000;
        let mut worst: f64 = 0.0;
        for kind in kinds {
            let shape = kind.shape().expect("a noisy kind");
            for coverage in [0.3, 0.7] {
                let layer = CloudLayer {
                    seed: 5,
                    ..CloudLayer::new(1_000.0, 3_000.0, coverage, 0.04, kind)
                };
                let field = layer.field_layer();
                let t = shape.coverage_threshold(coverage);
                let t_core = shape.core_threshold(coverage);
                for x in [0.05, 0.3, 0.6, 0.9] {
                    let h = 1_000.0 + 2_000.0 * x;
                    let mut sum = 0.0;
                    for i in 0..columns {
                        let a = f64::from(crate::atmosphere::clouds::noise::lowbias32(2 * i)) / 4_294_967_296.0;
                        let b = f64::from(crate::atmosphere::clouds::noise::lowbias32(2 * i + 1)) / 4_294_967_296.0;
                        let f = column_field(shape, kind, layer.seed, direction(a, b) * radius);
                        if f > t {
                            let s = ((f - t) / (t_core - t)).min(1.0);
                            sum += in_column(shape, s, x, || 0.5);
                        }
                    }
                    let average = layer.density_per_m * sum / f64::from(columns);
                    let mean = mean_density(&field, h, coverage);
                    let error = (mean - average).abs() / layer.density_per_m;
                    worst = worst.max(error);
                    assert!(
                        error < 0.02,
                        "{kind:?}, coverage {coverage}, x {x}: mean {mean:.5}, over columns {average:.5}"
                    );
                }
            }
        }
        println!("worst difference: {worst:.4} of density_per_m");
    }
}
