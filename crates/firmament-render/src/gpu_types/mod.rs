//! The one place where the `f64` core becomes `f32` GPU data.
//!
//! Everything is made camera-relative here, in `f64`, before it is rounded: the sky only needs the
//! view *rotation*, so a camera at 100 AU gives the same `f32` matrix as one at the origin.
//! Each struct mirrors a WGSL struct of the same name; a unit test checks sizes and offsets
//! against the shader source with naga.

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::color::LinearRgb;
use firmament_core::display::{DisplaySettings, ToneCurve};
use firmament_core::gradient_sky::{Blend, GradientSkyState};
use firmament_core::sun::SUN_HORIZON_FADE;
use glam::{DMat4, Mat4};

pub mod atmosphere;
mod planet_view;
pub mod seed;

pub use atmosphere::{AtmosphereParamsUniforms, AtmosphereSunUniform, AtmosphereViewUniforms, DensityProfileUniform};
pub use seed::{SeedSkyUniforms, SeedStarUniform};

/// `vec4<f32>` of a vector, `w` appended, rounded once.
fn vec3_w(v: glam::DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// `vec4<f32>` of a colour, alpha `w`.
fn rgbw(c: LinearRgb, w: f64) -> [f32; 4] {
    [c.r as f32, c.g as f32, c.b as f32, w as f32]
}

/// Clip space → camera-relative world position, for passes that only need view directions.
/// Computed in `f64` (the inverse of projection × view rotation), rounded once at the end.
pub fn clip_to_world_direction(camera: &Camera) -> Mat4 {
    let m: DMat4 = (camera.projection_matrix() * camera.view_rotation()).inverse();
    m.as_mat4()
}

/// Mirrors `GradientSky` in `shaders/sky_gradient.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GradientSkyUniforms {
    /// Clip space → camera-relative world position.
    pub clip_to_world: [[f32; 4]; 4],
    /// Zenith colour, rgb.
    pub zenith: [f32; 4],
    /// Upper colour (top of the horizon band), rgb.
    pub upper: [f32; 4],
    /// Horizon colour, rgb.
    pub horizon: [f32; 4],
    /// Lower colour (bottom of the horizon band), rgb.
    pub lower: [f32; 4],
    /// Ground colour, rgb.
    pub ground: [f32; 4],
    /// Unit direction to the sun; `w` = angular radius, radians.
    pub sun_direction: [f32; 4],
    /// Disc radiance, rgb; `w` = edge softness.
    pub sun_disc: [f32; 4],
    /// Glow radiance at the centre, rgb; `w` = glow falloff, radians.
    pub sun_glow: [f32; 4],
    /// zenith_start, horizon_half_width, ground_start (radians), blend (0 linear, 1 smooth).
    pub shape: [f32; 4],
    /// upper_exponent, lower_exponent, sun horizon fade (radians), unused.
    pub exponents: [f32; 4],
}

impl GradientSkyUniforms {
    /// The uniforms for a gradient sky seen by `camera`.
    pub fn new(sky: &GradientSkyState, camera: &Camera) -> Self {
        let b = &sky.bands;
        let s = &sky.shape;
        let sun = &sky.sun;
        let blend = match s.blend {
            Blend::Linear => 0.0,
            Blend::Smooth => 1.0,
        };
        Self {
            clip_to_world: clip_to_world_direction(camera).to_cols_array_2d(),
            zenith: rgbw(b.zenith, 0.0),
            upper: rgbw(b.upper, 0.0),
            horizon: rgbw(b.horizon, 0.0),
            lower: rgbw(b.lower, 0.0),
            ground: rgbw(b.ground, 0.0),
            sun_direction: {
                let d = sun.direction.normalize_or_zero().as_vec3();
                [d.x, d.y, d.z, sun.angular_radius as f32]
            },
            sun_disc: rgbw(sun.disc_radiance, sun.edge_softness),
            sun_glow: rgbw(sun.glow_radiance, sun.glow_falloff),
            shape: [
                s.zenith_start as f32,
                s.horizon_half_width as f32,
                s.ground_start as f32,
                blend,
            ],
            exponents: [
                s.upper_exponent as f32,
                s.lower_exponent as f32,
                SUN_HORIZON_FADE as f32,
                0.0,
            ],
        }
    }
}

