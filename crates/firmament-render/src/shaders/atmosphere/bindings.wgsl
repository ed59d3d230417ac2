// atmosphere/bindings.wgsl — the atmosphere passes' interface with Rust: the uniform and storage
// structs (mirrored by `gpu_types/atmosphere.rs` and `gpu_types/sky_lighting.rs`, checked by the
// layout tests in `shaders/mod.rs`) and every group-0 binding of every atmosphere pipeline, in one
// place (mirrored by the `binding` module of `passes/atmosphere/stages.rs`, checked by its tests).
//
// Conventions: as atmosphere/common.wgsl (planet frame, metres, spectra per model wavelength).
// Each pipeline's layout holds only the bindings its entry points use; the others are declared
// here unused, which WGSL and wgpu allow. A new binding takes a free number (21, 22, 27 or from 31) here and in `stages.rs`.

#import clouds/density

// How many suns the view uniforms carry (firmament_core::frame::MAX_SUNS).
const MAX_SUNS: u32 = 8u;
// How many eclipsing bodies (firmament_core::atmosphere::eclipse::MAX_ECLIPSERS).
const MAX_ECLIPSERS: u32 = 4u;
// How many bodies beside the planet (firmament_core::atmosphere::body::MAX_BODIES); body i is
// also eclipser i.
const MAX_BODIES: u32 = 4u;
// Entries of a body's table of the light inside the planet's shadow
// (firmament_core::atmosphere::planet_shadow::SHADOW_ENTRIES).
const BODY_SHADOW_ENTRIES: u32 = 64u;
// The terms of a body's air: molecules, aerosols, an absorbing gas (gpu_types/atmosphere.rs).
const BODY_AIR_TERMS: u32 = 3u;
// The rings' optical depth table: entries (firmament_core::atmosphere::rings::RING_TABLE_ENTRIES)
// and the vectors that hold them.
const RING_TABLE_ENTRIES: u32 = 128u;
const RING_TABLE_VECTORS: u32 = 32u;

// The medium's terms and tables (firmament-render's gpu_types/medium.rs): the most terms, and
// the values of each term's density table (altitudes evenly spread from the ground to the top)
// and phase table (scattering angles evenly spread from 0 to π), four to a vector.
const MAX_MEDIUM_TERMS: u32 = 8u;
const DENSITY_TABLE_SAMPLES: u32 = 128u;
const PHASE_TABLE_SAMPLES: u32 = 256u;

struct DensityProfile {
    layer0: vec4<f32>, // exp_term, exp_scale (m⁻¹), linear_term (m⁻¹), constant_term: below width
    layer1: vec4<f32>, // the same terms above width
    width: vec4<f32>,  // x = top of layer 0 (m); yzw unused
}

// One term of the medium.
struct MediumTerm {
    extinction: vec4<f32>, // rgb m⁻¹ at density 1 (scattering + absorption); w unused
    scattering: vec4<f32>, // rgb m⁻¹ at density 1; w = PHASE_*
    phase: vec4<f32>,      // x = g (the forward lobe's), y = the backward lobe's g, z = the forward lobe's
                           // weight; w = f, the delta-M forward peak (see Coefficients)
    legendre: vec4<f32>,   // the phase function's Legendre coefficients a_1 … a_4 (a_0 = 1)
    profile: DensityProfile, // all zeros for a term whose density is a table
}

// The medium: everything the LUTs depend on.
struct AtmosphereParams {
    radii: vec4<f32>,         // xyz ellipsoid semi-axes (m); w = atmosphere height (m)
    lut: vec4<f32>,           // x, y = bottom and top radius of the LUT sphere (m); z = number of terms;
                              // w = the height the multiple-scattering and irradiance LUTs span (m)
    ground_albedo: vec4<f32>, // rgb, dimensionless
    terms: array<MediumTerm, MAX_MEDIUM_TERMS>,
    table_counts: vec4<u32>,                      // x = terms with a density table, y = with a phase table;
                                                  // z = 1: a thick air (common.wgsl's thick_air)
    density_table_terms: array<vec4<u32>, 2>,     // their indices, four to a vector
    phase_table_terms: array<vec4<u32>, 2>,
    density_tables: array<vec4<f32>, 256>, // MAX_MEDIUM_TERMS · DENSITY_TABLE_SAMPLES / 4
    phase_tables: array<vec4<f32>, 512>,   // MAX_MEDIUM_TERMS · PHASE_TABLE_SAMPLES / 4
    lut_rows: array<vec4<f32>, 8>,         // a thick air's LUT_ROWS row altitudes (m), ground to lut.w
}

