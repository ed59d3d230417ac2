// atmosphere/aerial_perspective.wgsl — applies the aerial-perspective volume to whatever the depth
// buffer holds: colour · T + S, per channel.
//
// Conventions: as atmosphere/view.wgsl. Scattered light as linear sRGB (Y in cd/m²); the
// per-wavelength transmittance is applied to the sRGB channel of the same name (680 nm → R,
// 550 nm → G, 440 nm → B).
//
// Without dual-source blending one draw cannot multiply by a colour and add another, so the pass
// draws twice with fixed-function blending (`OUTPUT` picks the draw): first the transmittance,
// blended `dst · src`, then the scattered light, blended `dst + src`. Pixels at the far plane (the
// sky, which already holds its own scattering) are discarded. So is everything when the camera is
// far away (`view.center.w`): f32 distances there are no better than the planet's size. The
// volume lookup (aerial_lookup.wgsl) is the one users' shaders get. On the renderer's own targets
// `cs_main` does both in one compute pass instead (data-centre GPUs run fragment work on a few
// SMs; docs/PERFORMANCE.md).

//
// Light shafts (`cs_shafts`, the renderer's own targets with sun shadows): the single scattering
// the objects' shadows take away is marched along each pixel's ray, as far as its geometry or the
// shadow maps reach, and subtracted from the volume's light (and from the sky's, behind which no
// geometry stands). Multiple scattering is left as the volume has it: a shadow a few metres
// across hides the sun, not the sky. The f64 reference with occluders makes the same split
// (`Reference::with_occluders`).

#import common/fullscreen
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/view
#import atmosphere/eclipse
#import atmosphere/aerial_lookup
#import shadow/sampling
#import generated/constants

// Steps of the shafts' march, each offset by the pixel's own fraction of a step (interleaved
// gradient noise, Jimenez 2014) so the steps of neighbouring pixels interleave.
const SHAFT_STEPS: u32 = 48u;

// An AERIAL_OUTPUT_*: the transmittance draw or the scattered-light draw.
override OUTPUT: u32 = AERIAL_OUTPUT_TRANSMITTANCE;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

// The aerial perspective of the pixel at `pixel` (framebuffer coordinates, pixel centres at .5)
// and `ndc` with scene depth `depth`: the transmittance and the scattered light (linear sRGB) to
// lay over it, and whether any applies (not at the far plane, nor from far away).
struct Aerial {
    applies: bool,
    transmittance: vec3<f32>,
    scattered: vec3<f32>,
}

fn aerial_at(pixel: vec2<f32>, ndc: vec2<f32>, depth: f32) -> Aerial {
    var out: Aerial;
    out.applies = !(at_far_plane(depth) || view.center.w > 0.5);
    if !out.applies {
        return out;
    }
    let ray = view_ray(ndc);
    // The point's distance along the ray: its view depth times the length of the ray's
    // direction at depth 1, (ndc · tan half-fov, −1).
    let view_depth = view.aerial.z / (depth + view.aerial.y);
    let t = ray.near + view_depth * length(vec3<f32>(ndc * view.camera_shape.zw, -1.0));
    let span = aerial_span(ray);
    let through_air = clamp(t, span.x, span.y) - span.x;
    let screen_uv = pixel / vec2<f32>(textureDimensions(scene_depth));
    let coordinates = firmament_aerial_coordinates(screen_uv, through_air, view.aerial.x);
    out.transmittance = firmament_aerial_transmittance_at(aerial_transmittance, lut_sampler, coordinates);
    let scattered = firmament_aerial_scattering_at(aerial_scattering, lut_sampler, coordinates);
    out.scattered = min(to_linear_srgb(scattered), vec3<f32>(HDR_MAX));
    return out;
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let depth = textureLoad(scene_depth, vec2<i32>(in.clip.xy), 0).x;
    let aerial = aerial_at(in.clip.xy, in.ndc, depth);
    if !aerial.applies {
        discard;
    }
    if OUTPUT == AERIAL_OUTPUT_TRANSMITTANCE {
        return vec4<f32>(aerial.transmittance, 1.0);
    }
    return vec4<f32>(aerial.scattered, 0.0);
}

// The compute form for the renderer's own targets: one pass, colour · T + S from `hdr_in` into
// `hdr_out` (every pixel: the rest copied), which the caller copies back over `hdr_in`.
@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(scene_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(hdr_out, id.xy, applied(id.xy, size));
}

