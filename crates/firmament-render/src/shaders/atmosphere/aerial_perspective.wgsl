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
// volume lookup (aerial_lookup.wgsl) is the one users' shaders get.

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

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let depth = textureLoad(scene_depth, vec2<i32>(in.clip.xy), 0).x;
    // The far plane: 0 (reversed-Z) or 1 (standard), as `view.aerial.w` says.
    let at_far = select(depth <= 0.0, depth >= 1.0, view.aerial.w > 0.5);
    if at_far || view.center.w > 0.5 {
        discard;
    }
    let ray = view_ray(in.ndc);
    // The point's distance along the ray: its view depth times the length of the ray's
    // direction at depth 1, (ndc · tan half-fov, −1).
    let view_depth = view.aerial.z / (depth + view.aerial.y);
    let t = ray.near + view_depth * length(vec3<f32>(in.ndc * view.camera_shape.zw, -1.0));
    let span = aerial_span(ray);
    let through_air = clamp(t, span.x, span.y) - span.x;
    let screen_uv = in.clip.xy / vec2<f32>(textureDimensions(scene_depth));
    let coordinates = firmament_aerial_coordinates(screen_uv, through_air, view.aerial.x);
    if OUTPUT == AERIAL_OUTPUT_TRANSMITTANCE {
        return vec4<f32>(firmament_aerial_transmittance_at(aerial_transmittance, lut_sampler, coordinates), 1.0);
    }
    let scattered = firmament_aerial_scattering_at(aerial_scattering, lut_sampler, coordinates);
    return vec4<f32>(min(to_linear_srgb(scattered), vec3<f32>(HDR_MAX)), 0.0);
}
