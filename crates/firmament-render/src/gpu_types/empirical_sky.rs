//! The empirical atmosphere's GPU data (`atmosphere.model = "seed"`; `shaders/empirical_sky.wgsl`).
//!
//! Everything is in the seed's planet frame and computed in `f64` before rounding: the camera's
//! planet-frame position and its ellipsoid terms `|o/a|² − 1` (exact even 1 m above the ground,
//! where `f32` could not compute them from a rounded position), and, for a camera farther than
//! [`FAR_CAMERA_RADII`](super::atmosphere::FAR_CAMERA_RADII) top radii, the planet centre's offset on the image plane, so that rays
//! start at their closest approach to the planet and never at the camera's useless `f32`
//! position (the same scheme as [`super::atmosphere`]).

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::atmosphere::empirical::{EMPIRICAL_STAR_RADIUS_INV_SQ_FACTOR, EmpiricalStar};
use firmament_core::frame::{MAX_EMPIRICAL_STARS, EmpiricalSky};
use glam::DVec3;

use super::planet_view::PlanetView;
use super::pack::vec3_w;

/// Mirrors `EmpiricalStar` in `shaders/empirical_sky.wgsl`: one of the seed's `light_*` uniforms.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct EmpiricalStarUniform {
    /// Centre, planet frame, metres; `w` = the disc-test radius `radius / √0.75` (the seed's
    /// 0.75 enlargement, line 422), metres, or −1 when the star shows no disc.
    pub position: [f32; 4],
    /// Unit direction towards the star (`light_dir`), planet frame; zero when it has none.
    pub direction: [f32; 4],
    /// Colour × visual intensity (`light_col`), linear RGB, unitless.
    pub color: [f32; 4],
}

impl EmpiricalStarUniform {
    /// The star as the shader reads it; what the f64 port ignores (a non-finite or non-positive
    /// radius, position or colour: no disc; a zero or non-finite direction: lights nothing) is
    /// encoded so that the shader ignores it too.
    pub fn new(star: &EmpiricalStar) -> Self {
        let shows_disc =
            star.radius.is_finite() && star.radius > 0.0 && star.position.is_finite() && star.color.is_finite();
        let radius = if shows_disc {
            star.radius / EMPIRICAL_STAR_RADIUS_INV_SQ_FACTOR.sqrt()
        } else {
            -1.0
        };
        let direction = if star.direction.is_finite() {
            star.direction.normalize_or_zero()
        } else {
            DVec3::ZERO
        };
        let position = if star.position.is_finite() {
            star.position
        } else {
            DVec3::ZERO
        };
        let color = if star.color.is_finite() {
            star.color
        } else {
            DVec3::ZERO
        };
        Self {
            position: vec3_w(position, radius),
            direction: vec3_w(direction, 0.0),
            color: vec3_w(color, 0.0),
        }
    }
}

/// Mirrors `EmpiricalSky` in `shaders/empirical_sky.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct EmpiricalSkyUniforms {
    /// View-space direction → planet frame rotation.
    pub view_to_planet: [[f32; 4]; 4],
    /// Camera position in the planet frame, metres.
    pub camera: [f32; 4],
    /// `|o/a|² − 1` against the surface and the top (from `f64`); tan of half the horizontal and
    /// vertical fields of view.
    pub camera_shape: [f32; 4],
    /// Far camera: the planet centre's view-space x, y over its depth; the depth (m); 1 when far.
    pub center: [f32; 4],
    /// Semi-axes `re, re, rp`, metres; `w` = atmosphere height, metres.
    pub radii: [f32; 4],
    /// B0, linear RGB, unitless; `w` = overglow, unitless.
    pub b0: [f32; 4],
    /// View depth (m), unused, luminance of colour 1 (cd/m²), unused.
    pub params: [f32; 4],
    /// Number of stars; 1 when the parameters are valid (else the pass draws black); unused ×2.
    pub counts: [u32; 4],
    /// The stars; the first `counts[0]` are used.
    pub stars: [EmpiricalStarUniform; MAX_EMPIRICAL_STARS],
}

