//! `f32` data of the night-sky pass: one [`NightSkyUniforms`] per frame (the camera's view
//! rotation and projection, the pixel grid, the Moon) and one [`StarInstance`] per star.
//!
//! Stars and the Moon are direction-only objects: everything is camera-relative (the view
//! *rotation* only), computed in `f64` and rounded once, so a camera far from the origin sees the
//! same sky. The Moon's disc is described in its own orthonormal basis (`e1`, `e2` across the
//! disc, `d` towards its centre) so the shader works with offsets of a fraction of a degree
//! without cancellation.

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::atmosphere::planet_shadow::SHADOW_ENTRIES;
use firmament_core::sky::night::{MoonDisc, MoonShadow, StarPoint};
use glam::{DMat4, DVec3};

/// Standard deviation of a star's Gaussian footprint, pixels.
pub const STAR_SIGMA_PX: f64 = 0.6;

/// Half the side of a star's footprint, pixels: a star covers the 5 × 5 pixels whose centres
/// lie within this distance of its centre along each axis (the 3 × 3 core holds ~97 % of its
/// light at σ = 0.6 px; the ring around it the rest).
pub const STAR_HALF_WINDOW_PX: f64 = 2.5;

/// A Moon whose radius on the image is under this many pixels is drawn as a star — all its light
/// ([`MoonDisc::illuminance`]) in one footprint — rather than as a disc its pixels would sample
/// too coarsely.
pub const MIN_MOON_DISC_RADIUS_PX: f64 = 2.0;

/// Pixels the Moon's quad reaches beyond its rim (room for the antialiased edge).
const MOON_QUAD_MARGIN_PX: f64 = 2.0;

/// Rays per pixel along each axis for a Moon of `radius_px` pixels: `32 / radius` within [4, 16]
/// — 4 × 4 from 8 pixels up, finer below, where a thin crescent a pixel wide needs them to keep
/// its light (the cost stays at ~10⁴ rays for the whole disc).
pub fn moon_rays_per_axis(radius_px: f64) -> u32 {
    (32.0 / radius_px).ceil().clamp(4.0, 16.0) as u32
}

/// How a frame's Moon is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MoonDraw {
    /// Not at all: no Moon, a malformed or dark one, or one not wholly in front of the camera.
    Hidden,
    /// As a shaded disc (the uniforms' `moon_*` fields).
    Disc,
    /// As a star of the Moon's light, when it is under [`MIN_MOON_DISC_RADIUS_PX`] in radius.
    Point(StarInstance),
}

/// Mirrors `NightSky` in `shaders/night_sky.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct NightSkyUniforms {
    /// Camera-relative world direction (`w` = 0) → clip space: projection × view rotation.
    pub view_proj: [[f32; 4]; 4],
    /// Target width and height, pixels; tan of half the horizontal and vertical field of view.
    pub pixels: [f32; 4],
    /// Star footprint σ and half window, pixels; unused; unused.
    pub star: [f32; 4],
    /// Unit direction to the Moon's centre `d` (camera-relative world frame); `w` = sin α
    /// (α the angular radius).
    pub moon_center: [f32; 4],
    /// Unit vector `e1` across the disc; `w` = the quad's half size in the tangent plane (tan α
    /// plus two pixels).
    pub moon_e1: [f32; 4],
    /// Unit vector `e2 = d × e1` across the disc; `w` = cos α.
    pub moon_e2: [f32; 4],
    /// The Sun seen from the Moon in the (`e1`, `e2`, `d`) basis; `w` = rays per pixel along
    /// each axis ([`moon_rays_per_axis`]).
    pub moon_sun: [f32; 4],
    /// Radiance at normal incidence and emergence, linear RGB (frame units); `w` unused.
    pub moon_radiance: [f32; 4],
    /// In a lunar eclipse, the shadow's axis in the (`e1`, `e2`, `d`) basis; `w` = the distance
    /// between entries of `moon_shadow`, Moon radii (0: no eclipse).
    pub moon_shadow_axis: [f32; 4],
    /// From the axis to the Moon's centre across it, Moon radii, in the same basis; `w` unused.
    pub moon_shadow_offset: [f32; 4],
    /// The sunlight's share by distance from the axis, linear RGB ([`MoonShadow::light`]).
    pub moon_shadow: [[f32; 4]; SHADOW_ENTRIES],
}

