//! Environment maps for embedders and files: the full sphere of directions around a frame's
//! camera position, as six cube faces or an equirectangular (latitude-longitude) map, in the same
//! linear, scene-referred units as [`HeadlessRenderer::render_hdr`] (cd/m² in linear sRGB for
//! the physical atmosphere), as `f32` RGBA.
//!
//! The six 90° faces are drawn by the ordinary frame path (objects, sky, clouds, night sky,
//! aerial perspective as the frame says), without lens flares (a lens, not the sky) and before
//! the camera's passes (exposure, bloom, tone curve). The suns' discs do not fit the half-float
//! HDR target (a noon Sun is about 1.6·10⁹ cd/m²): the GPU draws the suns without them and
//! [`firmament_core::envmap::sun_disc`] adds them in `f32` on the CPU, each pixel receiving the
//! disc's mean radiance over it after the air, so that the map's radiance × solid angle over a
//! disc is that sun's irradiance at the eye whatever the map's size. Discs hidden by the
//! frame's objects are still added (the objects' depth is not consulted).
//!
//! Into your own wgpu textures, with no read-back: [`EnvironmentMapPass`] renders the six faces
//! into a cube texture's layers or the equirectangular map into a 2D texture, the same texels as
//! the images here (the discs only into `Rgba32Float`). [`CubeFaces::to_horizontal_cross`] lays
//! the faces out as one 4:3 horizontal cross.
//!
//! Layouts and frames: [`firmament_core::envmap`] (equirectangular: zenith on top, north a
//! quarter across, east in the middle, the seam in the west; cube faces: OpenGL's convention in
//! the Y-up frame `x` east, `y` up, `z` south).
//!
//! ```
//! use firmament_render::{Backend, GpuContext, envmap::SunDiscs, headless::HeadlessRenderer};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let scene = firmament_scene::load(firmament_scene::SceneSource::Preset("earth-noon"), None, &[])?;
//! let frame = scene.frame_at(None)?;
//! let ctx = GpuContext::headless(Backend::Auto)?;
//! let mut renderer = HeadlessRenderer::new(&ctx);
//! let map = renderer.render_equirect(&ctx, &frame, 64, SunDiscs::Included)?; // 64 × 32
//! assert_eq!((map.width, map.height), (64, 32));
//! let cube = renderer.render_cube_faces(&ctx, &frame, 16, SunDiscs::Omitted)?; // 6 × 16²
//! assert_eq!(cube.size(), 16);
//! # Ok(())
//! # }
//! ```

mod cross;
mod discs;
mod gpu;
mod resample;

#[cfg(test)]
pub(crate) use gpu::write_source;
pub use gpu::{ENVMAP_FORMATS, EnvironmentMapPass};

use firmament_core::envmap::{CubeFace, SunAtEye, sun_at_eye};
use firmament_core::flare::FlareLayer;
use firmament_core::frame::Sky;
use firmament_core::{Camera, CoreError, Frame};

use crate::context::GpuContext;
use crate::error::RenderError;
use crate::headless::{HeadlessRenderer, Image};

/// Whether an environment map holds the suns' discs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SunDiscs {
    /// Each sun's disc at its radiance after the air (the physical atmosphere's suns).
    Included,
    /// No discs: the sky around them only, for engines that light with the suns as separate
    /// directional lights ([`suns_at_eye`]). Only the physical atmosphere's suns are left out;
    /// the gradient and the seed's skies draw their suns as always.
    Omitted,
}

/// Six square cube faces in OpenGL's order (`+X, −X, +Y, −Y, +Z, −Z` of the Y-up frame
/// [`firmament_core::envmap::enu_to_y_up`]), each image's top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct CubeFaces {
    size: u32,
    faces: Vec<Image<f32>>,
}

impl CubeFaces {
    /// Each face's side, pixels.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// One face: linear RGBA `f32`, rows top first.
    pub fn face(&self, face: CubeFace) -> &Image<f32> {
        &self.faces[face.index()]
    }

    /// The radiance along unit world (ENU) `direction`, bilinear within the face it falls on.
    pub fn radiance(&self, direction: glam::DVec3) -> [f32; 3] {
        resample::sample_cube(self, direction)
    }

