//! A seeded planet surface: continents and oceans from fractal noise on the sphere, land
//! coloured by latitude and moisture, ice caps at the poles — baked into a [`SurfaceMap`].
//!
//! Noise is value noise on an integer lattice in 3-D (so the sphere has no seam or pinch at the
//! poles), hashed from the seed, summed over octaves (fractional Brownian motion). The land
//! share is exact: the sea level is the map's [`LAND_SHARE`] quantile by area. Albedos are typical
//! values of Earth's surfaces in linear sRGB (forest ~0.05–0.1, grassland ~0.15, desert ~0.3,
//! snow and ice ~0.8; the ranges of Liang, "Quantitative Remote Sensing of Land Surfaces", Wiley
//! 2004).

use std::f64::consts::{FRAC_PI_2, PI};

use glam::DVec3;
use rayon::prelude::*;

use super::SurfaceMap;
use crate::error::CoreError;

/// The share of the globe's area that is land (Earth's: 0.29).
pub const LAND_SHARE: f64 = 0.29;

/// The size [`bake`] makes a map at unless asked otherwise, texels.
pub const DEFAULT_SIZE: (u32, u32) = (1024, 512);

/// Deep water's diffuse albedo, linear sRGB: the light the water body sends back up (open ocean,
/// about 0.5 % in red to 3.5 % in blue), the glint aside.
pub const WATER_ALBEDO: [f32; 3] = [0.006, 0.012, 0.035];

const ICE: [f64; 3] = [0.80, 0.82, 0.86];
const FOREST: [f64; 3] = [0.05, 0.08, 0.04];
const GRASSLAND: [f64; 3] = [0.13, 0.15, 0.07];
const DESERT: [f64; 3] = [0.38, 0.29, 0.18];
const TUNDRA: [f64; 3] = [0.14, 0.13, 0.11];

/// Bakes the surface of `seed` into a `width` × `height` map (both ≥ 2).
pub fn bake(seed: u64, width: u32, height: u32) -> Result<SurfaceMap, CoreError> {
    if width < 2 || height < 2 {
        return Err(CoreError::Invalid {
            field: "surface_map",
            value: format!("{width}x{height}"),
            rule: "a procedural surface needs at least 2x2 texels",
        });
    }
    let points: Vec<(f64, DVec3)> = (0..height)
        .flat_map(|row| (0..width).map(move |column| (row, column)))
        .map(|(row, column)| {
            let latitude = FRAC_PI_2 - (f64::from(row) + 0.5) * PI / f64::from(height);
            let longitude = -PI + (f64::from(column) + 0.5) * 2.0 * PI / f64::from(width);
            (latitude, super::super::planet::geodetic_normal(latitude, longitude))
        })
        .collect();
    let elevation: Vec<f64> = points.par_iter().map(|(_, p)| fbm(seed, *p * 1.6, 7)).collect();
    let sea_level = area_quantile(&points, &elevation, 1.0 - LAND_SHARE);
    let texels = points
        .par_iter()
        .zip(&elevation)
        .map(|((latitude, p), e)| texel(seed, *latitude, *p, e - sea_level))
        .collect();
    SurfaceMap::new(width, height, texels)
}

/// The value below which `share` of the sphere's area lies, texels weighted by the cosine of
/// their latitude.
fn area_quantile(points: &[(f64, DVec3)], values: &[f64], share: f64) -> f64 {
    let mut weighted: Vec<(f64, f64)> = values.iter().zip(points).map(|(v, (lat, _))| (*v, lat.cos())).collect();
    weighted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = weighted.iter().map(|w| w.1).sum();
    let mut below = 0.0;
    for (value, weight) in &weighted {
        below += weight;
        if below >= share * total {
            return *value;
        }
    }
    weighted.last().map_or(0.0, |w| w.0)
}

