//! Projection matrices (glam, column-major).

use glam::{DMat4, DVec3, DVec4};

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

/// Standard-depth perspective with an infinite far plane: right-handed view space looking down
/// `-z`, wgpu clip depth `[0, 1]` with the near plane at 0 and infinity at 1.
pub fn perspective_infinite(fov_y: f64, aspect: f64, near: f64) -> DMat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, -1.0, -1.0),
        DVec4::new(0.0, 0.0, -near, 0.0),
    )
}

/// Standard-depth perspective with a finite far plane (Direct3D's and wgpu's `[0, 1]` clip
/// depth): near → depth 0, far → depth 1.
pub fn perspective(fov_y: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    let range = far / (near - far);
    DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, range, -1.0),
        DVec4::new(0.0, 0.0, near * range, 0.0),
    )
}

fn finite_all(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// `gluPerspective(fovy, aspect, zNear, zFar)` exactly as its man page defines it (OpenGL clip
/// depth `[-1, 1]`), with `fovy` in radians. `None` unless `0 < fovy < π`, `aspect > 0`,
/// `0 < z_near`, `z_near != z_far`, all finite.
pub fn glu_perspective(fovy: f64, aspect: f64, z_near: f64, z_far: f64) -> Option<DMat4> {
    let ok = finite_all(&[fovy, aspect, z_near, z_far])
        && fovy > 0.0
        && fovy < std::f64::consts::PI
        && aspect > 0.0
        && z_near > 0.0
        && z_near != z_far;
    if !ok {
        return None;
    }
    let f = 1.0 / (fovy / 2.0).tan();
    let depth = z_near - z_far;
    Some(DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, (z_far + z_near) / depth, -1.0),
        DVec4::new(0.0, 0.0, 2.0 * z_far * z_near / depth, 0.0),
    ))
}

/// `gluLookAt(eye, center, up)` exactly as its man page defines it: `M · translate(-eye)` with
/// `f = normalize(center − eye)`, `s = f × normalize(up)`, `u = normalize(s) × f`. `None` when
/// `center == eye`, `up` is zero or parallel to the view, or any input is not finite.
pub fn glu_look_at(eye: DVec3, center: DVec3, up: DVec3) -> Option<DMat4> {
    if !(eye.is_finite() && center.is_finite() && up.is_finite()) {
        return None;
    }
    let f = (center - eye).try_normalize()?;
    let s = f.cross(up.try_normalize()?);
    let s_norm = s.try_normalize()?;
    let u = s_norm.cross(f);
    // The man page's M has rows s', u, −f (s' normalised, as the GLU sample implementation does).
    let m = DMat4::from_cols(
        DVec4::new(s_norm.x, u.x, -f.x, 0.0),
        DVec4::new(s_norm.y, u.y, -f.y, 0.0),
        DVec4::new(s_norm.z, u.z, -f.z, 0.0),
        DVec4::W,
    );
    Some(m * DMat4::from_translation(-eye))
}

