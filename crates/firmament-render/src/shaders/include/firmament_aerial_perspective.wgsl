// include/firmament_aerial_perspective.wgsl — firmament's aerial perspective for your own
// shaders: the air between the camera and your surface, `colour · T + S` per channel, from the
// froxel volume the atmosphere pass builds at the camera each frame (the one its own geometry is
// fogged with).
//
// Use: put this text before your shader's code (`firmament_render::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`
// is this file after the lookup it imports; it declares five bindings at @group(1) @binding(1) …
// @binding(5), after firmament_lighting.wgsl's @binding(0);
// `firmament_render::firmament_aerial_perspective_wgsl(group, first_binding)` gives the same text
// at `first_binding` … `first_binding + 4` of your own group). Its bind group layout entries are
// `firmament_render::aerial_perspective_layout_entries(first_binding)` and the resources
// `AtmospherePass::aerial_perspective_bindings().bind_group_entries(first_binding)` (or
// `Renderer::aerial_perspective_bindings()`). Every name here starts with `firmament_`,
// `Firmament` or `FIRMAMENT_`.
//
// The volume is built by the atmosphere pass's `record_aerial_perspective_volume` (or
// `record_aerial_perspective`) after its `record_luts`: use it in commands encoded after those.
// Conventions (frames and units): colours linear sRGB with Y in cd/m² (the sky's units); the
// transmittance at 680/550/440 nm multiplies R/G/B. No aerial perspective from a camera beyond 10
// atmosphere top radii (the colour is returned as it is), as for firmament's own geometry.

#import atmosphere/aerial_lookup

// The atmosphere pass's per-frame view (its first members; Rust `gpu_types::AtmosphereViewUniforms`).
struct FirmamentAerialView {
    view_to_planet: mat4x4<f32>, // rotation: view-space direction → planet frame
    camera: vec4<f32>,           // xyz camera position, planet frame (m); w = its altitude (m)
    camera_shape: vec4<f32>,     // x, y = |o/a|² − 1 against the surface and the top; z, w = tan of half fov x, y
    center: vec4<f32>,           // w = 1 for a camera far away (then no aerial perspective)
    local_up: vec4<f32>,         // unused here
    to_srgb0: vec4<f32>,         // columns of spectral radiance → linear sRGB (Y in cd/m²)
    to_srgb1: vec4<f32>,
    to_srgb2: vec4<f32>,
    aerial: vec4<f32>,           // x = the volume's range (m)
}

// The atmosphere pass's medium (its first member; Rust `gpu_types::AtmosphereParamsUniforms`).
struct FirmamentAerialPlanet {
    radii: vec4<f32>, // xyz ellipsoid semi-axes (m); w = atmosphere height (m)
}

@group(1) @binding(1) var<uniform> firmament_aerial_view: FirmamentAerialView;
@group(1) @binding(2) var<uniform> firmament_aerial_planet: FirmamentAerialPlanet;
@group(1) @binding(3) var firmament_aerial_scattering: texture_2d<f32>;
@group(1) @binding(4) var firmament_aerial_transmittance: texture_2d<f32>;
@group(1) @binding(5) var firmament_aerial_sampler: sampler;

// Where the ray from the camera along the planet-frame unit direction d enters the air (metres
// from the camera): 0 inside the atmosphere, the top's entry point above it; 0 when it misses
// the air (the volume then holds no light and no extinction). The stable roots of
// common/ellipsoid.wgsl's `ellipsoid_hits`.
fn firmament_aerial_air_entry(d: vec3<f32>) -> f32 {
    let a = firmament_aerial_planet.radii.xyz + vec3<f32>(firmament_aerial_planet.radii.w);
    let c = firmament_aerial_view.camera_shape.y;
    if c <= 0.0 {
        return 0.0;
    }
    let os = firmament_aerial_view.camera.xyz / a;
    let ds = d / a;
    let qa = dot(ds, ds);
    let qb = dot(os, ds);
    let disc = qb * qb - qa * c;
    if disc < 0.0 || qb >= 0.0 {
        return 0.0; // misses the air, or it lies behind the camera
    }
    let q = -(qb - sqrt(disc));
    return min(q / qa, c / q);
}

// The planet-frame unit direction of the view ray through `ndc_xy` (normalised device
// coordinates: x right, y up, each in [−1, 1]).
fn firmament_aerial_ray_direction(ndc_xy: vec2<f32>) -> vec3<f32> {
    let v = firmament_aerial_view;
    let d_view = normalize(vec3<f32>(ndc_xy * v.camera_shape.zw, -1.0));
    let rotation = mat3x3<f32>(v.view_to_planet[0].xyz, v.view_to_planet[1].xyz, v.view_to_planet[2].xyz);
    return normalize(rotation * d_view);
}

// The transmittance (xyz, per channel) and the scattered light (linear sRGB, cd/m²) of the air in
// front of a surface seen at `ndc_xy`, `distance_m` metres from the camera along the view ray.
struct FirmamentAerialPerspective {
    transmittance: vec3<f32>,
    scattering: vec3<f32>,
}

fn firmament_aerial_perspective(ndc_xy: vec2<f32>, distance_m: f32) -> FirmamentAerialPerspective {
    var out: FirmamentAerialPerspective;
    out.transmittance = vec3<f32>(1.0);
    out.scattering = vec3<f32>(0.0);
    if firmament_aerial_view.center.w > 0.5 {
        return out;
    }
    let through_air = max(distance_m - firmament_aerial_air_entry(firmament_aerial_ray_direction(ndc_xy)), 0.0);
    let screen_uv = vec2<f32>(0.5 * ndc_xy.x + 0.5, 0.5 - 0.5 * ndc_xy.y);
    let coordinates = firmament_aerial_coordinates(screen_uv, through_air, firmament_aerial_view.aerial.x);
    out.transmittance =
        firmament_aerial_transmittance_at(firmament_aerial_transmittance, firmament_aerial_sampler, coordinates);
    let spectral = firmament_aerial_scattering_at(firmament_aerial_scattering, firmament_aerial_sampler, coordinates);
    let v = firmament_aerial_view;
    out.scattering = mat3x3<f32>(v.to_srgb0.xyz, v.to_srgb1.xyz, v.to_srgb2.xyz) * spectral;
    return out;
}

// `color` (linear sRGB radiance, cd/m²) of a surface seen at `ndc_xy`, `distance_m` metres from
// the camera, as the camera sees it through the air: color · T + S.
fn firmament_apply_aerial_perspective(color: vec3<f32>, ndc_xy: vec2<f32>, distance_m: f32) -> vec3<f32> {
    let air = firmament_aerial_perspective(ndc_xy, distance_m);
    return color * air.transmittance + air.scattering;
}
