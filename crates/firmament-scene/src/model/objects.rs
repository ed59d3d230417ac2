//! `[lighting]`, `[[lights]]`, `[[objects]]` and `[fog]`: objects and their classic lighting.
//!
//! Colours here are GL colours — `[r, g, b]` or `[r, g, b, a]`, linear, as a GL program passes
//! them to `glLight`/`glMaterial` — not sRGB hex strings. Absent light and material values take
//! GL's initial values (light 0 white, the others black; material ambient 0.2, diffuse 0.8).

use serde::Deserialize;

/// GL RGBA: `[r, g, b]` (alpha 1) or `[r, g, b, a]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum GlColor {
    /// `[r, g, b]`, alpha 1.
    Rgb([f64; 3]),
    /// `[r, g, b, a]`.
    Rgba([f64; 4]),
}

impl GlColor {
    /// As RGBA.
    pub fn rgba(self) -> [f64; 4] {
        match self {
            Self::Rgb([r, g, b]) => [r, g, b, 1.0],
            Self::Rgba(c) => c,
        }
    }
}

/// `lighting.model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LightingModelName {
    /// The OpenGL 2.1 fixed-function equations with `[[lights]]`.
    Classic,
    /// Lighting off: each object's `material.diffuse` passed through.
    Unlit,
    /// Lit by the atmosphere's `[[suns]]` (irradiance × transmittance) and sky (irradiance as the
    /// ambient term), in radiance units; needs `sky.model = "atmosphere"`. `[[lights]]` and
    /// `lighting.ambient` are not used.
    Sky,
}

/// `lighting.shading`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShadingName {
    /// `GL_FLAT`: each triangle the colour of its last vertex.
    Flat,
    /// `GL_SMOOTH`: lit per vertex, colours interpolated.
    Gouraud,
    /// Lit per fragment with interpolated normals.
    Phong,
}

/// `lighting.specular`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpecularName {
    /// The fixed-function half vector.
    Blinn,
    /// `reflect(−L, N)·V`, the SuperBible's model.
    Phong,
}

