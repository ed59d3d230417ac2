//! Integer-hashed lattice noise for the cloud density field, written so that the GPU's `f32`
//! mirror (`shaders/clouds/density.wgsl`) agrees with this `f64` code on the lattice exactly.
//!
//! # Why the mirror agrees
//! - Lattice cells are `floor(q)` of a point `q` in *cell units* (metres times a power of two:
//!   every feature size is `2^k` m, so the scaling is exact in `f32` as in `f64`). They are hashed
//!   as `u32` bit patterns with wrapping `u32` arithmetic only: Chris Wellons's "lowbias32"
//!   (<https://nullprogram.com/blog/2018/07/31/>), chained over the cell's x, y, z after a key
//!   made from the layer's seed, its kind and a salt per field. Every value derived from a hash is
//!   a small integer times a power of two (exact in `f32`).
//! - The fractional part `q − floor(q)` is exact in both precisions. `f32` cannot hold a
//!   planet-frame pattern point near 6.4·10⁶ m closer than 0.5 m, so the shader never forms it:
//!   it keeps `q = R·p` as three exact products and a small rest and splits each term into cell
//!   and fraction on its own (`cloud_cell` in the shader). Its lattice and fractions are then this
//!   code's to ~10⁻⁴ m for any drift; the noises are continuous (quintic fade; Worley's distance),
//!   so what rounding is left moves values by their gradient times that, never across a hash.
//! - `|q|` in cell units stays far below 2²⁴ (a point 10⁸ m from the centre at 256 m cells is at
//!   4·10⁵), so `i32(floor(q))` is exact and in range.
//!
//! Gradient noise is Perlin's improved noise ("Improving Noise", SIGGRAPH 2002: quintic fade,
//! 12 edge gradients picked by 4 hash bits); Worley's cellular noise ("A Cellular Texture Basis
//! Function", SIGGRAPH 1996) has one feature point per cell at 10-bit offsets, searched over the
//! 27 neighbouring cells, and is used squared (F1²: smooth, rounded puffs).

use glam::DVec3;

/// Chris Wellons's "lowbias32" integer hash (bias 0.17): a bijection of `u32` with good avalanche.
pub(crate) const fn lowbias32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// The key of one noise field of a layer of kind `kind_code` ([`CloudKind::code`]): its seed
/// mixed with the field's `salt` and the kind (so that two kinds with one seed differ).
///
/// [`CloudKind::code`]: super::CloudKind::code
pub(crate) const fn field_key(seed: u32, kind_code: u32, salt: u32) -> u32 {
    lowbias32(seed ^ lowbias32(salt ^ (kind_code << 24)))
}

/// Salts of the fields (one per field and octave, so no two share a lattice).
pub(crate) mod salt {
    /// The column field's Worley cells.
    pub(crate) const COLUMN_WORLEY: u32 = 0xc10d_0001;
    /// The column field's gradient noise, first octave.
    pub(crate) const COLUMN_PERLIN_1: u32 = 0xc10d_0002;
    /// The column field's gradient noise, second octave.
    pub(crate) const COLUMN_PERLIN_2: u32 = 0xc10d_0003;
    /// The column field's gradient noise, third octave.
    pub(crate) const COLUMN_PERLIN_3: u32 = 0xc10d_0004;
    /// The detail's Worley cells.
    pub(crate) const DETAIL_WORLEY: u32 = 0xc10d_0011;
    /// The detail's gradient noise, first octave.
    pub(crate) const DETAIL_PERLIN_1: u32 = 0xc10d_0012;
    /// The detail's gradient noise, second octave.
    pub(crate) const DETAIL_PERLIN_2: u32 = 0xc10d_0013;
}

/// The hash of lattice cell `cell` under `key`.
pub(crate) fn hash_cell(cell: [i32; 3], key: u32) -> u32 {
    let h = lowbias32(key ^ cell[0] as u32);
    let h = lowbias32(h ^ cell[1] as u32);
    lowbias32(h ^ cell[2] as u32)
}

/// The cell of `q` (cell units) and the offset within it, `[0, 1)`.
fn split(q: DVec3) -> ([i32; 3], DVec3) {
    let floor = q.floor();
    ([floor.x as i32, floor.y as i32, floor.z as i32], q - floor)
}

/// Perlin's quintic fade `6t⁵ − 15t⁴ + 10t³`.
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Perlin's improved-noise gradient: one of 12 cube edge directions (4 repeated), from the
/// hash's top four bits, dotted with `f`.
fn gradient(hash: u32, f: DVec3) -> f64 {
    let h = hash >> 28;
    let u = if h < 8 { f.x } else { f.y };
    let v = if h < 4 {
        f.y
    } else if h == 12 || h == 14 {
        f.x
    } else {
        f.z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

/// Perlin's improved gradient noise at `q` (cell units): about −1 … 1, 0 at lattice points.
pub(crate) fn perlin(q: DVec3, key: u32) -> f64 {
    let (c, f) = split(q);
    let corner = |dx: i32, dy: i32, dz: i32| {
        let h = hash_cell(
            [c[0].wrapping_add(dx), c[1].wrapping_add(dy), c[2].wrapping_add(dz)],
            key,
        );
        gradient(h, f - DVec3::new(f64::from(dx), f64::from(dy), f64::from(dz)))
    };
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), u);
    let x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), u);
    let x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), u);
    let x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), u);
    lerp(lerp(x00, x10, v), lerp(x01, x11, v), w)
}

