//! The WGSL shaders. Each file under `src/shaders/` is a module, named by its path there without
//! `.wgsl`; a module lists the modules it uses on `#import` lines at its top, and
//! [`compose`](crate::shaders::compose) puts an entry module together with everything it imports
//! (see `compose.rs`), so no Rust code lists include orders. Pipelines take the composed entries
//! below ([`ENTRIES`](crate::shaders::ENTRIES)), each composed once, on first use; the tests
//! validate every entry and every module (with its imports) with naga and check every Rust↔WGSL
//! struct layout.
//!
//! Conventions of the modules (tests check those marked ✓):
//! - Each file opens with a header: `// <module>.wgsl — what it is` ✓, its conventions (frames,
//!   units, depth), then its `#import` lines, then its code.
//! - A module imports exactly the modules whose names it uses, not counting on what its imports
//!   bring ✓; every module is an entry or imported by one ✓; every `.wgsl` file is in the table ✓.
//! - A pass family with several entry files declares its interface with Rust in one
//!   `<family>/bindings.wgsl`: the structs `gpu_types` mirrors and every group-0 binding with its
//!   number (`atmosphere/`, `flare/`), compared with the pass's Rust `binding` numbers by its
//!   tests ✓. A single-file pass declares its own.
//! - Codes Rust writes into uniforms and pipeline constants are named constants of the module
//!   Rust generates, `generated/constants` ([`crate::gpu_types::codes`]), never bare numbers.
//! - All modules of an entry share one namespace. The user includes (`include/`) import nothing
//!   but `atmosphere/aerial_lookup`, and every name in them starts with `firmament_`, `Firmament`
//!   or `FIRMAMENT_`, so they cannot collide with a user's own.

use std::borrow::Cow;
use std::fmt;
use std::sync::LazyLock;

mod compose;

pub use compose::ComposeError;

/// Every WGSL file, by module name (its path under `src/shaders/` without `.wgsl`).
const FILES: &[(&str, &str)] = &[
    ("common/fullscreen", include_str!("common/fullscreen.wgsl")),
    ("common/ellipsoid", include_str!("common/ellipsoid.wgsl")),
    ("common/view_ray", include_str!("common/view_ray.wgsl")),
    ("sky_gradient", include_str!("sky_gradient.wgsl")),
    ("tonemap", include_str!("tonemap.wgsl")),
    ("empirical_sky", include_str!("empirical_sky.wgsl")),
    ("shadow/sampling", include_str!("shadow/sampling.wgsl")),
    ("shadow/shadow_map", include_str!("shadow/shadow_map.wgsl")),
    ("classic_lighting", include_str!("classic_lighting.wgsl")),
    ("night_sky", include_str!("night_sky.wgsl")),
    ("flare/bindings", include_str!("flare/bindings.wgsl")),
    ("flare_occlusion", include_str!("flare_occlusion.wgsl")),
    ("flare", include_str!("flare.wgsl")),
    ("atmosphere/bindings", include_str!("atmosphere/bindings.wgsl")),
    ("atmosphere/common", include_str!("atmosphere/common.wgsl")),
    ("atmosphere/luts", include_str!("atmosphere/luts.wgsl")),
    ("atmosphere/rings", include_str!("atmosphere/rings.wgsl")),
    ("atmosphere/surface", include_str!("atmosphere/surface.wgsl")),
    ("atmosphere/eclipse", include_str!("atmosphere/eclipse.wgsl")),
    ("atmosphere/body_hits", include_str!("atmosphere/body_hits.wgsl")),
    ("atmosphere/body_air_medium", include_str!("atmosphere/body_air_medium.wgsl")),
    ("atmosphere/bodies", include_str!("atmosphere/bodies.wgsl")),
    ("atmosphere/body_air", include_str!("atmosphere/body_air.wgsl")),
    ("atmosphere/view", include_str!("atmosphere/view.wgsl")),
    ("atmosphere/sky_view", include_str!("atmosphere/sky_view.wgsl")),
    ("atmosphere/aerial_lookup", include_str!("atmosphere/aerial_lookup.wgsl")),
    (
        "atmosphere/transmittance_lut",
        include_str!("atmosphere/transmittance_lut.wgsl"),
    ),
    ("atmosphere/moments_out", include_str!("atmosphere/moments_out.wgsl")),
    (
        "atmosphere/multiscattering_lut",
        include_str!("atmosphere/multiscattering_lut.wgsl"),
    ),
    (
        "atmosphere/multiscattering_sum",
        include_str!("atmosphere/multiscattering_sum.wgsl"),
    ),
    (
        "atmosphere/multiscattering_ordinates",
        include_str!("atmosphere/multiscattering_ordinates.wgsl"),
    ),
    (
        "atmosphere/multiscattering_curvature",
        include_str!("atmosphere/multiscattering_curvature.wgsl"),
    ),
    ("atmosphere/sky_view_lut", include_str!("atmosphere/sky_view_lut.wgsl")),
    ("atmosphere/sky", include_str!("atmosphere/sky.wgsl")),
    ("atmosphere/sky_lighting", include_str!("atmosphere/sky_lighting.wgsl")),
    (
        "atmosphere/aerial_perspective_volume",
        include_str!("atmosphere/aerial_perspective_volume.wgsl"),
    ),
    (
        "atmosphere/aerial_perspective",
        include_str!("atmosphere/aerial_perspective.wgsl"),
    ),
    ("clouds/density", include_str!("clouds/density.wgsl")),
    ("clouds/extinction", include_str!("clouds/extinction.wgsl")),
    ("clouds/shadow", include_str!("clouds/shadow.wgsl")),
    ("clouds/shadow_map", include_str!("clouds/shadow_map.wgsl")),
    ("clouds/march", include_str!("clouds/march.wgsl")),
    ("camera/bindings", include_str!("camera/bindings.wgsl")),
    ("camera/exposure_meter", include_str!("camera/exposure_meter.wgsl")),
    ("camera/exposure_adapt", include_str!("camera/exposure_adapt.wgsl")),
    ("camera/bloom_from_image", include_str!("camera/bloom_from_image.wgsl")),
    ("camera/bloom_down", include_str!("camera/bloom_down.wgsl")),
    ("camera/bloom_up", include_str!("camera/bloom_up.wgsl")),
    ("envmap/from_faces", include_str!("envmap/from_faces.wgsl")),
    ("envmap/write", include_str!("envmap/write.wgsl")),
    ("include/firmament_lighting", FIRMAMENT_LIGHTING_WGSL),
    (
        "include/firmament_aerial_perspective",
        include_str!("include/firmament_aerial_perspective.wgsl"),
    ),
];

