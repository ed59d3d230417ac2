//! A perspective camera with an `f64` position, so it stays exact far from the origin.

pub mod frustum;
pub mod projection;
pub mod viewport;

use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, DVec4};

/// A perspective camera in the world frame (see the crate's conventions: +Z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Position of the eye in the world frame, metres.
    pub position: DVec3,
    /// Rotation from view space (x right, y up, looking down -z) into the world frame.
    pub orientation: DQuat,
    /// Vertical field of view, radians, in (0, π).
    pub fov_y: f64,
    /// Width / height of the image, dimensionless, > 0.
    pub aspect: f64,
    /// Distance to the near plane, metres, > 0.
    pub near: f64,
    /// Distance to the far plane, metres; `None` for an infinite far plane.
    pub far: Option<f64>,
}

impl Camera {
    /// A camera at `position` looking along `heading` (from north, clockwise) and `pitch` (up
    /// positive), both radians, with the world's +Z as up and no roll.
    pub fn from_heading_pitch(position: DVec3, heading: f64, pitch: f64) -> Self {
        Self {
            position,
            orientation: orientation_from_heading_pitch_roll(heading, pitch, 0.0),
            ..Self::default()
        }
    }

    /// A camera at `position` looking at `target`, with `up` as the approximate up direction.
    ///
    /// Returns `None` when the view direction is zero or parallel to `up`.
    pub fn looking_at(position: DVec3, target: DVec3, up: DVec3) -> Option<Self> {
        let forward = (target - position).try_normalize()?;
        let right = forward.cross(up).try_normalize()?;
        let true_up = right.cross(forward);
        // Columns are the view-space axes expressed in the world frame: x = right, y = up, z = -forward.
        let basis = DMat3::from_cols(right, true_up, -forward);
        Some(Self {
            position,
            orientation: DQuat::from_mat3(&basis).normalize(),
            ..Self::default()
        })
    }

    /// The same camera with a vertical field of view of `fov_y` radians, in (0, π).
    #[must_use]
    pub fn with_fov_y(self, fov_y: f64) -> Self {
        Self { fov_y, ..self }
    }

    /// The same camera with its near plane at `near` metres (> 0) and its far plane at `far`
    /// metres (`None`: infinite).
    #[must_use]
    pub fn with_clip_planes(self, near: f64, far: Option<f64>) -> Self {
        Self { near, far, ..self }
    }

    /// The unit direction the camera looks along, world frame.
    pub fn forward(&self) -> DVec3 {
        self.orientation * DVec3::NEG_Z
    }

    /// The unit direction to the right of the image, world frame.
    pub fn right(&self) -> DVec3 {
        self.orientation * DVec3::X
    }

    /// The unit direction up in the image, world frame.
    pub fn up(&self) -> DVec3 {
        self.orientation * DVec3::Y
    }

    /// World → view transform (rotation and translation).
    pub fn view_matrix(&self) -> DMat4 {
        self.view_rotation() * DMat4::from_translation(-self.position)
    }

    /// World → view rotation only: the view matrix of a camera moved to the origin. Passes that
    /// work camera-relative (the sky, anything far away) use this to keep `f32` precision.
    pub fn view_rotation(&self) -> DMat4 {
        DMat4::from_quat(self.orientation.conjugate())
    }

    /// View → clip projection for firmament's own passes: reversed depth in wgpu's `[0, 1]` clip
    /// range, with an infinite far plane when `far` is `None`.
    pub fn projection_matrix(&self) -> DMat4 {
        match self.far {
            None => projection::perspective_infinite_reverse_z(self.fov_y, self.aspect, self.near),
            Some(far) => projection::perspective_reverse_z(self.fov_y, self.aspect, self.near, far),
        }
    }

    /// View → clip projection in wgpu's `[0, 1]` clip depth for `convention`: near → 1 and
    /// far → 0 for [`DepthConvention::Reversed`] (what [`Self::projection_matrix`] gives), near → 0
    /// and far → 1 for [`DepthConvention::Standard`]; the far plane is infinite when `far` is
    /// `None`.
    pub fn projection_matrix_for(&self, convention: DepthConvention) -> DMat4 {
        match (convention, self.far) {
            (DepthConvention::Reversed, _) => self.projection_matrix(),
            (DepthConvention::Standard, None) => projection::perspective_infinite(self.fov_y, self.aspect, self.near),
            (DepthConvention::Standard, Some(far)) => projection::perspective(self.fov_y, self.aspect, self.near, far),
        }
    }

    /// The unit world-frame direction of the view ray through a point in normalised device
    /// coordinates (`x`, `y` in [-1, 1], +y up), independent of the far plane.
    pub fn view_direction(&self, ndc: DVec2) -> DVec3 {
        // Un-project a point on the near plane (reversed-Z: depth 1) — well defined even when the
        // far plane is infinite — and rotate its view-space direction into the world.
        let inverse = self.projection_matrix().inverse();
        let p = inverse * DVec4::new(ndc.x, ndc.y, 1.0, 1.0);
        let view_dir = (p.truncate() / p.w).normalize();
        (self.orientation * view_dir).normalize()
    }
}

/// How a depth buffer maps distance to depth, in wgpu's `[0, 1]` clip depth (the far plane
/// being finite or infinite as [`Camera::far`] says).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum DepthConvention {
    /// Reversed-Z, firmament's own: the near plane → 1, the far plane (or infinity) → 0; cleared
    /// to 0, nearer is greater.
    #[default]
    Reversed,
    /// Standard: the near plane → 0, the far plane (or infinity) → 1; cleared to 1, nearer is
    /// smaller.
    Standard,
}

