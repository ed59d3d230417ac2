//! The suns' discs added into a map: each piece of a disc ([`DiscSample`]) into the pixel it
//! falls in, as its irradiance over that pixel's solid angle.

use firmament_core::envmap::{
    DiscSample, SunAtEye, cube_position, cube_texel_solid_angle, equirect_pixel_solid_angle, equirect_position,
};

use super::CubeFaces;
use crate::headless::Image;

/// Adds every piece of every disc in `suns` into `pixels` (RGBA) at the place `locate` gives:
/// `(image, pixel index, pixel solid angle in steradians)`.
fn add_pieces(suns: &[SunAtEye], images: &mut [&mut Image<f32>], locate: impl Fn(&DiscSample) -> (usize, usize, f64)) {
    for piece in suns.iter().flat_map(|sun| &sun.disc) {
        let (image, index, solid_angle) = locate(piece);
        let pixel = &mut images[image].pixels[4 * index..4 * index + 3];
        let c = piece.irradiance;
        for (value, add) in pixel.iter_mut().zip([c.r, c.g, c.b]) {
            *value += (add / solid_angle) as f32;
        }
    }
}

/// Adds the discs of `suns` into an equirectangular `map`.
pub(super) fn add_to_equirect(map: &mut Image<f32>, suns: &[SunAtEye]) {
    let (width, height) = (map.width, map.height);
    add_pieces(suns, &mut [map], |piece| {
        let p = equirect_position(piece.direction, width, height);
        let (i, j) = ((p.x as u32).min(width - 1), (p.y as u32).min(height - 1));
        (
            0,
            (j * width + i) as usize,
            equirect_pixel_solid_angle(j, width, height),
        )
    });
}

/// Adds the discs of `suns` into `cube`'s faces.
pub(super) fn add_to_cube(cube: &mut CubeFaces, suns: &[SunAtEye]) {
    let size = cube.size;
    let mut faces: Vec<&mut Image<f32>> = cube.faces.iter_mut().collect();
    add_pieces(suns, &mut faces, |piece| {
        let (face, p) = cube_position(piece.direction, size);
        let (i, j) = ((p.x as u32).min(size - 1), (p.y as u32).min(size - 1));
        (
            face.index(),
            (j * size + i) as usize,
            cube_texel_solid_angle(i, j, size),
        )
    });
}
