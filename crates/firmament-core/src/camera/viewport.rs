//! Object ↔ window coordinates with `gluProject` / `gluUnProject` semantics.

use glam::{DMat4, DVec3, DVec4};

/// A viewport in pixels, origin at the **bottom-left** as in `glViewport`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewport {
    /// Left edge, pixels.
    pub x: f64,
    /// Bottom edge, pixels.
    pub y: f64,
    /// Width, pixels.
    pub width: f64,
    /// Height, pixels.
    pub height: f64,
}

impl Viewport {
    /// A viewport covering a `width` × `height` image.
    pub fn new(width: f64, height: f64) -> Self {
        Self {
            x: 0.0,
            y: 0.0,
            width,
            height,
        }
    }
}

/// `gluProject`: object coordinates → window coordinates `(x, y, depth)` with OpenGL's clip depth
/// `[-1, 1]` mapped to `[0, 1]`. `None` when the clip `w` is 0 (the point is in the eye plane).
pub fn project(obj: DVec3, model_view: &DMat4, projection: &DMat4, viewport: &Viewport) -> Option<DVec3> {
    let ndc = clip_to_ndc(*projection * *model_view * obj.extend(1.0))?;
    Some(ndc_to_window(ndc, viewport, |z| z * 0.5 + 0.5))
}

/// `gluUnProject`: window coordinates `(x, y, depth)` (depth in `[0, 1]`) → object coordinates.
/// `None` when `projection × model_view` is singular or the result has `w = 0`.
pub fn unproject(win: DVec3, model_view: &DMat4, projection: &DMat4, viewport: &Viewport) -> Option<DVec3> {
    unproject_ndc(window_to_ndc(win, viewport, |d| d * 2.0 - 1.0), model_view, projection)
}

/// [`project`] for wgpu's clip depth `[0, 1]` (firmament's own passes): window depth = NDC depth.
pub fn project_zero_to_one(obj: DVec3, model_view: &DMat4, projection: &DMat4, viewport: &Viewport) -> Option<DVec3> {
    let ndc = clip_to_ndc(*projection * *model_view * obj.extend(1.0))?;
    Some(ndc_to_window(ndc, viewport, |z| z))
}

/// [`unproject`] for wgpu's clip depth `[0, 1]`.
pub fn unproject_zero_to_one(win: DVec3, model_view: &DMat4, projection: &DMat4, viewport: &Viewport) -> Option<DVec3> {
    unproject_ndc(window_to_ndc(win, viewport, |d| d), model_view, projection)
}

fn clip_to_ndc(clip: DVec4) -> Option<DVec3> {
    (clip.w != 0.0).then(|| clip.truncate() / clip.w)
}

fn ndc_to_window(ndc: DVec3, v: &Viewport, depth: impl Fn(f64) -> f64) -> DVec3 {
    DVec3::new(
        v.x + (ndc.x * 0.5 + 0.5) * v.width,
        v.y + (ndc.y * 0.5 + 0.5) * v.height,
        depth(ndc.z),
    )
}

fn window_to_ndc(win: DVec3, v: &Viewport, depth: impl Fn(f64) -> f64) -> DVec4 {
    DVec4::new(
        (win.x - v.x) / v.width * 2.0 - 1.0,
        (win.y - v.y) / v.height * 2.0 - 1.0,
        depth(win.z),
        1.0,
    )
}

fn unproject_ndc(ndc: DVec4, model_view: &DMat4, projection: &DMat4) -> Option<DVec3> {
    let m = *projection * *model_view;
    let det = m.determinant();
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let obj = m.inverse() * ndc;
    (obj.w != 0.0).then(|| obj.truncate() / obj.w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::projection::{glu_look_at, glu_perspective};
    use proptest::prelude::*;

    fn classic() -> (DMat4, DMat4, Viewport) {
        let mv = glu_look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y).expect("valid");
        let p = glu_perspective(45f64.to_radians(), 640.0 / 480.0, 1.0, 100.0).expect("valid");
        (mv, p, Viewport::new(640.0, 480.0))
    }

    #[test]
    fn hand_computed_example() {
        let (mv, p, vp) = classic();
        // The look-at target projects to the viewport centre at depth for z_eye = −5:
        // z_ndc = (f + n)/(n − f)·(−5)/5 ... = ((101/−99)·−5 + 200/−99) / 5.
        let w = project(DVec3::ZERO, &mv, &p, &vp).expect("in front");
        let z_ndc = ((101.0 / -99.0) * -5.0 + (200.0 / -99.0)) / 5.0;
        assert!(
            (w - DVec3::new(320.0, 240.0, z_ndc * 0.5 + 0.5)).length() < 1e-12,
            "{w}"
        );
        // A point on the eye plane cannot be projected.
        assert!(project(DVec3::new(1.0, 0.0, 5.0), &mv, &p, &vp).is_none());
        assert!(unproject(DVec3::new(1.0, 1.0, 0.5), &DMat4::ZERO, &p, &vp).is_none());
    }

    proptest! {
        #[test]
        fn project_then_unproject_round_trips(x in -3.0..3.0f64, y in -3.0..3.0f64, z in -50.0..4.0f64) {
            let (mv, p, vp) = classic();
            let obj = DVec3::new(x, y, z);
            let win = project(obj, &mv, &p, &vp).expect("in front");
            let back = unproject(win, &mv, &p, &vp).expect("invertible");
            prop_assert!((back - obj).length() < 1e-7 * (1.0 + obj.length()), "{obj} → {win} → {back}");
            let win = project_zero_to_one(obj, &mv, &p, &vp).expect("in front");
            let back = unproject_zero_to_one(win, &mv, &p, &vp).expect("invertible");
            prop_assert!((back - obj).length() < 1e-7 * (1.0 + obj.length()));
        }
    }
}