impl DepthConvention {
    /// The depth of the far plane (and of a cleared buffer): 0 reversed, 1 standard.
    pub fn far_depth(self) -> f64 {
        match self {
            Self::Reversed => 0.0,
            Self::Standard => 1.0,
        }
    }

    /// Whether depth `a` is nearer the camera than depth `b` under this convention.
    pub fn is_nearer(self, a: f64, b: f64) -> bool {
        match self {
            Self::Reversed => a > b,
            Self::Standard => a < b,
        }
    }
}

impl Default for Camera {
    /// At the origin, looking north along the horizon, 60° vertical field of view, 16:9.
    fn default() -> Self {
        Self {
            position: DVec3::ZERO,
            orientation: orientation_from_heading_pitch_roll(0.0, 0.0, 0.0),
            fov_y: 60f64.to_radians(),
            aspect: 16.0 / 9.0,
            near: 0.1,
            far: None,
        }
    }
}

/// The unit direction for a heading (from north, clockwise towards east) and an elevation
/// (up positive), both radians, in the local +Z-up frame.
pub fn direction_from_heading_elevation(heading: f64, elevation: f64) -> DVec3 {
    let (sh, ch) = heading.sin_cos();
    let (se, ce) = elevation.sin_cos();
    DVec3::new(sh * ce, ch * ce, se)
}

/// The rotation from view space into the +Z-up world for a heading, pitch and roll (radians).
///
/// With all three zero the camera looks north (+y) with +z up on screen. Heading turns clockwise
/// seen from above, pitch raises the view, roll turns the image clockwise.
pub fn orientation_from_heading_pitch_roll(heading: f64, pitch: f64, roll: f64) -> DQuat {
    // View space looking north, level: view x → east (+x), view y → up (+z), view -z → north (+y).
    let level_north = DQuat::from_mat3(&DMat3::from_cols(DVec3::X, DVec3::Z, DVec3::NEG_Y));
    let yaw = DQuat::from_rotation_z(-heading);
    let pitch = DQuat::from_rotation_x(pitch);
    let roll = DQuat::from_rotation_z(-roll);
    (yaw * level_north * pitch * roll).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_for_each_convention_maps_near_and_far() {
        let at = |m: DMat4, d: f64| {
            let c = m * DVec4::new(0.0, 0.0, -d, 1.0);
            c.z / c.w
        };
        for far in [Some(5000.0), None] {
            let camera = Camera {
                near: 0.25,
                far,
                ..Camera::default()
            };
            let distant = far.unwrap_or(1e13);
            assert_eq!(
                camera.projection_matrix_for(DepthConvention::Reversed),
                camera.projection_matrix()
            );
            for convention in [DepthConvention::Reversed, DepthConvention::Standard] {
                let m = camera.projection_matrix_for(convention);
                assert!((at(m, 0.25) - (1.0 - convention.far_depth())).abs() < 1e-12);
                assert!((at(m, distant) - convention.far_depth()).abs() < 1e-9);
                assert!(convention.is_nearer(at(m, 10.0), at(m, 20.0)));
                // x and y are the same matrix's either way.
                assert_eq!(m.x_axis, camera.projection_matrix().x_axis);
                assert_eq!(m.y_axis, camera.projection_matrix().y_axis);
            }
        }
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn heading_pitch_match_direction_helper() {
        for (h, p) in [(0.0, 0.0), (90.0, 0.0), (200.0, 30.0), (-45.0, -60.0)] {
            let (h, p) = (f64::to_radians(h), f64::to_radians(p));
            let cam = Camera::from_heading_pitch(DVec3::ZERO, h, p);
            assert!(close(cam.forward(), direction_from_heading_elevation(h, p)));
            // No roll: the right vector stays horizontal.
            assert!(cam.right().z.abs() < 1e-12);
        }
    }

    #[test]
    fn looking_at_agrees_with_heading_pitch() {
        let target = direction_from_heading_elevation(1.0, 0.3) * 10.0;
        let a = Camera::looking_at(DVec3::ZERO, target, DVec3::Z).expect("valid");
        let b = Camera::from_heading_pitch(DVec3::ZERO, 1.0, 0.3);
        assert!(close(a.forward(), b.forward()));
        assert!(close(a.up(), b.up()));
        assert!(Camera::looking_at(DVec3::ZERO, DVec3::Z, DVec3::Z).is_none());
    }

    #[test]
    fn view_direction_centre_and_edges() {
        let cam = Camera::from_heading_pitch(DVec3::new(1e11, 0.0, 0.0), 0.4, 0.1);
        assert!(close(cam.view_direction(DVec2::ZERO), cam.forward()));
        // The top edge of the image is fov_y / 2 above the centre.
        let top = cam.view_direction(DVec2::new(0.0, 1.0));
        let angle = top.dot(cam.forward()).clamp(-1.0, 1.0).acos();
        assert!((angle - cam.fov_y / 2.0).abs() < 1e-12);
    }

    #[test]
    fn view_matrix_puts_target_on_negative_z() {
        let cam = Camera::from_heading_pitch(DVec3::new(5.0, -3.0, 2.0), 2.0, -0.2);
        let p = cam.position + cam.forward() * 7.0;
        let v = cam.view_matrix().transform_point3(p);
        assert!(close(v, DVec3::new(0.0, 0.0, -7.0)));
    }
}