// A body beside the planet (atmosphere/bodies.wgsl, its air atmosphere/body_air.wgsl;
// firmament_core::atmosphere::body).
struct AtmosphereBody {
    center: vec4<f32>, // xyz centre, planet frame (m); w = reflectance law (BODY_REFLECTANCE_*)
    radii: vec4<f32>,  // xyz semi-axes along the body's axes (m); w = surface (BODY_SURFACE_*)
    axis_x: vec4<f32>, // the body's axes in the planet frame (unit); w unused
    axis_y: vec4<f32>,
    axis_z: vec4<f32>,
    // rgb normal albedo per model wavelength; w = 1 + the sun whose shadow of the planet the body
    // stands in (0: none), its light there in `view.body_shadows[i]`
    albedo: vec4<f32>,
    // xyz unit direction of that shadow's axis from the planet's centre; w = the distance from
    // the axis between the table's entries (m)
    shadow: vec4<f32>,
    // x = the height of the body's air (m; 0: airless), its terms in `view.body_air[i]`; y = the
    // body's volumetric mean radius (m); zw unused
    air: vec4<f32>,
}

struct AtmosphereSun {
    direction: vec4<f32>,  // xyz unit direction to the sun, planet frame; w = angular radius (rad), < 0: no disc drawn
    irradiance: vec4<f32>, // rgb spectral irradiance at the top (W·m⁻²·nm⁻¹); w = limb darkening u
    // x = 1 + the body whose light this is (0: a star's), which neither hides it nor is lit by
    // it (firmament_core's Sun::from_body); yzw unused
    source: vec4<u32>,
}

// The camera and the suns, per frame.
struct AtmosphereView {
    view_to_planet: mat4x4<f32>, // rotation: view-space direction → planet frame
    camera: vec4<f32>,           // xyz camera position (m); w = its altitude (m)
    // x, y = |o/a|² − 1 of the camera against the surface and the top; z, w = tan of half the
    // horizontal and vertical fields of view
    camera_shape: vec4<f32>,
    // xy = planet centre's view-space x, y divided by its depth; z = that depth (m); w = 1 to march
    // from each ray's closest approach to the centre (camera far away), 0 from the camera
    center: vec4<f32>,
    local_up: vec4<f32>,         // xyz geodetic up at the camera; w = 0 sky-view LUT … 1 ray march
    to_srgb0: vec4<f32>,         // columns of spectral radiance → linear sRGB (Y in cd/m²)
    to_srgb1: vec4<f32>,
    to_srgb2: vec4<f32>,
    // x = range of the aerial-perspective volume (m); y, z = the projection's A, B (view depth =
    // B / (depth + A) for a depth-buffer value); w = the far plane's depth (0 reversed-Z, 1
    // standard)
    aerial: vec4<f32>,
    // x = number of suns; y = number of eclipsing bodies; z = 1: the sky-view LUT spans the
    // whole circle of azimuths (with eclipsers), 0: half of it; w = number of bodies (the first
    // w eclipsers)
    sun_count: vec4<u32>,
    suns: array<AtmosphereSun, MAX_SUNS>,
    eclipsers: array<vec4<f32>, MAX_ECLIPSERS>, // xyz centre, planet frame (m); w = radius (m)
    // The planet's rings (atmosphere/rings.wgsl): x, y = inner and outer radius (m), z = their
    // particles' Henyey–Greenstein g, w = 1 with rings, 0 without
    rings: vec4<f32>,
    ring_albedo: vec4<f32>,      // rgb single-scattering albedo
    // normal optical depth at inner + k·(outer − inner)/(RING_TABLE_ENTRIES − 1), four to a vector
    ring_depth: array<vec4<f32>, RING_TABLE_VECTORS>,
    // The planet's surface (atmosphere/surface.wgsl): x = 1 to read the ground from `surface_map`
    // (0: `ground_albedo` everywhere, no water); y = the sea's mean square slope (Cox–Munk); z = the
    // planet's geometric albedo (its light on the bodies, atmosphere/bodies.wgsl); w = its
    // volumetric mean radius (m)
    surface: vec4<f32>,
    bodies: array<AtmosphereBody, MAX_BODIES>,
    // Per body, the sunlight's share across the planet's shadow where it stands (rgb per model
    // wavelength; entry k at k·bodies[i].shadow.w from the axis, 1 beyond the last)
    body_shadows: array<array<vec4<f32>, BODY_SHADOW_ENTRIES>, MAX_BODIES>,
    // Per body, its air's molecules, aerosols and absorbing gas (altitudes over the body)
    body_air: array<array<MediumTerm, BODY_AIR_TERMS>, MAX_BODIES>,
}