/// The module Rust writes rather than a file: the codes of [`crate::gpu_types::codes`].
const GENERATED_CONSTANTS: &str = "generated/constants";

/// Every module's name: the files', then the generated one.
pub fn module_names() -> impl Iterator<Item = &'static str> {
    FILES.iter().map(|(name, _)| *name).chain([GENERATED_CONSTANTS])
}

/// Module `name`'s own text, `#import` lines included; `None` for no such module.
pub fn module_source(name: &str) -> Option<Cow<'static, str>> {
    if name == GENERATED_CONSTANTS {
        return Some(Cow::Owned(crate::gpu_types::codes::wgsl()));
    }
    FILES
        .iter()
        .find(|(file, _)| *file == name)
        .map(|(_, source)| Cow::Borrowed(*source))
}

/// Module `name` with every module it imports, directly or not, before it (each once, the
/// `#import` lines taken out): plain WGSL.
pub fn compose(name: &str) -> Result<String, ComposeError> {
    compose::compose_with(name, module_source)
}

/// The bindings module `name` (with its imports) declares, as (global name, binding number)
/// sorted by name, for the passes' tests against their Rust numbers. Every one must be in group 0
/// with a number of its own.
#[cfg(test)]
pub(crate) fn declared_bindings(name: &str) -> Vec<(String, u32)> {
    let source = compose(name).unwrap_or_else(|e| panic!("{e}"));
    let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut bindings: Vec<(String, u32)> = module
        .global_variables
        .iter()
        .filter_map(|(_, global)| {
            let binding = global.binding.as_ref()?;
            assert_eq!(binding.group, 0, "{name}: {:?}", global.name);
            Some((global.name.clone().unwrap_or_default(), binding.binding))
        })
        .collect();
    let mut numbers: Vec<u32> = bindings.iter().map(|(_, number)| *number).collect();
    numbers.sort_unstable();
    numbers.dedup();
    assert_eq!(numbers.len(), bindings.len(), "{name}: bindings sharing a number");
    bindings.sort();
    bindings
}

/// An entry module composed on first use and kept for the process: what a pipeline, or a user's
/// shader, is built from. Derefs to (and displays as) its WGSL.
pub struct Shader {
    name: &'static str,
    source: LazyLock<String>,
}

/// [`Shader`] of entry module `$name`.
macro_rules! entry {
    ($name:literal) => {
        Shader {
            name: $name,
            source: LazyLock::new(|| compose_entry($name)),
        }
    };
}

