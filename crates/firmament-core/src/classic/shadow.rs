//! Sun shadows for objects and the ground: what a scene asks for ([`ShadowSettings`]), which
//! lights cast ([`ShadowLight`]), and the cascaded shadow maps fitted to the view
//! ([`fit_cascades`]), all in `f64` so the GPU pass only rounds finished matrices.
//!
//! # Method
//! - **Cascades** (Dimitrov 2007, "Cascaded Shadow Maps", NVIDIA; Zhang et al. 2006, "Parallel-Split
//!   Shadow Maps"): the view distance up to [`ShadowSettings::distance_m`] is split between the
//!   uniform and the logarithmic scheme by [`ShadowSettings::split_blend`]; each slice of the view
//!   frustum is enclosed by a sphere, so the cascade's size does not change as the camera turns.
//! - **Stable edges**: the sphere's radius is rounded up to a whole number of centimetres and its
//!   centre, seen from the light, is snapped to whole texels of the world-anchored light frame, so
//!   a moving camera moves the map by whole texels and no edge crawls.
//! - **Casters outside the slice**: each cascade's depth range reaches towards the light until it
//!   holds every caster bounding sphere that overlaps the cascade.
//! - **Soft edges** (Fernando 2005, "Percentage-Closer Soft Shadows"): the GPU searches the map for
//!   blockers and widens its filter to the penumbra a disc of angular radius α casts,
//!   `w = d · tan α` on each side of the edge for a receiver `d` metres behind the blocker
//!   ([`penumbra_half_width`]).
//!
//! Frames: world (metres) in, eye space out: each cascade's matrix maps eye space (the camera at
//! the origin) to the light's clip space, so `f32` keeps its precision however far the camera is
//! from the world origin.

use glam::{DMat4, DVec3, DVec4};

use super::scene::{ClassicLighting, LightSpace};
use crate::camera::Camera;
use crate::error::CoreError;

/// The most cascades a light may have.
pub const MAX_SHADOW_CASCADES: u32 = 4;
/// The most lights that may cast shadows at once (every sun of a frame).
pub const MAX_SHADOW_LIGHTS: u32 = 8;
/// Shadow-map sizes allowed, texels per side of one cascade.
pub const SHADOW_MAP_SIZES: std::ops::RangeInclusive<u32> = 256..=8192;
/// The most memory all shadow maps of a frame may take (4-byte depth texels), bytes.
pub const MAX_SHADOW_MAP_BYTES: u64 = 512 << 20;
/// How far shadows may reach from the camera, metres.
pub const MAX_SHADOW_DISTANCE_M: f64 = 100_000.0;

/// How a frame's shadows are made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowSettings {
    /// Texels per side of each cascade's map.
    pub map_size: u32,
    /// Cascades per casting light, 1 to [`MAX_SHADOW_CASCADES`].
    pub cascades: u32,
    /// How far from the camera shadows reach, metres (beyond, everything is lit).
    pub distance_m: f64,
    /// Where the cascade splits lie between uniform (0) and logarithmic (1) spacing.
    pub split_blend: f64,
    /// Depth bias, in texels of the cascade (a receiver is moved this far towards the light).
    pub depth_bias_texels: f64,
    /// Normal bias, in texels of the cascade (a receiver is moved this far along its normal, more
    /// where the light grazes it).
    pub normal_bias_texels: f64,
    /// The most lights that cast (the brightest at the camera), 1 to [`MAX_SHADOW_LIGHTS`].
    pub max_lights: u32,
}

impl Default for ShadowSettings {
    fn default() -> Self {
        Self {
            map_size: 2048,
            cascades: 4,
            distance_m: 400.0,
            split_blend: 0.8,
            depth_bias_texels: 1.0,
            normal_bias_texels: 1.5,
            max_lights: 2,
        }
    }
}