/// One texel at `latitude` (radians), unit position `p`, `height` above the sea level (noise
/// units).
fn texel(seed: u64, latitude: f64, p: DVec3, height: f64) -> [f32; 4] {
    // A soft coast over a small band of heights, so coastlines are anti-aliased.
    let land = smoothstep(-0.004, 0.004, height);
    let moisture = fbm(seed ^ 0x9e37_79b9_7f4a_7c15, p * 2.3, 5);
    let wobble = fbm(seed ^ 0x5851_f42d_4c95_7f2d, p * 6.0, 3);
    let polar = latitude.abs().to_degrees() + 8.0 * wobble;
    // Deserts in the dry subtropics, forest where it is wet, tundra towards the ice.
    let subtropical = smoothstep(8.0, 18.0, polar) * (1.0 - smoothstep(32.0, 40.0, polar));
    let dry = subtropical * (1.0 - smoothstep(0.45, 0.6, moisture + 0.25 * height.min(0.2)));
    let wet = smoothstep(0.5, 0.62, moisture);
    let mut ground = mix(GRASSLAND, FOREST, wet);
    ground = mix(ground, DESERT, dry);
    ground = mix(ground, TUNDRA, smoothstep(52.0, 62.0, polar));
    // Ice caps: on land above ~66°, over the sea (pack ice) above ~74°.
    let ice = smoothstep(64.0, 68.0, polar) * land + smoothstep(72.0, 76.0, polar) * (1.0 - land);
    let water_albedo = WATER_ALBEDO.map(f64::from);
    let surface = mix(mix(water_albedo, ground, land), ICE, ice);
    let water = (1.0 - land) * (1.0 - ice);
    [surface[0] as f32, surface[1] as f32, surface[2] as f32, water as f32]
}

fn mix(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Fractional Brownian motion: `octaves` of value noise, each twice the frequency and half the
/// amplitude of the last, about 0.5 on average, in 0–1.
fn fbm(seed: u64, p: DVec3, octaves: u32) -> f64 {
    let (mut sum, mut amplitude, mut norm, mut frequency) = (0.0, 0.5, 0.0, 1.0);
    for octave in 0..octaves {
        sum += amplitude * value_noise(seed.wrapping_add(u64::from(octave)), p * frequency);
        norm += amplitude;
        amplitude *= 0.5;
        frequency *= 2.03;
    }
    sum / norm
}

/// Value noise: a hashed value at each lattice point, blended with a quintic fade, in 0–1.
fn value_noise(seed: u64, p: DVec3) -> f64 {
    let cell = p.floor();
    let f = p - cell;
    let fade = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    let (x, y, z) = (cell.x as i64, cell.y as i64, cell.z as i64);
    let corner = |dx: i64, dy: i64, dz: i64| lattice_value(seed, x + dx, y + dy, z + dz);
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), fade.x);
    let x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), fade.x);
    let x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), fade.x);
    let x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), fade.x);
    lerp(lerp(x00, x10, fade.y), lerp(x01, x11, fade.y), fade.z)
}

/// A value in 0–1 for a lattice point: SplitMix64's finaliser over the seed and coordinates.
fn lattice_value(seed: u64, x: i64, y: i64, z: i64) -> f64 {
    let mut h = seed
        ^ (x as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ (y as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)
        ^ (z as u64).wrapping_mul(0x1656_67b1_9e37_79f9);
    h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    h ^= h >> 31;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_makes_one_surface_with_earths_land_share() {
        let a = bake(7, 128, 64).unwrap();
        assert_eq!(a, bake(7, 128, 64).unwrap());
        assert_ne!(a, bake(8, 128, 64).unwrap());
        let [_, _, _, water] = a.mean();
        // Water is the sea not under ice: a little under 1 − LAND_SHARE.
        assert!(water > 0.6 && water < 1.0 - LAND_SHARE + 0.01, "{water}");
        // The poles are ice, bright.
        assert!(a.sample(FRAC_PI_2, 0.0)[1] > 0.7);
        assert!(a.sample(-FRAC_PI_2, 2.0)[1] > 0.7);
        assert!(bake(1, 1, 8).is_err());
    }
}
