// empirical_sky.wgsl — the seed's own atmosphere model (`atmosphere.model = "seed"`): a port of
// `atmosphere()` of version 3.1 of the GLSL "SSH GLSL Atmospheric Ray light scattering" shader in
// seed document 000_643abe256ac7a513.txt (lines 285–476, uniforms 477–495, CPU side 498–553),
// mirroring firmament_core::atmosphere::empirical::EmpiricalAtmosphere::color step for step (the
// f64 reference the GPU test compares with). In Rust the model is called "empirical".
//
// Conventions
// - Planet frame (the seed's "ellipsoid space"): origin at the planet centre, x and y in the
//   equatorial plane, z along the polar axis; metres. Radii (re, re, rp); the top of the
//   atmosphere is every semi-axis grown by `height` (seed line 513).
// - Colours are unitless linear RGB factors in [0, 1] (the seed's display values); the pass writes
//   them times `params.z` (cd/m² per unit colour) into the HDR target, blended like the seed
//   (ONE, ONE_MINUS_SRC_ALPHA, seed line 252) over what is behind (black when nothing is).
// - Which seed lines each part follows is noted at each part.
//
// Two corrections to the seed, as in the f64 port:
// 1. The view direction is normalised per pixel (the seed interpolates unnormalised corner
//    directions, lines 288 and 544–547), so every length is in metres.
// 2. The density is version 3.0's `exp(d / planet_h) / 2.78` (line 187, kept commented out in
//    3.1 at lines 446–447), `d` the distance from the sample along its geocentric up to the top of
//    the atmosphere; 3.1's "much much faster" one (lines 448–450) grows with altitude.
//
// f32 precision: the CPU computes the camera's position and its ellipsoid terms |o/a|² − 1 in
// f64; a far camera (beyond 10 top radii) starts each ray at its closest approach to the planet
// centre, found from the small offset between pixel and centre on the image plane (as
// atmosphere/sky.wgsl does), and every ray parameter is measured from there.

#import common/fullscreen
#import common/ellipsoid
#import common/view_ray

struct EmpiricalStar {
    position: vec4<f32>,  // centre, planet frame (m); w = radius / √0.75 (m), or −1: no disc
    direction: vec4<f32>, // unit direction to the star (light_dir), planet frame; 0 if none
    color: vec4<f32>,     // colour × visual intensity (light_col), unitless
}

const MAX_EMPIRICAL_STARS: u32 = 8u;

struct EmpiricalSky {
    view_to_planet: mat4x4<f32>, // view-space direction → planet frame rotation
    camera: vec4<f32>,           // camera position, planet frame (m)
    camera_shape: vec4<f32>,     // |o/a|² − 1 against the surface and the top; tan of half fov x, y
    center: vec4<f32>,           // far camera: centre's view x, y over depth; depth (m); 1 if far
    radii: vec4<f32>,            // re, re, rp (m); w = atmosphere height planet_h (m)
    b0: vec4<f32>,               // B0 rgb (unitless); w = overglow (B0.a)
    params: vec4<f32>,           // view_depth (m), unused, luminance (cd/m² per unit colour), unused
    counts: vec4<u32>,           // x = number of stars, y = 1 when the parameters are valid
    stars: array<EmpiricalStar, MAX_EMPIRICAL_STARS>,
}

@group(0) @binding(0) var<uniform> sky: EmpiricalSky;

const EMPIRICAL_STEPS: i32 = 8;              // the seed's `const int n=8`, line 390
const EMPIRICAL_DENSITY_DIVISOR: f32 = 2.78; // lines 187 and 450
const HDR_MAX: f32 = 65504.0;                // largest half float (firmament_render::HDR_MAX)

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

fn top_radii() -> vec3<f32> {
    return sky.radii.xyz + vec3<f32>(sky.radii.w);
}

// The seed's `_view_depth` (lines 310–348) for the ray that starts at parameter `near` of the
// line o + t·d: `hit` false when the ellipsoid is missed or wholly behind the start; else `t0` the
// first hit ahead (the exit when the start is inside) and, when both are ahead (`second`), `t1`
// the second. `t0` and `t1` are line parameters (from `o`, not from the start), so that segment
// lengths are differences of small numbers even when the far camera's `near` is 25 AU.
struct ViewDepth {
    hit: bool,
    second: bool,
    t0: f32,
    t1: f32,
}

fn view_depth(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, c: f32, near: f32) -> ViewDepth {
    var out = ViewDepth(false, false, -1.0, -1.0);
    let hits = ellipsoid_hits(o, d, a, c);
    if hits.x > hits.y || hits.y < near {
        return out;
    }
    out.hit = true;
    if hits.x < near {
        out.t0 = hits.y;
    } else {
        out.second = true;
        out.t0 = hits.x;
        out.t1 = hits.y;
    }
    return out;
}