/// The shadow's fields in the Moon's (`e1`, `e2`, `d`) basis: the axis with the step, the offset,
/// the table; zero without an eclipse.
fn shadow_fields(shadow: Option<&MoonShadow>, basis: [DVec3; 3]) -> ([f32; 4], [f32; 4], [[f32; 4]; SHADOW_ENTRIES]) {
    let Some(shadow) = shadow else {
        return ([0.0; 4], [0.0; 4], [[0.0; 4]; SHADOW_ENTRIES]);
    };
    let local = |v: DVec3| [v.dot(basis[0]), v.dot(basis[1]), v.dot(basis[2])].map(|x| x as f32);
    let [ax, ay, az] = local(shadow.axis);
    let [ox, oy, oz] = local(shadow.offset);
    (
        [ax, ay, az, shadow.step as f32],
        [ox, oy, oz, 0.0],
        shadow.light.map(|c| [c.x as f32, c.y as f32, c.z as f32, 0.0]),
    )
}

/// One star; mirrors `StarIn` in `shaders/night_sky.wgsl` (vertex attributes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct StarInstance {
    /// Unit direction, camera-relative world frame; `w` unused.
    pub direction: [f32; 4],
    /// Irradiance, linear RGB, frame units × sr (negative channels clamped to 0); `w` unused.
    pub color: [f32; 4],
}

impl StarInstance {
    /// The star, or `None` when its direction or colour is not finite, its direction is zero or
    /// it gives no light.
    pub fn new(star: &StarPoint) -> Option<Self> {
        let d = star.direction.try_normalize()?;
        if !star.color.is_finite() {
            return None;
        }
        let c = star.color.max(DVec3::ZERO);
        if c.max_element() <= 0.0 {
            return None;
        }
        Some(Self {
            direction: [d.x as f32, d.y as f32, d.z as f32, 0.0],
            color: [c.x as f32, c.y as f32, c.z as f32, 0.0],
        })
    }
}

/// The Moon's part of [`NightSkyUniforms`]: `moon_center`, `moon_e1`, `moon_e2`, `moon_sun`,
/// `moon_radiance`.
type MoonFields = [[f32; 4]; 5];