// The pixel `id` of a `size`-pixel target with the aerial perspective applied.
fn applied(id: vec2<u32>, size: vec2<u32>) -> vec4<f32> {
    let color = textureLoad(hdr_in, id, 0);
    let pixel = vec2<f32>(id) + 0.5;
    let aerial = aerial_at(pixel, pixel_ndc(id, size), textureLoad(scene_depth, id, 0).x);
    if aerial.applies {
        return vec4<f32>(color.rgb * aerial.transmittance + aerial.scattered, color.a);
    }
    return color;
}

// `cs_main` with the light shafts: the single scattering in the objects' shadows taken away.
@compute @workgroup_size(8, 8)
fn cs_shafts(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(scene_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    var out = applied(id.xy, size);
    let ndc = pixel_ndc(id.xy, size);
    let depth = textureLoad(scene_depth, id.xy, 0).x;
    // Where the pixel's geometry stands along its ray (none at the far plane), as `aerial_at`.
    var t_end = 3.0e38;
    if !at_far_plane(depth) {
        let view_depth = view.aerial.z / (depth + view.aerial.y);
        t_end = view_depth * length(vec3<f32>(ndc * view.camera_shape.zw, -1.0));
    }
    let lost = to_linear_srgb(shadowed_single_scattering(vec2<f32>(id.xy) + 0.5, ndc, t_end));
    out = vec4<f32>(max(out.rgb - lost, vec3<f32>(0.0)), out.a);
    textureStore(hdr_out, id.xy, out);
}

// The sunlight scattered once towards the camera from the air the objects shadow, along the ray
// of pixel `pixel` (at `ndc`) up to `t_end` metres (spectral radiance): for each casting sun,
// σ_s·p(ν)·E·T_sun·T_view·(1 − visibility), marched in `SHAFT_STEPS` steps as far as its maps
// reach. Near the camera (a few hundred metres), so the air's height is the camera's plus the
// ray's rise over a sphere of the bottom radius, and each point sees the sun at the camera's
// angle.
fn shadowed_single_scattering(pixel: vec2<f32>, ndc: vec2<f32>, t_end: f32) -> vec3<f32> {
    if view.center.w > 0.5 {
        return vec3<f32>(0.0); // far away: no shadow maps reach the air it sees
    }
    let eye = normalize(vec3<f32>(ndc * view.camera_shape.zw, -1.0));
    let d = view_ray(ndc).direction;
    let up = view.local_up.xyz;
    let rise = dot(d, up);
    let radius = atmosphere.lut.x;
    let jitter = fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
    var lost = vec3<f32>(0.0);
    for (var i = 0u; i < view.sun_count.x; i++) {
        let slot_plus_one = shadow_slot_plus_one(i);
        if slot_plus_one == 0u {
            continue;
        }
        let slot = slot_plus_one - 1u;
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        let nu = dot(d, s);
        let mu_s = dot(up, s);
        // The shadows reach a few kilometres: the eclipse there is the camera's.
        let irradiance = sun_irradiance_at(view.camera.xyz, i);
        var span = min(t_end, shadow_reach(slot, eye));
        if rise > 0.0 && mu_s > 0.0 {
            // Above the highest caster the air sees every sun above the horizon.
            span = min(span, max(shadows.bias.z, 0.0) / rise);
        }
        let dt = span / f32(SHAFT_STEPS);
        let cascades = min(shadows.counts.y, MAX_SHADOW_CASCADES);
        var c = 0u;
        var cascade = air_cascade(slot, 0u, eye);
        var transmittance = vec3<f32>(1.0);
        for (var k = 0u; k < SHAFT_STEPS; k++) {
            let t = (f32(k) + jitter) * dt;
            // t only grows: step on to the next cascade when this one ends.
            while c < cascades && t > cascade.end {
                c++;
                if c < cascades {
                    cascade = air_cascade(slot, c, eye);
                }
            }
            if c >= cascades {
                break;
            }
            let h = view.camera.w + t * rise + 0.5 * t * t * (1.0 - rise * rise) / radius;
            let air = coefficients_at(h);
            let shade = 1.0 - air_visibility(cascade, t);
            if shade > 0.0 {
                let sunlight = irradiance * transmittance_to_sun(h, mu_s, abs(sun.direction.w));
                lost += shade * transmittance * scattering_phase(air, nu) * sunlight * dt;
            }
            transmittance *= exp(-air.extinction * dt);
        }
    }
    return lost;
}
