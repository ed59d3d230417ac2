//! WGSL sources. Each pass has one entry file; shared include files are prepended at compile
//! time (WGSL has no `#include`), so what the GPU gets is exactly what the naga test validates.

/// Shared full-screen triangle (`common/fullscreen.wgsl`).
const FULLSCREEN: &str = include_str!("shaders/common/fullscreen.wgsl");
/// Shared ray/ellipsoid intersection (`common/ellipsoid.wgsl`).
const ELLIPSOID: &str = include_str!("shaders/common/ellipsoid.wgsl");
/// Shared planet-frame view ray (`common/view_ray.wgsl`), after the ellipsoid include it needs.
const VIEW_RAY: &str = concat!(
    include_str!("shaders/common/ellipsoid.wgsl"),
    "\n",
    include_str!("shaders/common/view_ray.wgsl")
);

/// The gradient sky pass, with its includes.
pub const SKY_GRADIENT: &str = concat!(
    include_str!("shaders/common/fullscreen.wgsl"),
    "\n",
    include_str!("shaders/sky_gradient.wgsl")
);

/// The tonemap pass, with its includes.
pub const TONEMAP: &str = concat!(
    include_str!("shaders/common/fullscreen.wgsl"),
    "\n",
    include_str!("shaders/tonemap.wgsl")
);

/// The seed's own atmosphere model (`atmosphere.model = "seed"`), with its include.
pub const SEED_SKY: &str = concat!(
    include_str!("shaders/common/fullscreen.wgsl"),
    "\n",
    include_str!("shaders/common/ellipsoid.wgsl"),
    "\n",
    include_str!("shaders/common/view_ray.wgsl"),
    "\n",
    include_str!("shaders/seed_sky.wgsl")
);

/// Composes an atmosphere pass (or an atmosphere include with the ones it needs): the full-screen
/// triangle, the ellipsoid intersection and view ray, the atmosphere includes in dependency order
/// (`common`, `luts`, `view`, …), then the entry file.
macro_rules! atmosphere_shader {
    ($($include:literal),* ; $entry:literal) => {
        concat!(
            include_str!("shaders/common/fullscreen.wgsl"),
            "\n",
            include_str!("shaders/common/ellipsoid.wgsl"),
            "\n",
            include_str!("shaders/common/view_ray.wgsl"),
            "\n",
            $(include_str!(concat!("shaders/atmosphere/", $include, ".wgsl")), "\n",)*
            include_str!(concat!("shaders/atmosphere/", $entry, ".wgsl"))
        )
    };
}

/// The atmosphere's transmittance LUT pass.
pub const ATMOSPHERE_TRANSMITTANCE_LUT: &str = atmosphere_shader!("common"; "transmittance_lut");
/// The atmosphere's multiple-scattering LUT pass.
pub const ATMOSPHERE_MULTISCATTERING_LUT: &str = atmosphere_shader!("common", "luts"; "multiscattering_lut");
/// The atmosphere's sky irradiance LUT pass.
pub const ATMOSPHERE_IRRADIANCE_LUT: &str = atmosphere_shader!("common", "luts"; "irradiance_lut");
/// The atmosphere's sky-view LUT pass.
pub const ATMOSPHERE_SKY_VIEW_LUT: &str = atmosphere_shader!("common", "luts", "view"; "sky_view_lut");
/// The atmosphere's sky pass.
pub const ATMOSPHERE_SKY: &str = atmosphere_shader!("common", "luts", "view", "sky_view"; "sky");
/// The atmosphere's sky lighting at the camera (compute): the suns and the sky's spherical
/// harmonics that [`FIRMAMENT_LIGHTING_WGSL`] reads.
pub const ATMOSPHERE_SKY_LIGHTING: &str = atmosphere_shader!("common", "luts", "view", "sky_view"; "sky_lighting");

