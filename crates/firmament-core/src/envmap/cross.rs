//! The horizontal cross: the six cube faces in one `4·size × 3·size` image, unfolded around
//! `+Z` (south) as the faces' texels join up:
//!
//! ```text
//!         ┌────┐
//!         │ +Y │
//!    ┌────┼────┼────┬────┐
//!    │ −X │ +Z │ +X │ −Z │
//!    └────┼────┼────┴────┘
//!         │ −Y │
//!         └────┘
//! ```
//!
//! Each cell holds its face's texels as they are ([`super::projection`]: OpenGL's orientation,
//! rows top first), so the image is continuous across every shared edge; the six other cells are
//! unused.

use glam::DVec2;

use super::projection::CubeFace;

/// The cross's size in faces: 4 across, 3 down.
pub const CROSS_CELLS: (u32, u32) = (4, 3);

impl CubeFace {
    /// The face's cell in the horizontal cross: (column, row), from the top left.
    pub fn cross_cell(self) -> (u32, u32) {
        match self {
            Self::PositiveY => (1, 0),
            Self::NegativeX => (0, 1),
            Self::PositiveZ => (1, 1),
            Self::PositiveX => (2, 1),
            Self::NegativeZ => (3, 1),
            Self::NegativeY => (1, 2),
        }
    }
}

/// The cross's continuous pixel coordinates of `face`'s texel coordinates `texel` (each in
/// `[0, size]`), faces of side `size`.
pub fn cross_position(face: CubeFace, texel: DVec2, size: u32) -> DVec2 {
    let (column, row) = face.cross_cell();
    texel + DVec2::new(f64::from(column), f64::from(row)) * f64::from(size)
}

/// The face and its texel coordinates at the cross's continuous pixel coordinates `pixel`
/// ([`cross_position`]'s inverse); `None` in the unused cells and outside the cross.
pub fn cross_face(pixel: DVec2, size: u32) -> Option<(CubeFace, DVec2)> {
    let s = f64::from(size);
    if !(pixel.x >= 0.0 && pixel.y >= 0.0) {
        return None;
    }
    let (column, row) = ((pixel.x / s).floor(), (pixel.y / s).floor());
    let face = CubeFace::ALL
        .into_iter()
        .find(|face| face.cross_cell() == (column as u32, row as u32))?;
    Some((face, pixel - DVec2::new(column, row) * s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envmap::{cube_direction, cube_position, equirect_direction};
    use glam::DVec3;

    /// Directions all over the sphere → face texel → cross pixel → face texel → direction.
    #[test]
    fn directions_round_trip_through_the_cross() {
        let size = 8;
        let (w, h) = (72, 36);
        for j in 0..h {
            for i in 0..w {
                let d = equirect_direction(f64::from(i) + 0.5, f64::from(j) + 0.5, w, h);
                let (face, texel) = cube_position(d, size);
                let pixel = cross_position(face, texel, size);
                assert!(pixel.x <= 4.0 * 8.0 && pixel.y <= 3.0 * 8.0);
                // Texel centres, so that a cell's far edge does not spill into the next.
                let centre = (texel.floor() + 0.5).min(DVec2::splat(f64::from(size) - 0.5));
                let (back, at) = cross_face(cross_position(face, centre, size), size).expect("a face's cell");
                assert_eq!(back, face);
                assert!((at - centre).length() < 1e-12);
                let again = cube_direction(back, texel.x, texel.y, size);
                assert!(
                    (again - d).length() < 1e-9,
                    "{d} → {face:?} {texel} → {pixel} → {again}"
                );
            }
        }
    }

    /// Each cell's neighbours across its edges are the faces whose texels continue it.
    #[test]
    fn the_cells_join_up() {
        let size = 16;
        let s = f64::from(size);
        // Just either side of the edge between two cells, along the edge's middle.
        let across = |pixel: DVec2, step: DVec2| {
            let a = cross_face(pixel - step * 1e-6, size).expect("a face");
            let b = cross_face(pixel + step * 1e-6, size).expect("a face");
            let (da, db) = (
                cube_direction(a.0, a.1.x, a.1.y, size),
                cube_direction(b.0, b.1.x, b.1.y, size),
            );
            assert!((da - db).length() < 1e-5, "{:?} {da} vs {:?} {db}", a.0, b.0);
        };
        for column in 1..4 {
            across(DVec2::new(f64::from(column) * s, 1.5 * s), DVec2::X);
        }
        across(DVec2::new(1.5 * s, s), DVec2::Y);
        across(DVec2::new(1.5 * s, 2.0 * s), DVec2::Y);
        // The unused cells, and outside.
        for pixel in [
            DVec2::new(0.5, 0.5),
            DVec2::new(3.5 * s, 2.5 * s),
            DVec2::new(-1.0, 9.0),
            DVec2::new(9.0, 3.0 * s),
        ] {
            assert!(cross_face(pixel, size).is_none(), "{pixel}");
        }
        // The middle row runs west, south, east, north: the horizon all the way round.
        let row: Vec<DVec3> = (0..4)
            .map(|c| {
                let (face, t) = cross_face(DVec2::new((f64::from(c) + 0.5) * s, 1.5 * s), size).expect("a face");
                cube_direction(face, t.x, t.y, size)
            })
            .collect();
        assert!((row[0] + DVec3::X).length() < 1e-12 && (row[1] + DVec3::Y).length() < 1e-12);
        assert!((row[2] - DVec3::X).length() < 1e-12 && (row[3] - DVec3::Y).length() < 1e-12);
    }
}
