//! The distribution of each kind's column field, as quantile tables: the thresholds that make a
//! layer's `coverage` the share of the sky it covers.
//!
//! Computed in `f64` by `measure` (the column field at 2¹⁸ points spread uniformly over a cube
//! 8000 km across, nearest-rank quantiles; the ends are the least and greatest samples) and
//! stored here. The test `the_stored_tables_are_the_measured_ones` recomputes them (deterministic:
//! only `+ − × √` and integer hashing) and, when a shape has changed, fails printing the new tables
//! to paste here. The field is statistically the same everywhere and for every
//! seed (its lattice noise is stationary), and its marginal distribution on the sphere of column
//! feet is its distribution in space, so one table per kind serves every layer.

/// Entries of a quantile table: the quantiles at 0, 1/32, …, 1.
pub const QUANTILES: usize = 33;

/// Column-field quantiles of [`super::shape::CUMULUS`].
pub(crate) const CUMULUS: [f64; QUANTILES] = [
    0.14923636, 0.39879423, 0.43337897, 0.45612312, 0.47361541, 0.48809921, 0.50041794, 0.51159833, 0.52176411,
    0.53112202, 0.53986240, 0.54824429, 0.55620573, 0.56394184, 0.57153355, 0.57860739, 0.58575847, 0.59284249,
    0.59988516, 0.60690950, 0.61386920, 0.62102100, 0.62827772, 0.63590801, 0.64385452, 0.65207717, 0.66067796,
    0.67022418, 0.68083777, 0.69360591, 0.70912054, 0.73158444, 0.86025497,
];
/// Column-field quantiles of [`super::shape::STRATOCUMULUS`].
pub(crate) const STRATOCUMULUS: [f64; QUANTILES] = [
    0.10681926, 0.39016028, 0.43173650, 0.45870334, 0.47957618, 0.49623536, 0.51095212, 0.52419127, 0.53595132,
    0.54691108, 0.55732723, 0.56704141, 0.57623864, 0.58498317, 0.59362434, 0.60207349, 0.61005328, 0.61787711,
    0.62580921, 0.63362855, 0.64153189, 0.64924767, 0.65723110, 0.66534129, 0.67358434, 0.68226555, 0.69142553,
    0.70123649, 0.71212319, 0.72459855, 0.73988976, 0.76169658, 0.88475420,
];
/// Column-field quantiles of [`super::shape::STRATUS`].
pub(crate) const STRATUS: [f64; QUANTILES] = [
    0.17321518, 0.33696000, 0.36284123, 0.38133200, 0.39595900, 0.40855852, 0.41949224, 0.42939729, 0.43850934,
    0.44717703, 0.45542782, 0.46347635, 0.47112616, 0.47864068, 0.48598003, 0.49322848, 0.50034907, 0.50749805,
    0.51463980, 0.52198588, 0.52925735, 0.53693192, 0.54483216, 0.55291646, 0.56148329, 0.57058983, 0.58077173,
    0.59165957, 0.60409969, 0.61824167, 0.63660405, 0.66332555, 0.84657801,
];
/// Column-field quantiles of [`super::shape::ALTOSTRATUS`].
pub(crate) const ALTOSTRATUS: [f64; QUANTILES] = [
    0.17041120, 0.33758610, 0.36364739, 0.38200015, 0.39634818, 0.40851771, 0.41938752, 0.42947158, 0.43864044,
    0.44732771, 0.45551074, 0.46342270, 0.47102318, 0.47837148, 0.48559378, 0.49272071, 0.49997833, 0.50713435,
    0.51435637, 0.52162044, 0.52915485, 0.53684474, 0.54460290, 0.55299310, 0.56158215, 0.57063812, 0.58062580,
    0.59158635, 0.60405469, 0.61856369, 0.63720199, 0.66340149, 0.83192581,
];
/// Column-field quantiles of [`super::shape::CIRRUS`].
pub(crate) const CIRRUS: [f64; QUANTILES] = [
    0.29022573, 0.62888232, 0.67373901, 0.70378181, 0.72700819, 0.74680462, 0.76374910, 0.77883969, 0.79258725,
    0.80531429, 0.81702011, 0.82843585, 0.83893392, 0.84907916, 0.85877528, 0.86817767, 0.87720314, 0.88599059,
    0.89461165, 0.90279690, 0.91084043, 0.91879443, 0.92666948, 0.93437149, 0.94217912, 0.94971946, 0.95709141,
    0.96438075, 0.97150194, 0.97864341, 0.98577426, 0.99279504, 0.99999825,
];

/// Samples of the column field [`measure`] sorts.
#[cfg(test)]
pub(crate) const SAMPLES: u32 = 1 << 18;

/// The quantile table of `shape`'s column field, measured as the module docs say.
#[cfg(test)]
pub(crate) fn measure(kind: super::CloudKind, shape: &super::CloudShape) -> [f64; QUANTILES] {
    use super::noise::lowbias32;
    let half_side = 4.0e6;
    let uniform = |i: u32, axis: u32| {
        let bits = lowbias32(lowbias32(i.wrapping_mul(3).wrapping_add(axis)) ^ 0x5eed_c10d);
        (f64::from(bits) + 0.5) / 4_294_967_296.0
    };
    let mut values: Vec<f64> = (0..SAMPLES)
        .map(|i| {
            let q = glam::DVec3::new(uniform(i, 0), uniform(i, 1), uniform(i, 2)) * (2.0 * half_side) - half_side;
            super::field::column_field(shape, kind, 0, q)
        })
        .collect();
    values.sort_by(f64::total_cmp);
    let mut table = [0.0; QUANTILES];
    for (k, entry) in table.iter_mut().enumerate() {
        let rank = (k as f64 / (QUANTILES - 1) as f64 * f64::from(SAMPLES)) as usize;
        *entry = values[rank.min(values.len() - 1)];
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::clouds::CloudKind;

    #[test]
    fn the_stored_tables_are_the_measured_ones() {
        let mut stale = String::new();
        for kind in CloudKind::ALL {
            let Some(shape) = kind.shape() else { continue };
            let measured = measure(kind, shape);
            if measured.iter().zip(&shape.quantiles).any(|(a, b)| (a - b).abs() > 1e-6) {
                let entries: Vec<String> = measured.iter().map(|v| format!("{v:.8}")).collect();
                stale += &format!(
                    "pub(crate) const {}: [f64; QUANTILES] = [\n    {},\n];\n",
                    kind.name().to_uppercase(),
                    entries.join(", ")
                );
            }
        }
        assert!(stale.is_empty(), "stale quantile tables; the measured ones:\n{stale}");
    }
}