impl EmpiricalSkyUniforms {
    /// The uniforms for `sky` seen by `camera` (whose aspect ratio is the target's). Stars past
    /// [`MAX_EMPIRICAL_STARS`] are dropped (the caller validates counts).
    pub fn new(sky: &EmpiricalSky, camera: &Camera) -> Self {
        let a = &sky.atmosphere;
        let radii = a.surface().radii;
        let top = a.top().radii;
        let o = sky.to_planet_frame(camera.position);
        let shape = PlanetView::new(camera, sky.center, sky.orientation, o, radii, top);
        let mut stars = [EmpiricalStarUniform::zeroed(); MAX_EMPIRICAL_STARS];
        for (slot, star) in stars.iter_mut().zip(&sky.stars) {
            *slot = EmpiricalStarUniform::new(star);
        }
        let valid = a.validate().is_ok() && o.is_finite() && sky.luminance.is_finite();
        Self {
            view_to_planet: shape.view_to_planet,
            camera: vec3_w(o, 0.0),
            camera_shape: shape.camera_shape,
            center: shape.center,
            radii: vec3_w(radii, a.height),
            b0: vec3_w(a.b0, a.overglow),
            params: [a.view_depth as f32, 0.0, sky.luminance as f32, 0.0],
            counts: [sky.stars.len().min(MAX_EMPIRICAL_STARS) as u32, u32::from(valid), 0, 0],
            stars,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use firmament_core::atmosphere::empirical::EmpiricalAtmosphere;
    use firmament_core::frame::EMPIRICAL_DEFAULT_LUMINANCE;
    use glam::DQuat;

    fn sky(center: DVec3) -> EmpiricalSky {
        EmpiricalSky {
            atmosphere: EmpiricalAtmosphere::seed_earth(),
            center,
            orientation: DQuat::from_rotation_x(0.3),
            stars: vec![EmpiricalStar::at(DVec3::X * 1.5e11, 7e8, DVec3::ONE)],
            luminance: EMPIRICAL_DEFAULT_LUMINANCE,
        }
    }

    #[test]
    fn the_camera_is_planet_relative_and_exact_near_the_ground() {
        let center = DVec3::new(1.0e7, -2.0e7, 3.0e6);
        let s = sky(center);
        // 2 m above the pole (the world z axis is the planet's, rotated by 0.3 rad about x).
        let pole = s.orientation * DVec3::Z * (s.atmosphere.polar_radius + 2.0) + center;
        let u = EmpiricalSkyUniforms::new(&s, &Camera::from_heading_pitch(pole, 0.0, 0.0));
        assert!((f64::from(u.camera[2]) - (s.atmosphere.polar_radius + 2.0)).abs() < 1.0);
        // |o/a|² − 1 ≈ 2·2 m / rp, from f64.
        let c = f64::from(u.camera_shape[0]);
        assert!((c - 4.0 / s.atmosphere.polar_radius).abs() < 1e-12, "{c}");
        assert_eq!(u.center[3], 0.0);
        assert_eq!(u.counts, [1, 1, 0, 0]);
        // The disc radius carries the seed's 0.75 enlargement.
        assert!((f64::from(u.stars[0].position[3]) - 7e8 / 0.75f64.sqrt()).abs() < 100.0);
    }

    #[test]
    fn a_far_camera_uses_the_image_plane_offset() {
        let s = sky(DVec3::ZERO);
        let au = firmament_core::atmosphere::presets::ASTRONOMICAL_UNIT;
        let camera = Camera::looking_at(DVec3::new(0.0, -25.0 * au, 1.0e6), DVec3::ZERO, DVec3::Z).expect("camera");
        let u = EmpiricalSkyUniforms::new(&s, &camera);
        assert_eq!(u.center[3], 1.0);
        assert!((f64::from(u.center[2]) - 25.0 * au).abs() < 1e-6 * 25.0 * au);
        // Invalid parameters are flagged, not uploaded as NaN work.
        let mut bad = s.clone();
        bad.atmosphere.height = f64::NAN;
        assert_eq!(EmpiricalSkyUniforms::new(&bad, &camera).counts[1], 0);
    }
}
