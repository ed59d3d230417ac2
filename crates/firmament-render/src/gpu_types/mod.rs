//! The one place where the `f64` core becomes `f32` GPU data.
//!
//! Everything is made camera-relative here, in `f64`, before it is rounded: the sky only needs the
//! view *rotation*, so a camera at 100 AU gives the same `f32` matrix as one at the origin.
//! Each struct mirrors a WGSL struct of the same name; a unit test checks sizes and offsets
//! against the shader source with naga.

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::auto_exposure::ExposureMode;
use firmament_core::display::{DisplaySettings, Encoding, ToneCurve};
use firmament_core::sky::gradient::{Blend, GradientSkyState};
use firmament_core::sky::sun::SUN_HORIZON_FADE;
use glam::{DMat4, Mat4};

use pack::rgbw;

pub mod atmosphere;
pub mod camera;
pub mod classic;
pub mod clouds;
pub mod codes;
pub mod empirical_sky;
pub mod envmap;
pub mod flare;
pub mod medium;
pub mod night_sky;
mod pack;
mod planet_view;
pub mod shadow;
pub mod sky_lighting;

pub use atmosphere::{AtmosphereParamsUniforms, AtmosphereSunUniform, AtmosphereViewUniforms};
pub use medium::{DensityProfileUniform, MediumTermUniform};
pub(crate) use atmosphere::{BODY_AIR_LIGHT_SIZE, BODY_MAP_SIZE, OrderSumsGpu, body_air_light_layers, half_texels};
pub use camera::{ExposureStateGpu, MeteringUniforms};
pub use classic::{ClassicFrameUniforms, ClassicLightUniform, ClassicMaterialUniform, ClassicObjectUniforms};
pub use clouds::{CloudLayerGpu, CloudsGpu};
pub use empirical_sky::{EmpiricalSkyUniforms, EmpiricalStarUniform};
pub use envmap::{DiscTexelInstance, EnvmapParamsUniforms};
pub use flare::{FlareFrameUniforms, FlareInstance, FlareSourceGpu};
pub use night_sky::{MoonDraw, NightSkyUniforms, StarInstance};
pub use shadow::{ShadowCascadeGpu, ShadowCasterUniform, ShadowFrameUniforms};
pub use sky_lighting::{SkyLightingGpu, SkyLightingParamsUniforms, SkyLightingSunGpu};

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
    /// zenith_start, horizon_half_width, ground_start (radians), blend (a `GRADIENT_BLEND_*` of
    /// [`codes`]).
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
            Blend::Linear => codes::GRADIENT_BLEND_LINEAR,
            Blend::Smooth => codes::GRADIENT_BLEND_SMOOTH,
        } as f32;
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
    /// The scene's exposure multiplier (used when `metered` is 0).
    pub exposure: f32,
    /// The tone curve: a `TONE_CURVE_*` of [`codes`].
    pub curve: u32,
    /// What the shader does about the sRGB encoding: a `TRANSFER_*` of [`codes`] (decoding
    /// cancels an `*Srgb` output's encoding for [`Encoding::None`]).
    pub transfer: u32,
    /// 1: the exposure is the meter's (auto-exposure's texture), not `exposure`.
    pub metered: u32,
    /// Bloom's share of each pixel, [0, 1].
    pub bloom: f32,
    /// 1: the eye's night vision.
    pub night_vision: u32,
    /// Padding to 32 bytes.
    pub _pad: [u32; 2],
}

impl TonemapUniforms {
    /// The uniforms for `display`, writing to a texture of `output_format`.
    pub fn new(display: &DisplaySettings, output_format: wgpu::TextureFormat) -> Self {
        Self {
            exposure: display.exposure.multiplier as f32,
            curve: match display.tone_curve {
                ToneCurve::None => codes::TONE_CURVE_NONE,
                ToneCurve::AcesFitted => codes::TONE_CURVE_ACES_FITTED,
                ToneCurve::PbrNeutral => codes::TONE_CURVE_PBR_NEUTRAL,
                ToneCurve::Agx => codes::TONE_CURVE_AGX,
            },
            transfer: match (display.encoding, output_format.is_srgb()) {
                (Encoding::Srgb, false) => codes::TRANSFER_ENCODE_SRGB,
                (Encoding::None, true) => codes::TRANSFER_DECODE_SRGB,
                (Encoding::Srgb, true) | (Encoding::None, false) => codes::TRANSFER_NONE,
            },
            metered: u32::from(matches!(display.exposure_mode, ExposureMode::Auto(_))),
            bloom: display.bloom as f32,
            night_vision: u32::from(display.night_vision),
            _pad: [0; 2],
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
