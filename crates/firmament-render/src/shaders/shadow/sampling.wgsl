// shadow/sampling.wgsl — sun shadows for the object pass: which cascade, the receiver's biases,
// and percentage-closer soft shadows (Fernando 2005) whose penumbra follows each sun's disc;
// for the light shafts, whether a point of the air sees a sun; and how much of a sun the clouds'
// shadow map lets through (`cloud_visibility`).
//
// Conventions: positions and normals in GL eye space (the object pass's); each cascade maps eye
// space to its light's clip space (x, y in [−1, 1], +y up the map; depth 0 nearest the light,
// growing linearly, `params.y` metres over [0, 1]). The f64 side (cascades, splits, snapping)
// is `firmament_core::classic::shadow`; the Rust mirrors are `gpu_types/shadow.rs`. Bindings:
// group 1 of the object pass (`passes/objects/shadow_maps.rs`).

#import clouds/shadow

const MAX_SHADOW_LIGHTS: u32 = 8u;
const MAX_SHADOW_CASCADES: u32 = 4u;
// Blocker-search and filter taps (a Vogel disc, the same pattern at every pixel so edges stay
// still as the camera moves).
const SHADOW_SEARCH_TAPS: u32 = 16u;
const SHADOW_FILTER_TAPS: u32 = 32u;
// The widest filter radius, texels: penumbrae wider than this are clipped to it.
const SHADOW_MAX_FILTER_TEXELS: f32 = 24.0;

struct ShadowCascade {
    eye_to_clip: mat4x4<f32>,
    // x = texel side (m), y = depth range (m), z = where the cascade ends (view distance, m)
    params: vec4<f32>,
}

struct ShadowFrame {
    // x = casting lights, y = cascades per light, z = map size (texels), w = 1: shadows on
    counts: vec4<u32>,
    // x = depth bias (texels), y = normal bias (texels), z = the highest caster's top above the
    // camera (m, along world up)
    bias: vec4<f32>,
    // The casting slot + 1 of light i at [i / 4][i % 4] (0: it casts nothing).
    slot_of_light: array<vec4<u32>, 2>,
    // tan(angular radius) of the light in slot s at [s / 4][s % 4].
    tan_radius: array<vec4<f32>, 2>,
    // Slot s, cascade c at s * MAX_SHADOW_CASCADES + c.
    cascades: array<ShadowCascade, 32>,
    // The clouds' shadow map for light i (a sun): rows 3i, 3i + 1, 3i + 2 hold the map's axes
    // across the sun's rays and the sun's direction in eye space (xyz); row 3i's w is the sun's
    // square in the map + 1 (0: no cloud shadow). clouds/shadow.wgsl.
    clouds: array<vec4<f32>, 24>,
}

@group(1) @binding(0) var<uniform> shadows: ShadowFrame;
@group(1) @binding(1) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(2) var shadow_compare: sampler_comparison;
// The same maps again as unfilterable floats, for the blocker search's depths: GLSL can neither
// `textureLoad` a depth texture nor pair one texture binding with two samplers.
@group(1) @binding(3) var shadow_depths: texture_2d_array<f32>;
// The clouds' shadow map (clouds/shadow.wgsl), centred on the camera: the eye's origin.
@group(1) @binding(4) var object_cloud_shadows: texture_2d<f32>;

// How much of light `light`'s beam reaches eye-space point p through the clouds: e^(−τ) from the
// clouds' shadow map; 1 for lights without one and beyond its reach.
fn cloud_visibility(light: u32, p: vec3<f32>) -> f32 {
    if light >= MAX_SHADOW_LIGHTS {
        return 1.0;
    }
    let first = shadows.clouds[3u * light];
    if first.w < 0.5 {
        return 1.0;
    }
    let across = vec2<f32>(dot(p, first.xyz), dot(p, shadows.clouds[3u * light + 1u].xyz));
    let t = dot(p, shadows.clouds[3u * light + 2u].xyz);
    return exp(-cloud_shadow_lookup(object_cloud_shadows, across, t, u32(first.w) - 1u));
}

// Tap k of n on a Vogel disc of unit radius.
fn vogel_tap(k: u32, n: u32) -> vec2<f32> {
    let r = sqrt((f32(k) + 0.5) / f32(n));
    let theta = f32(k) * 2.3999632; // the golden angle
    return r * vec2<f32>(cos(theta), sin(theta));
}

// The casting slot of light `light` + 1 (0: it casts nothing, or shadows are off).
fn shadow_slot_plus_one(light: u32) -> u32 {
    if shadows.counts.w == 0u || light >= MAX_SHADOW_LIGHTS {
        return 0u;
    }
    return shadows.slot_of_light[light / 4u][light % 4u];
}

// The cascade that holds view distance `view_distance` (m), or the cascade count beyond the last.
fn shadow_cascade(slot: u32, view_distance: f32) -> u32 {
    let cascade_count = min(shadows.counts.y, MAX_SHADOW_CASCADES);
    var c = 0u;
    while c < cascade_count && view_distance > shadows.cascades[slot * MAX_SHADOW_CASCADES + c].params.z {
        c++;
    }
    return c;
}