    /// The `width` × `width / 2` equirectangular map of these faces (each pixel bilinear at its
    /// centre's direction). Suns' discs in the faces are resampled like the sky; render the map
    /// with [`HeadlessRenderer::render_equirect`] to have them exact.
    pub fn to_equirect(&self, width: u32) -> Result<Image<f32>, RenderError> {
        check_equirect_width(width)?;
        Ok(resample::equirect_from_cube(self, width))
    }
}

/// Every sun of `frame`'s physical atmosphere as seen from its camera: direction, transmittance,
/// irradiance after the air and its disc in pieces ([`firmament_core::envmap::sun_at_eye`]);
/// empty for other skies. For engines that light with the suns as directional lights beside a
/// map rendered with [`SunDiscs::Omitted`].
pub fn suns_at_eye(frame: &Frame) -> Vec<SunAtEye> {
    match &frame.sky {
        Sky::Atmosphere(sky) => sky
            .suns
            .iter()
            .map(|sun| sun_at_eye(&sky.atmosphere, &sky.clouds, &sky.eclipsers, sun, frame.camera.position))
            .collect(),
        Sky::Gradient(_) | Sky::Empirical(_) | Sky::Clear(_) => Vec::new(),
    }
}

impl HeadlessRenderer {
    /// Renders the six `size` × `size` cube faces around `frame`'s camera position (its
    /// orientation and field of view are not used), with or without the suns' discs.
    pub fn render_cube_faces(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        size: u32,
        discs: SunDiscs,
    ) -> Result<CubeFaces, RenderError> {
        let mut cube = self.render_sky_faces(ctx, frame, size)?;
        if discs == SunDiscs::Included {
            discs::add_to_cube(&mut cube, &suns_at_eye(frame));
        }
        Ok(cube)
    }

    /// Renders the `width` × `width / 2` equirectangular map around `frame`'s camera position
    /// (`width` even, at least 4), with or without the suns' discs: cube faces of side
    /// `⌈width / 4⌉` resampled bilinearly, the discs added into the map itself.
    pub fn render_equirect(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        width: u32,
        discs: SunDiscs,
    ) -> Result<Image<f32>, RenderError> {
        check_equirect_width(width)?;
        let cube = self.render_sky_faces(ctx, frame, width.div_ceil(4))?;
        let mut map = resample::equirect_from_cube(&cube, width);
        if discs == SunDiscs::Included {
            discs::add_to_equirect(&mut map, &suns_at_eye(frame));
        }
        Ok(map)
    }

    /// The six faces as the GPU draws them: no sun discs, no flares, radiance before the camera.
    fn render_sky_faces(&mut self, ctx: &GpuContext, frame: &Frame, size: u32) -> Result<CubeFaces, RenderError> {
        ctx.check_image_size(size, size)?;
        let mut faces = Vec::with_capacity(CubeFace::ALL.len());
        for_each_face_frame(frame, |_, face_frame| {
            faces.push(mirrored(self.render_hdr(ctx, face_frame, size, size)?));
            Ok(())
        })?;
        Ok(CubeFaces { size, faces })
    }
}

/// Calls `draw` with each face of [`CubeFace::ALL`] and `frame` as its face camera sees it for
/// the map: flares off, the display's defaults, no sun discs (they do not fit the half-float
/// target; they are added afterwards).
fn for_each_face_frame(
    frame: &Frame,
    mut draw: impl FnMut(CubeFace, &Frame) -> Result<(), RenderError>,
) -> Result<(), RenderError> {
    let mut base = frame.clone();
    base.flares = FlareLayer::default();
    base.display = Default::default();
    if let Sky::Atmosphere(sky) = &mut base.sky {
        sky.suns.iter_mut().for_each(|sun| sun.disc = false);
    }
    for face in CubeFace::ALL {
        base.camera = face_camera(&frame.camera, face)?;
        draw(face, &base)?;
    }
    Ok(())
}

