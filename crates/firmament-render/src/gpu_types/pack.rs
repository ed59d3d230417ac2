//! Rounding `f64` values into the `vec4<f32>` slots of GPU structs, once each.

use firmament_core::color::LinearRgb;

/// `vec4<f32>` of a vector, `w` appended, rounded once.
pub(crate) fn vec3_w(v: glam::DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// `vec4<f32>` of a colour, alpha `w`.
pub(crate) fn rgbw(c: LinearRgb, w: f64) -> [f32; 4] {
    [c.r as f32, c.g as f32, c.b as f32, w as f32]
}
