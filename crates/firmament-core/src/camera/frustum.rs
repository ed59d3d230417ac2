//! View-frustum planes from a view-projection matrix, and point/sphere/box culling tests.
//!
//! Planes are extracted with the method of Gribb & Hartmann, "Fast Extraction of Viewing Frustum
//! Planes from the World-View-Projection Matrix" (2001), as in NeHe lesson 44's `UpdateFrustum`.

use glam::{DMat4, DVec3, DVec4};

/// Which clip-space depth range the matrix targets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClipDepth {
    /// OpenGL: `-w <= z <= w`.
    NegativeOneToOne,
    /// wgpu, Direct3D, Vulkan, Metal (and firmament's reversed-Z): `0 <= z <= w`.
    ZeroToOne,
}

/// A plane `normal · p + d = 0`; points with `normal · p + d >= 0` are inside. `normal` is unit
/// length, or zero for a degenerate plane (the far plane of an infinite projection), which
/// every point is inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Unit inward normal (or zero).
    pub normal: DVec3,
    /// Offset, metres.
    pub d: f64,
}

impl Plane {
    fn from_row(v: DVec4) -> Self {
        let n = v.truncate();
        let len = n.length();
        // A zero normal (up to rounding) is the plane at infinity: keep it as "always inside".
        if len <= 1e-300 || !len.is_finite() {
            return Self {
                normal: DVec3::ZERO,
                d: 0.0,
            };
        }
        Self {
            normal: n / len,
            d: v.w / len,
        }
    }

    /// Signed distance of `p` from the plane, metres (positive inside; 0 for degenerate planes).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) + self.d
    }
}

/// The six planes of a view frustum: left, right, bottom, top, near, far.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    /// Left, right, bottom, top, near, far.
    pub planes: [Plane; 6],
}

impl Frustum {
    /// Extracts the planes of `view_projection` (projection × view) in world coordinates.
    pub fn from_view_projection(view_projection: &DMat4, depth: ClipDepth) -> Self {
        let m = view_projection.transpose(); // rows of the original as columns
        let (r0, r1, r2, r3) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let near = match depth {
            ClipDepth::NegativeOneToOne => r3 + r2,
            ClipDepth::ZeroToOne => r2,
        };
        Self {
            planes: [
                Plane::from_row(r3 + r0),
                Plane::from_row(r3 - r0),
                Plane::from_row(r3 + r1),
                Plane::from_row(r3 - r1),
                Plane::from_row(near),
                Plane::from_row(r3 - r2),
            ],
        }
    }

    /// True when `p` is inside or on every plane.
    pub fn contains_point(&self, p: DVec3) -> bool {
        self.planes.iter().all(|plane| plane.distance(p) >= 0.0)
    }

    /// False only when the sphere is entirely outside one plane (NeHe lesson 44's
    /// `SphereInFrustum`); conservative near the frustum's corners.
    pub fn intersects_sphere(&self, center: DVec3, radius: f64) -> bool {
        self.planes.iter().all(|plane| plane.distance(center) >= -radius)
    }

