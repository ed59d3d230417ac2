//! Objects in a frame and how they are lit: the plain data the object pass draws.
//!
//! # Frames
//! An object's `model` matrix takes its mesh into the **world** frame (metres, +Z up). A GL
//! program's modelview is `view · model`; firmament builds the view from the scene's camera. A
//! camera at the origin with heading 0, pitch −90° (looking down −z, north up on screen) makes the
//! world frame GL's eye frame, so a ported program's `glTranslate`/`glRotate` steps carry over
//! unchanged (the `superbible-*` presets do this).
//!
//! Lights are given in eye space (fixed to the camera, like a light set while the modelview is
//! the identity) or in world space (moving with the scene, like one set after the view transform):
//! [`LightSpace`].

use std::sync::Arc;

use glam::{DMat4, DVec3, DVec4};

use super::fog::{Fog, FogSun, HeightFog};
use super::lighting::{Light, LightModel, Material, SpecularModel};
use crate::classic::ground::Ground;
use crate::classic::mesh::Mesh;
use crate::classic::shadow::Shadows;
use crate::texture::{TextureFilter, TextureImage};

/// Most lights classic lighting takes at once (GL guarantees 8; so do we).
pub const MAX_CLASSIC_LIGHTS: usize = 8;

/// Where a light's position and spot direction are given.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LightSpace {
    /// Eye space: the light moves with the camera (GL: set while the modelview is the identity).
    #[default]
    Eye,
    /// World space: the light stays in the scene (GL: set after the viewing transform); turned
    /// into eye space with the frame's view matrix.
    World,
}

/// A light with the space its position and spot direction are given in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneLight {
    /// The GL light parameters (position and spot direction in `space`).
    pub light: Light,
    /// The space of `light.position` and `light.spot_direction`.
    pub space: LightSpace,
}

impl SceneLight {
    /// The light in eye space for a camera with world → eye matrix `view` (what GL stores when
    /// `glLight(GL_POSITION)` is called under that modelview: the position times the matrix, the
    /// spot direction times its upper 3×3).
    pub fn in_eye_space(&self, view: &DMat4) -> Light {
        match self.space {
            LightSpace::Eye => self.light,
            LightSpace::World => Light {
                position: *view * self.light.position,
                spot_direction: view.transform_vector3(self.light.spot_direction),
                ..self.light
            },
        }
    }
}

/// Where lighting is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Shading {
    /// GL's `GL_FLAT`: the triangle takes the colour lit at its provoking vertex, which in GL is
    /// the **last** vertex of the triangle.
    Flat,
    /// GL's `GL_SMOOTH`: lit per vertex in eye space, colours clamped (unless
    /// `LightModel::clamp_vertex_color` is off) then interpolated.
    #[default]
    Gouraud,
    /// The same equation per fragment with interpolated normals (the SuperBible's Phong shader).
    Phong,
}

/// The fixed-function lighting of a classic scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ClassicLighting {
    /// The enabled lights, at most [`MAX_CLASSIC_LIGHTS`].
    pub lights: Vec<SceneLight>,
    /// `glLightModel` state.
    pub model: LightModel,
    /// Flat, Gouraud or Phong.
    pub shading: Shading,
    /// Blinn (fixed-function) or Phong specular.
    pub specular: SpecularModel,
}

/// How objects are lit.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ObjectLighting {
    /// Lighting off: each object's colour (its front material's diffuse colour, textured) passed
    /// through, clamped, as GL draws with `GL_LIGHTING` disabled.
    #[default]
    Unlit,
    /// The OpenGL 2.1 fixed-function equations.
    Classic(ClassicLighting),
    /// The same equations in radiance units and without GL's clamping to [0, 1]: objects under a
    /// physical atmosphere, lit by its suns and sky ([`super::sky_light::sky_lighting`]).
    Sky(ClassicLighting),
}

impl ObjectLighting {
    /// The lights, light model, shading and specular model, unless lighting is off.
    pub fn equations(&self) -> Option<&ClassicLighting> {
        match self {
            Self::Unlit => None,
            Self::Classic(c) | Self::Sky(c) => Some(c),
        }
    }

    /// Whether colours are clamped to [0, 1] as GL does (not for [`Self::Sky`]'s radiance).
    pub fn clamps(&self) -> bool {
        !matches!(self, Self::Sky(_))
    }
}

/// A texture on an object, modulating its lit colour (`GL_MODULATE`, repeat wrapping).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectTexture {
    /// The texels (shared between objects and frames).
    pub image: Arc<TextureImage>,
    /// Filtering.
    pub filter: TextureFilter,
}