// How far along the unit eye-space direction `d` the last cascade of `slot` reaches (m).
fn shadow_reach(slot: u32, d: vec3<f32>) -> f32 {
    let last = min(shadows.counts.y, MAX_SHADOW_CASCADES) - 1u;
    return shadows.cascades[slot * MAX_SHADOW_CASCADES + last].params.z / max(-d.z, 1e-4);
}

// A ray from the eye along unit eye-space direction `d` in one cascade `c` of the light in
// casting slot `slot`: where the cascade ends along it (m), and the ray in the cascade's clip
// space as `origin + t·step` (the light's projection is orthographic: a straight ray stays
// straight, linear in t). For the light shafts (atmosphere/aerial_perspective.wgsl), which walk
// the cascades in order as t grows.
struct AirCascade {
    end: f32,
    layer: i32,
    origin: vec4<f32>,
    step: vec4<f32>,
}

fn air_cascade(slot: u32, c: u32, d: vec3<f32>) -> AirCascade {
    let cascade = shadows.cascades[slot * MAX_SHADOW_CASCADES + c];
    var out: AirCascade;
    out.end = cascade.params.z / max(-d.z, 1e-4);
    out.layer = i32(slot * min(shadows.counts.y, MAX_SHADOW_CASCADES) + c);
    out.origin = cascade.eye_to_clip * vec4<f32>(0.0, 0.0, 0.0, 1.0);
    out.step = cascade.eye_to_clip * vec4<f32>(d, 0.0);
    return out;
}

// Whether the air `t` metres along a ray in `cascade` sees its light (one bilinear comparison,
// no bias: the air is no surface): 1 lit, 0 shadowed, 1 outside the cascade's map.
fn air_visibility(cascade: AirCascade, t: f32) -> f32 {
    let q = cascade.origin + cascade.step * t;
    let uv = vec2<f32>(q.x * 0.5 + 0.5, 0.5 - q.y * 0.5);
    if any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || q.z <= 0.0 || q.z > 1.0 {
        return 1.0;
    }
    return textureSampleCompareLevel(shadow_maps, shadow_compare, uv, cascade.layer, q.z);
}

// How much of light `light`'s disc the point `p` (normal `n`, unit direction to the light `l`,
// eye space) sees past the objects: 1 lit, 0 in the umbra; 1 for lights that cast nothing and
// beyond the last cascade.
fn shadow_visibility(light: u32, p: vec3<f32>, n: vec3<f32>, l: vec3<f32>) -> f32 {
    let slot_plus_one = shadow_slot_plus_one(light);
    if slot_plus_one == 0u {
        return 1.0;
    }
    let slot = slot_plus_one - 1u;
    let cascade_count = min(shadows.counts.y, MAX_SHADOW_CASCADES);
    let c = shadow_cascade(slot, -p.z);
    if c == cascade_count {
        return 1.0;
    }
    let cascade = shadows.cascades[slot * MAX_SHADOW_CASCADES + c];
    let texel = cascade.params.x;
    let range = cascade.params.y;
    // Biases in metres of this cascade: towards the light, and along the normal more where the
    // light grazes (sin of the angle from the normal).
    let cos_l = clamp(dot(n, l), 0.0, 1.0);
    let sin_l = sqrt(1.0 - cos_l * cos_l);
    let moved = p + l * (shadows.bias.x * texel) + n * (shadows.bias.y * texel * sin_l);
    let q = cascade.eye_to_clip * vec4<f32>(moved, 1.0);
    let uv = vec2<f32>(q.x * 0.5 + 0.5, 0.5 - q.y * 0.5);
    let z = q.z;
    if any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || z <= 0.0 || z > 1.0 {
        return 1.0;
    }
    let layer = i32(slot * cascade_count + c);
    let size = f32(shadows.counts.z);
    let tan_a = shadows.tan_radius[slot / 4u][slot % 4u];
    // Blockers: where the map is nearer the light than the receiver, within the widest penumbra
    // a blocker at the light's end of the range could cast.
    let search = clamp(tan_a * z * range / texel, 1.0, SHADOW_MAX_FILTER_TEXELS);
    var blocker_sum = 0.0;
    var blockers = 0.0;
    for (var k = 0u; k < SHADOW_SEARCH_TAPS; k++) {
        let at = uv * size + vogel_tap(k, SHADOW_SEARCH_TAPS) * search;
        let texel_xy = clamp(vec2<i32>(floor(at)), vec2<i32>(0), vec2<i32>(i32(size) - 1));
        let d = textureLoad(shadow_depths, texel_xy, layer, 0).r;
        if d < z {
            blocker_sum += d;
            blockers += 1.0;
        }
    }
    if blockers == 0.0 {
        return 1.0;
    }
    // The penumbra's half-width: the receiver's distance behind the blockers × tan α.
    let behind = (z - blocker_sum / blockers) * range;
    let radius = clamp(tan_a * behind / texel, 1.0, SHADOW_MAX_FILTER_TEXELS);
    var lit = 0.0;
    for (var k = 0u; k < SHADOW_FILTER_TAPS; k++) {
        let at = uv + vogel_tap(k, SHADOW_FILTER_TAPS) * (radius / size);
        lit += textureSampleCompareLevel(shadow_maps, shadow_compare, at, layer, z);
    }
    return lit / f32(SHADOW_FILTER_TAPS);
}
