//! [`SurfaceMap`]: albedo and water over the globe, an equirectangular map.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::sync::Arc;

use crate::error::CoreError;

/// An equirectangular map of the surface: per texel the linear albedo in red, green and blue and
/// the water fraction, all 0–1. Longitude −180° … 180° from left to right, latitude 90° … −90°
/// from top to bottom (geodetic).
///
/// Texel `(i, j)` (column `i`, row `j`, row 0 at the top) holds the value at its centre; between
/// centres the map is bilinear, wrapping in longitude and clamped to the first and last rows
/// towards the poles — what a GPU sampler with linear filtering, `Repeat` in u and `ClampToEdge`
/// in v reads at `u = (longitude + π)/2π`, `v = (π/2 − latitude)/π` (as
/// [`CoverageMap`](crate::atmosphere::clouds::coverage::CoverageMap)).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMap {
    width: u32,
    height: u32,
    texels: Arc<[[f32; 4]]>,
    /// [`Self::mean`], taken once: a scene's surface is converted every frame.
    mean: [f64; 4],
}

impl SurfaceMap {
    /// A `width` × `height` map of `texels` (`[red, green, blue, water]`), row by row from the
    /// top, each row from longitude −180°. Both sizes must be ≥ 1, one texel per cell, every
    /// value finite and in 0–1.
    pub fn new(width: u32, height: u32, texels: Vec<[f32; 4]>) -> Result<Self, CoreError> {
        let invalid = |value: String, rule| {
            Err(CoreError::Invalid {
                field: "surface_map",
                value,
                rule,
            })
        };
        if width == 0 || height == 0 {
            return invalid(format!("{width}x{height}"), "a surface map needs at least 1x1 texels");
        }
        if texels.len() as u64 != u64::from(width) * u64::from(height) {
            return invalid(
                format!("{} texels for {width}x{height}", texels.len()),
                "a surface map needs one texel per cell",
            );
        }
        if let Some(bad) = texels.iter().flatten().find(|v| !(0.0..=1.0).contains(*v)) {
            return invalid(bad.to_string(), "albedos and water fractions must be finite and in 0-1");
        }
        let mean = area_mean(width, height, &texels);
        Ok(Self {
            width,
            height,
            texels: texels.into(),
            mean,
        })
    }

    /// One value everywhere: `[red, green, blue, water]`.
    pub fn uniform(texel: [f32; 4]) -> Result<Self, CoreError> {
        Self::new(1, 1, vec![texel])
    }

    /// Texels across (longitude).
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Texels down (latitude).
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texels, row by row from the top, each row from longitude −180°.
    pub fn texels(&self) -> &[[f32; 4]] {
        &self.texels
    }

    /// `[red, green, blue, water]` at geodetic `latitude_rad` and `longitude_rad` (any
    /// longitude, wrapped), bilinear between texel centres.
    pub fn sample(&self, latitude_rad: f64, longitude_rad: f64) -> [f64; 4] {
        let mut out = [0.0; 4];
        for (index, weight) in equirect_bilinear(self.width, self.height, latitude_rad, longitude_rad) {
            for (o, v) in out.iter_mut().zip(self.texels[index]) {
                *o += weight * f64::from(v);
            }
        }
        out.map(|v| v.clamp(0.0, 1.0))
    }

    /// The map's mean over the sphere, each texel weighted by its area (the cosine of its
    /// latitude): `[red, green, blue, water]`.
    pub fn mean(&self) -> [f64; 4] {
        self.mean
    }
}

/// The area-weighted mean of `width` × `height` texels (see [`SurfaceMap::mean`]).
fn area_mean(width: u32, height: u32, texels: &[[f32; 4]]) -> [f64; 4] {
    let mut sum = [0.0; 4];
    let mut weights = 0.0;
    for (row, texels) in texels.chunks(width as usize).enumerate() {
        let latitude = FRAC_PI_2 - (row as f64 + 0.5) * PI / f64::from(height);
        let weight = latitude.cos();
        weights += weight * f64::from(width);
        for texel in texels {
            for (s, v) in sum.iter_mut().zip(texel) {
                *s += weight * f64::from(*v);
            }
        }
    }
    sum.map(|s| s / weights)
}