/// `glFrustum(left, right, bottom, top, nearVal, farVal)` as its man page defines it. `None`
/// unless `near > 0`, `far > 0`, `left != right`, `bottom != top`, `near != far`, all finite.
pub fn gl_frustum(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> Option<DMat4> {
    let ok = finite_all(&[left, right, bottom, top, near, far])
        && near > 0.0
        && far > 0.0
        && left != right
        && bottom != top
        && near != far;
    if !ok {
        return None;
    }
    let (a, b) = ((right + left) / (right - left), (top + bottom) / (top - bottom));
    let (c, d) = (-(far + near) / (far - near), -2.0 * far * near / (far - near));
    Some(DMat4::from_cols(
        DVec4::new(2.0 * near / (right - left), 0.0, 0.0, 0.0),
        DVec4::new(0.0, 2.0 * near / (top - bottom), 0.0, 0.0),
        DVec4::new(a, b, c, -1.0),
        DVec4::new(0.0, 0.0, d, 0.0),
    ))
}

/// `glOrtho(left, right, bottom, top, nearVal, farVal)` as its man page defines it. `None` for
/// empty ranges or non-finite input.
pub fn gl_ortho(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> Option<DMat4> {
    let ok = finite_all(&[left, right, bottom, top, near, far]) && left != right && bottom != top && near != far;
    if !ok {
        return None;
    }
    Some(DMat4::from_cols(
        DVec4::new(2.0 / (right - left), 0.0, 0.0, 0.0),
        DVec4::new(0.0, 2.0 / (top - bottom), 0.0, 0.0),
        DVec4::new(0.0, 0.0, -2.0 / (far - near), 0.0),
        DVec4::new(
            -(right + left) / (right - left),
            -(top + bottom) / (top - bottom),
            -(far + near) / (far - near),
            1.0,
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Element (row, column) in the man pages' row-major notation.
    fn at(m: &DMat4, row: usize, col: usize) -> f64 {
        m.col(col)[row]
    }

    fn clip_depth(m: &DMat4, view_z: f64) -> f64 {
        let c = *m * DVec4::new(0.0, 0.0, view_z, 1.0);
        c.z / c.w
    }

    /// The four `[0, 1]` perspective matrices against their textbook forms (row-major), and
    /// their near and far planes' depths.
    #[test]
    fn zero_to_one_perspectives_are_the_textbook_matrices() {
        let (fovy, aspect, n, f) = (50f64.to_radians(), 1.25, 0.5, 2000.0);
        let cot = 1.0 / (fovy / 2.0).tan();
        let rows = |z: [f64; 2]| {
            [
                [cot / aspect, 0.0, 0.0, 0.0],
                [0.0, cot, 0.0, 0.0],
                [0.0, 0.0, z[0], z[1]],
                [0.0, 0.0, -1.0, 0.0],
            ]
        };
        let cases = [
            // (matrix, textbook row 3, depth at near, depth at far or at 1e12 m)
            (
                perspective(fovy, aspect, n, f),
                rows([f / (n - f), n * f / (n - f)]),
                0.0,
                1.0,
            ),
            (perspective_infinite(fovy, aspect, n), rows([-1.0, -n]), 0.0, 1.0),
            (
                perspective_reverse_z(fovy, aspect, n, f),
                rows([n / (f - n), n * f / (f - n)]),
                1.0,
                0.0,
            ),
            (
                perspective_infinite_reverse_z(fovy, aspect, n),
                rows([0.0, n]),
                1.0,
                0.0,
            ),
        ];
        for (i, (m, expected, near_depth, far_depth)) in cases.iter().enumerate() {
            for (r, row) in expected.iter().enumerate() {
                for (c, value) in row.iter().enumerate() {
                    assert!((at(m, r, c) - value).abs() < 1e-12, "case {i} ({r}, {c})");
                }
            }
            assert!((clip_depth(m, -n) - near_depth).abs() < 1e-12, "case {i} near");
            let far = if i % 2 == 0 { f } else { 1e12 };
            assert!((clip_depth(m, -far) - far_depth).abs() < 1e-9, "case {i} far");
        }
    }

    #[test]
    fn glu_perspective_is_the_man_page_matrix() {
        let (fovy, aspect, n, f) = (35f64.to_radians(), 1.5, 1.0, 100.0);
        let m = glu_perspective(fovy, aspect, n, f).expect("valid");
        let cot = 1.0 / (fovy / 2.0).tan();
        let expected = [
            [cot / aspect, 0.0, 0.0, 0.0],
            [0.0, cot, 0.0, 0.0],
            [0.0, 0.0, (f + n) / (n - f), 2.0 * f * n / (n - f)],
            [0.0, 0.0, -1.0, 0.0],
        ];
        for (r, row) in expected.iter().enumerate() {
            for (c, value) in row.iter().enumerate() {
                assert!((at(&m, r, c) - value).abs() < 1e-15, "({r}, {c})");
            }
        }
        assert!((clip_depth(&m, -n) + 1.0).abs() < 1e-12);
        assert!((clip_depth(&m, -f) - 1.0).abs() < 1e-12);
        // gluPerspective is glFrustum with a symmetric frustum.
        let top = n * (fovy / 2.0).tan();
        let frustum = gl_frustum(-top * aspect, top * aspect, -top, top, n, f).expect("valid");
        assert!(m.abs_diff_eq(frustum, 1e-12));
        for bad in [
            (0.0, 1.0, 1.0, 2.0),
            (1.0, 0.0, 1.0, 2.0),
            (1.0, 1.0, 0.0, 2.0),
            (1.0, 1.0, 2.0, 2.0),
            (f64::NAN, 1.0, 1.0, 2.0),
        ] {
            assert!(glu_perspective(bad.0, bad.1, bad.2, bad.3).is_none(), "{bad:?}");
        }
    }

    #[test]
    fn glu_look_at_is_the_man_page_matrix() {
        let (eye, center, up) = (
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-4.0, 0.5, 1.0),
            DVec3::new(0.1, 1.0, 0.0),
        );
        let m = glu_look_at(eye, center, up).expect("valid");
        let f = (center - eye).normalize();
        let s = f.cross(up.normalize()).normalize();
        let u = s.cross(f);
        let rows = [[s.x, s.y, s.z], [u.x, u.y, u.z], [-f.x, -f.y, -f.z]];
        for (r, row) in rows.iter().enumerate() {
            for (c, value) in row.iter().enumerate() {
                assert!((at(&m, r, c) - value).abs() < 1e-15);
            }
        }
        // The eye goes to the origin and the centre onto −z.
        assert!(m.transform_point3(eye).length() < 1e-12);
        let c = m.transform_point3(center);
        assert!(c.x.abs() < 1e-12 && c.y.abs() < 1e-12 && c.z < 0.0);
        assert!(glu_look_at(eye, eye, up).is_none());
        assert!(glu_look_at(eye, center, center - eye).is_none());
    }

    #[test]
    fn gl_ortho_maps_the_box_to_the_cube() {
        let m = gl_ortho(-2.0, 4.0, -1.0, 3.0, 0.5, 10.0).expect("valid");
        assert!(
            m.transform_point3(DVec3::new(-2.0, -1.0, -0.5))
                .abs_diff_eq(DVec3::new(-1.0, -1.0, -1.0), 1e-12)
        );
        assert!(
            m.transform_point3(DVec3::new(4.0, 3.0, -10.0))
                .abs_diff_eq(DVec3::new(1.0, 1.0, 1.0), 1e-12)
        );
        assert!(gl_ortho(1.0, 1.0, 0.0, 1.0, 0.0, 1.0).is_none());
    }

    #[test]
    fn reversed_z_maps_near_to_one_and_far_to_zero() {
        let (fov, aspect, n, f) = (1.0, 1.3, 0.5, 1000.0);
        let finite = perspective_reverse_z(fov, aspect, n, f);
        assert!((clip_depth(&finite, -n) - 1.0).abs() < 1e-12);
        assert!(clip_depth(&finite, -f).abs() < 1e-12);
        let infinite = perspective_infinite_reverse_z(fov, aspect, n);
        assert!((clip_depth(&infinite, -n) - 1.0).abs() < 1e-12);
        assert!(clip_depth(&infinite, -1e300) < 1e-290);
        // The infinite matrix is the limit of the finite one.
        let far_away = perspective_reverse_z(fov, aspect, n, 1e15);
        assert!(far_away.abs_diff_eq(infinite, 1e-12));
    }
}
