//! The camera's view of a planet, shared by the full-screen passes that march rays through an
//! atmosphere shell (the physical atmosphere and the seed's model): everything computed in `f64`
//! and rounded once, so the planet holds from 1 m above the ground to 100 AU.

use firmament_core::Camera;
use glam::{DMat3, DMat4, DQuat, DVec3};

/// How far the camera must be, in top-of-atmosphere radii, before view rays start at their
/// closest approach to the planet centre instead of at the camera.
pub const FAR_CAMERA_RADII: f64 = 10.0;

/// `|o/a|² − 1`, in f64: its sign says inside or outside, and near the surface it is tiny, which
/// f32 could not compute from a rounded position.
pub(crate) fn ellipsoid_c(o: DVec3, radii: DVec3) -> f64 {
    (o / radii).length_squared() - 1.0
}

/// The `f32` fields a planet-relative view needs (mirrored by `view_to_planet`, `camera_shape`
/// and `center` in the WGSL structs that hold them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlanetView {
    /// View-space direction → planet frame rotation.
    pub(crate) view_to_planet: [[f32; 4]; 4],
    /// `|o/a|² − 1` against the surface and the top; tan of half the horizontal and vertical
    /// fields of view.
    pub(crate) camera_shape: [f32; 4],
    /// Planet centre's view-space x, y over its depth; the depth (m); 1 for far-camera rays.
    pub(crate) center: [f32; 4],
    /// True when rays start at their closest approach (the camera is beyond
    /// [`FAR_CAMERA_RADII`]).
    pub(crate) far: bool,
}

impl PlanetView {
    /// The view by `camera` of a planet centred at `center` (world) with `orientation`, the
    /// camera at planet-frame `o`, surface semi-axes `radii` and top semi-axes `top`.
    pub(crate) fn new(camera: &Camera, center: DVec3, orientation: DQuat, o: DVec3, radii: DVec3, top: DVec3) -> Self {
        let camera_orientation = camera.orientation.normalize();
        let view_to_planet = DMat3::from_quat(orientation.normalize().inverse() * camera_orientation);
        // The planet centre in view space, exactly: far cameras march from closest approaches.
        let center_view = camera_orientation.inverse() * (center - camera.position);
        let depth = -center_view.z;
        let far = depth > 0.0 && center_view.length() > FAR_CAMERA_RADII * top.max_element();
        let center = if far {
            [
                (center_view.x / depth) as f32,
                (center_view.y / depth) as f32,
                depth as f32,
                1.0,
            ]
        } else {
            [0.0, 0.0, depth as f32, 0.0]
        };
        let tan_y = (0.5 * camera.fov_y).tan();
        Self {
            view_to_planet: DMat4::from_mat3(view_to_planet).as_mat4().to_cols_array_2d(),
            camera_shape: [
                ellipsoid_c(o, radii) as f32,
                ellipsoid_c(o, top) as f32,
                (tan_y * camera.aspect) as f32,
                tan_y as f32,
            ],
            center,
            far,
        }
    }
}
