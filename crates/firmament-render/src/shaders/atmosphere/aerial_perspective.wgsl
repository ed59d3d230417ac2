// atmosphere/aerial_perspective.wgsl — applies the aerial-perspective volume to whatever the depth
// buffer holds: colour · T + S, per channel. Includes: common/fullscreen.wgsl, common/ellipsoid.wgsl,
// atmosphere/common.wgsl, luts.wgsl, view.wgsl.
//
// Without dual-source blending one draw cannot multiply by a colour and add another, so the pass
// draws twice with fixed-function blending (`OUTPUT` picks the draw): first the transmittance,
// blended `dst · src`, then the scattered light, blended `dst + src`. Pixels at the far plane (the
// sky, which already holds its own scattering) are discarded. So is everything when the camera is
// far away (`view.center.w`): f32 distances there are no better than the planet's size.
//
// Units: scattered light as linear sRGB (Y in cd/m²); the per-wavelength transmittance is applied
// to the sRGB channel of the same name (680 nm → R, 550 nm → G, 440 nm → B).

@group(0) @binding(10) var aerial_scattering: texture_2d<f32>;
@group(0) @binding(11) var aerial_transmittance: texture_2d<f32>;
@group(0) @binding(12) var scene_depth: texture_2d<f32>; // a depth view, read as unfilterable float

// 0: the transmittance draw, 1: the scattered-light draw.
override OUTPUT: u32 = 0u;

// Trilinear filtering of the volume's slice atlas: bilinear in each of the two nearest slices
// (u kept half a texel inside its slice so it never bleeds into the next), linear between them.
fn sample_aerial(atlas: texture_2d<f32>, uvw: vec3<f32>) -> vec4<f32> {
    let n = f32(AERIAL_PERSPECTIVE_SIZE.z);
    let width = f32(AERIAL_PERSPECTIVE_SIZE.x);
    let slice = clamp(uvw.z * n - 0.5, 0.0, n - 1.0);
    let k0 = floor(slice);
    let k1 = min(k0 + 1.0, n - 1.0);
    let u = clamp(uvw.x, 0.5 / width, 1.0 - 0.5 / width);
    let a = textureSampleLevel(atlas, lut_sampler, vec2<f32>((u + k0) / n, uvw.y), 0.0);
    let b = textureSampleLevel(atlas, lut_sampler, vec2<f32>((u + k1) / n, uvw.y), 0.0);
    return mix(a, b, slice - k0);
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let depth = textureLoad(scene_depth, vec2<i32>(in.clip.xy), 0).x;
    if depth <= 0.0 || view.center.w > 0.5 {
        discard;
    }
    let ray = view_ray(in.ndc);
    // The point's distance along the ray: its view depth times the length of the ray's
    // direction at depth 1, (ndc · tan half-fov, −1).
    let view_depth = view.aerial.z / (depth + view.aerial.y);
    let t = ray.near + view_depth * length(vec3<f32>(in.ndc * view.camera_shape.zw, -1.0));
    let span = aerial_span(ray);
    let through_air = clamp(t, span.x, span.y) - span.x;
    let n = f32(AERIAL_PERSPECTIVE_SIZE.z);
    let w = sqrt(through_air / view.aerial.x);
    let uvw = vec3<f32>(in.clip.xy / vec2<f32>(textureDimensions(scene_depth)), w);
    // Closer than the first slice's centre: scale its values down linearly with distance.
    let first = 0.5 / n;
    let near_fraction = min(w / first, 1.0);
    let fade = near_fraction * near_fraction;
    if OUTPUT == 0u {
        let transmittance = sample_aerial(aerial_transmittance, uvw).rgb;
        return vec4<f32>(mix(vec3<f32>(1.0), transmittance, fade), 1.0);
    }
    let scattered = sample_aerial(aerial_scattering, uvw).rgb * fade;
    return vec4<f32>(min(to_linear_srgb(scattered), vec3<f32>(HDR_MAX)), 0.0);
}