impl ShadowSettings {
    /// Checks every field against its rule (the names are the scene file's keys).
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        if !SHADOW_MAP_SIZES.contains(&self.map_size) {
            return invalid(
                "shadows.map_size",
                self.map_size.to_string(),
                "must be 256 to 8192 texels",
            );
        }
        if !(1..=MAX_SHADOW_CASCADES).contains(&self.cascades) {
            return invalid("shadows.cascades", self.cascades.to_string(), "must be 1 to 4");
        }
        if !(self.distance_m.is_finite() && self.distance_m > 0.0 && self.distance_m <= MAX_SHADOW_DISTANCE_M) {
            return invalid(
                "shadows.distance",
                self.distance_m.to_string(),
                "must be more than 0 and at most 100000 metres",
            );
        }
        if !(0.0..=1.0).contains(&self.split_blend) {
            return invalid("shadows.split_blend", self.split_blend.to_string(), "must be 0 to 1");
        }
        if !(0.0..=16.0).contains(&self.depth_bias_texels) {
            return invalid(
                "shadows.depth_bias",
                self.depth_bias_texels.to_string(),
                "must be 0 to 16 texels",
            );
        }
        if !(0.0..=16.0).contains(&self.normal_bias_texels) {
            return invalid(
                "shadows.normal_bias",
                self.normal_bias_texels.to_string(),
                "must be 0 to 16 texels",
            );
        }
        if !(1..=MAX_SHADOW_LIGHTS).contains(&self.max_lights) {
            return invalid("shadows.max_suns", self.max_lights.to_string(), "must be 1 to 8");
        }
        if self.map_bytes() > MAX_SHADOW_MAP_BYTES {
            return invalid(
                "shadows.map_size",
                format!(
                    "{} with {} cascades × {} suns",
                    self.map_size, self.cascades, self.max_lights
                ),
                "all maps together must fit in 512 MiB (map_size² × cascades × max_suns × 4 bytes)",
            );
        }
        Ok(())
    }

    /// The bytes of every map at the budget (`map_size² × cascades × max_lights × 4`).
    pub fn map_bytes(&self) -> u64 {
        u64::from(self.map_size).pow(2) * u64::from(self.cascades) * u64::from(self.max_lights) * 4
    }
}

/// A light that casts shadows this frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowLight {
    /// Its index in the frame's classic lights (a directional light in world space).
    pub light: usize,
    /// Unit world-frame direction towards it.
    pub direction: DVec3,
    /// Its disc's angular radius, radians (0: a point, hard edges).
    pub angular_radius: f64,
}

impl ShadowLight {
    /// The casting lights of a classic scene: its directional lights placed in world space
    /// (`GL_POSITION` with w = 0, [`LightSpace::World`]), brightest first by the luminance of
    /// their diffuse colour, at most `max_lights`; hard-edged (no disc). Lights that move with the
    /// eye, positional lights and spots cast nothing.
    pub fn from_classic(lighting: &ClassicLighting, max_lights: u32) -> Vec<Self> {
        let mut directional: Vec<(usize, f64, DVec3)> = lighting
            .lights
            .iter()
            .enumerate()
            .filter(|(_, l)| l.space == LightSpace::World && l.light.position.w == 0.0)
            .filter_map(|(i, l)| {
                let d = l.light.diffuse;
                let luminance = 0.2126 * d.x + 0.7152 * d.y + 0.0722 * d.z;
                let direction = l.light.position.truncate().try_normalize()?;
                (luminance > 0.0).then_some((i, luminance, direction))
            })
            .collect();
        directional.sort_by(|a, b| b.1.total_cmp(&a.1));
        directional
            .into_iter()
            .take(max_lights as usize)
            .map(|(light, _, direction)| Self {
                light,
                direction,
                angular_radius: 0.0,
            })
            .collect()
    }
}

/// A frame's shadows: how, and which lights cast.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Shadows {
    /// How; `None`: no shadows (the default, and GL's).
    pub settings: Option<ShadowSettings>,
    /// The casting lights, at most `settings.max_lights`.
    pub lights: Vec<ShadowLight>,
}

impl Shadows {
    /// Whether anything casts.
    pub fn any(&self) -> bool {
        self.settings.is_some() && !self.lights.is_empty()
    }
}