/// Two octaves of [`perlin`] (lacunarity 2, gain ½) scaled back to about −1 … 1; `keys` per
/// octave.
pub(crate) fn fbm2(q: DVec3, keys: [u32; 2]) -> f64 {
    (perlin(q, keys[0]) + 0.5 * perlin(q * 2.0, keys[1])) * (2.0 / 3.0)
}

/// Three octaves of [`perlin`] (lacunarity 2, gain ½) scaled back to about −1 … 1; `keys` per
/// octave.
pub(crate) fn fbm3(q: DVec3, keys: [u32; 3]) -> f64 {
    (perlin(q, keys[0]) + 0.5 * perlin(q * 2.0, keys[1]) + 0.25 * perlin(q * 4.0, keys[2])) * (4.0 / 7.0)
}

/// Worley's F1² at `q` (cell units): the squared distance to the nearest feature point, one per
/// cell at offsets `(k + ½)/1024` (10 bits per axis of the cell's hash), 0 … about 1.4 (typically
/// ≤ 0.8). Squared, `1 − F1²` is a smooth paraboloid about each feature point: rounded tops.
pub(crate) fn worley_squared(q: DVec3, key: u32) -> f64 {
    let (c, f) = split(q);
    let mut nearest = f64::INFINITY;
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let h = hash_cell(
                    [c[0].wrapping_add(dx), c[1].wrapping_add(dy), c[2].wrapping_add(dz)],
                    key,
                );
                let offset = DVec3::new(
                    f64::from(h & 1023),
                    f64::from((h >> 10) & 1023),
                    f64::from((h >> 20) & 1023),
                ) * (1.0 / 1024.0)
                    + 1.0 / 2048.0;
                let d = DVec3::new(f64::from(dx), f64::from(dy), f64::from(dz)) + offset - f;
                nearest = nearest.min(d.length_squared());
            }
        }
    }
    nearest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lowbias32_matches_published_values() {
        // Values of Wellons's reference C code (the WGSL mirror must give the same), and the
        // hash is a bijection.
        assert_eq!(lowbias32(0), 0);
        assert_eq!(lowbias32(1), 0x6889_90c0);
        assert_eq!(lowbias32(2), 0xd113_2181);
        assert_eq!(lowbias32(0xdead_beef), 0xe628_c683);
        let mut seen = std::collections::HashSet::new();
        for x in 0..100_000u32 {
            assert!(seen.insert(lowbias32(x)), "collision at {x}");
        }
    }

    #[test]
    fn perlin_is_zero_on_the_lattice_continuous_and_bounded() {
        let key = field_key(7, 0, salt::COLUMN_PERLIN_1);
        let mut max: f64 = 0.0;
        for i in 0..20_000 {
            let t = f64::from(i);
            let q = DVec3::new(t * 0.137 - 900.0, t * 0.071 + 13.0, (t * 0.31).sin() * 50.0);
            let n = perlin(q, key);
            max = max.max(n.abs());
            // Continuity across cell faces: a step of 1e-9 cells changes the value by ≲ 1e-8.
            let e = DVec3::splat(1e-9);
            assert!((perlin(q + e, key) - n).abs() < 1e-7);
            assert_eq!(perlin(q.floor(), key), 0.0);
        }
        assert!(max <= 1.1 && max > 0.5, "{max}");
    }

    #[test]
    fn worley_is_continuous_and_bounded() {
        let key = field_key(3, 0, salt::COLUMN_WORLEY);
        for i in 0..5_000 {
            let t = f64::from(i);
            let q = DVec3::new(t * 0.0137 + 1e4, t * 0.0071 - 3e3, t * 0.0031);
            let f1 = worley_squared(q, key);
            assert!((0.0..1.7).contains(&f1), "{f1}");
            assert!((worley_squared(q + DVec3::splat(1e-6), key) - f1).abs() < 1e-5);
        }
    }

    #[test]
    fn cells_beside_each_other_and_keys_hash_apart() {
        let a = hash_cell([0, 0, 0], 1);
        assert_ne!(a, hash_cell([1, 0, 0], 1));
        assert_ne!(a, hash_cell([0, 1, 0], 1));
        assert_ne!(a, hash_cell([0, 0, 1], 1));
        assert_ne!(a, hash_cell([0, 0, 0], 2));
        assert_ne!(hash_cell([-1, 0, 0], 1), hash_cell([1, 0, 0], 1));
    }
}