/// The atmosphere's aerial-perspective volume (compute).
pub const ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME: &str =
    atmosphere_shader!("common", "luts", "view"; "aerial_perspective_volume");
/// The atmosphere's aerial-perspective application over geometry.
pub const ATMOSPHERE_AERIAL_PERSPECTIVE: &str =
    atmosphere_shader!("common", "luts", "view", "aerial_lookup"; "aerial_perspective");

/// The object pass: classic (fixed-function) lighting, textures and fog.
pub const CLASSIC_LIGHTING: &str = include_str!("shaders/classic_lighting.wgsl");

/// The lens-flare occlusion pass (compute), with its includes.
pub const FLARE_OCCLUSION: &str = concat!(
    include_str!("shaders/common/ellipsoid.wgsl"),
    "\n",
    include_str!("shaders/flare_common.wgsl"),
    "\n",
    include_str!("shaders/flare_occlusion.wgsl")
);

/// The lens-flare element pass, with its include.
pub const FLARE: &str = concat!(
    include_str!("shaders/flare_common.wgsl"),
    "\n",
    include_str!("shaders/flare.wgsl")
);

/// The night-sky pass: stars and the Moon (one entry file, no includes).
pub const NIGHT_SKY: &str = include_str!("shaders/night_sky.wgsl");

/// The WGSL users put before their own shaders to read firmament's per-frame lighting: the
/// `FirmamentSkyLighting` struct (mirrored by [`crate::gpu_types::SkyLightingGpu`]), its uniform
/// binding `firmament_sky_lighting` at `@group(`[`FIRMAMENT_LIGHTING_GROUP`]`)
/// @binding(`[`FIRMAMENT_LIGHTING_BINDING`]`)`, and the functions `firmament_sun_count()`,
/// `firmament_sun_direction(i)`, `firmament_sun_color(i)`, `firmament_sky_irradiance(n)` and
/// `firmament_irradiance(n)`. Bind
/// [`AtmospherePass::sky_lighting_buffer`](crate::passes::AtmospherePass::sky_lighting_buffer)
/// there with a layout entry from
/// [`sky_lighting_layout_entry`](crate::passes::atmosphere::sky_lighting_layout_entry); for
/// another group or binding use [`firmament_lighting_wgsl`]. Units and conventions are in the file
/// (`shaders/include/firmament_lighting.wgsl`) and in `docs/ATMOSPHERE.md`.
pub const FIRMAMENT_LIGHTING_WGSL: &str = include_str!("shaders/include/firmament_lighting.wgsl");

/// The bind group [`FIRMAMENT_LIGHTING_WGSL`] declares its buffer in.
pub const FIRMAMENT_LIGHTING_GROUP: u32 = 1;
/// The binding [`FIRMAMENT_LIGHTING_WGSL`] declares its buffer at.
pub const FIRMAMENT_LIGHTING_BINDING: u32 = 0;

/// The binding declaration of [`FIRMAMENT_LIGHTING_WGSL`], after its group and binding.
const FIRMAMENT_LIGHTING_DECLARATION: &str = " var<uniform> firmament_sky_lighting: FirmamentSkyLighting;";

/// [`FIRMAMENT_LIGHTING_WGSL`] with its buffer at `@group(group) @binding(binding)` instead of
/// the default ([`FIRMAMENT_LIGHTING_GROUP`], [`FIRMAMENT_LIGHTING_BINDING`]).
pub fn firmament_lighting_wgsl(group: u32, binding: u32) -> String {
    let default = format!(
        "@group({FIRMAMENT_LIGHTING_GROUP}) @binding({FIRMAMENT_LIGHTING_BINDING}){FIRMAMENT_LIGHTING_DECLARATION}"
    );
    FIRMAMENT_LIGHTING_WGSL.replacen(
        &default,
        &format!("@group({group}) @binding({binding}){FIRMAMENT_LIGHTING_DECLARATION}"),
        1,
    )
}

