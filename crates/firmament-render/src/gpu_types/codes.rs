//! The codes Rust writes into uniforms and pipeline constants where a shader branches on them,
//! listed once for both sides: [`wgsl`] writes them as WGSL constants of the same names (the
//! shader module `generated/constants`), so a shader says `frame.mode.x == SHADING_PHONG` and
//! neither side can drift. Every code is a `u32`; where a uniform carries one in an `f32` (exact
//! for these small integers), the shader compares `u32(value)`.

/// Declares the codes as Rust constants and lists them, with their docs, for [`wgsl`].
macro_rules! codes {
    ($($(#[doc = $doc:literal])+ $name:ident = $value:literal;)*) => {
        $(
            $(#[doc = $doc])+
            pub const $name: u32 = $value;
        )*

        /// Every code: its name, value and doc lines.
        const ALL: &[(&str, u32, &[&str])] = &[$((stringify!($name), $name, &[$($doc),+])),*];
    };
}

codes! {
    /// Tone curve (`TonemapUniforms::curve`): none, values clamped to [0, 1].
    TONE_CURVE_NONE = 0;
    /// Tone curve: Stephen Hill's ACES fit.
    TONE_CURVE_ACES_FITTED = 1;
    /// Tone curve: Khronos PBR Neutral.
    TONE_CURVE_PBR_NEUTRAL = 2;
    /// Tone curve: AgX.
    TONE_CURVE_AGX = 3;
    /// Transfer (`TonemapUniforms::transfer`): values written as they are.
    TRANSFER_NONE = 0;
    /// Transfer: the sRGB encoding applied in the shader (the output format does not).
    TRANSFER_ENCODE_SRGB = 1;
    /// Transfer: the sRGB encoding's inverse, so that an `*Srgb` output's own encoding cancels.
    TRANSFER_DECODE_SRGB = 2;

    /// Gradient sky band blend (`GradientSkyUniforms::shape.w`, in an `f32`): linear.
    GRADIENT_BLEND_LINEAR = 0;
    /// Gradient sky band blend: smoothstep.
    GRADIENT_BLEND_SMOOTH = 1;

    /// Classic shading (`ClassicFrameUniforms::mode.x`): Gouraud, lit per vertex (flat shading
    /// too, over a mesh whose vertices carry their triangle's provoking vertex).
    SHADING_GOURAUD = 0;
    /// Classic shading: Phong, lit per fragment.
    SHADING_PHONG = 1;
    /// Classic shading: unlit, the front diffuse colour (GL lighting off).
    SHADING_UNLIT = 2;
    /// Classic specular model (`ClassicFrameUniforms::mode.y`): Blinn's half vector.
    SPECULAR_BLINN = 0;
    /// Classic specular model: Phong's reflection vector.
    SPECULAR_PHONG = 1;
    /// Fog equation (`ClassicFrameUniforms::fog_mode.x`): no fog.
    FOG_NONE = 0;
    /// Fog equation: GL's linear fog (GL 2.1 eq. 3.18).
    FOG_LINEAR = 1;
    /// Fog equation: GL's `GL_EXP` (eq. 3.16).
    FOG_EXP = 2;
    /// Fog equation: GL's `GL_EXP2` (eq. 3.17).
    FOG_EXP2 = 3;
    /// Fog equation: height fog, exponential in height.
    FOG_HEIGHT = 4;
    /// Fog coordinate (`ClassicFrameUniforms::fog_mode.y`): the eye-plane depth |z_eye|.
    FOG_COORDINATE_EYE_PLANE_DEPTH = 0;
    /// Fog coordinate: the distance from the eye.
    FOG_COORDINATE_EYE_DISTANCE = 1;
    /// Fog coordinate: the vertex's own (`GL_FOG_COORD`), else the object's current one.
    FOG_COORDINATE_VERTEX = 2;

    /// Flare element shape (`FlareInstance::shape.x`, in an `f32`): a glow.
    FLARE_GLOW = 0;
    /// Flare element shape: streaks.
    FLARE_STREAKS = 1;
    /// Flare element shape: a halo ring.
    FLARE_HALO = 2;
    /// Flare element shape: an aperture ghost (a regular polygon or a disc).
    FLARE_GHOST = 3;
    /// Flare element shape: a picture from the element image array.
    FLARE_IMAGE = 4;
    /// Depth convention (`FlareFrameUniforms::fade.z`, in an `f32`): reversed-Z, near 1 and far 0.
    DEPTH_REVERSED = 0;
    /// Depth convention: standard, near 0 and far 1.
    DEPTH_STANDARD = 1;

    /// A medium term's phase function (`MediumTermUniform::scattering.w`, in an `f32`): Rayleigh.
    PHASE_RAYLEIGH = 0;
    /// Phase function: Cornette–Shanks.
    PHASE_CORNETTE_SHANKS = 1;
    /// Phase function: Henyey–Greenstein.
    PHASE_HENYEY_GREENSTEIN = 2;
    /// Phase function: two Henyey–Greenstein lobes.
    PHASE_DUAL_HENYEY_GREENSTEIN = 3;
    /// Phase function: the term's row of the phase tables.
    PHASE_TABLE = 4;
    /// Sky pass variant (`SKY_MODE` of `atmosphere/sky.wgsl`): the sky-view LUT only.
    SKY_MODE_LUT = 0;
    /// Sky pass variant: a ray march per pixel only.
    SKY_MODE_MARCH = 1;
    /// Sky pass variant: both, blended by `view.local_up.w` (across the top of the atmosphere).
    SKY_MODE_BLEND = 2;
    /// Aerial-perspective draw (`OUTPUT` of `atmosphere/aerial_perspective.wgsl`): the
    /// transmittance, blended `dst · src`.
    AERIAL_OUTPUT_TRANSMITTANCE = 0;
    /// Aerial-perspective draw: the scattered light, blended `dst + src`.
    AERIAL_OUTPUT_SCATTERING = 1;

    /// Cloud kind (`CloudLayerGpu::codes.x`; `firmament_core`'s `CloudKind::code`): cumulus.
    CLOUD_KIND_CUMULUS = 0;
    /// Cloud kind: stratocumulus.
    CLOUD_KIND_STRATOCUMULUS = 1;
    /// Cloud kind: stratus.
    CLOUD_KIND_STRATUS = 2;
    /// Cloud kind: altostratus.
    CLOUD_KIND_ALTOSTRATUS = 3;
    /// Cloud kind: cirrus.
    CLOUD_KIND_CIRRUS = 4;
    /// Cloud kind: a uniform slab, no noise.
    CLOUD_KIND_UNIFORM = 5;

    /// A body's reflectance law (`AtmosphereBodyUniform::center.w`, in an `f32`;
    /// `firmament_core`'s `Reflectance::gpu_code`): Lambert.
    BODY_REFLECTANCE_LAMBERT = 0;
    /// A body's reflectance law: Lommel–Seeliger.
    BODY_REFLECTANCE_LOMMEL_SEELIGER = 1;
    /// A body's reflectance law: the Moon's (Lommel–Seeliger times its phase factor).
    BODY_REFLECTANCE_LUNAR = 2;
    /// A body's surface (`AtmosphereBodyUniform::radii.w`, in an `f32`; `firmament_core`'s
    /// `BodySurface::gpu_code`): the albedo everywhere.
    BODY_SURFACE_UNIFORM = 0;
    /// A body's surface: the Moon's maria.
    BODY_SURFACE_LUNAR_MARIA = 1;
    /// A body's surface: its albedo map (layer i of `body_maps` for body i).
    BODY_SURFACE_MAP = 2;
}

/// The WGSL of the shader module `generated/constants`: every code as a `const` of its Rust name,
/// its doc as a comment.
pub fn wgsl() -> String {
    let mut text = String::from(
        "// generated/constants — written by Rust (firmament-render's `gpu_types/codes.rs`), not read\n\
         // from a file: the codes Rust writes into uniforms and pipeline constants, by name.\n",
    );
    for (name, value, doc) in ALL {
        text.push('\n');
        for line in *doc {
            text.push_str(&format!("//{line}\n"));
        }
        text.push_str(&format!("const {name}: u32 = {value}u;\n"));
    }
    text.push_str(&eclipse_quadrature_wgsl());
    text.push_str(&lunar_maria_wgsl());
    text.push_str(&format!(
        "\n// How far apart, in column cells, a ray across a broken cloud layer meets independent\n\
         // columns (firmament_core::atmosphere::clouds).\n\
         const CLOUD_COLUMN_SPACING_CELLS: f32 = {:?};\n",
        firmament_core::atmosphere::clouds::COLUMN_SPACING_CELLS as f32
    ));
    text.push_str(&format!(
        "\n// The phase angle past which the Moon's phase factor is held, radians\n\
         // (firmament_core::atmosphere::body::phase).\n\
         const LUNAR_PHASE_MAX_RAD: f32 = {:?};\n",
        firmament_core::atmosphere::body::phase::LUNAR_PHASE_MAX_RAD as f32
    ));
    text
}

/// The Moon's maria (`atmosphere/bodies.wgsl`), from the core's table
/// ([`firmament_core::atmosphere::body::maria`]): each patch's centre in the body's axes and its
/// angular radius, and the pattern's factors.
fn lunar_maria_wgsl() -> String {
    use firmament_core::atmosphere::body::maria::{EDGE_INNER, EDGE_OUTER, HIGHLAND_FACTOR, MARE_FACTOR, MARIA};
    let patches = MARIA
        .iter()
        .map(|m| {
            let c = m.center().as_vec3();
            format!("vec4<f32>({:e}, {:e}, {:e}, {:e})", c.x, c.y, c.z, m.angular_radius() as f32)
        })
        .collect::<Vec<_>>()
        .join(",\n    ");
    let n = MARIA.len();
    format!(
        "\n// The Moon's maria: centre in the body's axes (xyz), angular radius (w, rad); the albedo's\n\
         // factor on highlands and maria, and the rims (firmament_core::atmosphere::body::maria).\n\
         const LUNAR_MARIA_COUNT: u32 = {n}u;\n\
         const LUNAR_MARIA: array<vec4<f32>, {n}> = array<vec4<f32>, {n}>(\n    {patches}\n);\n\
         const LUNAR_HIGHLAND_FACTOR: f32 = {:?};\n\
         const LUNAR_MARE_FACTOR: f32 = {:?};\n\
         const LUNAR_EDGE_INNER: f32 = {:?};\n\
         const LUNAR_EDGE_OUTER: f32 = {:?};\n",
        HIGHLAND_FACTOR as f32, MARE_FACTOR as f32, EDGE_INNER as f32, EDGE_OUTER as f32
    )
}

/// The Gauss–Legendre rule of the eclipse quadrature (`atmosphere/eclipse.wgsl`), from the core's
/// own ([`firmament_core::atmosphere::eclipse`]), so both integrate alike, and the corona's reach.
fn eclipse_quadrature_wgsl() -> String {
    use firmament_core::atmosphere::eclipse::{ECLIPSE_QUADRATURE_POINTS, eclipse_quadrature};
    use firmament_core::atmosphere::star::CORONA_MAX_RADII;
    let (nodes, weights) = eclipse_quadrature();
    let list = |values: &[f32]| values.iter().map(|v| format!("{v:e}")).collect::<Vec<_>>().join(", ");
    let n = ECLIPSE_QUADRATURE_POINTS;
    format!(
        "\n// The eclipse quadrature's Gauss–Legendre nodes on [−1, 1] and their weights\n\
         // (firmament_core::atmosphere::eclipse).\n\
         const ECLIPSE_QUADRATURE_POINTS: u32 = {n}u;\n\
         const ECLIPSE_NODES: array<f32, {n}> = array<f32, {n}>({});\n\
         const ECLIPSE_WEIGHTS: array<f32, {n}> = array<f32, {n}>({});\n\
         // How far out a sun's corona is drawn, solar radii (firmament_core::atmosphere::star).\n\
         const CORONA_MAX_RADII: f32 = {CORONA_MAX_RADII:?};\n",
        list(&nodes),
        list(&weights)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cloud_kinds_are_the_cores() {
        use firmament_core::atmosphere::clouds::CloudKind;
        let codes = [
            (CloudKind::Cumulus, CLOUD_KIND_CUMULUS),
            (CloudKind::Stratocumulus, CLOUD_KIND_STRATOCUMULUS),
            (CloudKind::Stratus, CLOUD_KIND_STRATUS),
            (CloudKind::Altostratus, CLOUD_KIND_ALTOSTRATUS),
            (CloudKind::Cirrus, CLOUD_KIND_CIRRUS),
            (CloudKind::Uniform, CLOUD_KIND_UNIFORM),
        ];
        assert_eq!(codes.len(), CloudKind::ALL.len());
        for (kind, code) in codes {
            assert_eq!(kind.code(), code, "{kind:?}");
        }
    }

    #[test]
    fn the_reflectance_laws_are_the_cores() {
        use firmament_core::atmosphere::body::Reflectance;
        assert_eq!(Reflectance::Lambert.gpu_code(), BODY_REFLECTANCE_LAMBERT);
        assert_eq!(Reflectance::LommelSeeliger.gpu_code(), BODY_REFLECTANCE_LOMMEL_SEELIGER);
        assert_eq!(Reflectance::Lunar.gpu_code(), BODY_REFLECTANCE_LUNAR);
        use firmament_core::atmosphere::body::BodySurface;
        assert_eq!(BodySurface::Uniform.gpu_code(), BODY_SURFACE_UNIFORM);
        assert_eq!(BodySurface::LunarMaria.gpu_code(), BODY_SURFACE_LUNAR_MARIA);
        let map = firmament_core::atmosphere::surface::SurfaceMap::uniform([0.5; 4]).unwrap();
        assert_eq!(BodySurface::Map(map.into()).gpu_code(), BODY_SURFACE_MAP);
    }

    #[test]
    fn the_wgsl_declares_every_code_once() {
        let text = wgsl();
        for (name, value, _) in ALL {
            assert_eq!(
                text.matches(&format!("const {name}: u32 = {value}u;\n")).count(),
                1,
                "{name}"
            );
        }
    }
}