/// `[lighting]`: how objects are lit (`glLightModel`, `glShadeModel`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightingSection {
    /// `"classic"`, `"unlit"` or `"sky"`.
    pub model: LightingModelName,
    /// `"flat"`, `"gouraud"` or `"phong"`.
    pub shading: ShadingName,
    /// `"blinn"` or `"phong"`.
    pub specular: SpecularName,
    /// `GL_LIGHT_MODEL_AMBIENT`, GL RGBA (GL's initial value 0.2 grey).
    pub ambient: GlColor,
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER`.
    pub local_viewer: bool,
    /// `GL_LIGHT_MODEL_TWO_SIDE`.
    pub two_side: bool,
    /// `GL_SEPARATE_SPECULAR_COLOR` (specular added after texturing).
    pub separate_specular: bool,
    /// `GL_CLAMP_VERTEX_COLOR`: lit vertex colours clamped to [0, 1] before Gouraud
    /// interpolation (GL's default); `false` for a shader program's unclamped varyings.
    pub clamp_vertex_color: bool,
}

/// `space` of a light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum LightSpaceName {
    /// Fixed to the camera.
    #[default]
    Eye,
    /// Fixed in the world.
    World,
}

/// One `[[lights]]` entry: a GL light. Absent values are GL's initial values for its index.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightEntry {
    /// `"eye"` (default) or `"world"`: the space of `position` and `spot_direction`.
    #[serde(default)]
    pub space: LightSpaceName,
    /// `GL_POSITION` `[x, y, z, w]`: `w = 0` directional (towards the light), `w = 1` positional.
    #[serde(default)]
    pub position: Option<[f64; 4]>,
    /// `GL_AMBIENT`.
    #[serde(default)]
    pub ambient: Option<GlColor>,
    /// `GL_DIFFUSE`.
    #[serde(default)]
    pub diffuse: Option<GlColor>,
    /// `GL_SPECULAR`.
    #[serde(default)]
    pub specular: Option<GlColor>,
    /// `GL_SPOT_DIRECTION` `[x, y, z]`.
    #[serde(default)]
    pub spot_direction: Option<[f64; 3]>,
    /// `GL_SPOT_EXPONENT`, [0, 128].
    #[serde(default)]
    pub spot_exponent: Option<f64>,
    /// `GL_SPOT_CUTOFF`, degrees: [0, 90], or 180 for no spot.
    #[serde(default, rename = "spot_cutoff")]
    pub spot_cutoff_deg: Option<f64>,
    /// Constant, linear and quadratic attenuation, each >= 0 (GL's initial `[1, 0, 0]`).
    #[serde(default)]
    pub attenuation: Option<[f64; 3]>,
    /// Whether the light is a lens-flare source (drawn when `flare.enabled`).
    #[serde(default)]
    pub flare: bool,
    /// The disc its flare's occlusion samples cover, > 0: a radius in metres for a positional
    /// light (default 0.05), an angular radius in **radians** for a directional one (`w = 0`,
    /// default 0.005, below π/2).
    #[serde(default)]
    pub flare_radius: Option<f64>,
}

/// A material (`glMaterial`); absent values are GL's initial ones.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialEntry {
    /// `GL_AMBIENT` (initial 0.2 grey).
    #[serde(default)]
    pub ambient: Option<GlColor>,
    /// `GL_DIFFUSE` (initial 0.8 grey); with lighting off, the object's colour.
    #[serde(default)]
    pub diffuse: Option<GlColor>,
    /// `GL_SPECULAR` (initial black).
    #[serde(default)]
    pub specular: Option<GlColor>,
    /// `GL_EMISSION` (initial black).
    #[serde(default)]
    pub emission: Option<GlColor>,
    /// `GL_SHININESS`, [0, 128] (initial 0).
    #[serde(default)]
    pub shininess: Option<f64>,
}

/// An object's mesh: built in, or from a file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum MeshEntry {
    /// GLTools' `gltMakeSphere(radius, slices, stacks)` (the SuperBible's sphere).
    GltSphere {
        /// Radius, metres.
        radius: f64,
        /// Slices around the axis, 3 to 4096.
        slices: u32,
        /// Stacks from pole to pole, 2 to 4096.
        stacks: u32,
    },
    /// GLU's `gluSphere(quadric, radius, slices, stacks)` with texture coordinates.
    GluSphere {
        /// Radius, metres.
        radius: f64,
        /// Slices around the axis (GLU caps at 239).
        slices: u32,
        /// Stacks from pole to pole (GLU caps at 239).
        stacks: u32,
    },
    /// A square in the xy plane facing +z, `size` metres on a side, `subdivisions` cells per side.
    Quad {
        /// Side, metres.
        size: f64,
        /// Cells per side, 1 to 4096.
        subdivisions: u32,
    },
    /// An axis-aligned cube, `size` metres on a side.
    Cube {
        /// Side, metres.
        size: f64,
    },
    /// An OBJ (`.obj`) or glTF (`.gltf`, `.glb`) file; relative paths are from the scene file.
    File {
        /// The path.
        path: String,
    },
}

/// One transform step.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TransformEntry {
    /// `{ translate = [x, y, z] }`, metres.
    Translate([f64; 3]),
    /// `{ rotate = [degrees, x, y, z] }`: counter-clockwise about the axis.
    Rotate([f64; 4]),
    /// `{ scale = [x, y, z] }`.
    Scale([f64; 3]),
}

/// `filter` of a texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum FilterName {
    /// `GL_NEAREST`.
    Nearest,
    /// `GL_LINEAR`.
    #[default]
    Linear,
}

/// An object's texture: an image file or a built-in checkerboard.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureEntry {
    /// An image file (PNG); relative paths are from the scene file. Exclusive with `checkerboard`.
    #[serde(default)]
    pub file: Option<String>,
    /// A built-in checkerboard. Exclusive with `file`.
    #[serde(default)]
    pub checkerboard: Option<CheckerboardEntry>,
    /// `"nearest"` or `"linear"` (default).
    #[serde(default)]
    pub filter: FilterName,
}

/// A checkerboard texture.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckerboardEntry {
    /// Texels per side, 1 to 8192 (default 64).
    #[serde(default = "default_checker_size")]
    pub size: u32,
    /// Squares per side, 1 to `size` (default 8).
    #[serde(default = "default_checker_squares")]
    pub squares: u32,
    /// The two colours, GL RGBA in [0, 1] (default white and dark grey).
    #[serde(default = "default_checker_colors")]
    pub colors: [GlColor; 2],
}

fn default_checker_size() -> u32 {
    64
}

fn default_checker_squares() -> u32 {
    8
}

fn default_checker_colors() -> [GlColor; 2] {
    [GlColor::Rgb([1.0; 3]), GlColor::Rgb([0.25; 3])]
}

/// An object's spin: a rotation about an axis through its origin, growing with the time of day.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpinEntry {
    /// Axis in the object's frame (any length > 0).
    pub axis: [f64; 3],
    /// Angular speed, degrees per second (negative turns the other way).
    pub degrees_per_second: f64,
}

/// One `[[objects]]` entry.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectEntry {
    /// A label for people.
    #[serde(default)]
    pub name: Option<String>,
    /// The mesh.
    pub mesh: MeshEntry,
    /// Steps applied in order like `glTranslate`/`glRotate`/`glScale` calls.
    #[serde(default)]
    pub transform: Vec<TransformEntry>,
    /// Front and back material (`GL_FRONT_AND_BACK`).
    #[serde(default)]
    pub material: MaterialEntry,
    /// The back material when it differs (`GL_BACK`); values it leaves out come from `material`.
    #[serde(default)]
    pub back_material: Option<MaterialEntry>,
    /// Optional texture, modulating the lit colour.
    #[serde(default)]
    pub texture: Option<TextureEntry>,
    /// Optional spin, applied after `transform` (innermost, about the object's own origin).
    #[serde(default)]
    pub spin: Option<SpinEntry>,
    /// GL's current fog coordinate (`glFogCoord`, default 0): the fog coordinate of every vertex
    /// when `fog.coordinate = "vertex"` and the mesh has none of its own (a glTF mesh may carry
    /// them as the `_FOG_COORD` attribute).
    #[serde(default)]
    pub fog_coord: f64,
}

/// `fog.mode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FogModeName {
    /// No fog.
    None,
    /// `GL_LINEAR` with `start`, `end`.
    Linear,
    /// `GL_EXP` with `density`.
    Exp,
    /// `GL_EXP2` with `density`.
    Exp2,
    /// Exponential height fog with `density`, `falloff`, `base_height`.
    Height,
}