/// The Moon's fields for a quad reaching `margin` (tangent-plane units) beyond the rim, or `None`
/// when the quad is not wholly in front of the camera (then the disc is far outside any field of
/// view).
fn moon_fields(moon: &MoonDisc, camera: &Camera, margin: f64, samples: u32) -> Option<MoonFields> {
    let d = moon.direction.normalize();
    let e1 = d.any_orthonormal_vector();
    let e2 = d.cross(e1);
    let (sin_a, cos_a) = moon.angular_radius.sin_cos();
    let half = sin_a / cos_a + margin;
    let forward = camera.forward();
    let in_front = [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .iter()
        .all(|(x, y)| (d + (e1 * *x + e2 * *y) * half).dot(forward) > 1e-6);
    if !in_front {
        return None;
    }
    let s = moon.sun_direction.normalize();
    let r = moon.radiance;
    Some([
        [d.x as f32, d.y as f32, d.z as f32, sin_a as f32],
        [e1.x as f32, e1.y as f32, e1.z as f32, half as f32],
        [e2.x as f32, e2.y as f32, e2.z as f32, cos_a as f32],
        [s.dot(e1) as f32, s.dot(e2) as f32, s.dot(d) as f32, samples as f32],
        [r.x as f32, r.y as f32, r.z as f32, 0.0],
    ])
}

impl NightSkyUniforms {
    /// The uniforms for `camera` (whose aspect must be the target's) over a target of `width` ×
    /// `height` pixels, with `moon` when there is one, and how the Moon is to be drawn.
    pub fn new(camera: &Camera, width: u32, height: u32, moon: Option<&MoonDisc>) -> (Self, MoonDraw) {
        let projection = camera.projection_matrix();
        let view_proj: DMat4 = projection * camera.view_rotation();
        // A symmetric perspective: x_ndc = (x / −z) / tan(fov_x/2), likewise y.
        let tan_x = 1.0 / projection.x_axis.x;
        let tan_y = 1.0 / projection.y_axis.y;
        // A pixel at the image centre in tangent-plane units (off axis pixels subtend less).
        let pixel = 2.0 * tan_y / f64::from(height.max(1));
        let mut fields = None;
        let draw = match moon.filter(|m| m.is_valid() && m.radiance.max_element() > 0.0) {
            None => MoonDraw::Hidden,
            Some(m) if m.angular_radius.tan() < MIN_MOON_DISC_RADIUS_PX * pixel => {
                let point = StarPoint {
                    direction: m.direction,
                    color: m.illuminance(),
                };
                StarInstance::new(&point).map_or(MoonDraw::Hidden, MoonDraw::Point)
            }
            Some(m) => {
                let rays = moon_rays_per_axis(m.angular_radius.tan() / pixel);
                fields = moon_fields(m, camera, MOON_QUAD_MARGIN_PX * pixel, rays);
                if fields.is_some() {
                    MoonDraw::Disc
                } else {
                    MoonDraw::Hidden
                }
            }
        };
        let [moon_center, moon_e1, moon_e2, moon_sun, moon_radiance] = fields.unwrap_or_default();
        let basis = |v: [f32; 4]| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
        let shadow = moon.and_then(|m| m.shadow.as_ref()).filter(|_| draw == MoonDraw::Disc);
        let (moon_shadow_axis, moon_shadow_offset, moon_shadow) =
            shadow_fields(shadow, [basis(moon_e1), basis(moon_e2), basis(moon_center)]);
        (
            Self {
                view_proj: view_proj.as_mat4().to_cols_array_2d(),
                pixels: [width as f32, height as f32, tan_x as f32, tan_y as f32],
                star: [STAR_SIGMA_PX as f32, STAR_HALF_WINDOW_PX as f32, 0.0, 0.0],
                moon_center,
                moon_e1,
                moon_e2,
                moon_sun,
                moon_radiance,
                moon_shadow_axis,
                moon_shadow_offset,
                moon_shadow,
            },
            draw,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    #[test]
    fn bad_stars_and_moons_are_left_out() {
        let good = StarPoint {
            direction: DVec3::new(0.0, 2.0, 0.0),
            color: DVec3::new(1.0, -1.0, 0.5),
        };
        let star = StarInstance::new(&good).expect("kept");
        assert_eq!(star.direction, [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(star.color, [1.0, 0.0, 0.5, 0.0]);
        for bad in [
            StarPoint {
                direction: DVec3::NAN,
                ..good
            },
            StarPoint {
                direction: DVec3::ZERO,
                ..good
            },
            StarPoint {
                color: DVec3::new(f64::INFINITY, 0.0, 0.0),
                ..good
            },
            StarPoint {
                color: DVec3::ZERO,
                ..good
            },
        ] {
            assert_eq!(StarInstance::new(&bad), None, "{bad:?}");
        }
        let camera = Camera {
            orientation: DQuat::IDENTITY,
            ..Camera::default()
        };
        let moon = MoonDisc {
            direction: DVec3::NEG_Z,
            angular_radius: 0.0045,
            sun_direction: DVec3::X,
            radiance: DVec3::ONE,
            shadow: None,
        };
        // 0.26° is ~4.6 px of a 60° view 1080 px high, ~0.04 px of one 9 px high.
        assert_eq!(
            NightSkyUniforms::new(&camera, 1920, 1080, Some(&moon)).1,
            MoonDraw::Disc
        );
        assert!(matches!(
            NightSkyUniforms::new(&camera, 16, 9, Some(&moon)).1,
            MoonDraw::Point(_)
        ));
        assert_eq!(NightSkyUniforms::new(&camera, 1920, 1080, None).1, MoonDraw::Hidden);
        let behind = MoonDisc {
            direction: DVec3::Z,
            ..moon
        };
        assert_eq!(
            NightSkyUniforms::new(&camera, 1920, 1080, Some(&behind)).1,
            MoonDraw::Hidden
        );
        let nan = MoonDisc {
            angular_radius: f64::NAN,
            ..moon
        };
        assert_eq!(
            NightSkyUniforms::new(&camera, 1920, 1080, Some(&nan)).1,
            MoonDraw::Hidden
        );
    }
}