    /// False only when the axis-aligned box lies entirely outside one plane (the positive-vertex
    /// test); conservative near corners.
    pub fn intersects_box(&self, min: DVec3, max: DVec3) -> bool {
        self.planes.iter().all(|plane| {
            let n = plane.normal;
            let positive = DVec3::new(
                if n.x >= 0.0 { max.x } else { min.x },
                if n.y >= 0.0 { max.y } else { min.y },
                if n.z >= 0.0 { max.z } else { min.z },
            );
            plane.distance(positive) >= 0.0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::camera::projection::{glu_look_at, glu_perspective};
    use crate::camera::viewport::{Viewport, project, project_zero_to_one};
    use proptest::prelude::*;

    fn gl_setup() -> (DMat4, DMat4) {
        let mv = glu_look_at(DVec3::new(1.0, 2.0, 8.0), DVec3::new(0.0, 0.5, 0.0), DVec3::Y).expect("valid");
        let p = glu_perspective(50f64.to_radians(), 1.6, 0.5, 30.0).expect("valid");
        (mv, p)
    }

    fn camera() -> Camera {
        Camera {
            near: 0.5,
            ..Camera::from_heading_pitch(DVec3::new(1.0, -2.0, 3.0), 0.4, 0.2)
        }
    }

    const VP: Viewport = Viewport {
        x: 0.0,
        y: 0.0,
        width: 2.0,
        height: 2.0,
    };

    fn window_inside(w: DVec3, zero_to_one_depth: (f64, f64)) -> bool {
        (0.0..=2.0).contains(&w.x)
            && (0.0..=2.0).contains(&w.y)
            && (zero_to_one_depth.0..=zero_to_one_depth.1).contains(&w.z)
    }

    proptest! {
        #[test]
        fn gl_frustum_agrees_with_glu_project(x in -20.0..20.0f64, y in -20.0..20.0f64, z in -40.0..20.0f64) {
            let (mv, p) = gl_setup();
            let f = Frustum::from_view_projection(&(p * mv), ClipDepth::NegativeOneToOne);
            let point = DVec3::new(x, y, z);
            let eye_z = mv.transform_point3(point).z;
            let projected = if eye_z < 0.0 { project(point, &mv, &p, &VP) } else { None };
            let inside = projected.is_some_and(|w| window_inside(w, (0.0, 1.0)));
            // Points within rounding of a plane may go either way.
            let margin = f.planes.iter().map(|pl| pl.distance(point).abs()).fold(f64::INFINITY, f64::min);
            prop_assume!(margin > 1e-9);
            prop_assert_eq!(f.contains_point(point), inside);
        }

        #[test]
        fn reversed_infinite_frustum_agrees_with_projection(x in -50.0..50.0f64, y in -50.0..50.0f64, z in -50.0..50.0f64) {
            let cam = camera();
            let (v, p) = (cam.view_matrix(), cam.projection_matrix());
            let f = Frustum::from_view_projection(&(p * v), ClipDepth::ZeroToOne);
            let point = DVec3::new(x, y, z);
            let eye_z = v.transform_point3(point).z;
            let projected = if eye_z < 0.0 { project_zero_to_one(point, &v, &p, &VP) } else { None };
            let inside = projected.is_some_and(|w| window_inside(w, (0.0, 1.0)));
            let margin = f.planes.iter().filter(|pl| pl.normal != DVec3::ZERO).map(|pl| pl.distance(point).abs()).fold(f64::INFINITY, f64::min);
            prop_assume!(margin > 1e-9);
            prop_assert_eq!(f.contains_point(point), inside);
        }
    }

    #[test]
    fn infinite_far_plane_is_degenerate_and_harmless() {
        let cam = camera();
        let f = Frustum::from_view_projection(&(cam.projection_matrix() * cam.view_matrix()), ClipDepth::ZeroToOne);
        assert_eq!(
            f.planes[4].normal,
            DVec3::ZERO,
            "reversed-Z: the z >= 0 plane is at infinity"
        );
        let far_ahead = cam.position + cam.forward() * 1e12;
        assert!(f.contains_point(far_ahead));
        assert!(!f.contains_point(cam.position - cam.forward()));
    }

    #[test]
    fn spheres_and_boxes() {
        let (mv, p) = gl_setup();
        let f = Frustum::from_view_projection(&(p * mv), ClipDepth::NegativeOneToOne);
        let centre = DVec3::new(0.0, 0.5, 0.0);
        assert!(f.intersects_sphere(centre, 0.1));
        // Behind the eye: outside even with a radius, until the radius reaches the frustum.
        let behind = DVec3::new(1.0, 2.0, 20.0);
        assert!(!f.intersects_sphere(behind, 1.0));
        assert!(f.intersects_sphere(behind, 13.0));
        assert!(f.intersects_box(centre - 0.1, centre + 0.1));
        assert!(!f.intersects_box(behind - 1.0, behind + 1.0));
        // A huge box around everything intersects.
        assert!(f.intersects_box(DVec3::splat(-1e3), DVec3::splat(1e3)));
    }
}
