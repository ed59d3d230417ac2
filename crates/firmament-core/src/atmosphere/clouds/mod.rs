//! Cloud layers: volumetric clouds on shells that follow the planet's ellipsoid, inside its air.
//!
//! # Names and units
//! - Altitudes `h` above the ellipsoid surface, metres, as in [`super`]; a layer fills
//!   `bottom_m ≤ h ≤ top_m`.
//! - Densities are extinction coefficients, m⁻¹, grey (the same at every model wavelength: cloud
//!   droplets are far larger than the wavelengths). Scattering is `albedo ×` extinction.
//! - Positions are in the planet frame ([`Planet`]), metres. A layer's pattern is fixed in its own
//!   frame, which [`CloudLayer::drift`] rotates about the planet centre (the wind, see
//!   [`wind_drift`]).
//!
//! The density field ([`CloudLayer::density_at`], formula in [`field`]) is what the GPU's cloud
//! pass evaluates too (`shaders/clouds/density.wgsl` mirrors it in `f32`); the reference
//! integrator marches it in `f64`. Its largest value is the layer's `density_per_m`, the majorant
//! for delta tracking.
//!
//! # Files
//! - `noise`: integer-hashed gradient and Worley noise that the `f32` mirror reproduces.
//! - [`shape`]: each kind's parameters ([`CloudShape`]); [`quantiles`]: their column fields'
//!   distributions, which turn `coverage` into a threshold.
//! - [`field`]: the density formula. [`phase`]: the droplets' phase function.
//! - [`coverage`]: coverage maps. [`wind`]: the drift of a layer's pattern.

use glam::{DQuat, DVec3};

use super::Planet;
use crate::error::CoreError;

pub mod coverage;
pub mod field;
mod noise;
pub mod phase;
pub mod quantiles;
pub mod shape;
#[cfg(test)]
mod tests;
pub mod wind;

pub use coverage::CoverageMap;
pub use phase::DualHenyeyGreenstein;
pub use quantiles::QUANTILES;
pub use shape::CloudShape;
pub use wind::wind_drift;

/// How far apart, in column cells ([`CloudLayer::column_cell_m`]), a ray crossing a broken layer
/// meets independent columns at a grazing look ([`CloudLayer::cover_seen`]): fitted to the
/// field's mean transmittance (docs/CLOUDS.md, "Level of detail").
pub const COLUMN_SPACING_CELLS: f64 = 1.0;

/// The most cloud layers a sky may have (the GPU pass loops over a fixed-size array).
pub const MAX_CLOUD_LAYERS: usize = 8;

/// What a layer looks like: its shape and vertical profile, or a uniform slab.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CloudKind {
    /// Fair-weather heaps: separate rounded towers, flat bases.
    Cumulus,
    /// Low lumpy sheets broken into rolls and patches.
    Stratocumulus,
    /// A low, nearly featureless grey sheet.
    Stratus,
    /// A mid-level sheet, thinner and smoother than stratus.
    Altostratus,
    /// High thin wisps of ice, streaked.
    Cirrus,
    /// A homogeneous slab of the layer's density over the whole sky, with no noise: the case
    /// that can be checked by hand.
    Uniform,
}

impl CloudKind {
    /// Every kind, in the order of their codes.
    pub const ALL: [Self; 6] = [
        Self::Cumulus,
        Self::Stratocumulus,
        Self::Stratus,
        Self::Altostratus,
        Self::Cirrus,
        Self::Uniform,
    ];

