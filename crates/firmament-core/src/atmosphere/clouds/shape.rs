//! What each kind of cloud looks like: the parameters of the one density formula
//! ([`super::field`]) that every kind but [`CloudKind::Uniform`] shares.

use super::CloudKind;
use super::quantiles::{self, QUANTILES};

/// The shape of a kind of cloud: feature sizes (metres, each a power of two so that the `f32`
/// mirror scales exactly), the vertical profile (fractions of the layer's thickness) and the
/// erosion by 3D detail. [`super::field`] documents the formula.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudShape {
    /// Worley cell of the column field, m: one rounded tower per cell.
    pub worley_cell_m: f64,
    /// Worley's share of the column field, 0–1 (the rest is gradient noise).
    pub worley_weight: f64,
    /// Gradient-noise cells of the column field along the pattern frame's x and y, and along its
    /// z (the polar axis at time 0), m: a longer x/y cell stretches features east–west.
    pub perlin_cell_m: [f64; 2],
    /// The share of the covered columns at full strength (`s = 1`): the cores that reach the
    /// cloud's full thickness and density (flat-topped where they do), 0–1.
    pub core_share: f64,
    /// 1: the gradient noise is ridged (`1 − |n|`, thin streaks where it crosses zero); 0:
    /// plain (`½ + ½n`).
    pub ridge: f64,
    /// Height fraction the cloud grows from (0: a flat base on the layer's bottom).
    pub anchor: f64,
    /// Share of a column's cloud below the anchor (0: all above it; ½: a lens centred on it).
    pub share_below: f64,
    /// Thickness of the weakest covered column's cloud, fraction of the layer.
    pub height_min: f64,
    /// Thickness of the strongest column's cloud, fraction of the layer.
    pub height_max: f64,
    /// Column strength over which a cloud's outline rounds off from nothing to full thickness
    /// (a quarter circle), 0–1: 1 for domes over the whole cloud, small for sheets with edges.
    pub dome_edge: f64,
    /// Distance over which density fades in above the cloud's bottom, fraction of the layer.
    pub base_softness: f64,
    /// Distance over which density fades out below the cloud's top, fraction of the layer.
    pub top_softness: f64,
    /// Relative density of the weakest column (the strongest has 1): denser cores.
    pub core_min: f64,
    /// Cell of the 3D detail noise, m.
    pub detail_cell_m: f64,
    /// Share of Worley billows in the detail at the layer's top (they blend in linearly with
    /// height from the wispy gradient noise at the bottom, as in Schneider & Vos 2015).
    pub detail_worley: f64,
    /// How much the detail lowers the cloud's top where it is low (billows), 0–1 (< 1).
    pub top_erosion: f64,
    /// How much the detail thins the inside where it is low, 0–1 (< 1).
    pub interior_erosion: f64,
    /// Quantiles of the column field at 0, 1/32, …, 1 (the ends: the least and greatest of the
    /// samples they were measured from): the threshold for a coverage `c` is the `1 − c`
    /// quantile, so that `c` of the columns are covered; the last is the strongest column.
    pub quantiles: [f64; QUANTILES],
}

/// Fair-weather cumulus: separate domed towers ~1–2 km across (2 km Worley cells, made irregular
/// and clustered by 4–1 km noise), flat bases, stronger columns taller and denser, billowed
/// tops.
pub const CUMULUS: CloudShape = CloudShape {
    worley_cell_m: 2048.0,
    worley_weight: 0.4,
    perlin_cell_m: [4096.0, 4096.0],
    core_share: 0.05,
    ridge: 0.0,
    anchor: 0.0,
    share_below: 0.0,
    height_min: 0.25,
    height_max: 1.0,
    dome_edge: 1.0,
    base_softness: 0.03,
    top_softness: 0.15,
    core_min: 0.35,
    detail_cell_m: 512.0,
    detail_worley: 1.0,
    top_erosion: 0.35,
    interior_erosion: 0.4,
    quantiles: quantiles::CUMULUS,
};

/// Stratocumulus: a lumpy sheet broken into patches (1 km Worley lumps in 8–2 km noise),
/// flat-based, its outline rounding off over the weakest third of its columns.
pub const STRATOCUMULUS: CloudShape = CloudShape {
    worley_cell_m: 1024.0,
    worley_weight: 0.5,
    perlin_cell_m: [8192.0, 8192.0],
    core_share: 0.25,
    ridge: 0.0,
    anchor: 0.0,
    share_below: 0.0,
    height_min: 0.5,
    height_max: 1.0,
    dome_edge: 0.35,
    base_softness: 0.05,
    top_softness: 0.25,
    core_min: 0.6,
    detail_cell_m: 512.0,
    detail_worley: 0.6,
    top_erosion: 0.3,
    interior_erosion: 0.3,
    quantiles: quantiles::STRATOCUMULUS,
};

/// Stratus: a nearly featureless low sheet (16 km noise), full thickness almost everywhere it
/// covers, faint 1 km texture.
pub const STRATUS: CloudShape = CloudShape {
    worley_cell_m: 16384.0,
    worley_weight: 0.0,
    perlin_cell_m: [16384.0, 16384.0],
    core_share: 0.5,
    ridge: 0.0,
    anchor: 0.0,
    share_below: 0.0,
    height_min: 0.8,
    height_max: 1.0,
    dome_edge: 0.1,
    base_softness: 0.1,
    top_softness: 0.3,
    core_min: 0.8,
    detail_cell_m: 1024.0,
    detail_worley: 0.0,
    top_erosion: 0.1,
    interior_erosion: 0.15,
    quantiles: quantiles::STRATUS,
};