/// Composes entry `name`, which the tests compose for every entry: a failure is firmament's bug.
fn compose_entry(name: &str) -> String {
    compose(name).unwrap_or_else(|error| panic!("firmament's WGSL modules do not compose: {error}"))
}

impl Shader {
    /// Its module name (`"atmosphere/sky"`).
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// Its composed WGSL.
    pub fn source(&self) -> &str {
        &self.source
    }
}

impl std::ops::Deref for Shader {
    type Target = str;

    fn deref(&self) -> &str {
        &self.source
    }
}

impl AsRef<str> for Shader {
    fn as_ref(&self) -> &str {
        &self.source
    }
}

impl fmt::Display for Shader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.source)
    }
}

impl fmt::Debug for Shader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Shader").field("name", &self.name).finish_non_exhaustive()
    }
}

/// The gradient sky pass.
pub static SKY_GRADIENT: Shader = entry!("sky_gradient");
/// The tonemap pass.
pub static TONEMAP: Shader = entry!("tonemap");
/// The seed's own atmosphere model, the empirical one (`atmosphere.model = "seed"`).
pub static EMPIRICAL_SKY: Shader = entry!("empirical_sky");
/// The atmosphere's transmittance LUT pass (compute).
pub static ATMOSPHERE_TRANSMITTANCE_LUT: Shader = entry!("atmosphere/transmittance_lut");
/// The atmosphere's multiple-scattering LUTs: one order of scattering.
pub static ATMOSPHERE_MULTISCATTERING_LUT: Shader = entry!("atmosphere/multiscattering_lut");
/// The atmosphere's multiple-scattering LUTs: the orders summed.
pub static ATMOSPHERE_MULTISCATTERING_SUM: Shader = entry!("atmosphere/multiscattering_sum");
/// The atmosphere's multiple-scattering LUTs: the orders after the last marched in a thick air,
/// by discrete ordinates.
pub static ATMOSPHERE_MULTISCATTERING_ORDINATES: Shader = entry!("atmosphere/multiscattering_ordinates");
/// The atmosphere's multiple-scattering LUTs: how ln Ψ bends between a thick air's rows.
pub static ATMOSPHERE_MULTISCATTERING_CURVATURE: Shader = entry!("atmosphere/multiscattering_curvature");
/// The atmosphere's sky-view LUT pass.
pub static ATMOSPHERE_SKY_VIEW_LUT: Shader = entry!("atmosphere/sky_view_lut");
/// The atmosphere's sky pass.
pub static ATMOSPHERE_SKY: Shader = entry!("atmosphere/sky");
/// The atmosphere's sky lighting at the camera (compute): the suns and the sky's spherical
/// harmonics that [`FIRMAMENT_LIGHTING_WGSL`] reads.
pub static ATMOSPHERE_SKY_LIGHTING: Shader = entry!("atmosphere/sky_lighting");
/// The atmosphere's aerial-perspective volume (compute).
pub static ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME: Shader = entry!("atmosphere/aerial_perspective_volume");
/// The atmosphere's aerial-perspective application over geometry.
pub static ATMOSPHERE_AERIAL_PERSPECTIVE: Shader = entry!("atmosphere/aerial_perspective");
/// The object pass: classic (fixed-function) lighting, textures and fog.
pub static CLASSIC_LIGHTING: Shader = entry!("classic_lighting");
/// The shadow-map pass: casters' depth seen from a sun.
pub static SHADOW_MAP: Shader = entry!("shadow/shadow_map");
/// The lens-flare occlusion pass (compute).
pub static FLARE_OCCLUSION: Shader = entry!("flare_occlusion");
/// The lens-flare element pass.
pub static FLARE: Shader = entry!("flare");
/// The night-sky pass: stars and the Moon.
pub static NIGHT_SKY: Shader = entry!("night_sky");
/// Auto-exposure's meter: the luminance histogram (compute).
pub static EXPOSURE_METER: Shader = entry!("camera/exposure_meter");
/// Auto-exposure's adaptation: the EV100 from the histogram (compute).
pub static EXPOSURE_ADAPT: Shader = entry!("camera/exposure_adapt");
/// Bloom's first step down, from the image (compute).
pub static BLOOM_FROM_IMAGE: Shader = entry!("camera/bloom_from_image");
/// Bloom's way down from the first level (compute).
pub static BLOOM_DOWN: Shader = entry!("camera/bloom_down");
/// Bloom's way up (compute).
pub static BLOOM_UP: Shader = entry!("camera/bloom_up");
/// The cloud layers' density field, `cloud_density(layer, p, h)` and its `CloudsGpu` uniforms
/// (binding-free: `atmosphere/bindings` imports it, and the tests compose it with kernels of their
/// own to hold it against the core's `f64` field).
pub static CLOUD_DENSITY: Shader = entry!("clouds/density");
/// The cloud layers over the renderer's own HDR target, or as a layer to blend over a caller's
/// (compute; and the blend's full-screen draw).
pub static CLOUDS_MARCH: Shader = entry!("clouds/march");
/// The clouds' shadow map: their optical depth along each sun's rays around the camera (compute).
pub static CLOUD_SHADOW_MAP: Shader = entry!("clouds/shadow_map");

