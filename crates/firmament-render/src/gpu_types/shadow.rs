//! `f32` uniforms of the sun shadows: what the object pass samples ([`ShadowFrameUniforms`],
//! mirroring `ShadowFrame` in `shaders/shadow/sampling.wgsl`, the clouds' shadow map's axes in
//! eye space included: [`cloud_shadow_axes`]) and what each caster draw of the shadow-map pass
//! takes ([`ShadowCasterUniform`], `shaders/shadow/shadow_map.wgsl`).
//!
//! The cascades come fitted in `f64` from `firmament_core::classic::shadow`; matrices are
//! composed in `f64` (eye → light clip, object → light clip) and rounded once.

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::classic::shadow::{CascadeSet, MAX_SHADOW_CASCADES, MAX_SHADOW_LIGHTS, ShadowLight, ShadowSettings};
use firmament_core::frame::AtmosphereSky;
use glam::{DMat4, DVec3};

/// Mirrors `ShadowCascade` in `shaders/shadow/sampling.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ShadowCascadeGpu {
    /// Eye space → the light's clip space.
    pub eye_to_clip: [[f32; 4]; 4],
    /// Texel side (m), depth range (m), where the cascade ends (view distance, m), unused.
    pub params: [f32; 4],
}

const SLOTS: usize = (MAX_SHADOW_LIGHTS * MAX_SHADOW_CASCADES) as usize;

/// Mirrors `ShadowFrame` in `shaders/shadow/sampling.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ShadowFrameUniforms {
    /// Casting lights, cascades per light, map size (texels), 1 when shadows are on.
    pub counts: [u32; 4],
    /// Depth bias (texels), normal bias (texels), the highest caster's top above the camera
    /// (m, along world up), unused.
    pub bias: [f32; 4],
    /// The casting slot + 1 of light `i` at `[i / 4][i % 4]` (0: none).
    pub slot_of_light: [[u32; 4]; 2],
    /// tan(angular radius) of the light in slot `s` at `[s / 4][s % 4]`.
    pub tan_radius: [[f32; 4]; 2],
    /// Slot `s`, cascade `c` at `s * MAX_SHADOW_CASCADES + c`.
    pub cascades: [ShadowCascadeGpu; SLOTS],
    /// The clouds' shadow map for light `i` (a sun): rows `3i`, `3i + 1`, `3i + 2` hold the
    /// map's two axes across the sun's rays and the sun's direction, in eye space (xyz); row
    /// `3i`'s w is the sun's square in the map + 1 (0: no cloud shadow) ([`cloud_shadow_axes`]).
    pub clouds: [[f32; 4]; CLOUD_ROWS],
}

/// Rows of [`ShadowFrameUniforms::clouds`]: three per light.
pub const CLOUD_ROWS: usize = 3 * MAX_SHADOW_LIGHTS as usize;

/// The axes of the clouds' shadow map for each of `sky`'s suns (the first
/// `MAX_SHADOW_LIGHTS`, which are the object pass's lights in order) in the eye space of
/// `camera`: `clouds/shadow.wgsl`'s `cloud_shadow_axes` of the sun's planet-frame direction,
/// turned into eye space, whose origin is the camera the map is centred on. All zero without
/// cloud layers.
pub fn cloud_shadow_axes(sky: &AtmosphereSky, camera: &Camera) -> [[f32; 4]; CLOUD_ROWS] {
    let mut rows = [[0.0; 4]; CLOUD_ROWS];
    if sky.clouds.is_empty() {
        return rows;
    }
    let planet = &sky.atmosphere.planet;
    let world_to_eye = camera.view_matrix();
    let to_eye = |planet_frame: DVec3| {
        let world = planet.orientation.normalize() * planet_frame;
        world_to_eye.transform_vector3(world)
    };
    for (i, sun) in sky.suns.iter().take(MAX_SHADOW_LIGHTS as usize).enumerate() {
        // As the shader computes them, from the planet-frame direction the atmosphere uploads.
        let s = planet.direction_to_planet_frame(sun.direction).normalize_or_zero().as_vec3().as_dvec3();
        let helper = if s.z.abs() > 0.9 { DVec3::X } else { DVec3::Z };
        let across = s.cross(helper).normalize_or_zero();
        let axes = [across, s.cross(across), s].map(to_eye);
        for (k, axis) in axes.iter().enumerate() {
            let w = if k == 0 { i as f32 + 1.0 } else { 0.0 };
            rows[3 * i + k] = [axis.x as f32, axis.y as f32, axis.z as f32, w];
        }
    }
    rows
}

impl ShadowFrameUniforms {
    /// Shadows off: every light sees everything.
    pub fn off() -> Self {
        Self::zeroed()
    }

    /// The uniforms of the casting `lights` (slot = their index) whose cascades are `cascades`
    /// (`cascades[slot][c]`), maps of `settings.map_size`.
    pub fn new(settings: &ShadowSettings, lights: &[ShadowLight], cascades: &CascadeSet) -> Self {
        let mut u = Self::zeroed();
        let casting = &lights[..lights.len().min(MAX_SHADOW_LIGHTS as usize)];
        u.counts = [
            casting.len() as u32,
            settings.cascades,
            settings.map_size,
            u32::from(!casting.is_empty()),
        ];
        u.bias = [
            settings.depth_bias_texels as f32,
            settings.normal_bias_texels as f32,
            0.0,
            0.0,
        ];
        for (slot, light) in casting.iter().enumerate() {
            if light.light < MAX_SHADOW_LIGHTS as usize {
                u.slot_of_light[light.light / 4][light.light % 4] = slot as u32 + 1;
            }
            u.tan_radius[slot / 4][slot % 4] = light.angular_radius.tan() as f32;
            for (c, cascade) in cascades[slot].iter().enumerate() {
                u.cascades[slot * MAX_SHADOW_CASCADES as usize + c] = ShadowCascadeGpu {
                    eye_to_clip: cascade.eye_to_clip.as_mat4().to_cols_array_2d(),
                    params: [
                        cascade.texel_m as f32,
                        cascade.depth_range_m as f32,
                        cascade.far_m as f32,
                        0.0,
                    ],
                };
            }
        }
        u
    }
}

/// Mirrors `ShadowCaster` in `shaders/shadow/shadow_map.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ShadowCasterUniform {
    /// Object space → the cascade's light clip space.
    pub model_to_clip: [[f32; 4]; 4],
}

impl ShadowCasterUniform {
    /// A caster of model matrix `model` (object → world) in the cascade of world → clip
    /// `world_to_clip`.
    pub fn new(world_to_clip: &DMat4, model: &DMat4) -> Self {
        Self {
            model_to_clip: (*world_to_clip * *model).as_mat4().to_cols_array_2d(),
        }
    }
}