/// The geodetic (latitude, longitude), radians, of every texel centre of a `width` × `height`
/// equirectangular map, row by row from the top, each row from longitude −180°: where a map is
/// resampled onto a GPU texture of that size.
pub fn texel_centres(width: u32, height: u32) -> impl Iterator<Item = (f64, f64)> {
    (0..height).flat_map(move |row| {
        let latitude = FRAC_PI_2 - (f64::from(row) + 0.5) * PI / f64::from(height);
        (0..width).map(move |column| (latitude, -PI + (f64::from(column) + 0.5) * TAU / f64::from(width)))
    })
}

/// The four texels (indices into a row-major `width` × `height` map, row 0 at latitude 90°) and
/// their bilinear weights at geodetic `latitude_rad`, `longitude_rad`: texel centres as
/// [`SurfaceMap`] places them, wrapping in longitude, clamped to the end rows.
pub(crate) fn equirect_bilinear(width: u32, height: u32, latitude_rad: f64, longitude_rad: f64) -> [(usize, f64); 4] {
    let (w, h) = (f64::from(width), f64::from(height));
    let u = (longitude_rad + PI).rem_euclid(TAU) / TAU;
    let x = u * w - 0.5;
    let y = ((FRAC_PI_2 - latitude_rad) / PI * h - 0.5).clamp(0.0, h - 1.0);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let column = |c: f64| c.rem_euclid(w) as usize % width as usize;
    let (c0, c1) = (column(x0), column(x0 + 1.0));
    let r0 = y0 as usize;
    let r1 = (r0 + 1).min(height as usize - 1);
    let at = |r: usize, c: usize| r * width as usize + c;
    [
        (at(r0, c0), (1.0 - fx) * (1.0 - fy)),
        (at(r0, c1), fx * (1.0 - fy)),
        (at(r1, c0), (1.0 - fx) * fy),
        (at(r1, c1), fx * fy),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_centres_hold_their_values_and_longitude_wraps() {
        // 4 × 2: longitudes −135°, −45°, 45°, 135°; latitudes 45°, −45°.
        let texels = (0..8)
            .map(|i| [i as f32 / 8.0, 0.5, 0.25, if i < 4 { 1.0 } else { 0.0 }])
            .collect();
        let map = SurfaceMap::new(4, 2, texels).unwrap();
        let d = f64::to_radians;
        assert!((map.sample(d(45.0), d(-135.0))[0] - 0.0).abs() < 1e-7);
        assert!((map.sample(d(-45.0), d(45.0))[0] - 6.0 / 8.0).abs() < 1e-7);
        // Across the date line, halfway between 135° (3/8) and −135° (0).
        assert!((map.sample(d(45.0), d(180.0))[0] - 3.0 / 16.0).abs() < 1e-7);
        // Halfway between the rows: water 1 above, 0 below.
        assert!((map.sample(0.0, d(45.0))[3] - 0.5).abs() < 1e-7);
        // The end rows hold towards the poles.
        assert!((map.sample(d(90.0), d(45.0))[3] - 1.0).abs() < 1e-7);
    }

    #[test]
    fn the_mean_weights_by_area() {
        // Water in the top row only; rows are weighted by the cosine of their centres'
        // latitudes (60°, 0°, −60°): 0.5 / (0.5 + 1 + 0.5).
        let height = 3;
        let texels = (0..height)
            .flat_map(|row| std::iter::repeat_n([0.1, 0.2, 0.3, if row == 0 { 1.0 } else { 0.0 }], 2))
            .collect();
        let map = SurfaceMap::new(2, height, texels).unwrap();
        let mean = map.mean();
        assert!((mean[0] - 0.1).abs() < 1e-7 && (mean[2] - 0.3).abs() < 1e-7);
        // Texel-centre weights: cos 60°, cos 0°, cos 60° → 0.5 / 2.
        assert!((mean[3] - 0.25).abs() < 1e-12, "{}", mean[3]);
    }

    #[test]
    fn bad_maps_are_refused() {
        assert!(SurfaceMap::new(0, 1, vec![]).is_err());
        assert!(SurfaceMap::new(2, 1, vec![[0.0; 4]]).is_err());
        assert!(SurfaceMap::uniform([0.1, 0.2, f32::NAN, 0.0]).is_err());
        assert!(SurfaceMap::uniform([0.1, 0.2, 0.3, 1.5]).is_err());
        assert!(SurfaceMap::uniform([0.1, -0.2, 0.3, 0.0]).is_err());
    }
}
