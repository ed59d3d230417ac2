//! Directions ↔ pixels of an equirectangular map and of cube faces, and each pixel's solid
//! angle. Pixel coordinates are continuous: pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)`, its
//! centre at `(i + 0.5, j + 0.5)`, `j = 0` the top row. Directions are unit ENU vectors (see the
//! [module](super) for the layouts).

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

/// A direction in the Y-up frame of the cube faces (`x` east, `y` up, `z` south) from ENU.
pub fn enu_to_y_up(enu: DVec3) -> DVec3 {
    DVec3::new(enu.x, enu.z, -enu.y)
}

/// A direction in ENU from the Y-up frame of the cube faces ([`enu_to_y_up`]'s inverse).
pub fn y_up_to_enu(y_up: DVec3) -> DVec3 {
    DVec3::new(y_up.x, -y_up.z, y_up.y)
}

/// The unit direction at continuous pixel coordinates (`x`, `y`) of a `width` × `height`
/// equirectangular map: azimuth `2π·(x/width − 1/4)` clockwise from north, zenith angle
/// `π·y/height`.
pub fn equirect_direction(x: f64, y: f64, width: u32, height: u32) -> DVec3 {
    let azimuth = TAU * (x / f64::from(width) - 0.25);
    let zenith = PI * y / f64::from(height);
    let (sin_z, cos_z) = zenith.sin_cos();
    let (sin_a, cos_a) = azimuth.sin_cos();
    DVec3::new(sin_z * sin_a, sin_z * cos_a, cos_z)
}

/// The continuous pixel coordinates of unit `direction` in a `width` × `height` equirectangular
/// map: `x` in `[0, width)`, `y` in `[0, height]` ([`equirect_direction`]'s inverse).
pub fn equirect_position(direction: DVec3, width: u32, height: u32) -> DVec2 {
    let azimuth = direction.x.atan2(direction.y);
    let zenith = direction.z.clamp(-1.0, 1.0).acos();
    let u = (azimuth / TAU + 0.25).rem_euclid(1.0);
    // rem_euclid can round up to exactly 1 for tiny negative inputs.
    let u = if u >= 1.0 { 0.0 } else { u };
    DVec2::new(u * f64::from(width), zenith / PI * f64::from(height))
}

/// The solid angle of one pixel of row `row` of a `width` × `height` equirectangular map,
/// steradians: `(2π / width)·(cos θ_top − cos θ_bottom)`. The rows sum to 4π.
pub fn equirect_pixel_solid_angle(row: u32, width: u32, height: u32) -> f64 {
    let zenith = |y: u32| PI * f64::from(y) / f64::from(height);
    TAU / f64::from(width) * (zenith(row).cos() - zenith(row + 1).cos())
}

/// A face of a cube map, in the OpenGL order (`+X, −X, +Y, −Y, +Z, −Z`) of the Y-up frame
/// ([`enu_to_y_up`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CubeFace {
    /// `+X`: east.
    PositiveX,
    /// `−X`: west.
    NegativeX,
    /// `+Y`: up.
    PositiveY,
    /// `−Y`: down.
    NegativeY,
    /// `+Z`: south.
    PositiveZ,
    /// `−Z`: north.
    NegativeZ,
}

impl CubeFace {
    /// Every face, in the OpenGL order.
    pub const ALL: [Self; 6] = [
        Self::PositiveX,
        Self::NegativeX,
        Self::PositiveY,
        Self::NegativeY,
        Self::PositiveZ,
        Self::NegativeZ,
    ];