/// The WGSL users put before their own shaders to fog their surfaces with firmament's aerial
/// perspective: the volume lookup shared with firmament's own pass
/// (`shaders/atmosphere/aerial_lookup.wgsl`), then `shaders/include/firmament_aerial_perspective.wgsl`
/// with its five bindings at `@group(`[`FIRMAMENT_AERIAL_PERSPECTIVE_GROUP`]`)
/// @binding(`[`FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING`]` + 0 … 4)`: the atmosphere pass's view
/// and medium uniforms, the volume's scattering and transmittance atlases and a filtering sampler,
/// laid out by [`aerial_perspective_layout_entries`](crate::passes::atmosphere::aerial_perspective_layout_entries)
/// and bound from
/// [`AtmospherePass::aerial_perspective_bindings`](crate::passes::AtmospherePass::aerial_perspective_bindings).
/// Its functions: `firmament_apply_aerial_perspective(color, ndc_xy, distance_m)` (`color · T + S`)
/// and `firmament_aerial_perspective(ndc_xy, distance_m)` (T and S apart). The default slots follow
/// [`FIRMAMENT_LIGHTING_WGSL`]'s, so both fit one bind group; for others use
/// [`firmament_aerial_perspective_wgsl`]. Units and conventions: the file and `docs/ATMOSPHERE.md`.
pub const FIRMAMENT_AERIAL_PERSPECTIVE_WGSL: &str = concat!(
    include_str!("shaders/atmosphere/aerial_lookup.wgsl"),
    "\n",
    include_str!("shaders/include/firmament_aerial_perspective.wgsl")
);

/// The bind group [`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`] declares its bindings in.
pub const FIRMAMENT_AERIAL_PERSPECTIVE_GROUP: u32 = 1;
/// The first of the five consecutive bindings [`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`] declares.
pub const FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING: u32 = 1;

/// The declarations of [`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`]'s bindings, in binding order, after
/// their group and binding.
const FIRMAMENT_AERIAL_PERSPECTIVE_DECLARATIONS: [&str; 5] = [
    " var<uniform> firmament_aerial_view: FirmamentAerialView;",
    " var<uniform> firmament_aerial_planet: FirmamentAerialPlanet;",
    " var firmament_aerial_scattering: texture_2d<f32>;",
    " var firmament_aerial_transmittance: texture_2d<f32>;",
    " var firmament_aerial_sampler: sampler;",
];

/// [`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`] with its bindings at `@group(group)
/// @binding(first_binding)` … `@binding(first_binding + 4)` instead of the default
/// ([`FIRMAMENT_AERIAL_PERSPECTIVE_GROUP`], [`FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING`]).
pub fn firmament_aerial_perspective_wgsl(group: u32, first_binding: u32) -> String {
    let mut source = FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.to_owned();
    for (offset, declaration) in (0..).zip(FIRMAMENT_AERIAL_PERSPECTIVE_DECLARATIONS) {
        let default = format!(
            "@group({FIRMAMENT_AERIAL_PERSPECTIVE_GROUP}) @binding({}){declaration}",
            FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING + offset
        );
        source = source.replacen(
            &default,
            &format!("@group({group}) @binding({}){declaration}", first_binding + offset),
            1,
        );
    }
    source
}

/// Every composed shader by name, for validation and tooling.
pub const ALL: &[(&str, &str)] = &[
    ("sky_gradient", SKY_GRADIENT),
    ("tonemap", TONEMAP),
    ("classic_lighting", CLASSIC_LIGHTING),
    ("flare_occlusion", FLARE_OCCLUSION),
    ("flare", FLARE),
    ("night_sky", NIGHT_SKY),
    ("seed_sky", SEED_SKY),
    ("atmosphere/transmittance_lut", ATMOSPHERE_TRANSMITTANCE_LUT),
    ("atmosphere/multiscattering_lut", ATMOSPHERE_MULTISCATTERING_LUT),
    ("atmosphere/irradiance_lut", ATMOSPHERE_IRRADIANCE_LUT),
    ("atmosphere/sky_view_lut", ATMOSPHERE_SKY_VIEW_LUT),
    ("atmosphere/sky", ATMOSPHERE_SKY),
    (
        "atmosphere/aerial_perspective_volume",
        ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME,
    ),
    ("atmosphere/aerial_perspective", ATMOSPHERE_AERIAL_PERSPECTIVE),
    ("atmosphere/sky_lighting", ATMOSPHERE_SKY_LIGHTING),
];