/// The environment-map pass's kernels (compute): the six faces into a cube layer or an
/// equirectangular map, with the suns' disc pieces (an `rgba16float` output; the pass derives the
/// `rgba32float` one).
pub static ENVMAP_WRITE: Shader = entry!("envmap/write");

/// Every entry module composed by firmament: the passes' and the user includes'
/// ([`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`]; [`FIRMAMENT_LIGHTING_WGSL`] is a file of its own,
/// `include/firmament_lighting`, imports nothing and so needs no composing).
pub static ENTRIES: [&Shader; 27] = [
    &SKY_GRADIENT,
    &TONEMAP,
    &EMPIRICAL_SKY,
    &ATMOSPHERE_TRANSMITTANCE_LUT,
    &ATMOSPHERE_MULTISCATTERING_LUT,
    &ATMOSPHERE_MULTISCATTERING_SUM,
    &ATMOSPHERE_MULTISCATTERING_ORDINATES,
    &ATMOSPHERE_MULTISCATTERING_CURVATURE,
    &ATMOSPHERE_SKY_VIEW_LUT,
    &ATMOSPHERE_SKY,
    &ATMOSPHERE_SKY_LIGHTING,
    &ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME,
    &ATMOSPHERE_AERIAL_PERSPECTIVE,
    &CLASSIC_LIGHTING,
    &SHADOW_MAP,
    &FLARE_OCCLUSION,
    &FLARE,
    &NIGHT_SKY,
    &EXPOSURE_METER,
    &EXPOSURE_ADAPT,
    &BLOOM_FROM_IMAGE,
    &BLOOM_DOWN,
    &BLOOM_UP,
    &CLOUDS_MARCH,
    &CLOUD_SHADOW_MAP,
    &ENVMAP_WRITE,
    &FIRMAMENT_AERIAL_PERSPECTIVE_WGSL,
];