    /// The usual short name: `px`, `nx`, `py`, `ny`, `pz`, `nz`.
    pub fn suffix(self) -> &'static str {
        match self {
            Self::PositiveX => "px",
            Self::NegativeX => "nx",
            Self::PositiveY => "py",
            Self::NegativeY => "ny",
            Self::PositiveZ => "pz",
            Self::NegativeZ => "nz",
        }
    }

    /// The face's place in [`Self::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The Y-up direction through texel coordinates `(sc, tc)` in `[−1, 1]²` of the face
    /// (OpenGL's table: `sc` to the right, `tc` down the image), not normalised.
    fn y_up_direction(self, sc: f64, tc: f64) -> DVec3 {
        match self {
            Self::PositiveX => DVec3::new(1.0, -tc, -sc),
            Self::NegativeX => DVec3::new(-1.0, -tc, sc),
            Self::PositiveY => DVec3::new(sc, 1.0, tc),
            Self::NegativeY => DVec3::new(sc, -1.0, -tc),
            Self::PositiveZ => DVec3::new(sc, -tc, 1.0),
            Self::NegativeZ => DVec3::new(-sc, -tc, -1.0),
        }
    }

    /// The unit ENU direction through the face's centre.
    pub fn forward(self) -> DVec3 {
        y_up_to_enu(self.y_up_direction(0.0, 0.0))
    }

    /// The unit ENU direction towards the face image's top edge, seen from its centre.
    pub fn up(self) -> DVec3 {
        y_up_to_enu(self.y_up_direction(0.0, -1.0) - self.y_up_direction(0.0, 0.0))
    }
}

/// The unit ENU direction at continuous texel coordinates (`x`, `y`) of `face`, `size` × `size`.
pub fn cube_direction(face: CubeFace, x: f64, y: f64, size: u32) -> DVec3 {
    let s = f64::from(size);
    y_up_to_enu(face.y_up_direction(2.0 * x / s - 1.0, 2.0 * y / s - 1.0)).normalize()
}

/// The face and continuous texel coordinates (each in `[0, size]`) of unit ENU `direction`
/// ([`cube_direction`]'s inverse; a direction on an edge goes to the first face of
/// [`CubeFace::ALL`] whose axis is largest).
pub fn cube_position(direction: DVec3, size: u32) -> (CubeFace, DVec2) {
    let r = enu_to_y_up(direction);
    let a = r.abs();
    let (face, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
        match r.x >= 0.0 {
            true => (CubeFace::PositiveX, -r.z, -r.y, a.x),
            false => (CubeFace::NegativeX, r.z, -r.y, a.x),
        }
    } else if a.y >= a.z {
        match r.y >= 0.0 {
            true => (CubeFace::PositiveY, r.x, r.z, a.y),
            false => (CubeFace::NegativeY, r.x, -r.z, a.y),
        }
    } else {
        match r.z >= 0.0 {
            true => (CubeFace::PositiveZ, r.x, -r.y, a.z),
            false => (CubeFace::NegativeZ, -r.x, -r.y, a.z),
        }
    };
    let s = f64::from(size);
    (face, DVec2::new((sc / ma + 1.0) * 0.5 * s, (tc / ma + 1.0) * 0.5 * s))
}