/// Altostratus: a mid-level sheet, thinner and smoother than stratus (32 km noise, 2 km
/// texture), a lens about the layer's middle and less dense.
pub const ALTOSTRATUS: CloudShape = CloudShape {
    worley_cell_m: 32768.0,
    worley_weight: 0.0,
    perlin_cell_m: [32768.0, 32768.0],
    core_share: 0.5,
    ridge: 0.0,
    anchor: 0.5,
    share_below: 0.5,
    height_min: 0.5,
    height_max: 0.8,
    dome_edge: 0.15,
    base_softness: 0.25,
    top_softness: 0.25,
    core_min: 0.5,
    detail_cell_m: 2048.0,
    detail_worley: 0.0,
    top_erosion: 0.1,
    interior_erosion: 0.1,
    quantiles: quantiles::ALTOSTRATUS,
};

/// Cirrus: thin streaks of ice, ridged noise stretched 8:1 east–west (16 km by 2 km cells),
/// lenses about the layer's middle, frayed by 1 km detail.
pub const CIRRUS: CloudShape = CloudShape {
    worley_cell_m: 16384.0,
    worley_weight: 0.0,
    perlin_cell_m: [16384.0, 2048.0],
    core_share: 0.2,
    ridge: 1.0,
    anchor: 0.5,
    share_below: 0.5,
    height_min: 0.2,
    height_max: 0.8,
    dome_edge: 0.3,
    base_softness: 0.2,
    top_softness: 0.2,
    core_min: 0.3,
    detail_cell_m: 1024.0,
    detail_worley: 0.0,
    top_erosion: 0.5,
    interior_erosion: 0.6,
    quantiles: quantiles::CIRRUS,
};

impl CloudKind {
    /// The kind's shape; `None` for [`CloudKind::Uniform`], which has none.
    pub fn shape(self) -> Option<&'static CloudShape> {
        match self {
            Self::Cumulus => Some(&CUMULUS),
            Self::Stratocumulus => Some(&STRATOCUMULUS),
            Self::Stratus => Some(&STRATUS),
            Self::Altostratus => Some(&ALTOSTRATUS),
            Self::Cirrus => Some(&CIRRUS),
            Self::Uniform => None,
        }
    }
}

impl CloudShape {
    /// The column-field threshold that leaves `coverage` (0–1) of the columns covered: the
    /// `1 − coverage` quantile, linear between the table's entries.
    pub fn coverage_threshold(&self, coverage: f64) -> f64 {
        let steps = (QUANTILES - 1) as f64;
        let u = (1.0 - coverage.clamp(0.0, 1.0)) * steps;
        let i = (u.floor() as usize).min(QUANTILES - 2);
        let f = u - i as f64;
        self.quantiles[i] + (self.quantiles[i + 1] - self.quantiles[i]) * f
    }

    /// The column-field value from which a column is at full strength for `coverage`: the
    /// threshold of `coverage · core_share`.
    pub fn core_threshold(&self, coverage: f64) -> f64 {
        self.coverage_threshold(coverage * self.core_share)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feature_sizes_are_powers_of_two_and_parameters_in_range() {
        for kind in CloudKind::ALL {
            let Some(s) = kind.shape() else { continue };
            for cell in [s.worley_cell_m, s.perlin_cell_m[0], s.perlin_cell_m[1], s.detail_cell_m] {
                assert!(cell >= 64.0 && cell.log2().fract() == 0.0, "{kind:?}: {cell}");
            }
            for v in [
                s.worley_weight,
                s.core_share,
                s.ridge,
                s.anchor,
                s.share_below,
                s.height_min,
                s.height_max,
                s.core_min,
                s.detail_worley,
            ] {
                assert!((0.0..=1.0).contains(&v), "{kind:?}");
            }
            for v in [s.dome_edge, s.base_softness, s.top_softness] {
                assert!(v > 0.0 && v <= 1.0, "{kind:?}");
            }
            assert!(s.top_erosion < 1.0 && s.interior_erosion < 1.0 && s.top_erosion >= 0.0);
            // The cloud stays inside the layer: anchor − share·H ≥ 0 and anchor + (1 − share)·H ≤ 1.
            assert!(s.anchor - s.share_below * s.height_max >= 0.0, "{kind:?}");
            assert!(s.anchor + (1.0 - s.share_below) * s.height_max <= 1.0, "{kind:?}");
            assert!(s.height_min <= s.height_max);
            assert!(s.quantiles.windows(2).all(|w| w[0] < w[1]), "{kind:?}");
            assert!(s.quantiles[0] >= 0.0 && s.quantiles[QUANTILES - 1] <= 1.0, "{kind:?}");
        }
    }

    #[test]
    fn thresholds_run_from_the_greatest_value_at_no_coverage_to_the_least_at_full() {
        for kind in CloudKind::ALL {
            let Some(s) = kind.shape() else { continue };
            assert_eq!(s.coverage_threshold(0.0), s.quantiles[QUANTILES - 1]);
            assert_eq!(s.coverage_threshold(1.0), s.quantiles[0]);
            assert_eq!(s.coverage_threshold(0.5), s.quantiles[QUANTILES / 2]);
            let mut last = 1.0;
            for i in 0..=100 {
                let t = s.coverage_threshold(f64::from(i) / 100.0);
                assert!(t <= last);
                last = t;
            }
        }
    }
}
