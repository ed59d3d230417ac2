//! Projection matrices (glam, column-major).

use glam::{DMat4, DVec4};

/// Reversed-Z perspective with an infinite far plane: right-handed view space looking down
/// `-z`, wgpu clip depth `[0, 1]` with the near plane at 1 and infinity at 0.
pub fn perspective_infinite_reverse_z(fov_y: f64, aspect: f64, near: f64) -> DMat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 0.0, -1.0),
        DVec4::new(0.0, 0.0, near, 0.0),
    )
}

/// Reversed-Z perspective with a finite far plane: near → depth 1, far → depth 0.
pub fn perspective_reverse_z(fov_y: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    let range = near / (far - near);
    DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, range, -1.0),
        DVec4::new(0.0, 0.0, far * range, 0.0),
    )
}
