//! A layer's coverage over the planet: an equirectangular map.

use std::sync::Arc;

use crate::atmosphere::surface::map::equirect_bilinear;
use crate::error::CoreError;

/// An equirectangular map of a layer's coverage over the planet: longitude −180° … 180° from
/// left to right, latitude 90° … −90° from top to bottom (geodetic), values 0–1.
///
/// Texel `(i, j)` (column `i`, row `j`, row 0 at the top) is the value at its centre, longitude
/// `−180° + (i + ½)·360°/width` and latitude `90° − (j + ½)·180°/height`; between centres the map
/// is bilinear, wrapping around in longitude and clamped to the first and last rows towards the
/// poles: what a GPU sampler with linear filtering, `Repeat` in u and `ClampToEdge` in v reads at
/// `u = (longitude + π)/2π`, `v = (π/2 − latitude)/π`.
#[derive(Debug, Clone, PartialEq)]
pub struct CoverageMap {
    width: u32,
    height: u32,
    values: Arc<[f32]>,
}

impl CoverageMap {
    /// A `width` × `height` map of `values`, row by row from the top (latitude 90°), each row from
    /// longitude −180°. Both sizes must be ≥ 1, `values.len() == width · height`, and every value
    /// finite and in 0–1.
    pub fn new(width: u32, height: u32, values: Vec<f32>) -> Result<Self, CoreError> {
        let invalid = |value: String, rule| {
            Err(CoreError::Invalid {
                field: "coverage_map",
                value,
                rule,
            })
        };
        if width == 0 || height == 0 {
            return invalid(format!("{width}x{height}"), "a coverage map needs at least 1x1 texels");
        }
        if values.len() as u64 != u64::from(width) * u64::from(height) {
            return invalid(
                format!("{} values for {width}x{height} texels", values.len()),
                "a coverage map needs one value per texel",
            );
        }
        if let Some(bad) = values.iter().find(|v| !(0.0..=1.0).contains(*v)) {
            return invalid(bad.to_string(), "coverage map values must be finite and in 0-1");
        }
        Ok(Self {
            width,
            height,
            values: values.into(),
        })
    }

    /// Texels across (longitude).
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Texels down (latitude).
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The values, row by row from the top, each row from longitude −180°.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The coverage at geodetic `latitude` and `longitude` (radians; any longitude, wrapped),
    /// bilinear between texel centres, 0–1.
    pub fn sample(&self, latitude_rad: f64, longitude_rad: f64) -> f64 {
        let value: f64 = equirect_bilinear(self.width, self.height, latitude_rad, longitude_rad)
            .iter()
            .map(|(index, weight)| weight * f64::from(self.values[*index]))
            .sum();
        value.clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> CoverageMap {
        // 4 × 2: longitudes −135°, −45°, 45°, 135° at the centres; latitudes 45°, −45°.
        CoverageMap::new(4, 2, vec![0.0, 0.25, 0.5, 1.0, 0.1, 0.2, 0.3, 0.4]).unwrap()
    }

    #[test]
    fn texel_centres_hold_their_values() {
        let m = map();
        let d = f64::to_radians;
        assert!((m.sample(d(45.0), d(-135.0)) - 0.0).abs() < 1e-7);
        assert!((m.sample(d(45.0), d(-45.0)) - 0.25).abs() < 1e-7);
        assert!((m.sample(d(45.0), d(135.0)) - 1.0).abs() < 1e-7);
        assert!((m.sample(d(-45.0), d(45.0)) - 0.3).abs() < 1e-7);
    }

    #[test]
    fn bilinear_wrapping_in_longitude_and_clamped_at_the_poles() {
        let m = map();
        let d = f64::to_radians;
        // Halfway between centres.
        assert!((m.sample(d(45.0), d(-90.0)) - 0.125).abs() < 1e-7);
        assert!((m.sample(d(0.0), d(-135.0)) - 0.05).abs() < 1e-7);
        // Across the date line: between 135° (1.0) and −135° (0.0).
        assert!((m.sample(d(45.0), d(180.0)) - 0.5).abs() < 1e-7);
        assert!((m.sample(d(45.0), d(-180.0)) - 0.5).abs() < 1e-7);
        assert!((m.sample(d(45.0), d(180.0 + 360.0)) - 0.5).abs() < 1e-7);
        // Towards the poles the first and last rows hold.
        assert!((m.sample(d(90.0), d(45.0)) - 0.5).abs() < 1e-7);
        assert!((m.sample(d(-90.0), d(45.0)) - 0.3).abs() < 1e-7);
        // One texel is the same everywhere.
        let one = CoverageMap::new(1, 1, vec![0.7]).unwrap();
        assert!((one.sample(0.3, -2.0) - 0.7).abs() < 1e-6);
    }

    #[test]
    fn bad_maps_are_refused() {
        assert!(CoverageMap::new(0, 2, vec![]).is_err());
        assert!(CoverageMap::new(2, 2, vec![0.0; 3]).is_err());
        assert!(CoverageMap::new(1, 1, vec![1.5]).is_err());
        assert!(CoverageMap::new(1, 1, vec![f32::NAN]).is_err());
        assert!(CoverageMap::new(1, 1, vec![-0.1]).is_err());
        let m = map();
        assert_eq!((m.width(), m.height(), m.values().len()), (4, 2, 8));
    }
}
