//! Cube faces → equirectangular map, bilinear, on every core.

use firmament_core::envmap::{cube_position, equirect_direction};
use glam::DVec3;
use rayon::prelude::*;

use super::CubeFaces;
use crate::headless::Image;

/// The radiance of `cube` along unit ENU `direction`: bilinear between the four texel centres
/// around it on its face (clamped to the face's outer texel centres at its edges).
pub(super) fn sample_cube(cube: &CubeFaces, direction: DVec3) -> [f32; 3] {
    let size = cube.size;
    let (face, p) = cube_position(direction, size);
    let image = &cube.faces[face.index()];
    let last = f64::from(size - 1);
    let x = (p.x - 0.5).clamp(0.0, last);
    let y = (p.y - 0.5).clamp(0.0, last);
    let (x0, y0) = (x.floor() as u32, y.floor() as u32);
    let (x1, y1) = ((x0 + 1).min(size - 1), (y0 + 1).min(size - 1));
    let (fx, fy) = ((x - x.floor()) as f32, (y - y.floor()) as f32);
    let texel = |i: u32, j: u32| {
        let k = 4 * (j as usize * size as usize + i as usize);
        [image.pixels[k], image.pixels[k + 1], image.pixels[k + 2]]
    };
    let (a, b, c, d) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
    std::array::from_fn(|ch| {
        let top = a[ch] + (b[ch] - a[ch]) * fx;
        let bottom = c[ch] + (d[ch] - c[ch]) * fx;
        top + (bottom - top) * fy
    })
}

/// The `width` × `width / 2` equirectangular map of `cube`, each pixel sampled at its centre.
pub(super) fn equirect_from_cube(cube: &CubeFaces, width: u32) -> Image<f32> {
    let height = width / 2;
    let mut pixels = vec![0.0_f32; 4 * width as usize * height as usize];
    pixels
        .par_chunks_exact_mut(4 * width as usize)
        .enumerate()
        .for_each(|(j, row)| {
            for (i, pixel) in row.chunks_exact_mut(4).enumerate() {
                let d = equirect_direction(i as f64 + 0.5, j as f64 + 0.5, width, height);
                let [r, g, b] = sample_cube(cube, d);
                pixel.copy_from_slice(&[r, g, b, 1.0]);
            }
        });
    Image { width, height, pixels }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envmap::tests::direction_cube;
    use firmament_core::envmap::equirect_pixel_solid_angle;

    /// Resampled, every equirectangular pixel holds (nearly) its own direction: the two
    /// projections agree, and the map's ∫ z·cos over the upper hemisphere is 2π/3.
    #[test]
    fn resampling_keeps_directions() {
        let cube = direction_cube(64);
        let (width, height) = (256, 128);
        let map = equirect_from_cube(&cube, width);
        let mut worst: f64 = 0.0;
        let mut integral = 0.0;
        for j in 0..height {
            for i in 0..width {
                let want = equirect_direction(f64::from(i) + 0.5, f64::from(j) + 0.5, width, height);
                let p = map.pixel(i, j).expect("inside");
                let got = DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                worst = worst.max((got - want).length());
                if want.z > 0.0 {
                    integral += got.z * want.z * equirect_pixel_solid_angle(j, width, height);
                }
            }
        }
        // Bilinear between texel centres 1.4° apart on a curved field: at most ~1 %.
        assert!(worst < 0.02, "worst {worst}");
        let want = 2.0 * std::f64::consts::PI / 3.0;
        assert!((integral / want - 1.0).abs() < 1e-3, "{integral} vs {want}");
    }
}
