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

#import common/fullscreen
#import atmosphere/bindings
#import atmosphere/view
#import atmosphere/aerial_lookup
#import generated/constants

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
    let color = textureLoad(hdr_in, id.xy, 0);
    let pixel = vec2<f32>(id.xy) + 0.5;
    let aerial = aerial_at(pixel, pixel_ndc(id.xy, size), textureLoad(scene_depth, id.xy, 0).x);
    var out = color;
    if aerial.applies {
        out = vec4<f32>(color.rgb * aerial.transmittance + aerial.scattered, color.a);
    }
    textureStore(hdr_out, id.xy, out);
}
