//! Cube faces → one horizontal-cross image ([`firmament_core::envmap::cross`]).

use firmament_core::envmap::{CROSS_CELLS, CubeFace};

use super::CubeFaces;
use crate::headless::Image;

impl CubeFaces {
    /// The six faces in one `4·size × 3·size` image laid out as a horizontal cross
    /// ([`firmament_core::envmap::cross`]: `+Y` above the second column, `−X +Z +X −Z` across
    /// the middle row, `−Y` below the second column), each face's texels as they are; the six
    /// unused cells are black with alpha 0.
    pub fn to_horizontal_cross(&self) -> Image<f32> {
        let size = self.size as usize;
        let width = CROSS_CELLS.0 as usize * size;
        let height = CROSS_CELLS.1 as usize * size;
        let mut pixels = vec![0.0_f32; 4 * width * height];
        for face in CubeFace::ALL {
            let (column, row) = face.cross_cell();
            let (x0, y0) = (column as usize * size, row as usize * size);
            let image = self.face(face);
            for (j, line) in image.pixels.chunks_exact(4 * size).enumerate() {
                let start = 4 * ((y0 + j) * width + x0);
                pixels[start..start + 4 * size].copy_from_slice(line);
            }
        }
        Image {
            width: width as u32,
            height: height as u32,
            pixels,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::envmap::tests::direction_cube;
    use firmament_core::envmap::{cross_face, cross_position, cube_direction, cube_position};
    use glam::{DVec2, DVec3};

    /// A direction → its face texel → that texel's pixel in the cross, which holds the direction;
    /// the unused cells are transparent black.
    #[test]
    fn the_cross_holds_each_direction_where_the_layout_says() {
        let size = 8;
        let cross = direction_cube(size).to_horizontal_cross();
        assert_eq!((cross.width, cross.height), (32, 24));
        for d in [
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
            DVec3::new(0.3, -0.8, 0.2),
        ] {
            let d = d.normalize();
            let (face, texel) = cube_position(d, size);
            let centre = (texel.floor() + 0.5).min(DVec2::splat(f64::from(size) - 0.5));
            let p = cross_position(face, centre, size);
            let pixel = cross.pixel(p.x as u32, p.y as u32).expect("inside");
            let want = cube_direction(face, centre.x, centre.y, size);
            let got = DVec3::new(f64::from(pixel[0]), f64::from(pixel[1]), f64::from(pixel[2]));
            assert!((got - want).length() < 1e-6, "{d}: {got} vs {want}");
            assert!(got.dot(d) > 0.95, "{d}: {got}");
            assert_eq!(pixel[3], 1.0);
        }
        for j in 0..cross.height {
            for i in 0..cross.width {
                let used = cross_face(DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5), size).is_some();
                let alpha = cross.pixel(i, j).expect("inside")[3];
                assert_eq!(alpha, if used { 1.0 } else { 0.0 }, "({i}, {j})");
            }
        }
    }
}