/// One cascade of one light's shadow map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowCascade {
    /// World → light clip space: x, y in [−1, 1] across the map (+y up the map), depth in
    /// [0, 1] from the light's side (0 nearest the light).
    pub world_to_clip: DMat4,
    /// Eye space → light clip space (`world_to_clip` × the view's inverse), for the GPU.
    pub eye_to_clip: DMat4,
    /// The view distance (along the camera's forward axis) where this cascade ends, metres.
    pub far_m: f64,
    /// The side of one texel, metres.
    pub texel_m: f64,
    /// The depth range the map's [0, 1] spans, metres.
    pub depth_range_m: f64,
}

/// Every cascade of every casting light: `cascades[light][cascade]`.
pub type CascadeSet = Vec<Vec<ShadowCascade>>;

/// The far end of each cascade along the view axis, metres: `split_blend` between the uniform
/// split `near + (far − near)·i/n` and the logarithmic `near·(far/near)^(i/n)`.
pub fn cascade_splits(near_m: f64, far_m: f64, cascades: u32, split_blend: f64) -> Vec<f64> {
    let n = f64::from(cascades.max(1));
    let near = near_m.max(1e-3).min(far_m);
    (1..=cascades.max(1))
        .map(|i| {
            let f = f64::from(i) / n;
            let uniform = near + (far_m - near) * f;
            let log = near * (far_m / near).powf(f);
            split_blend * log + (1.0 - split_blend) * uniform
        })
        .collect()
}

/// The half-width of the penumbra a light of angular radius `angular_radius` (radians) casts on
/// a receiver `behind_m` metres behind the blocker along the light, metres.
pub fn penumbra_half_width(angular_radius: f64, behind_m: f64) -> f64 {
    behind_m.max(0.0) * angular_radius.tan()
}

/// A right-handed basis whose z points towards the light: x and y span the map.
fn light_basis(direction: DVec3) -> (DVec3, DVec3, DVec3) {
    let z = direction.normalize();
    // World up as the hint, or north when the light stands at the zenith or nadir.
    let hint = if z.z.abs() < 0.99 { DVec3::Z } else { DVec3::Y };
    let x = hint.cross(z).normalize();
    let y = z.cross(x);
    (x, y, z)
}

/// The corners (world frame) of the view frustum's slice between view distances `near` and
/// `far` (along the forward axis).
fn slice_corners(camera: &Camera, near: f64, far: f64) -> [DVec3; 8] {
    let tan_y = (camera.fov_y * 0.5).tan();
    let tan_x = tan_y * camera.aspect;
    let (forward, right, up) = (camera.forward(), camera.right(), camera.up());
    let mut corners = [DVec3::ZERO; 8];
    for (i, corner) in corners.iter_mut().enumerate() {
        let d = if i < 4 { near } else { far };
        let sx = if i & 1 == 0 { -1.0 } else { 1.0 };
        let sy = if i & 2 == 0 { -1.0 } else { 1.0 };
        *corner = camera.position + forward * d + right * (sx * tan_x * d) + up * (sy * tan_y * d);
    }
    corners
}