// The sky-lighting stage's parameters (atmosphere/sky_lighting.wgsl).
struct SkyLightingParams {
    planet_to_world: mat4x4<f32>, // rotation: planet frame → world frame
    flags: vec4<f32>,             // x = 1: no sky light (the camera is far away); yzw unused
}

struct SkyLightingSun {
    direction: vec4<f32>, // xyz unit direction to the sun, world frame; w = angular radius (rad)
    color: vec4<f32>,     // rgb E·T at the camera, linear sRGB (Y in lux); w = 0
}

// What the sky-lighting stage writes, read by users' shaders (include/firmament_lighting.wgsl
// mirrors it as FirmamentSkyLighting).
struct SkyLighting {
    sun_count: vec4<u32>,                   // x = number of suns; yzw = 0
    suns: array<SkyLightingSun, MAX_SUNS>,  // the first sun_count.x are set, the others zero
    sky_sh: array<vec4<f32>, 9>,            // rgb L_lm at index l(l + 1) + m, linear sRGB (Y in cd/m²)
}

// ---- Uniforms ----
@group(0) @binding(0) var<uniform> atmosphere: AtmosphereParams;
@group(0) @binding(1) var<uniform> view: AtmosphereView;
@group(0) @binding(25) var<uniform> lighting: SkyLightingParams;
// The cloud layers (clouds/density.wgsl declares their struct).
@group(0) @binding(15) var<uniform> clouds: CloudsGpu;
// Their coverage maps, one array layer per layer that has one (`codes.w`), R16Float, resampled to
// passes/atmosphere/clouds.rs COVERAGE_MAP_SIZE; read at equirect_uv (common/ellipsoid.wgsl) with
// `map_sampler`.
@group(0) @binding(16) var cloud_coverage_maps: texture_2d_array<f32>;
// Every equirectangular map's (the cloud coverage maps', the surface map's): linear, repeating in
// longitude, clamped at the poles.
@group(0) @binding(17) var map_sampler: sampler;
// The planet's surface (atmosphere/surface.wgsl): an equirectangular map, Rgba16Float, of linear
// albedo (rgb) and water fraction (a), resampled to passes/atmosphere/surface.rs SURFACE_MAP_SIZE;
// read at equirect_uv (common/ellipsoid.wgsl) with `map_sampler`.
@group(0) @binding(18) var surface_map: texture_2d<f32>;
// The bodies' albedo maps (atmosphere/bodies.wgsl), layer i body i's where its surface is
// BODY_SURFACE_MAP: equirectangular in the body's axes, the map's linear albedo (Rgba8UnormSrgb,
// mip-mapped), resampled to gpu_types/atmosphere.rs BODY_MAP_SIZE;
// read at equirect_uv with `map_sampler`.
@group(0) @binding(21) var body_maps: texture_2d_array<f32>;
// The light of the bodies' airs (atmosphere/body_air_medium.wgsl), Rgba16Float: for body i with
// air, layer 2i the light scattered more than once (Ψ, sr⁻¹ per unit irradiance; the sun's
// zenith cosine −1…1 across, altitude ground…top down) and layer 2i + 1 the sky's irradiance on
// its ground per unit irradiance (across; every row alike): the core's AirLight nodes at texel
// centres (gpu_types/atmosphere.rs BODY_AIR_LIGHT_SIZE); read with `lut_sampler`.
@group(0) @binding(22) var body_air_light: texture_2d_array<f32>;
// The rings' light on the ground (atmosphere/rings.wgsl), Rgba16Float, layer i sun i's: the
// irradiance through the air per unit of the sun's (rgb; a unused) over the globe, azimuth from
// the sun's 0…π across, geodetic latitude −90°…90° down (crowded at the equator: rings.wgsl), at
// texel centres (the core's Rings::light_table; passes/atmosphere/ring_light.rs); read with
// `lut_sampler`.
@group(0) @binding(27) var ring_light: texture_2d_array<f32>;
// The clouds' shadow map (clouds/shadow.wgsl): per sun a square of texels across its rays around
// the camera, the suns' squares side by side; written by clouds/shadow_map.wgsl, read by the
// march (unfilterable: textureLoad).
@group(0) @binding(29) var cloud_shadow_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(30) var cloud_shadow_map: texture_2d<f32>;