/// The solid angle of texel (`x`, `y`) of a `size` × `size` cube face, steradians (exact: the
/// area element `(1 + u² + v²)^(−3/2)` integrated over the texel). The six faces sum to 4π.
pub fn cube_texel_solid_angle(x: u32, y: u32, size: u32) -> f64 {
    let edge = |i: u32| 2.0 * f64::from(i) / f64::from(size) - 1.0;
    let corner = |u: f64, v: f64| (u * v).atan2((u * u + v * v + 1.0).sqrt());
    let (u0, u1, v0, v1) = (edge(x), edge(x + 1), edge(y), edge(y + 1));
    corner(u1, v1) - corner(u0, v1) - corner(u1, v0) + corner(u0, v0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    /// The elevation of a unit direction above the horizontal plane, radians.
    fn elevation(direction: DVec3) -> f64 {
        FRAC_PI_2 - direction.z.clamp(-1.0, 1.0).acos()
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn equirect_pixels_round_trip() {
        let (w, h) = (64, 32);
        for j in 0..h {
            for i in 0..w {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let d = equirect_direction(x, y, w, h);
                assert!((d.length() - 1.0).abs() < 1e-12);
                let p = equirect_position(d, w, h);
                assert!((p - DVec2::new(x, y)).length() < 1e-9, "({x}, {y}) → {d} → {p}");
            }
        }
    }

    #[test]
    fn equirect_layout_puts_north_at_a_quarter_and_east_in_the_middle() {
        let (w, h) = (360, 180);
        let at = |x: f64, y: f64| equirect_direction(x, y, w, h);
        assert!(close(at(90.0, 90.0), DVec3::Y), "north");
        assert!(close(at(180.0, 90.0), DVec3::X), "east");
        assert!(close(at(270.0, 90.0), -DVec3::Y), "south");
        assert!(close(at(0.0, 90.0), -DVec3::X), "west, the seam");
        assert!(close(at(17.0, 0.0), DVec3::Z), "zenith");
        assert!(close(at(17.0, 180.0), -DVec3::Z), "nadir");
        // 30° up in the north-east.
        let d = at(135.0, 60.0);
        assert!((elevation(d).to_degrees() - 30.0).abs() < 1e-9);
        assert!((d.x.atan2(d.y).to_degrees() - 45.0).abs() < 1e-9);
    }

    #[test]
    fn cube_texels_round_trip_and_faces_match_their_axes() {
        let size = 16;
        for face in CubeFace::ALL {
            for j in 0..size {
                for i in 0..size {
                    let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                    let d = cube_direction(face, x, y, size);
                    let (got, p) = cube_position(d, size);
                    assert_eq!(got, face);
                    assert!((p - DVec2::new(x, y)).length() < 1e-9, "{face:?} ({x}, {y}) → {p}");
                }
            }
            let centre = cube_direction(face, 8.0, 8.0, size);
            assert!(close(centre, face.forward()), "{face:?}");
            // Up the image is `up`; right is forward × up (the faces are seen from outside the
            // cube: OpenGL's convention is mirrored against a right-handed camera).
            // The part of `d` across the face, unit.
            let across = |d: DVec3| (d - centre * d.dot(centre)).normalize();
            let top = cube_direction(face, 8.0, 0.0, size);
            assert!(across(top).dot(face.up()) > 1.0 - 1e-12, "{face:?}");
            let right = cube_direction(face, 16.0, 8.0, size);
            let camera_right = face.forward().cross(face.up());
            assert!(across(right).dot(camera_right) < -1.0 + 1e-12, "{face:?}");
        }
        assert!(close(CubeFace::PositiveX.forward(), DVec3::X), "+X east");
        assert!(close(CubeFace::PositiveY.forward(), DVec3::Z), "+Y up");
        assert!(close(CubeFace::PositiveZ.forward(), -DVec3::Y), "+Z south");
        assert!(close(CubeFace::NegativeZ.forward(), DVec3::Y), "−Z north");
    }

    #[test]
    fn solid_angles_cover_the_sphere() {
        let (w, h) = (40, 20);
        let equirect: f64 = (0..h).map(|j| f64::from(w) * equirect_pixel_solid_angle(j, w, h)).sum();
        assert!((equirect / (4.0 * PI) - 1.0).abs() < 1e-12, "{equirect}");
        let size = 7;
        let face: f64 = (0..size)
            .flat_map(|j| (0..size).map(move |i| cube_texel_solid_angle(i, j, size)))
            .sum();
        assert!((6.0 * face / (4.0 * PI) - 1.0).abs() < 1e-12, "{face}");
        // A centre texel of a fine face is nearly (2/size)².
        let fine = 1000;
        let centre = cube_texel_solid_angle(500, 500, fine);
        assert!((centre / (2.0 / f64::from(fine)).powi(2) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn frames_convert_both_ways() {
        let d = DVec3::new(0.3, -0.5, 0.8);
        assert!(close(y_up_to_enu(enu_to_y_up(d)), d));
        assert!(close(enu_to_y_up(DVec3::Y), -DVec3::Z), "north is −Z");
        assert!(close(enu_to_y_up(DVec3::Z), DVec3::Y), "up is +Y");
    }
}