/// Mirrors `Tonemap` in `shaders/tonemap.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct TonemapUniforms {
    /// Exposure multiplier.
    pub exposure: f32,
    /// 0 none, 1 ACES fitted, 2 PBR Neutral.
    pub curve: u32,
    /// 1 when the shader must apply the sRGB transfer function itself.
    pub encode_srgb: u32,
    /// Padding to 16 bytes.
    pub _pad: u32,
}

impl TonemapUniforms {
    /// The uniforms for `display`, writing to a texture of `output_format`.
    pub fn new(display: &DisplaySettings, output_format: wgpu::TextureFormat) -> Self {
        Self {
            exposure: display.exposure.multiplier as f32,
            curve: match display.tone_curve {
                ToneCurve::None => 0,
                ToneCurve::AcesFitted => 1,
                ToneCurve::PbrNeutral => 2,
            },
            encode_srgb: u32::from(!output_format.is_srgb()),
            _pad: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3, Vec4};

    #[test]
    fn directions_survive_100_au() {
        // The same view from the origin and from 100 AU must give the same f32 matrix.
        let au = 1.495_978_707e11;
        let near = Camera::from_heading_pitch(DVec3::ZERO, 0.7, 0.2);
        let far = Camera {
            position: DVec3::new(100.0 * au, -3.0 * au, 7.0 * au),
            ..near
        };
        assert_eq!(clip_to_world_direction(&near), clip_to_world_direction(&far));
        // And the f32 matrix reproduces the f64 view directions closely.
        let m = clip_to_world_direction(&far);
        for ndc in [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(-0.3, 0.8)] {
            let p: Vec4 = m * Vec4::new(ndc.x as f32, ndc.y as f32, 1.0, 1.0);
            let d = (p.truncate() / p.w).normalize().as_dvec3();
            let reference = far.view_direction(ndc);
            assert!((d - reference).length() < 1e-6, "{d} vs {reference}");
        }
    }
}

/// Mirrors `ClassicLight` in `shaders/classic_lighting.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ClassicLightUniform {
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// `GL_POSITION`, eye space.
    pub position: [f32; 4],
    /// Spot direction (eye space); `w` = cos(cutoff), or −2 for no spot.
    pub spot_direction: [f32; 4],
    /// Spot exponent, constant, linear, quadratic attenuation.
    pub spot_attenuation: [f32; 4],
}

/// Mirrors `ClassicMaterial` in `shaders/classic_lighting.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ClassicMaterialUniform {
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// `GL_EMISSION`.
    pub emission: [f32; 4],
    /// `x` = `GL_SHININESS`.
    pub shininess: [f32; 4],
}

/// Most lights the classic pass takes (GL guarantees 8).
pub const MAX_CLASSIC_LIGHTS: usize = 8;

/// Per-vertex or per-fragment lighting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ClassicShading {
    /// Lit per vertex in eye space, colours clamped and interpolated (GL's smooth shading).
    #[default]
    Gouraud,
    /// The same equation per fragment with interpolated normals (SuperBible's Phong shading).
    Phong,
}

/// Mirrors `ClassicFrame` in `shaders/classic_lighting.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ClassicFrameUniforms {
    /// Object → eye.
    pub model_view: [[f32; 4]; 4],
    /// GL's normal matrix (inverse transpose of the model-view's 3×3), columns padded to vec4.
    pub normal_matrix: [[f32; 4]; 3],
    /// Eye → clip (reversed-Z for firmament's depth buffer).
    pub projection: [[f32; 4]; 4],
    /// `GL_LIGHT_MODEL_AMBIENT`.
    pub scene_ambient: [f32; 4],
    /// Light count, local viewer, two-sided, separate specular.
    pub model_flags: [u32; 4],
    /// Shading (0 Gouraud, 1 Phong), specular model (0 Blinn, 1 Phong).
    pub mode: [u32; 4],
    /// Fog equation (0 off, 1 linear, 2 exp, 3 exp2), coordinate (0 eye-plane depth, 1 distance).
    pub fog_mode: [u32; 4],
    /// Fog start, end, density.
    pub fog_params: [f32; 4],
    /// `GL_FOG_COLOR`.
    pub fog_color: [f32; 4],
    /// Front material.
    pub front: ClassicMaterialUniform,
    /// Back material.
    pub back: ClassicMaterialUniform,
    /// Lights; only the first `model_flags[0]` are used.
    pub lights: [ClassicLightUniform; MAX_CLASSIC_LIGHTS],
}