// Density factor at `p` (correction 2): exp(d / planet_h) / 2.78, `d` the seed's
// `_view_depth(p, normalize(p), planet_R)` l0, −1 when the top is not ahead (or `p` has no up).
fn density(p: vec3<f32>) -> f32 {
    var d = -1.0;
    let r = length(p);
    if r > 0.0 {
        let top = top_radii();
        let up = view_depth(p, p / r, top, ellipsoid_c(p, top), 0.0);
        if up.hit {
            d = up.t0;
        }
    }
    return exp(d / sky.radii.w) / EMPIRICAL_DENSITY_DIVISOR;
}

// The seed's `_star_colide` (lines 351–386) with the 0.75 enlargement of line 422 (folded into
// `position.w` on the CPU): the line from `start` along unit `d` meets the enlarged sphere at or
// ahead of `start`. The discriminant is r² − |f − (f·d)d|², which keeps its precision for a star
// 1 AU away.
fn star_on_ray(start: vec3<f32>, d: vec3<f32>, star: EmpiricalStar) -> bool {
    let r = star.position.w;
    if r <= 0.0 {
        return false;
    }
    let f = start - star.position.xyz;
    let along = dot(f, d);
    let perp = f - along * d;
    let disc = r * r - dot(perp, perp);
    if disc < 0.0 {
        return false;
    }
    return -along + sqrt(disc) >= 0.0;
}

// This pass's view ray (common/view_ray.wgsl), the seed's "correction 1": the direction is
// normalised in the planet frame.
fn view_ray(ndc: vec2<f32>) -> ViewRay {
    let planet = PlanetView(sky.view_to_planet, sky.camera, sky.camera_shape, sky.center);
    return planet_view_ray(ndc, planet, sky.radii.xyz, top_radii());
}

// The seed's `atmosphere()`, lines 388–472: (rgb, alpha).
fn atmosphere(ray: ViewRay) -> vec4<f32> {
    var c = vec4<f32>(0.0);
    let d = ray.direction;
    // Lines 399–406: nothing outside the atmosphere, nothing under ground.
    let atm = view_depth(ray.origin, d, top_radii(), ray.c_top, ray.near);
    if !atm.hit {
        return c;
    }
    let ground = view_depth(ray.origin, d, sky.radii.xyz, ray.c_surface, ray.near);
    if ground.hit && !ground.second {
        return c;
    }
    // Lines 408–437: the visible segment from line parameter `t_start`, `length_m` metres long.
    var t_start = ray.near;
    var length_m: f32;
    if !ground.hit {
        if !atm.second {
            length_m = atm.t0 - ray.near; // inside the atmosphere to its boundary
        } else {
            t_start = atm.t0; // boundary to boundary
            length_m = atm.t1 - atm.t0;
        }
        // Lines 420–426: a star disc on the ray starts the integration with its colour.
        let start = ray.origin + d * t_start;
        for (var i = 0u; i < min(sky.counts.x, MAX_EMPIRICAL_STARS); i++) {
            if star_on_ray(start, d, sky.stars[i]) {
                c = vec4<f32>(c.rgb + sky.stars[i].color.rgb, 1.0);
            }
        }
    } else if atm.t0 < ground.t0 {
        t_start = atm.t0; // from the boundary to the ground
        length_m = ground.t0 - atm.t0;
    } else {
        length_m = ground.t0 - ray.near; // inside the atmosphere to the ground
    }
    // Lines 439–443: step, and the light factor with star 0's direction once per star (the
    // seed's `light_dir[0]`, kept as written); not clamped.
    let end = ray.origin + d * (t_start + length_m);
    let step = d * (length_m / f32(EMPIRICAL_STEPS));
    let dl = length_m / f32(EMPIRICAL_STEPS) / sky.params.x;
    let up_at_end = select(vec3<f32>(0.0), normalize(end), dot(end, end) > 0.0);
    var ll = sky.b0.w;
    for (var i = 0u; i < min(sky.counts.x, MAX_EMPIRICAL_STARS); i++) {
        ll += dot(up_at_end, sky.stars[0].direction.xyz);
    }
    // Lines 444–456: from the far end towards the start; the start itself is not sampled.
    var rgb = c.rgb;
    for (var k = 0; k < EMPIRICAL_STEPS; k++) {
        let p = end - step * f32(k);
        let b = sky.b0.rgb * (density(p) * dl);
        rgb = rgb * (vec3<f32>(1.0) - b) + b * ll;
    }
    // Lines 457–470: negative channels to 0; divide by the largest channel when it exceeds 1.
    rgb = max(rgb, vec3<f32>(0.0));
    let largest = max(rgb.r, max(rgb.g, rgb.b));
    if largest > 1.0 {
        rgb = rgb / largest;
    }
    return vec4<f32>(rgb, c.a);
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    if sky.counts.y == 0u {
        return vec4<f32>(0.0); // invalid parameters: nothing, like the f64 port
    }
    let c = atmosphere(view_ray(in.ndc));
    return vec4<f32>(min(c.rgb * sky.params.z, vec3<f32>(HDR_MAX)), c.a);
}