/// A 90° square camera at `camera`'s position looking through `face`: right-handed, so its image
/// is the face mirrored left to right (OpenGL's faces are seen from outside the cube).
fn face_camera(camera: &Camera, face: CubeFace) -> Result<Camera, RenderError> {
    let position = camera.position;
    let looking = Camera::looking_at(position, position + face.forward(), face.up()).ok_or_else(|| {
        RenderError::Invalid(CoreError::Invalid {
            field: "camera.position",
            value: format!("{position:?}"),
            rule: "must be small enough for a direction to be added to it",
        })
    })?;
    Ok(Camera {
        orientation: looking.orientation,
        fov_y: std::f64::consts::FRAC_PI_2,
        aspect: 1.0,
        ..*camera
    })
}

/// `image` mirrored left to right.
fn mirrored(mut image: Image<f32>) -> Image<f32> {
    let row = 4 * image.width as usize;
    for line in image.pixels.chunks_exact_mut(row) {
        let (mut left, mut right) = (0, image.width as usize - 1);
        while left < right {
            for c in 0..4 {
                line.swap(4 * left + c, 4 * right + c);
            }
            left += 1;
            right -= 1;
        }
    }
    image
}

/// Fails unless `width` is an even number of pixels, at least 4.
fn check_equirect_width(width: u32) -> Result<(), RenderError> {
    if width < 4 || !width.is_multiple_of(2) {
        return Err(RenderError::Invalid(CoreError::Invalid {
            field: "equirectangular width",
            value: width.to_string(),
            rule: "must be an even number of pixels, at least 4 (the height is half of it)",
        }));
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use firmament_core::envmap::cube_direction;
    use glam::{DVec2, DVec3};

    /// A cube whose texels hold their own direction's `(x, y, z)` (ENU) in RGB, alpha 1.
    pub(crate) fn direction_cube(size: u32) -> CubeFaces {
        let faces = CubeFace::ALL
            .iter()
            .map(|&face| Image {
                width: size,
                height: size,
                pixels: (0..size * size)
                    .flat_map(|k| {
                        let d = cube_direction(face, f64::from(k % size) + 0.5, f64::from(k / size) + 0.5, size);
                        [d.x as f32, d.y as f32, d.z as f32, 1.0]
                    })
                    .collect(),
            })
            .collect();
        CubeFaces { size, faces }
    }

    /// The mirrored face camera's pixel centres are the OpenGL faces' texel directions.
    #[test]
    fn face_cameras_see_the_opengl_faces_mirrored() {
        let size = 8;
        let scene_camera = Camera::from_heading_pitch(DVec3::new(3.0, -2.0, 1.7), 0.7, 0.2);
        for face in CubeFace::ALL {
            let camera = face_camera(&scene_camera, face).expect("a camera");
            assert_eq!(camera.position, scene_camera.position);
            for j in 0..size {
                for i in 0..size {
                    let mirrored_i = size - 1 - i;
                    let ndc = DVec2::new(
                        (f64::from(mirrored_i) + 0.5) / f64::from(size) * 2.0 - 1.0,
                        1.0 - (f64::from(j) + 0.5) / f64::from(size) * 2.0,
                    );
                    let want = cube_direction(face, f64::from(i) + 0.5, f64::from(j) + 0.5, size);
                    let got = camera.view_direction(ndc);
                    assert!((got - want).length() < 1e-9, "{face:?} ({i}, {j}): {got} vs {want}");
                }
            }
        }
    }

    #[test]
    fn mirroring_swaps_columns() {
        let image = Image {
            width: 3,
            height: 1,
            pixels: (0..12).map(|v| v as f32).collect(),
        };
        let m = mirrored(image);
        assert_eq!(
            m.pixels,
            vec![8.0, 9.0, 10.0, 11.0, 4.0, 5.0, 6.0, 7.0, 0.0, 1.0, 2.0, 3.0]
        );
    }

    #[test]
    fn widths_must_be_even() {
        assert!(check_equirect_width(4).is_ok());
        assert!(check_equirect_width(2048).is_ok());
        for bad in [0, 2, 5, 2047] {
            assert!(check_equirect_width(bad).is_err(), "{bad}");
        }
    }
}
