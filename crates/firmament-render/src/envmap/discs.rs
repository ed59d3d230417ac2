//! The suns' discs added into a map: each piece of a disc ([`DiscSample`]) into the pixel it
//! falls in, as its irradiance over that pixel's solid angle — on the CPU into an image, or as
//! per-texel runs of pieces for the GPU pass ([`texel_runs`]).

use firmament_core::envmap::{
    DiscSample, SunAtEye, cube_position, cube_texel_solid_angle, equirect_pixel_solid_angle, equirect_position,
};

use super::CubeFaces;
use crate::gpu_types::DiscTexelInstance;
use crate::headless::Image;

/// Where a piece lands: (image — the cube face's index, 0 for an equirectangular map — column,
/// row, the pixel's solid angle in steradians).
type Place = (usize, u32, u32, f64);

/// Where pieces land in an equirectangular `width` × `height` map.
fn equirect_place(width: u32, height: u32) -> impl Fn(&DiscSample) -> Place {
    move |piece| {
        let p = equirect_position(piece.direction, width, height);
        let (i, j) = ((p.x as u32).min(width - 1), (p.y as u32).min(height - 1));
        (0, i, j, equirect_pixel_solid_angle(j, width, height))
    }
}

/// Where pieces land in cube faces of side `size`.
fn cube_place(size: u32) -> impl Fn(&DiscSample) -> Place {
    move |piece| {
        let (face, p) = cube_position(piece.direction, size);
        let (i, j) = ((p.x as u32).min(size - 1), (p.y as u32).min(size - 1));
        (face.index(), i, j, cube_texel_solid_angle(i, j, size))
    }
}

/// Every piece of every disc of `suns` in order, with where it lands and what it adds to that
/// pixel's RGB: its irradiance over the pixel's solid angle, rounded to `f32`.
fn contributions(suns: &[SunAtEye], place: impl Fn(&DiscSample) -> Place) -> impl Iterator<Item = (Place, [f32; 3])> {
    suns.iter().flat_map(|sun| &sun.disc).map(move |piece| {
        let at = place(piece);
        let c = piece.irradiance;
        (at, [c.r, c.g, c.b].map(|add| (add / at.3) as f32))
    })
}

/// Adds every piece of every disc in `suns` into `images` (RGBA) at the place `place` gives.
fn add_pieces(suns: &[SunAtEye], images: &mut [&mut Image<f32>], place: impl Fn(&DiscSample) -> Place) {
    for ((image, i, j, _), add) in contributions(suns, place) {
        let image = &mut images[image];
        let index = 4 * (j as usize * image.width as usize + i as usize);
        for (value, add) in image.pixels[index..index + 3].iter_mut().zip(add) {
            *value += add;
        }
    }
}

/// Adds the discs of `suns` into an equirectangular `map`.
pub(super) fn add_to_equirect(map: &mut Image<f32>, suns: &[SunAtEye]) {
    let place = equirect_place(map.width, map.height);
    add_pieces(suns, &mut [map], place);
}

/// Adds the discs of `suns` into `cube`'s faces.
pub(super) fn add_to_cube(cube: &mut CubeFaces, suns: &[SunAtEye]) {
    let place = cube_place(cube.size);
    let mut faces: Vec<&mut Image<f32>> = cube.faces.iter_mut().collect();
    add_pieces(suns, &mut faces, place);
}

/// Where discs go in the GPU's output: each texel they touch, once, with its run of pieces; the
/// pieces' RGB contributions (`w` unused), each texel's run in the CPU's order.
#[derive(Debug, Default)]
pub(super) struct TexelRuns {
    pub(super) texels: Vec<DiscTexelInstance>,
    pub(super) pieces: Vec<[f32; 4]>,
}

/// The GPU's runs for an equirectangular `width` × `height` map, or for cube faces of side `size`.
pub(super) enum Target {
    Equirect { width: u32, height: u32 },
    Cube { size: u32 },
}

/// The discs of `suns` as runs of pieces per texel of `target`: the same pieces, places and `f32`
/// contributions as the CPU path, each texel's pieces in the CPU's order (a stable sort), so a
/// texel that sums its run onto its sky adds exactly what [`add_to_cube`] and
/// [`add_to_equirect`] add.
pub(super) fn texel_runs(suns: &[SunAtEye], target: Target) -> TexelRuns {
    let mut all: Vec<(Place, [f32; 3])> = match target {
        Target::Equirect { width, height } => contributions(suns, equirect_place(width, height)).collect(),
        Target::Cube { size } => contributions(suns, cube_place(size)).collect(),
    };
    all.sort_by_key(|((image, i, j, _), _)| (*image, *j, *i));
    let mut runs = TexelRuns::default();
    for ((image, i, j, _), [r, g, b]) in all {
        let first = runs.pieces.len() as u32;
        runs.pieces.push([r, g, b, 0.0]);
        match runs.texels.last_mut() {
            Some(t) if (t.face, t.x, t.y) == (image as u32, i, j) => t.count += 1,
            _ => runs.texels.push(DiscTexelInstance {
                x: i,
                y: j,
                face: image as u32,
                first,
                count: 1,
            }),
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;
    use firmament_core::color::LinearRgb;
    use glam::DVec3;

    fn sun(pieces: &[(DVec3, f64)]) -> SunAtEye {
        SunAtEye {
            direction: DVec3::X,
            transmittance: Default::default(),
            irradiance: Default::default(),
            irradiance_rgb: LinearRgb::new(0.0, 0.0, 0.0),
            disc: pieces
                .iter()
                .map(|&(direction, e)| DiscSample {
                    direction: direction.normalize(),
                    irradiance: LinearRgb::new(e, 2.0 * e, 3.0 * e),
                })
                .collect(),
        }
    }

    /// The runs hold every piece once, grouped by texel in the CPU's order, and summing each run
    /// onto a blank cube gives the CPU's faces bit for bit.
    #[test]
    fn runs_sum_to_what_the_cpu_adds() {
        let size = 4;
        let a = DVec3::new(1.0, 0.1, 0.1);
        let b = DVec3::new(1.0, -0.3, 0.2);
        let suns = [sun(&[(a, 1.0), (b, 2.0), (a, 0.5)]), sun(&[(b, 7.0), (-DVec3::Z, 1.0)])];
        let runs = texel_runs(&suns, Target::Cube { size });
        assert_eq!(runs.pieces.len(), 5);
        assert_eq!(runs.texels.len(), 3);
        assert_eq!(runs.texels.iter().map(|t| t.count).sum::<u32>(), 5);
        let blank = Image {
            width: size,
            height: size,
            pixels: vec![0.0; (4 * size * size) as usize],
        };
        let mut cpu = CubeFaces {
            size,
            faces: vec![blank; 6],
        };
        add_to_cube(&mut cpu, &suns);
        let mut gpu = cpu
            .faces
            .iter()
            .map(|f| vec![0.0_f32; f.pixels.len()])
            .collect::<Vec<_>>();
        for t in &runs.texels {
            let k = 4 * (t.y * size + t.x) as usize;
            for piece in &runs.pieces[t.first as usize..(t.first + t.count) as usize] {
                for c in 0..3 {
                    gpu[t.face as usize][k + c] += piece[c];
                }
            }
        }
        for (face, pixels) in cpu.faces.iter().zip(&gpu) {
            assert_eq!(&face.pixels, pixels);
        }
    }
}