// One texel's multiple-scattering orders (and sky irradiance) while the LUTs are built, as the seven sums over
// directions that multiscattering_lut.wgsl reduces (`ORDER_SUMS` there: Ψ, zz, xx, xz, x, z in
// rgb, bands 3 and 4 in the w components and the seventh), in f32: orders differ from each other
// by less than a half float resolves.
struct OrderSums {
    sum: array<vec4<f32>, 7>,  // over the orders so far
    last: array<vec4<f32>, 7>, // the last order alone
    previous_psi: vec4<f32>,   // the order before it: Ψ (rgb) and Ψ summed over wavelengths (w)
    irradiance: vec4<f32>,     // rgb: the sky irradiance on a horizontal surface, orders so far
    last_irradiance: vec4<f32>, // rgb: the same, the last order alone
}

// ---- The LUTs, read (layouts: passes/atmosphere/luts.rs) ----
// Rgba32Float, not filterable everywhere: read with textureLoad (`load_bilinear` in luts.wgsl).
@group(0) @binding(2) var transmittance_lut: texture_2d<f32>;
@group(0) @binding(7) var irradiance_lut: texture_2d<f32>;
@group(0) @binding(4) var sky_view_lut: texture_2d<f32>;
// The multiple-scattering moments, one layer each in `Moments` order (luts.wgsl).
@group(0) @binding(3) var multiscattering_lut: texture_2d_array<f32>;
// The previous order's ground irradiance row, while the multiple-scattering LUTs are built
// (multiscattering_lut.wgsl; the previous order's moments are read through the bindings above).
@group(0) @binding(14) var previous_ground_irradiance: texture_2d<f32>;
// The aerial-perspective volume's slice atlases (aerial_perspective_volume.wgsl).
@group(0) @binding(10) var aerial_scattering: texture_2d<f32>;
@group(0) @binding(11) var aerial_transmittance: texture_2d<f32>;
// Linear, clamp to edge.
@group(0) @binding(5) var lut_sampler: sampler;

// ---- Other inputs ----
// The scene's depth buffer, a depth view read as unfilterable float (aerial_perspective.wgsl).
@group(0) @binding(12) var scene_depth: texture_2d<f32>;

// ---- Outputs of the compute stages ----
@group(0) @binding(6) var transmittance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(8) var aerial_scattering_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(9) var aerial_transmittance_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(19) var sky_view_out: texture_storage_2d<rgba16float, write>;
// The renderer's own HDR target (targets.rs HDR_FORMAT), for the compute sky (sky.wgsl).
@group(0) @binding(20) var sky_out: texture_storage_2d<rgba16float, write>;
// The same target read, and a scratch copy of it written, by the compute aerial perspective
// (aerial_perspective.wgsl).
@group(0) @binding(23) var hdr_in: texture_2d<f32>;
@group(0) @binding(24) var hdr_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(26) var<storage, read_write> sky_lighting: SkyLighting;
// One order's moments and ground row, or the LUTs' sums, as packed Rgba16Float texels
// (multiscattering_lut.wgsl, multiscattering_sum.wgsl).
@group(0) @binding(13) var<storage, read_write> multiscattering_out: array<vec2<u32>>;
// Per texel of the multiple-scattering LUTs, the orders summed so far (multiscattering_lut.wgsl).
@group(0) @binding(28) var<storage, read_write> multiscattering_orders: array<OrderSums>;