/// One drawable object.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneObject {
    /// The triangles (shared between objects and frames, so the renderer uploads them once).
    pub mesh: Arc<Mesh>,
    /// Object → world, metres.
    pub model: DMat4,
    /// Front material.
    pub front: Material,
    /// Back material (used for back faces when two-sided lighting is on).
    pub back: Material,
    /// Optional texture.
    pub texture: Option<ObjectTexture>,
    /// GL's current fog coordinate (`glFogCoord`), used for every vertex when fog takes the
    /// vertex's coordinate and the mesh has no per-vertex array; GL's initial value is 0.
    pub fog_coord: f64,
    /// Light colours for this object alone, replacing each light's diffuse and specular colour
    /// (index by index; lights past the end keep theirs). Set under a physical sky, where a sun's
    /// light is what its transmittance lets through *at the object*
    /// ([`super::sky_light::SkyLight::sun_colors`]); empty otherwise.
    pub light_colors: Vec<DVec4>,
}

impl SceneObject {
    /// An untextured object with one material on both sides, GL's current fog coordinate 0 and
    /// the frame's own light colours.
    pub fn new(mesh: Arc<Mesh>, model: DMat4, material: Material) -> Self {
        Self {
            mesh,
            model,
            front: material,
            back: material,
            texture: None,
            fog_coord: 0.0,
            light_colors: Vec::new(),
        }
    }
}

/// Fog over objects.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum SceneFog {
    /// No fog.
    #[default]
    None,
    /// GL's fixed-function fog.
    Classic(Fog),
    /// Exponential height fog (world +z up), coloured `color`.
    Height {
        /// Density profile.
        fog: HeightFog,
        /// In-scattered colour (the fog's own colour; GL units).
        color: DVec4,
        /// Optional sunlight in-scattered around the sun's direction.
        sun: Option<FogSun>,
    },
}

/// Everything about objects in a frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ObjectLayer {
    /// The objects, drawn in order.
    pub objects: Vec<SceneObject>,
    /// How they are lit.
    pub lighting: ObjectLighting,
    /// Fog over them.
    pub fog: SceneFog,
    /// Sun shadows cast by the objects onto themselves and the ground (none by default, as GL).
    pub shadows: Shadows,
    /// The planet's surface near the camera, and the light it bounces up (under a physical sky).
    pub ground: Option<Ground>,
}

/// An object's model matrix from a list of GL-style steps, applied in the listed order as
/// `glTranslate` / `glRotate` / `glScale` would be: each step multiplies the current matrix on the
/// right, so the **last** step acts first on the vertices.
pub fn transform_from_steps(steps: &[TransformStep]) -> DMat4 {
    steps.iter().fold(DMat4::IDENTITY, |m, step| m * step.matrix())
}

/// One `glTranslate` / `glRotate` / `glScale`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TransformStep {
    /// `glTranslated(x, y, z)`, metres.
    Translate(DVec3),
    /// `glRotated(degrees, x, y, z)`: counter-clockwise about the axis (normalised here).
    Rotate {
        /// Angle, degrees.
        degrees: f64,
        /// Axis (any length > 0).
        axis: DVec3,
    },
    /// `glScaled(x, y, z)`.
    Scale(DVec3),
}

impl TransformStep {
    /// The step's matrix.
    pub fn matrix(&self) -> DMat4 {
        match *self {
            Self::Translate(t) => DMat4::from_translation(t),
            Self::Rotate { degrees, axis } => DMat4::from_axis_angle(axis.normalize(), degrees.to_radians()),
            Self::Scale(s) => DMat4::from_scale(s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_compose_like_gl_calls() {
        // glTranslate(1,0,0); glRotate(90, 0,0,1); glScale(2,2,2): a vertex at (1,0,0) is scaled
        // to (2,0,0), rotated to (0,2,0), translated to (1,2,0).
        let m = transform_from_steps(&[
            TransformStep::Translate(DVec3::X),
            TransformStep::Rotate {
                degrees: 90.0,
                axis: DVec3::new(0.0, 0.0, 5.0),
            },
            TransformStep::Scale(DVec3::splat(2.0)),
        ]);
        let p = m.transform_point3(DVec3::X);
        assert!((p - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn world_lights_follow_the_view() {
        let view = DMat4::from_translation(DVec3::new(0.0, 0.0, -4.0)) * DMat4::from_rotation_x(0.5);
        let light = SceneLight {
            light: Light {
                position: DVec4::new(1.0, 2.0, 3.0, 1.0),
                spot_direction: DVec3::new(0.0, 0.0, -1.0),
                ..Light::gl_default(0)
            },
            space: LightSpace::World,
        };
        let eye = light.in_eye_space(&view);
        assert!((eye.position - view * light.light.position).length() < 1e-12);
        assert!((eye.spot_direction - view.transform_vector3(DVec3::NEG_Z)).length() < 1e-12);
        let fixed = SceneLight {
            space: LightSpace::Eye,
            ..light
        };
        assert_eq!(fixed.in_eye_space(&view), light.light);
    }
}