/// Fits `settings.cascades` cascades of a map of `settings.map_size` texels to the view of
/// `camera` for each of `lights` (world directions towards them), holding every caster of
/// `casters` (world-frame bounding spheres: centre, radius in metres) that can shade the view.
pub fn fit_cascades(
    camera: &Camera,
    settings: &ShadowSettings,
    lights: &[ShadowLight],
    casters: &[(DVec3, f64)],
) -> CascadeSet {
    let splits = cascade_splits(
        camera.near,
        settings.distance_m,
        settings.cascades,
        settings.split_blend,
    );
    let eye_to_world = camera.view_matrix().inverse();
    let size = f64::from(settings.map_size);
    lights
        .iter()
        .map(|light| {
            let (x, y, z) = light_basis(light.direction);
            let mut near = camera.near;
            splits
                .iter()
                .map(|&far| {
                    let corners = slice_corners(camera, near, far);
                    near = far;
                    let centre = corners.iter().copied().sum::<DVec3>() / 8.0;
                    let radius = corners.iter().map(|c| c.distance(centre)).fold(0.0, f64::max);
                    // Whole centimetres: the same slice gives the same texel size every frame.
                    let radius = (radius * 100.0).ceil() / 100.0;
                    let texel = 2.0 * radius / size;
                    // The centre in the world-anchored light frame, snapped to whole texels.
                    let snap = |v: f64| (v / texel).round() * texel;
                    let (cx, cy, cz) = (snap(centre.dot(x)), snap(centre.dot(y)), centre.dot(z));
                    // Towards the light: as far as the slice's sphere, or the farthest caster
                    // that overlaps the cascade's square.
                    let mut top = cz + radius;
                    for &(c, r) in casters {
                        let (px, py) = (c.dot(x) - cx, c.dot(y) - cy);
                        if px.abs() <= radius + r && py.abs() <= radius + r {
                            top = top.max(c.dot(z) + r);
                        }
                    }
                    let bottom = cz - radius;
                    let depth_range = (top - bottom).max(1e-3);
                    // Rows of the light view: x, y, and −z so depth grows away from the light.
                    let light_view = DMat4::from_cols(
                        DVec4::new(x.x, y.x, -z.x, 0.0),
                        DVec4::new(x.y, y.y, -z.y, 0.0),
                        DVec4::new(x.z, y.z, -z.z, 0.0),
                        DVec4::new(-cx, -cy, top, 1.0),
                    );
                    let ortho = DMat4::from_cols(
                        DVec4::new(1.0 / radius, 0.0, 0.0, 0.0),
                        DVec4::new(0.0, 1.0 / radius, 0.0, 0.0),
                        DVec4::new(0.0, 0.0, 1.0 / depth_range, 0.0),
                        DVec4::new(0.0, 0.0, 0.0, 1.0),
                    );
                    let world_to_clip = ortho * light_view;
                    ShadowCascade {
                        world_to_clip,
                        eye_to_clip: world_to_clip * eye_to_world,
                        far_m: far,
                        texel_m: texel,
                        depth_range_m: depth_range,
                    }
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            aspect: 16.0 / 9.0,
            ..Camera::from_heading_pitch(DVec3::new(0.0, 0.0, 1.7), 0.0, 0.0)
        }
    }

    fn sun() -> ShadowLight {
        ShadowLight {
            light: 0,
            direction: DVec3::new(0.3, -0.4, 0.5).normalize(),
            angular_radius: 0.267f64.to_radians(),
        }
    }

    #[test]
    fn splits_end_at_the_distance_and_blend_between_schemes() {
        let uniform = cascade_splits(1.0, 401.0, 4, 0.0);
        assert_eq!(uniform, vec![101.0, 201.0, 301.0, 401.0]);
        let log = cascade_splits(1.0, 10_000.0, 4, 1.0);
        for (got, want) in log.iter().zip([10.0, 100.0, 1000.0, 10_000.0]) {
            assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
        }
    }

    #[test]
    fn every_cascade_holds_its_slice_of_the_view() {
        let settings = ShadowSettings::default();
        let camera = camera();
        let set = fit_cascades(&camera, &settings, &[sun()], &[]);
        let mut near = camera.near;
        for cascade in &set[0] {
            for corner in slice_corners(&camera, near, cascade.far_m) {
                let p = cascade.world_to_clip.project_point3(corner);
                assert!(p.x.abs() <= 1.0 + 1e-9 && p.y.abs() <= 1.0 + 1e-9, "{p}");
                assert!((-1e-9..=1.0 + 1e-9).contains(&p.z), "{p}");
            }
            near = cascade.far_m;
        }
        // Eye space maps where world space does.
        let point = DVec3::new(3.0, 20.0, 0.5);
        let eye = camera.view_matrix().transform_point3(point);
        let (a, b) = (
            set[0][1].world_to_clip.project_point3(point),
            set[0][1].eye_to_clip.project_point3(eye),
        );
        assert!(a.distance(b) < 1e-9, "{a} vs {b}");
    }

    #[test]
    fn depth_grows_away_from_the_light_and_reaches_tall_casters() {
        let settings = ShadowSettings::default();
        let camera = camera();
        let light = sun();
        // A tower whose top is well above the first cascade's sphere.
        let tower = (DVec3::new(0.0, 5.0, 40.0), 41.0);
        let set = fit_cascades(&camera, &settings, &[light], &[tower]);
        let c = &set[0][0];
        let near_light = c
            .world_to_clip
            .project_point3(DVec3::new(0.0, 5.0, 1.0) + light.direction);
        let far_light = c.world_to_clip.project_point3(DVec3::new(0.0, 5.0, 1.0));
        assert!(near_light.z < far_light.z);
        let top = c.world_to_clip.project_point3(tower.0 + light.direction * tower.1);
        assert!(top.z >= -1e-9, "the tower's top is in range: {top}");
    }

    #[test]
    fn a_moving_camera_moves_the_map_by_whole_texels() {
        let settings = ShadowSettings::default();
        let mut camera = camera();
        let light = sun();
        let point = DVec3::new(2.0, 8.0, 0.0);
        let before = fit_cascades(&camera, &settings, &[light], &[]);
        camera.position += DVec3::new(0.37, 0.61, 0.0);
        let after = fit_cascades(&camera, &settings, &[light], &[]);
        for (a, b) in before[0].iter().zip(&after[0]) {
            assert_eq!(a.texel_m, b.texel_m, "the same texel size");
            let texels = |c: &ShadowCascade| {
                let p = c.world_to_clip.project_point3(point);
                (p.x, p.y)
            };
            let half = f64::from(settings.map_size) / 2.0;
            let ((ax, ay), (bx, by)) = (texels(a), texels(b));
            for shift in [(bx - ax) * half, (by - ay) * half] {
                assert!((shift - shift.round()).abs() < 1e-6, "{shift} texels");
            }
        }
    }

    #[test]
    fn the_penumbra_grows_with_distance_behind_the_blocker() {
        let alpha = 0.267f64.to_radians();
        assert!((penumbra_half_width(alpha, 10.0) - 10.0 * alpha.tan()).abs() < 1e-15);
        assert_eq!(penumbra_half_width(alpha, -1.0), 0.0);
    }

    #[test]
    fn a_classic_scene_casts_from_its_world_directional_lights_brightest_first() {
        use crate::classic::lighting::Light;
        use crate::classic::scene::SceneLight;
        let light = |position: DVec4, grey: f64, space| SceneLight {
            light: Light {
                position,
                diffuse: DVec4::new(grey, grey, grey, 1.0),
                ..Light::gl_default(1)
            },
            space,
        };
        let lighting = ClassicLighting {
            lights: vec![
                light(DVec4::new(0.0, 0.0, 2.0, 0.0), 0.3, LightSpace::World),
                light(DVec4::new(1.0, 0.0, 1.0, 1.0), 0.9, LightSpace::World), // positional
                light(DVec4::new(0.0, 1.0, 1.0, 0.0), 0.8, LightSpace::World),
                light(DVec4::new(0.0, 0.0, 1.0, 0.0), 1.0, LightSpace::Eye), // a headlight
            ],
            ..ClassicLighting::default()
        };
        let cast = ShadowLight::from_classic(&lighting, 8);
        assert_eq!(cast.iter().map(|l| l.light).collect::<Vec<_>>(), [2, 0]);
        assert!(cast[1].direction.distance(DVec3::Z) < 1e-12 && cast[0].angular_radius == 0.0);
        assert_eq!(ShadowLight::from_classic(&lighting, 1).len(), 1);
    }

    #[test]
    fn bad_settings_name_their_key() {
        let bad = |s: ShadowSettings| s.validate().unwrap_err().to_string();
        let ok = ShadowSettings::default();
        assert!(ok.validate().is_ok());
        assert!(bad(ShadowSettings { map_size: 100, ..ok }).starts_with("shadows.map_size = 100"));
        assert!(bad(ShadowSettings { cascades: 5, ..ok }).starts_with("shadows.cascades"));
        assert!(
            bad(ShadowSettings {
                distance_m: f64::NAN,
                ..ok
            })
            .starts_with("shadows.distance")
        );
        assert!(
            bad(ShadowSettings {
                depth_bias_texels: -1.0,
                ..ok
            })
            .starts_with("shadows.depth_bias")
        );
        assert!(bad(ShadowSettings { max_lights: 9, ..ok }).starts_with("shadows.max_suns"));
        assert!(
            bad(ShadowSettings {
                map_size: 8192,
                max_lights: 8,
                ..ok
            })
            .contains("512 MiB")
        );
    }
}