/// The include files on their own (validated as modules too, so errors point at the right file).
/// Each atmosphere include comes with the ones it needs before it.
pub const INCLUDES: &[(&str, &str)] = &[
    ("common/fullscreen", FULLSCREEN),
    ("common/ellipsoid", ELLIPSOID),
    ("common/view_ray", VIEW_RAY),
    ("flare_common", include_str!("shaders/flare_common.wgsl")),
    ("atmosphere/common", atmosphere_shader!(; "common")),
    ("atmosphere/luts", atmosphere_shader!("common"; "luts")),
    ("atmosphere/view", atmosphere_shader!("common", "luts"; "view")),
    (
        "atmosphere/sky_view",
        atmosphere_shader!("common", "luts", "view"; "sky_view"),
    ),
    ("include/firmament_lighting", FIRMAMENT_LIGHTING_WGSL),
    (
        "atmosphere/aerial_lookup",
        include_str!("shaders/atmosphere/aerial_lookup.wgsl"),
    ),
    (
        "include/firmament_aerial_perspective",
        FIRMAMENT_AERIAL_PERSPECTIVE_WGSL,
    ),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu_types::{
        AtmosphereParamsUniforms, AtmosphereSunUniform, AtmosphereViewUniforms, ClassicFrameUniforms,
        ClassicLightUniform, ClassicMaterialUniform, ClassicObjectUniforms, DensityProfileUniform, FlareFrameUniforms,
        FlareInstance, FlareSourceGpu, GradientSkyUniforms, TonemapUniforms,
    };

    fn validate(name: &str, source: &str) -> naga::Module {
        let module =
            naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        module
    }

    #[test]
    fn every_shader_parses_and_validates() {
        for (name, source) in ALL.iter().chain(INCLUDES) {
            validate(name, source);
        }
    }

    /// Size and member offsets of the WGSL struct `name`.
    fn wgsl_layout(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
        let ty = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no WGSL struct {name}"))
            .1;
        match &ty.inner {
            naga::TypeInner::Struct { members, span } => (
                *span,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect(),
            ),
            other => panic!("{name} is not a struct: {other:?}"),
        }
    }

    macro_rules! assert_layout {
        ($module:expr, $wgsl:literal, $rust:ty, [$($field:ident),* $(,)?]) => {{
            let (size, members) = wgsl_layout(&$module, $wgsl);
            assert_eq!(size as usize, std::mem::size_of::<$rust>(), "size of {}", $wgsl);
            let rust: Vec<(String, u32)> =
                vec![$((stringify!($field).trim_start_matches('_').to_owned(), std::mem::offset_of!($rust, $field) as u32)),*];
            let wgsl: Vec<(String, u32)> =
                members.into_iter().map(|(n, o)| (n.trim_start_matches('_').to_owned(), o)).collect();
            assert_eq!(wgsl, rust, "members of {}", $wgsl);
        }};
    }

    #[test]
    fn night_sky_layouts_match() {
        use crate::gpu_types::{NightSkyUniforms, StarInstance};
        let night = validate("night_sky", NIGHT_SKY);
        assert_layout!(
            night,
            "NightSky",
            NightSkyUniforms,
            [
                view_proj,
                pixels,
                star,
                moon_center,
                moon_e1,
                moon_e2,
                moon_sun,
                moon_radiance
            ]
        );
        assert_layout!(night, "StarIn", StarInstance, [direction, color]);
    }

    #[test]
    fn sky_lighting_layouts_match() {
        use crate::gpu_types::{SkyLightingGpu, SkyLightingParamsUniforms, SkyLightingSunGpu};
        let stage = validate("atmosphere/sky_lighting", ATMOSPHERE_SKY_LIGHTING);
        assert_layout!(
            stage,
            "SkyLightingParams",
            SkyLightingParamsUniforms,
            [planet_to_world, flags]
        );
        assert_layout!(stage, "SkyLightingSun", SkyLightingSunGpu, [direction, color]);
        assert_layout!(stage, "SkyLighting", SkyLightingGpu, [sun_count, suns, sky_sh]);
        let include = validate("include/firmament_lighting", FIRMAMENT_LIGHTING_WGSL);
        assert_layout!(include, "FirmamentSun", SkyLightingSunGpu, [direction, color]);
        assert_layout!(
            include,
            "FirmamentSkyLighting",
            SkyLightingGpu,
            [sun_count, suns, sky_sh]
        );
    }

    /// A user's own shader after the include: its camera in group 0, a mesh lit by firmament.
    const USER_SHADER: &str = r"
struct UserCamera {
    view_proj: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> user_camera: UserCamera;

struct UserVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> UserVertex {
    var out: UserVertex;
    out.clip = user_camera.view_proj * vec4<f32>(position, 1.0);
    out.normal = normal;
    return out;
}

@fragment
fn fs_main(in: UserVertex) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let albedo = vec3<f32>(0.18);
    var e = firmament_sky_irradiance(n);
    for (var i = 0u; i < firmament_sun_count(); i++) {
        e += firmament_sun_color(i) * max(dot(n, firmament_sun_direction(i)), 0.0);
    }
    let check = firmament_irradiance(n) - e;
    return vec4<f32>(albedo / 3.14159265 * e + 0.0 * check, 1.0);
}
";

    #[test]
    fn a_user_shader_including_the_lighting_validates() {
        let chosen = firmament_lighting_wgsl(3, 7);
        assert_ne!(chosen, FIRMAMENT_LIGHTING_WGSL, "the binding line was found");
        for (include, group, binding) in [
            (
                FIRMAMENT_LIGHTING_WGSL,
                FIRMAMENT_LIGHTING_GROUP,
                FIRMAMENT_LIGHTING_BINDING,
            ),
            (chosen.as_str(), 3, 7),
        ] {
            let module = validate("user shader", &format!("{include}\n{USER_SHADER}"));
            let (_, lighting) = module
                .global_variables
                .iter()
                .find(|(_, v)| v.name.as_deref() == Some("firmament_sky_lighting"))
                .expect("the lighting binding");
            assert_eq!(lighting.binding, Some(naga::ResourceBinding { group, binding }));
            assert_eq!(lighting.space, naga::AddressSpace::Uniform);
        }
    }

    /// A user's material after both includes: lit by firmament's suns and sky, fogged by its air.
    const USER_FOGGED_SHADER: &str = r"
struct UserVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) ndc: vec2<f32>,
    @location(2) distance: f32,
}