    /// The kind's name in scene files (`"cumulus"`, …).
    pub fn name(self) -> &'static str {
        match self {
            Self::Cumulus => "cumulus",
            Self::Stratocumulus => "stratocumulus",
            Self::Stratus => "stratus",
            Self::Altostratus => "altostratus",
            Self::Cirrus => "cirrus",
            Self::Uniform => "uniform",
        }
    }

    /// The kind named `name` in scene files.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// The code the GPU passes use (`CLOUD_KIND_*` in `generated/constants`).
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// One layer of clouds. Build with [`CloudLayer::new`], set the other fields, then
/// [`validate`](Self::validate).
#[derive(Debug, Clone, PartialEq)]
pub struct CloudLayer {
    /// Altitude of the layer's base above the ellipsoid surface, metres, ≥ 0.
    pub bottom_m: f64,
    /// Altitude of the layer's top above the ellipsoid surface, metres, above `bottom_m`.
    pub top_m: f64,
    /// The share of the sky the layer covers, 0–1 (ignored by [`CloudKind::Uniform`]).
    pub coverage: f64,
    /// Extinction coefficient of the cloud at full density, m⁻¹ (typical cumulus 0.02–0.1).
    pub density_per_m: f64,
    /// Shape and vertical profile.
    pub kind: CloudKind,
    /// Wind, metres per second towards the east and towards the north (see [`wind_drift`]).
    pub wind_mps: [f64; 2],
    /// Seed of the procedural noise.
    pub seed: u32,
    /// Single-scattering albedo, 0–1.
    pub albedo: f64,
    /// The droplets' phase function.
    pub phase: DualHenyeyGreenstein,
    /// Coverage over the planet, multiplying `coverage`; `None` for the same coverage
    /// everywhere.
    pub coverage_map: Option<CoverageMap>,
    /// Rotation from the planet frame into the layer's pattern frame: how far the wind has
    /// carried the pattern ([`wind_drift`]); identity for none.
    pub drift: DQuat,
}

impl CloudLayer {
    /// A layer of `kind` between `bottom_m` and `top_m` (metres above the surface) covering
    /// `coverage` of the sky with extinction `density_per_m` (m⁻¹) at full density: no wind,
    /// seed 0, albedo 1, the droplets' phase function ([`DualHenyeyGreenstein::CLOUD_DROPLETS`]),
    /// no coverage map.
    pub fn new(bottom_m: f64, top_m: f64, coverage: f64, density_per_m: f64, kind: CloudKind) -> Self {
        Self {
            bottom_m,
            top_m,
            coverage,
            density_per_m,
            kind,
            wind_mps: [0.0, 0.0],
            seed: 0,
            albedo: 1.0,
            phase: DualHenyeyGreenstein::CLOUD_DROPLETS,
            coverage_map: None,
            drift: DQuat::IDENTITY,
        }
    }

    /// Extinction coefficient at planet-frame point `p` (metres), m⁻¹: the field of [`field`]
    /// at `p`'s exact altitude, with the coverage map (if any) read at `p`'s geodetic latitude
    /// and longitude ([`coverage_at`](Self::coverage_at)). At most `density_per_m`.
    pub fn density_at(&self, planet: &Planet, p: DVec3) -> f64 {
        let h = planet.altitude(p);
        if !(h >= self.bottom_m && h <= self.top_m) {
            return 0.0;
        }
        self.density_with_coverage(p, h, self.coverage_at(planet, p))
    }

    /// [`density_at`](Self::density_at) with the altitude `h` (m) of `p` given, m⁻¹. Without a
    /// coverage map it is what the GPU's `cloud_density` computes, and `density_at` exactly
    /// when `h` is `p`'s altitude; on a sphere it is `density_at` with a map too. With a map it reads it at the latitude and longitude of `p`'s
    /// direction from the planet centre (geocentric: this function has no planet to find the
    /// geodetic ones), up to 0.19° from `density_at`'s on the Earth; for the exact geodetic
    /// lookup use [`density_with_coverage`](Self::density_with_coverage) with
    /// [`coverage_at`](Self::coverage_at).
    pub fn density_at_altitude(&self, p: DVec3, h: f64) -> f64 {
        let coverage = match &self.coverage_map {
            Some(map) if h >= self.bottom_m && h <= self.top_m => {
                let n = p.normalize_or_zero();
                self.coverage * map.sample(n.z.clamp(-1.0, 1.0).asin(), n.y.atan2(n.x))
            }
            _ => self.coverage,
        };
        self.density_with_coverage(p, h, coverage)
    }

    /// The field at `p` (planet frame, m) and altitude `h` (m) with the coverage there given,
    /// 0–1 (the layer's `coverage` times its map's value: [`coverage_at`](Self::coverage_at)),
    /// m⁻¹ — the GPU's `cloud_density_with_coverage`.
    pub fn density_with_coverage(&self, p: DVec3, h: f64, coverage: f64) -> f64 {
        field::density(&self.field_layer(), p, h, coverage)
    }

