//! `f32` uniforms of the classic (fixed-function) object pass: one [`ClassicFrameUniforms`] per
//! frame (projection, lights in eye space, light model, fog) and one [`ClassicObjectUniforms`]
//! per object (model-view, normal matrix, materials); the shadow maps' are in `shadow.rs`.
//!
//! Eye-space quantities are computed in `f64` (view × model, lights through the view) and rounded
//! once, so a far-away camera loses nothing before the cast.

use bytemuck::{Pod, Zeroable};
use firmament_core::classic::fog::{FogCoordinate, FogMode};
use firmament_core::classic::ground::Ground;
use firmament_core::classic::lighting::{Material, SpecularModel};
use firmament_core::classic::scene::{MAX_CLASSIC_LIGHTS, ObjectLighting, SceneFog, SceneObject, Shading};
use glam::{DMat3, DMat4, DVec3};

use super::codes;

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

/// Mirrors `ClassicFrame` in `shaders/classic_lighting.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ClassicFrameUniforms {
    /// Eye → clip (reversed-Z for firmament's depth buffer).
    pub projection: [[f32; 4]; 4],
    /// `GL_LIGHT_MODEL_AMBIENT`.
    pub scene_ambient: [f32; 4],
    /// Light count, local viewer, two-sided, separate specular.
    pub model_flags: [u32; 4],
    /// Shading (a `SHADING_*` of [`codes`]), specular model (a `SPECULAR_*`), radiance (1: no
    /// clamping to [0, 1], objects under a physical sky), unclamped vertex colours (1:
    /// `GL_CLAMP_VERTEX_COLOR` off, only the fragment stage clamps).
    pub mode: [u32; 4],
    /// Fog equation (a `FOG_*` of [`codes`]), coordinate (a `FOG_COORDINATE_*`), sun
    /// in-scattering (1 on, height fog).
    pub fog_mode: [u32; 4],
    /// Linear/exp/exp2: start, end, density. Height: extinction at the camera (1/m), falloff (1/m).
    pub fog_params: [f32; 4],
    /// `GL_FOG_COLOR`, or the height fog's colour.
    pub fog_color: [f32; 4],
    /// World +z in eye space (height fog).
    pub eye_up: [f32; 4],
    /// Height fog's sun: unit direction to it in eye space, `w` = lobe exponent.
    pub fog_sun: [f32; 4],
    /// Height fog's sun: in-scattered colour at the lobe's centre.
    pub fog_sun_color: [f32; 4],
    /// World up in eye space; `w` = the camera's height above the ground patch, metres.
    pub ground_up: [f32; 4],
    /// The ground's radiance from the suns, unshadowed (cd/m², linear sRGB).
    pub bounced_sun: [f32; 4],
    /// The ground's radiance from the sky (cd/m², linear sRGB).
    pub bounced_sky: [f32; 4],
    /// `x` = 1: the ambient by view factors of sky and ground ([`Ground`]); `yzw` unused.
    pub ground_mode: [u32; 4],
    /// Lights in eye space; only the first `model_flags[0]` are used.
    pub lights: [ClassicLightUniform; MAX_CLASSIC_LIGHTS],
}

/// Mirrors `ClassicObject` in `shaders/classic_lighting.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ClassicObjectUniforms {
    /// Object → eye.
    pub model_view: [[f32; 4]; 4],
    /// GL's normal matrix (inverse transpose of the model-view's 3×3), columns padded to vec4.
    pub normal_matrix: [[f32; 4]; 3],
    /// Front material.
    pub front: ClassicMaterialUniform,
    /// Back material.
    pub back: ClassicMaterialUniform,
    /// Textured (`GL_MODULATE`), the mesh has per-vertex fog coordinates, how many of
    /// `light_colors` replace the lights' colours, unused.
    pub flags: [u32; 4],
    /// `x` = the object's current fog coordinate (`glFogCoord`); `yzw` unused.
    pub fog_coord: [f32; 4],
    /// This object's own light colours (diffuse and specular), the first `flags.z` used.
    pub light_colors: [[f32; 4]; MAX_CLASSIC_LIGHTS],
}

fn v4(v: glam::DVec4) -> [f32; 4] {
    v.as_vec4().to_array()
}

fn material_uniform(m: &Material) -> ClassicMaterialUniform {
    ClassicMaterialUniform {
        ambient: v4(m.ambient),
        diffuse: v4(m.diffuse),
        specular: v4(m.specular),
        emission: v4(m.emission),
        shininess: [m.shininess as f32, 0.0, 0.0, 0.0],
    }
}