/// `fog.coordinate`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FogCoordinateName {
    /// `|z_eye|`.
    EyePlaneDepth,
    /// `|p_eye|`.
    EyeDistance,
    /// The vertex's own fog coordinate (`GL_FOG_COORD`).
    Vertex,
}

/// `[fog]` over objects.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FogSection {
    /// `"none"`, `"linear"`, `"exp"`, `"exp2"` or `"height"`.
    pub mode: FogModeName,
    /// `GL_FOG_COLOR` (or the height fog's colour), GL RGBA.
    pub color: GlColor,
    /// Linear fog start, metres (eye units).
    pub start: f64,
    /// Linear fog end, metres, > `start`.
    pub end: f64,
    /// `GL_FOG_DENSITY` (exp, exp2; per metre), or the height fog's extinction at `base_height`
    /// (1/m); >= 0.
    pub density: f64,
    /// `"eye_plane_depth"` (GL's usual), `"eye_distance"` or `"vertex"` (`GL_FOG_COORD`).
    pub coordinate: FogCoordinateName,
    /// Height fog: how fast the density falls with height, 1/m, >= 0.
    pub falloff: f64,
    /// Height fog: the world height (z) where the density is `density`, metres.
    pub base_height: f64,
    /// Height fog: sunlight in-scattered around the sun's direction, added to `color` at the
    /// centre of the lobe (GL RGBA); absent = none.
    #[serde(default)]
    pub sun_color: Option<GlColor>,
    /// Height fog: the lobe's exponent, >= 1 (larger = tighter around the sun).
    #[serde(default = "default_fog_sun_exponent")]
    pub sun_exponent: f64,
    /// Height fog: the direction towards the sun (world frame, any length > 0); absent = the
    /// first of `[[suns]]`.
    #[serde(default)]
    pub sun_direction: Option<[f64; 3]>,
}

fn default_fog_sun_exponent() -> f64 {
    8.0
}