    /// The density at altitude `h` (m) averaged over the layer's columns with the coverage there
    /// given (0–1), m⁻¹: the field's level of detail from afar, where a pixel spans many columns
    /// (the detail at its mean), with exactly `coverage` of the columns covered — the GPU's
    /// `cloud_mean_density_with_coverage`. `density_per_m` throughout a [`CloudKind::Uniform`]
    /// slab.
    pub fn mean_density_with_coverage(&self, h: f64, coverage: f64) -> f64 {
        field::mean_density(&self.field_layer(), h, coverage)
    }

    /// The size of the layer's columns, metres: its Worley cell (one tower per cell), or its
    /// gradient noise's across cell for kinds without Worley; `None` for a
    /// [`CloudKind::Uniform`] slab, which has no columns. The GPU's level of detail measures a
    /// pixel's footprint in these.
    pub fn column_cell_m(&self) -> Option<f64> {
        let shape = self.kind.shape().filter(|_| self.kind != CloudKind::Uniform)?;
        Some(if shape.worley_weight > 0.0 {
            shape.worley_cell_m
        } else {
            shape.perlin_cell_m[0]
        })
    }

    /// The share of rays through the layer that meet cloud where a pixel spans many columns,
    /// 0–1, for a ray that crosses the layer over `horizontal_m` metres measured along the
    /// ground, with `coverage` (0–1, the map's included) of the columns covered. The columns
    /// are taken as independent (Cahalan et al. 1994's independent-pixel approximation, along
    /// the ray), each covered with the chance `c = coverage ×`
    /// [`cover_share`](Self::cover_share): a ray that crosses `n` of them meets none with
    /// probability `(1 − c)ⁿ`. With `r` the crossing in units of [`COLUMN_SPACING_CELLS`]
    /// cells, `n = 1 + r²/(1 + r)`: one column looking straight down, where the layer shows its
    /// gaps; a column more every `COLUMN_SPACING_CELLS` cells at a grazing look, where it shows
    /// cloud everywhere; slowly at first, as domed clouds with gaps between show their sides
    /// only when seen well off the vertical. Fitted to the field's own mean transmittance
    /// (docs/CLOUDS.md, "Level of detail"). 1 for a uniform slab. The GPU's `cloud_cover_seen`.
    ///
    /// From afar the GPU marches the columns' mean density over this share (the cloud the rays
    /// that meet it see) and weights what it finds by it: the mean transmittance of the columns,
    /// `1 − cover + cover·e^(−τ/cover)`, rather than the mean optical depth's `e^(−τ)`, which
    /// would make a broken layer an even veil.
    pub fn cover_seen(&self, coverage: f64, horizontal_m: f64) -> f64 {
        let Some(cell) = self.column_cell_m() else {
            return 1.0;
        };
        let c = (coverage * self.cover_share()).clamp(0.0, 1.0);
        let r = horizontal_m.max(0.0) / (COLUMN_SPACING_CELLS * cell);
        1.0 - (1.0 - c).powf(1.0 + r * r / (1.0 + r))
    }

    /// The share `s` of the layer's `coverage` that counts as opaque cloud from afar, 0–1:
    /// covered columns thin out towards their edges, so that straight down the layer lets more
    /// through than its clear share. With `c = s·coverage` of the columns holding all the cloud,
    /// they let `1 − c + c·e^(−τ̄/c)` through, which `s` makes what the columns do, `mean
    /// e^(−τ)` (τ̄ their mean optical depth; the columns as the level of detail averages them,
    /// at the layer's own coverage, each integrated in 512 steps). 1 for a uniform slab and for
    /// a layer without cloud.
    pub fn cover_share(&self) -> f64 {
        if self.kind == CloudKind::Uniform || self.coverage.is_nan() || self.coverage <= 0.0 {
            return 1.0;
        }
        let (tau, transmittance) = field::columns_straight_down(&self.field_layer(), self.coverage);
        let blocked = 1.0 - transmittance;
        if tau.is_nan() || tau <= 0.0 || blocked.is_nan() || blocked <= 0.0 {
            return 1.0;
        }
        // c·(1 − e^(−τ̄/c)) rises with c; at c = coverage it is at least `blocked` (Jensen: one
        // optical depth for every covered column lets the least through).
        let blocked_by = |c: f64| c * (1.0 - (-tau / c).exp());
        let (mut lo, mut hi) = (0.0, self.coverage.min(1.0));
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if blocked_by(mid) < blocked {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi) / self.coverage
    }