impl ClassicFrameUniforms {
    /// The frame's uniforms: `lighting` and `fog` seen through world → eye `view`, projected by
    /// eye → clip `projection`; `camera_height` is the camera's world `z`, metres (height fog).
    /// Lights past [`MAX_CLASSIC_LIGHTS`] are dropped (scenes validate the count).
    pub fn new(
        lighting: &ObjectLighting,
        fog: &SceneFog,
        view: &DMat4,
        projection: &DMat4,
        camera_height: f64,
    ) -> Self {
        let mut uniforms = Self {
            projection: projection.as_mat4().to_cols_array_2d(),
            eye_up: {
                let up = view.transform_vector3(DVec3::Z).as_vec3();
                [up.x, up.y, up.z, 0.0]
            },
            ..Self::zeroed()
        };
        match lighting.equations() {
            None => uniforms.mode = [codes::SHADING_UNLIT, 0, 0, 0],
            Some(classic) => {
                for (slot, scene_light) in uniforms.lights.iter_mut().zip(&classic.lights) {
                    let l = scene_light.in_eye_space(view);
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
                let m = &classic.model;
                uniforms.scene_ambient = v4(m.ambient);
                uniforms.model_flags = [
                    classic.lights.len().min(MAX_CLASSIC_LIGHTS) as u32,
                    u32::from(m.local_viewer),
                    u32::from(m.two_side),
                    u32::from(m.separate_specular),
                ];
                uniforms.mode = [
                    match classic.shading {
                        Shading::Flat | Shading::Gouraud => codes::SHADING_GOURAUD,
                        Shading::Phong => codes::SHADING_PHONG,
                    },
                    match classic.specular {
                        SpecularModel::Blinn => codes::SPECULAR_BLINN,
                        SpecularModel::Phong => codes::SPECULAR_PHONG,
                    },
                    u32::from(!lighting.clamps()),
                    u32::from(!m.clamp_vertex_color),
                ];
            }
        }
        match fog {
            SceneFog::None => uniforms.fog_mode = [codes::FOG_NONE, 0, 0, 0],
            SceneFog::Classic(f) => {
                let equation = match f.mode {
                    FogMode::Linear { .. } => codes::FOG_LINEAR,
                    FogMode::Exp { .. } => codes::FOG_EXP,
                    FogMode::Exp2 { .. } => codes::FOG_EXP2,
                };
                let coordinate = match f.coordinate {
                    FogCoordinate::EyePlaneDepth => codes::FOG_COORDINATE_EYE_PLANE_DEPTH,
                    FogCoordinate::EyeDistance => codes::FOG_COORDINATE_EYE_DISTANCE,
                    FogCoordinate::Vertex => codes::FOG_COORDINATE_VERTEX,
                };
                uniforms.fog_mode = [equation, coordinate, 0, 0];
                uniforms.fog_params = match f.mode {
                    FogMode::Linear { start, end } => [start as f32, end as f32, 0.0, 0.0],
                    FogMode::Exp { density } | FogMode::Exp2 { density } => [0.0, 0.0, density as f32, 0.0],
                };
                uniforms.fog_color = v4(f.color);
            }
            SceneFog::Height { fog, color, sun } => {
                let at_camera = fog.density * (-fog.falloff * (camera_height - fog.base_height)).exp();
                uniforms.fog_mode = [codes::FOG_HEIGHT, 0, u32::from(sun.is_some()), 0];
                uniforms.fog_params = [at_camera as f32, fog.falloff as f32, 0.0, 0.0];
                uniforms.fog_color = v4(*color);
                if let Some(sun) = sun {
                    let d = view.transform_vector3(sun.direction).normalize_or_zero().as_vec3();
                    uniforms.fog_sun = [d.x, d.y, d.z, sun.exponent as f32];
                    uniforms.fog_sun_color = v4(sun.color);
                }
            }
        }
        uniforms
    }

    /// Sets the view-factor ambient of `ground` (world → eye `view`); `scene_ambient` becomes
    /// the sky's part ([`Ground::sky`]).
    pub fn with_ground(mut self, ground: &Ground, view: &DMat4) -> Self {
        let up = view.transform_vector3(ground.up).normalize_or_zero().as_vec3();
        self.ground_up = [up.x, up.y, up.z, ground.camera_height_m as f32];
        self.scene_ambient = v4(ground.sky);
        self.bounced_sun = v4(ground.bounced_sun);
        self.bounced_sky = v4(ground.bounced_sky);
        self.ground_mode = [1, 0, 0, 0];
        self
    }
}

impl ClassicObjectUniforms {
    /// The uniforms of `object` seen through world → eye `view`. Light colours past
    /// [`MAX_CLASSIC_LIGHTS`] are dropped.
    pub fn new(object: &SceneObject, view: &DMat4) -> Self {
        let model_view = *view * object.model;
        let normal = DMat3::from_mat4(model_view).inverse().transpose().as_mat3();
        let pad = |c: glam::Vec3| [c.x, c.y, c.z, 0.0];
        let mut light_colors = [[0.0; 4]; MAX_CLASSIC_LIGHTS];
        for (slot, color) in light_colors.iter_mut().zip(&object.light_colors) {
            *slot = v4(*color);
        }
        Self {
            model_view: model_view.as_mat4().to_cols_array_2d(),
            normal_matrix: [pad(normal.x_axis), pad(normal.y_axis), pad(normal.z_axis)],
            front: material_uniform(&object.front),
            back: material_uniform(&object.back),
            flags: [
                u32::from(object.texture.is_some()),
                u32::from(!object.mesh.fog_coords.is_empty()),
                object.light_colors.len().min(MAX_CLASSIC_LIGHTS) as u32,
                0,
            ],
            fog_coord: [object.fog_coord as f32, 0.0, 0.0, 0.0],
            light_colors,
        }
    }
}