fn v4(v: glam::DVec4) -> [f32; 4] {
    v.as_vec4().to_array()
}

fn material_uniform(m: &firmament_core::classic::lighting::Material) -> ClassicMaterialUniform {
    ClassicMaterialUniform {
        ambient: v4(m.ambient),
        diffuse: v4(m.diffuse),
        specular: v4(m.specular),
        emission: v4(m.emission),
        shininess: [m.shininess as f32, 0.0, 0.0, 0.0],
    }
}

impl ClassicFrameUniforms {
    /// Uniforms for `lighting` with object → eye `model_view` and eye → clip `projection`,
    /// fogged by `fog` if given. Lights past [`MAX_CLASSIC_LIGHTS`] are dropped (the caller
    /// validates counts).
    pub fn new(
        lighting: &firmament_core::classic::lighting::Lighting<'_>,
        model_view: &DMat4,
        projection: &DMat4,
        shading: ClassicShading,
        fog: Option<&firmament_core::classic::fog::Fog>,
    ) -> Self {
        use firmament_core::classic::fog::{FogCoordinate, FogMode};
        use firmament_core::classic::lighting::SpecularModel;
        let normal = glam::DMat3::from_mat4(*model_view).inverse().transpose().as_mat3();
        let pad = |c: glam::Vec3| [c.x, c.y, c.z, 0.0];
        let mut lights = [ClassicLightUniform::zeroed(); MAX_CLASSIC_LIGHTS];
        for (slot, l) in lights.iter_mut().zip(lighting.lights) {
            let cos_cutoff = if l.spot_cutoff == 180.0 {
                -2.0
            } else {
                l.spot_cutoff.to_radians().cos() as f32
            };
            let d = l.spot_direction.as_vec3();
            *slot = ClassicLightUniform {
                ambient: v4(l.ambient),
                diffuse: v4(l.diffuse),
                specular: v4(l.specular),
                position: v4(l.position),
                spot_direction: [d.x, d.y, d.z, cos_cutoff],
                spot_attenuation: [
                    l.spot_exponent as f32,
                    l.constant_attenuation as f32,
                    l.linear_attenuation as f32,
                    l.quadratic_attenuation as f32,
                ],
            };
        }
        let m = &lighting.model;
        Self {
            model_view: model_view.as_mat4().to_cols_array_2d(),
            normal_matrix: [pad(normal.x_axis), pad(normal.y_axis), pad(normal.z_axis)],
            projection: projection.as_mat4().to_cols_array_2d(),
            scene_ambient: v4(m.ambient),
            model_flags: [
                lighting.lights.len().min(MAX_CLASSIC_LIGHTS) as u32,
                u32::from(m.local_viewer),
                u32::from(m.two_side),
                u32::from(m.separate_specular),
            ],
            mode: [
                match shading {
                    ClassicShading::Gouraud => 0,
                    ClassicShading::Phong => 1,
                },
                match lighting.specular {
                    SpecularModel::Blinn => 0,
                    SpecularModel::Phong => 1,
                },
                0,
                0,
            ],
            fog_mode: match fog {
                None => [0; 4],
                Some(f) => [
                    match f.mode {
                        FogMode::Linear { .. } => 1,
                        FogMode::Exp { .. } => 2,
                        FogMode::Exp2 { .. } => 3,
                    },
                    match f.coordinate {
                        FogCoordinate::EyePlaneDepth => 0,
                        FogCoordinate::EyeDistance => 1,
                    },
                    0,
                    0,
                ],
            },
            fog_params: match fog.map(|f| f.mode) {
                Some(FogMode::Linear { start, end }) => [start as f32, end as f32, 0.0, 0.0],
                Some(FogMode::Exp { density } | FogMode::Exp2 { density }) => [0.0, 0.0, density as f32, 0.0],
                None => [0.0; 4],
            },
            fog_color: fog.map_or([0.0; 4], |f| v4(f.color)),
            front: material_uniform(&lighting.front),
            back: material_uniform(&lighting.back),
            lights,
        }
    }
}