    /// What the field reads of the layer.
    fn field_layer(&self) -> field::FieldLayer<'_> {
        field::FieldLayer {
            bottom_m: self.bottom_m,
            top_m: self.top_m,
            density_per_m: self.density_per_m,
            kind: self.kind,
            seed: self.seed,
            drift: self.drift,
            shape: self.kind.shape(),
        }
    }

    /// The layer's coverage at planet-frame point `p`, 0–1: `coverage`, times the coverage map
    /// at `p`'s geodetic latitude and longitude (its surface normal's) if it has one. The map is
    /// fixed to the planet: the wind moves the clouds, not the map.
    pub fn coverage_at(&self, planet: &Planet, p: DVec3) -> f64 {
        match &self.coverage_map {
            Some(map) => {
                let up = planet.up(p);
                self.coverage * map.sample(up.z.clamp(-1.0, 1.0).asin(), up.y.atan2(up.x))
            }
            None => self.coverage,
        }
    }

    /// The threshold of the column field for the layer's own `coverage` (no map): the
    /// `1 − coverage` quantile of its kind's column field ([`CloudShape::coverage_threshold`]);
    /// 0 for [`CloudKind::Uniform`]. What the GPU's uniforms carry, computed in `f64`.
    pub fn coverage_threshold(&self) -> f64 {
        self.kind
            .shape()
            .map_or(0.0, |shape| shape.coverage_threshold(self.coverage))
    }

    /// Checks the rules, naming the scene key with the layer's `index` (`clouds[2].coverage`):
    /// `0 ≤ bottom < top`, both finite (metres); `coverage` and `albedo` in 0–1; `density`
    /// finite and ≥ 0 (m⁻¹); `wind` finite; `phase` by [`DualHenyeyGreenstein::validate`]; and
    /// the wind's `drift` a finite unit rotation (reported as `wind`).
    pub fn validate(&self, index: usize) -> Result<(), CoreError> {
        let invalid = |key: &str, value: String, rule| {
            Err(CoreError::InvalidItem {
                field: format!("clouds[{index}].{key}"),
                value,
                rule,
            })
        };
        if !(self.bottom_m.is_finite() && self.bottom_m >= 0.0) {
            return invalid("bottom", self.bottom_m.to_string(), "must be a finite altitude >= 0 m");
        }
        if !self.top_m.is_finite() {
            return invalid("top", self.top_m.to_string(), "must be a finite altitude in m");
        }
        if self.top_m <= self.bottom_m {
            return invalid(
                "top",
                format!("{} (bottom = {})", self.top_m, self.bottom_m),
                "must be above bottom: 0 <= bottom < top",
            );
        }
        if !(0.0..=1.0).contains(&self.coverage) {
            return invalid("coverage", self.coverage.to_string(), "must be in 0-1");
        }
        if !(self.density_per_m.is_finite() && self.density_per_m >= 0.0) {
            return invalid(
                "density",
                self.density_per_m.to_string(),
                "must be a finite extinction >= 0 per m",
            );
        }
        if !self.wind_mps.iter().all(|w| w.is_finite()) {
            return invalid(
                "wind",
                format!("{:?}", self.wind_mps),
                "must be finite [east, north] m/s",
            );
        }
        if !(self.drift.is_finite() && self.drift.is_normalized()) {
            return invalid(
                "wind",
                format!("drift {:?}", self.drift.to_array()),
                "the wind's drift must be a finite unit rotation",
            );
        }
        if !(0.0..=1.0).contains(&self.albedo) {
            return invalid("albedo", self.albedo.to_string(), "must be in 0-1");
        }
        self.phase.validate(&format!("clouds[{index}].phase"))
    }
}

/// Checks the number of layers (at most [`MAX_CLOUD_LAYERS`], reported as `clouds`) and every
/// layer ([`CloudLayer::validate`]).
pub fn validate_layers(layers: &[CloudLayer]) -> Result<(), CoreError> {
    if layers.len() > MAX_CLOUD_LAYERS {
        return Err(CoreError::Invalid {
            field: "clouds",
            value: format!("{} layers", layers.len()),
            rule: "a sky has at most 8 cloud layers",
        });
    }
    layers
        .iter()
        .enumerate()
        .try_for_each(|(index, layer)| layer.validate(index))
}