/// The WGSL users put before their own shaders to read firmament's per-frame lighting: the
/// `FirmamentSkyLighting` struct (mirrored by [`SkyLightingGpu`](crate::SkyLightingGpu)), its uniform
/// binding `firmament_sky_lighting` at `@group(`[`FIRMAMENT_LIGHTING_GROUP`]`)
/// @binding(`[`FIRMAMENT_LIGHTING_BINDING`]`)`, and the functions `firmament_sun_count()`,
/// `firmament_sun_direction(i)`, `firmament_sun_color(i)`, `firmament_sky_irradiance(n)` and
/// `firmament_irradiance(n)`. Bind
/// [`Renderer::sky_lighting_buffer`](crate::Renderer::sky_lighting_buffer) (or the atmosphere
/// pass's own) there with a layout entry from
/// [`sky_lighting_layout_entry`](crate::sky_lighting_layout_entry); for
/// another group or binding use [`firmament_lighting_wgsl`]. Units and conventions are in the file
/// (`shaders/include/firmament_lighting.wgsl`, which imports nothing, so this is its text) and in
/// `docs/ATMOSPHERE.md`.
pub const FIRMAMENT_LIGHTING_WGSL: &str = include_str!("include/firmament_lighting.wgsl");

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
/// perspective: `shaders/include/firmament_aerial_perspective.wgsl` composed with the volume
/// lookup it imports, shared with firmament's own pass (`shaders/atmosphere/aerial_lookup.wgsl`),
/// with its five bindings at `@group(`[`FIRMAMENT_AERIAL_PERSPECTIVE_GROUP`]`)
/// @binding(`[`FIRMAMENT_AERIAL_PERSPECTIVE_FIRST_BINDING`]` + 0 … 4)`: the atmosphere pass's view
/// and medium uniforms, the volume's scattering and transmittance atlases and a filtering sampler,
/// laid out by [`aerial_perspective_layout_entries`](crate::aerial_perspective_layout_entries)
/// and bound from
/// [`Renderer::aerial_perspective_bindings`](crate::Renderer::aerial_perspective_bindings) (or the
/// atmosphere pass's own).
/// Its functions: `firmament_apply_aerial_perspective(color, ndc_xy, distance_m)` (`color · T + S`)
/// and `firmament_aerial_perspective(ndc_xy, distance_m)` (T and S apart). The default slots follow
/// [`FIRMAMENT_LIGHTING_WGSL`]'s, so both fit one bind group; for others use
/// [`firmament_aerial_perspective_wgsl`]. Units and conventions: the file and `docs/ATMOSPHERE.md`.
///
/// Composed on first use: it derefs to `str` and displays as its text (`format!("{}", …)`,
/// `&*FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`).
pub static FIRMAMENT_AERIAL_PERSPECTIVE_WGSL: Shader = entry!("include/firmament_aerial_perspective");

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
    let mut source = FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.source().to_owned();
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;
    use crate::gpu_types::{
        AtmosphereParamsUniforms, AtmosphereSunUniform, AtmosphereViewUniforms, ClassicFrameUniforms,
        ClassicLightUniform, ClassicMaterialUniform, ClassicObjectUniforms, DensityProfileUniform, FlareFrameUniforms, MediumTermUniform,
        FlareInstance, FlareSourceGpu, GradientSkyUniforms, ShadowCascadeGpu, ShadowCasterUniform, ShadowFrameUniforms,
        TonemapUniforms,
    };

    fn validate(name: &str, source: &str) -> naga::Module {
        let module =
            naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        // f16 packing (`pack2x16float`, core WGSL) is the one capability: wgpu grants it with
        // `DownlevelFlags::SHADER_F16_IN_F32`, which its Vulkan and GL backends always report.
        let capabilities = naga::valid::Capabilities::SHADER_FLOAT16_IN_FLOAT32;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), capabilities)
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        module
    }

    #[test]
    fn every_entry_composes_and_validates() {
        for entry in ENTRIES {
            assert_eq!(entry.source(), compose(entry.name()).unwrap());
            validate(entry.name(), entry);
        }
        validate("include/firmament_lighting", FIRMAMENT_LIGHTING_WGSL);
    }

    #[test]
    fn every_module_validates_with_its_imports() {
        for name in module_names() {
            validate(name, &compose(name).unwrap_or_else(|e| panic!("{e}")));
        }
    }

    /// A module's direct imports.
    fn imports(name: &str) -> Vec<String> {
        let source = module_source(name).unwrap();
        let module = compose::parse(name, &source).unwrap();
        module.imports.iter().map(|import| (*import).to_owned()).collect()
    }

    /// Every module `name` imports, directly or not.
    fn closure(name: &str) -> BTreeSet<String> {
        let mut found = BTreeSet::new();
        let mut to_visit = imports(name);
        while let Some(module) = to_visit.pop() {
            if found.insert(module.clone()) {
                to_visit.extend(imports(&module));
            }
        }
        found
    }

    #[test]
    fn every_module_is_an_entry_or_imported_by_one() {
        let entries: Vec<&str> = ENTRIES
            .iter()
            .map(|entry| entry.name())
            .chain(["include/firmament_lighting"])
            .collect();
        let mut reached: BTreeSet<String> = entries.iter().map(|entry| (*entry).to_owned()).collect();
        for entry in &entries {
            reached.extend(closure(entry));
        }
        let all: BTreeSet<String> = module_names().map(str::to_owned).collect();
        assert_eq!(reached, all, "modules nothing composes");
        for name in module_names() {
            for entry in &entries {
                assert!(!imports(name).iter().any(|i| i == entry), "{name} imports the entry {entry}");
            }
        }
    }

    #[test]
    fn every_wgsl_file_is_in_the_table() {
        fn walk(dir: &std::path::Path, found: &mut BTreeSet<String>) {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    walk(&path, found);
                } else if path.extension().is_some_and(|e| e == "wgsl") {
                    found.insert(path.display().to_string());
                }
            }
        }
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/shaders");
        let mut found = BTreeSet::new();
        walk(&root, &mut found);
        let table: BTreeSet<String> = FILES
            .iter()
            .map(|(name, _)| root.join(format!("{name}.wgsl")).display().to_string())
            .collect();
        assert_eq!(found, table);
        for (name, source) in FILES {
            let file = std::fs::read_to_string(root.join(format!("{name}.wgsl"))).unwrap();
            assert_eq!(*source, file, "{name}");
        }
    }

    #[test]
    fn every_module_opens_with_a_header_naming_it() {
        for name in module_names() {
            let source = module_source(name).unwrap();
            let first = source.lines().next().unwrap_or_default();
            let expected = if name == GENERATED_CONSTANTS {
                format!("// {name} — ")
            } else {
                format!("// {name}.wgsl — ")
            };
            assert!(first.starts_with(&expected), "{name}: {first}");
            assert!(
                source.lines().take_while(|l| l.starts_with("//")).count() >= 2,
                "{name}: a header of its conventions"
            );
        }
    }

    #[test]
    fn each_import_is_included_once() {
        for entry in ENTRIES {
            for module in closure(entry.name()).iter().chain([&entry.name().to_owned()]) {
                let header = module_source(module).unwrap().lines().next().unwrap().to_owned();
                assert_eq!(entry.matches(&header).count(), 1, "{module} in {}", entry.name());
            }
            assert!(!entry.contains("#import"), "{}", entry.name());
        }
    }

    #[test]
    fn composing_reports_unknown_modules() {
        assert_eq!(compose("nowhere"), Err(ComposeError::NoSuchModule("nowhere".into())));
    }

    #[test]
    fn the_user_includes_are_their_files() {
        assert_eq!(compose("include/firmament_lighting").unwrap(), FIRMAMENT_LIGHTING_WGSL);
        let lookup = compose("atmosphere/aerial_lookup").unwrap();
        let include =
            include_str!("include/firmament_aerial_perspective.wgsl").replace("#import atmosphere/aerial_lookup\n", "");
        assert_eq!(FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.source(), format!("{lookup}\n{include}"));
    }

    /// The names module `name` declares at module scope (types, constants, overrides, globals,
    /// functions), from naga.
    fn declared(name: &str) -> BTreeSet<String> {
        let names = |source: &str| -> BTreeSet<String> {
            let module = naga::front::wgsl::parse_str(source).unwrap();
            let types = module.types.iter().filter_map(|(_, t)| t.name.clone());
            let constants = module.constants.iter().filter_map(|(_, c)| c.name.clone());
            let overrides = module.overrides.iter().filter_map(|(_, o)| o.name.clone());
            let globals = module.global_variables.iter().filter_map(|(_, g)| g.name.clone());
            let functions = module.functions.iter().filter_map(|(_, f)| f.name.clone());
            types.chain(constants).chain(overrides).chain(globals).chain(functions).collect()
        };
        let mut own = names(&compose(name).unwrap());
        for import in imports(name) {
            for inherited in names(&compose(&import).unwrap()) {
                own.remove(&inherited);
            }
        }
        own
    }

    /// The identifiers module `name`'s own code uses, outside comments and member accesses.
    fn used(name: &str) -> BTreeSet<String> {
        let source = module_source(name).unwrap();
        let body = compose::parse(name, &source).unwrap().body;
        let mut found = BTreeSet::new();
        for line in body.lines() {
            let code = line.split("//").next().unwrap_or_default();
            let mut previous = ' ';
            let mut word = String::new();
            for c in code.chars().chain([' ']) {
                if c.is_ascii_alphanumeric() || c == '_' {
                    if word.is_empty() && previous == '.' {
                        word.push('.');
                    }
                    word.push(c);
                } else {
                    if !word.is_empty() && !word.starts_with('.') && !word.starts_with(|c: char| c.is_ascii_digit()) {
                        found.insert(std::mem::take(&mut word));
                    }
                    word.clear();
                    previous = c;
                }
            }
        }
        found
    }

    #[test]
    fn each_module_imports_exactly_the_modules_it_uses() {
        let declared: Vec<(String, BTreeSet<String>)> =
            module_names().map(|name| (name.to_owned(), declared(name))).collect();
        let mut wrong = Vec::new();
        for name in module_names() {
            let direct = imports(name);
            let used = used(name);
            for (module, names) in &declared {
                let uses = names.intersection(&used).next();
                if direct.contains(module) && uses.is_none() {
                    wrong.push(format!("{name} imports {module} but uses none of its names"));
                }
                if module == name || direct.contains(module) || !closure(name).contains(module) {
                    continue;
                }
                if let Some(used_name) = uses {
                    wrong.push(format!("{name} uses `{used_name}` of {module} without importing it"));
                }
            }
        }
        assert!(wrong.is_empty(), "{wrong:#?}");
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
        let night = validate("night_sky", &NIGHT_SKY);
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
                moon_radiance,
                moon_shadow_axis,
                moon_shadow_offset,
                moon_shadow
            ]
        );
        assert_layout!(night, "StarIn", StarInstance, [direction, color]);
    }

    #[test]
    fn envmap_layouts_match() {
        use crate::gpu_types::{DiscTexelInstance, EnvmapParamsUniforms};
        let module = validate("envmap/write", &ENVMAP_WRITE);
        assert_layout!(module, "EnvmapParams", EnvmapParamsUniforms, [face, size, width, height]);
        assert_layout!(module, "DiscTexel", DiscTexelInstance, [x, y, face, first, count]);
        // The pass's rgba32float variant is the same module with one word changed.
        let wide = crate::envmap::write_source(wgpu::TextureFormat::Rgba32Float);
        assert_ne!(wide, ENVMAP_WRITE.source());
        validate("envmap/write (rgba32float)", &wide);
    }

    #[test]
    fn sky_lighting_layouts_match() {
        use crate::gpu_types::{SkyLightingGpu, SkyLightingParamsUniforms, SkyLightingSunGpu};
        let stage = validate("atmosphere/sky_lighting", &ATMOSPHERE_SKY_LIGHTING);
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
                FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.to_string(),
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
    }

    #[test]
    fn the_aerial_perspective_include_mirrors_the_pass() {
        use crate::gpu_types::{AtmosphereParamsUniforms, AtmosphereViewUniforms};
        let module = validate(
            "include/firmament_aerial_perspective",
            &FIRMAMENT_AERIAL_PERSPECTIVE_WGSL,
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
    }

    #[test]
    fn the_sky_lighting_grid_is_the_documented_one() {
        let (columns, rows) = crate::gpu_types::sky_lighting::SKY_LIGHTING_GRID;
        assert!(ATMOSPHERE_SKY_LIGHTING.contains(&format!("const GRID_AZIMUTH: u32 = {columns}u;")));
        assert!(ATMOSPHERE_SKY_LIGHTING.contains(&format!("const GRID_ROWS: u32 = {rows}u;")));
    }

    #[test]
    fn camera_layouts_match() {
        use crate::gpu_types::camera::METERING_BINS;
        use crate::gpu_types::{ExposureStateGpu, MeteringUniforms};
        let meter = validate("camera/exposure_meter", &EXPOSURE_METER);
        assert_layout!(
            meter,
            "Metering",
            MeteringUniforms,
            [clip_to_world, discs, range, ev, step, counts]
        );
        assert_layout!(meter, "ExposureState", ExposureStateGpu, [ev100, target_ev100, metered_log2, frames]);
        let (size, _) = wgsl_layout(&meter, "Histogram");
        assert_eq!(size, 2 * 4 * METERING_BINS, "the histogram's bins");
        let constant = |name: &str| {
            let (_, c) = meter.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).expect(name);
            match meter.global_expressions[c.init] {
                naga::Expression::Literal(naga::Literal::U32(value)) => value,
                ref other => panic!("{name}: {other:?}"),
            }
        };
        let cell = firmament_core::auto_exposure::METERING_CELL;
        assert_eq!(constant("METERING_CELL"), cell);
        assert_eq!(constant("METERING_TILE"), 16 * cell);
        assert_eq!(constant("METERING_BINS"), METERING_BINS);
    }

    #[test]
    fn cloud_layouts_and_constants_match() {
        use crate::gpu_types::{CloudLayerGpu, CloudsGpu};
        use firmament_core::atmosphere::clouds::{MAX_CLOUD_LAYERS, QUANTILES};
        let clouds = validate("clouds/density", &CLOUD_DENSITY);
        assert_layout!(
            clouds,
            "CloudLayerGpu",
            CloudLayerGpu,
            [
                shell,
                coverage,
                phase,
                codes,
                drift,
                drift_rest,
                column,
                column_scale,
                profile,
                edges,
                detail,
                quantiles,
                mean_profile,
                lod
            ]
        );
        assert_layout!(clouds, "CloudsGpu", CloudsGpu, [count, layers]);
        let literal = |name: &str| {
            let (_, c) = clouds.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).expect(name);
            clouds.global_expressions[c.init].clone()
        };
        assert_eq!(
            literal("MAX_CLOUD_LAYERS"),
            naga::Expression::Literal(naga::Literal::U32(MAX_CLOUD_LAYERS as u32))
        );
        assert_eq!(
            literal("CLOUD_QUANTILE_STEPS"),
            naga::Expression::Literal(naga::Literal::U32(QUANTILES as u32 - 1))
        );
        assert_eq!(
            literal("CLOUD_COLUMN_SPACING_CELLS"),
            naga::Expression::Literal(naga::Literal::F32(
                firmament_core::atmosphere::clouds::COLUMN_SPACING_CELLS as f32
            ))
        );
    }

    #[test]
    fn empirical_sky_layouts_match() {
        use crate::gpu_types::{EmpiricalSkyUniforms, EmpiricalStarUniform};
        let empirical = validate("empirical_sky", &EMPIRICAL_SKY);
        assert_layout!(empirical, "EmpiricalStar", EmpiricalStarUniform, [position, direction, color]);
        assert_layout!(
            empirical,
            "EmpiricalSky",
            EmpiricalSkyUniforms,
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
        let sky = validate("sky_gradient", &SKY_GRADIENT);
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
        let tonemap = validate("tonemap", &TONEMAP);
        assert_layout!(
            tonemap,
            "Tonemap",
            TonemapUniforms,
            [exposure, curve, transfer, metered, bloom, night_vision, _pad]
        );
        let classic = validate("classic_lighting", &CLASSIC_LIGHTING);
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
                ground_up,
                bounced_sun,
                bounced_sky,
                ground_mode,
                lights
            ]
        );
        assert_layout!(classic, "ShadowCascade", ShadowCascadeGpu, [eye_to_clip, params]);
        assert_layout!(
            classic,
            "ShadowFrame",
            ShadowFrameUniforms,
            [counts, bias, slot_of_light, tan_radius, cascades, clouds]
        );
        let shadow_map = validate("shadow/shadow_map", &SHADOW_MAP);
        assert_layout!(shadow_map, "ShadowCaster", ShadowCasterUniform, [model_to_clip]);
        assert_layout!(
            classic,
            "ClassicObject",
            ClassicObjectUniforms,
            [model_view, normal_matrix, front, back, flags, fog_coord, light_colors]
        );
        let occlusion = validate("flare_occlusion", &FLARE_OCCLUSION);
        let flare = validate("flare", &FLARE);
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
        let atmosphere = validate("atmosphere/sky", &ATMOSPHERE_SKY);
        assert_layout!(
            atmosphere,
            "DensityProfile",
            DensityProfileUniform,
            [layer0, layer1, width]
        );
        assert_layout!(
            atmosphere,
            "MediumTerm",
            MediumTermUniform,
            [extinction, scattering, phase, legendre, profile]
        );
        assert_layout!(
            atmosphere,
            "AtmosphereParams",
            AtmosphereParamsUniforms,
            [
                radii,
                lut,
                ground_albedo,
                terms,
                table_counts,
                density_table_terms,
                phase_table_terms,
                density_tables,
                phase_tables,
                lut_rows
            ]
        );
        let literal = |name: &str| {
            let (_, c) = atmosphere.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).expect(name);
            atmosphere.global_expressions[c.init].clone()
        };
        {
            use crate::gpu_types::medium::{DENSITY_TABLE_SAMPLES, LUT_ROWS, MAX_MEDIUM_TERMS, PHASE_TABLE_SAMPLES};
            use firmament_core::atmosphere::body::MAX_BODIES;
            use firmament_core::atmosphere::planet_shadow::SHADOW_ENTRIES;
            for (name, value) in [
                ("MAX_BODIES", MAX_BODIES),
                ("BODY_SHADOW_ENTRIES", SHADOW_ENTRIES),
                ("BODY_AIR_TERMS", crate::gpu_types::atmosphere::BODY_AIR_TERMS),
                ("LUT_ROWS", LUT_ROWS),
                ("MAX_MEDIUM_TERMS", MAX_MEDIUM_TERMS),
                ("DENSITY_TABLE_SAMPLES", DENSITY_TABLE_SAMPLES),
                ("PHASE_TABLE_SAMPLES", PHASE_TABLE_SAMPLES),
            ] {
                assert_eq!(literal(name), naga::Expression::Literal(naga::Literal::U32(value as u32)), "{name}");
            }
        }
        assert_layout!(
            atmosphere,
            "AtmosphereSun",
            AtmosphereSunUniform,
            [direction, irradiance, source]
        );
        assert_layout!(
            atmosphere,
            "OrderSums",
            crate::gpu_types::OrderSumsGpu,
            [sum, last, previous_psi, irradiance, last_irradiance]
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
                suns,
                eclipsers,
                rings,
                ring_albedo,
                ring_depth,
                surface,
                bodies,
                body_shadows,
                body_air
            ]
        );
        assert_layout!(
            atmosphere,
            "AtmosphereBody",
            crate::gpu_types::atmosphere::AtmosphereBodyUniform,
            [center, radii, axis_x, axis_y, axis_z, albedo, shadow, air]
        );
    }
}