@fragment
fn fs_main(in: UserVertex) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let lit = vec3<f32>(0.18) / 3.14159265 * firmament_irradiance(n);
    let air = firmament_aerial_perspective(in.ndc, in.distance);
    let check = lit * air.transmittance + air.scattering - firmament_apply_aerial_perspective(lit, in.ndc, in.distance);
    return vec4<f32>(firmament_apply_aerial_perspective(lit, in.ndc, in.distance) + 0.0 * check, 1.0);
}
";

    #[test]
    fn a_user_shader_including_the_aerial_perspective_validates() {
        let names = [
            "firmament_aerial_view",
            "firmament_aerial_planet",
            "firmament_aerial_scattering",
            "firmament_aerial_transmittance",
            "firmament_aerial_sampler",
        ];
        let chosen = firmament_aerial_perspective_wgsl(2, 10);
        for (include, group, first) in [
            (
                FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.to_owned(),
                FIRMAMENT_AERIAL_PERSPECTIVE_GROUP,
                FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING,
            ),
            (chosen, 2, 10),
        ] {
            let source = format!("{FIRMAMENT_LIGHTING_WGSL}\n{include}\n{USER_FOGGED_SHADER}");
            let module = validate("user fogged shader", &source);
            for (offset, name) in (0..).zip(names) {
                let (_, global) = module
                    .global_variables
                    .iter()
                    .find(|(_, v)| v.name.as_deref() == Some(name))
                    .unwrap_or_else(|| panic!("no {name}"));
                assert_eq!(
                    global.binding,
                    Some(naga::ResourceBinding {
                        group,
                        binding: first + offset
                    }),
                    "{name}"
                );
            }
        }
        // The layout entries name the same five bindings, in the same order.
        let entries = crate::passes::atmosphere::aerial_perspective_layout_entries(10);
        assert_eq!(entries.map(|e| e.binding), [10, 11, 12, 13, 14]);
    }

    #[test]
    fn the_aerial_perspective_include_mirrors_the_pass() {
        use crate::gpu_types::{AtmosphereParamsUniforms, AtmosphereViewUniforms};
        let module = validate(
            "include/firmament_aerial_perspective",
            FIRMAMENT_AERIAL_PERSPECTIVE_WGSL,
        );
        let (_, members) = wgsl_layout(&module, "FirmamentAerialView");
        let rust = [
            (
                "view_to_planet",
                std::mem::offset_of!(AtmosphereViewUniforms, view_to_planet),
            ),
            ("camera", std::mem::offset_of!(AtmosphereViewUniforms, camera)),
            (
                "camera_shape",
                std::mem::offset_of!(AtmosphereViewUniforms, camera_shape),
            ),
            ("center", std::mem::offset_of!(AtmosphereViewUniforms, center)),
            ("local_up", std::mem::offset_of!(AtmosphereViewUniforms, local_up)),
            ("to_srgb0", std::mem::offset_of!(AtmosphereViewUniforms, to_srgb0)),
            ("to_srgb1", std::mem::offset_of!(AtmosphereViewUniforms, to_srgb1)),
            ("to_srgb2", std::mem::offset_of!(AtmosphereViewUniforms, to_srgb2)),
            ("aerial", std::mem::offset_of!(AtmosphereViewUniforms, aerial)),
        ]
        .map(|(n, o)| (n.to_owned(), o as u32));
        assert_eq!(
            members,
            rust.to_vec(),
            "FirmamentAerialView is a prefix of AtmosphereView"
        );
        let (_, members) = wgsl_layout(&module, "FirmamentAerialPlanet");
        assert_eq!(
            members,
            vec![(
                "radii".to_owned(),
                std::mem::offset_of!(AtmosphereParamsUniforms, radii) as u32
            )]
        );
        // The volume's size, as the compute pass that writes it declares it.
        let size = crate::passes::atmosphere::luts::AERIAL_PERSPECTIVE_SIZE;
        let declared = format!("vec3<u32>({}u, {}u, {}u)", size.0, size.1, size.2);
        assert!(FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.contains(&format!(
            "const FIRMAMENT_AERIAL_PERSPECTIVE_SIZE: vec3<u32> = {declared};"
        )));
        assert!(
            ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME
                .contains(&format!("const AERIAL_PERSPECTIVE_SIZE: vec3<u32> = {declared};"))
        );
    }

    #[test]
    fn the_sky_lighting_grid_is_the_documented_one() {
        let (columns, rows) = crate::gpu_types::sky_lighting::SKY_LIGHTING_GRID;
        assert!(ATMOSPHERE_SKY_LIGHTING.contains(&format!("const GRID_AZIMUTH: u32 = {columns}u;")));
        assert!(ATMOSPHERE_SKY_LIGHTING.contains(&format!("const GRID_ROWS: u32 = {rows}u;")));
    }

    #[test]
    fn seed_sky_layouts_match() {
        use crate::gpu_types::{SeedSkyUniforms, SeedStarUniform};
        let seed = validate("seed_sky", SEED_SKY);
        assert_layout!(seed, "SeedStar", SeedStarUniform, [position, direction, color]);
        assert_layout!(
            seed,
            "SeedSky",
            SeedSkyUniforms,
            [
                view_to_planet,
                camera,
                camera_shape,
                center,
                radii,
                b0,
                params,
                counts,
                stars
            ]
        );
    }

    #[test]
    fn rust_and_wgsl_struct_layouts_match() {
        let sky = validate("sky_gradient", SKY_GRADIENT);
        assert_layout!(
            sky,
            "GradientSky",
            GradientSkyUniforms,
            [
                clip_to_world,
                zenith,
                upper,
                horizon,
                lower,
                ground,
                sun_direction,
                sun_disc,
                sun_glow,
                shape,
                exponents
            ]
        );
        let tonemap = validate("tonemap", TONEMAP);
        assert_layout!(tonemap, "Tonemap", TonemapUniforms, [exposure, curve, transfer, _pad]);
        let classic = validate("classic_lighting", CLASSIC_LIGHTING);
        assert_layout!(
            classic,
            "ClassicLight",
            ClassicLightUniform,
            [ambient, diffuse, specular, position, spot_direction, spot_attenuation]
        );
        assert_layout!(
            classic,
            "ClassicMaterial",
            ClassicMaterialUniform,
            [ambient, diffuse, specular, emission, shininess]
        );
        assert_layout!(
            classic,
            "ClassicFrame",
            ClassicFrameUniforms,
            [
                projection,
                scene_ambient,
                model_flags,
                mode,
                fog_mode,
                fog_params,
                fog_color,
                eye_up,
                fog_sun,
                fog_sun_color,
                lights
            ]
        );
        assert_layout!(
            classic,
            "ClassicObject",
            ClassicObjectUniforms,
            [model_view, normal_matrix, front, back, flags, fog_coord, light_colors]
        );
        let occlusion = validate("flare_occlusion", FLARE_OCCLUSION);
        let flare = validate("flare", FLARE);
        for module in [&occlusion, &flare] {
            assert_layout!(
                module,
                "FlareFrame",
                FlareFrameUniforms,
                [view_to_planet, planet_origin, planet_radii, counts, view, fade]
            );
        }
        assert_layout!(occlusion, "FlareSource", FlareSourceGpu, [disc, depth]);
        assert_layout!(flare, "InstanceIn", FlareInstance, [placement, color, shape, source]);
        let atmosphere = validate("atmosphere/sky", ATMOSPHERE_SKY);
        assert_layout!(
            atmosphere,
            "DensityProfile",
            DensityProfileUniform,
            [layer0, layer1, width]
        );
        assert_layout!(
            atmosphere,
            "AtmosphereParams",
            AtmosphereParamsUniforms,
            [
                radii,
                lut,
                rayleigh_scattering,
                mie_scattering,
                mie_extinction,
                absorption,
                ground_albedo,
                mie_legendre,
                mie_forward_peak,
                rayleigh_density,
                mie_density,
                absorber_density
            ]
        );
        assert_layout!(
            atmosphere,
            "AtmosphereSun",
            AtmosphereSunUniform,
            [direction, irradiance]
        );
        assert_layout!(
            atmosphere,
            "AtmosphereView",
            AtmosphereViewUniforms,
            [
                view_to_planet,
                camera,
                camera_shape,
                center,
                local_up,
                to_srgb0,
                to_srgb1,
                to_srgb2,
                aerial,
                sun_count,
                suns
            ]
        );
    }
}
