// flare_common.wgsl — shared include of the lens-flare passes: the frame's uniforms.
//
// Conventions: NDC x right and y up in [-1, 1]; view space has the camera at the origin looking
// down -z; reversed-Z depth (near = 1, nothing drawn = 0) unless `fade.z` says standard. Mirrors `FlareFrameUniforms` in
// `gpu_types/flare.rs`.

struct FlareFrame {
    // View-space direction -> planet frame rotation.
    view_to_planet: mat4x4<f32>,
    // The camera in the planet frame (m); w = |o/a|^2 - 1 from f64.
    planet_origin: vec4<f32>,
    // Planet semi-axes (m); w = 1 when a planet can hide sources.
    planet_radii: vec4<f32>,
    // x = sources, y = samples per source, z/w = target width and height (pixels).
    counts: vec4<u32>,
    // x/y = tan of half the horizontal/vertical field of view, z = seconds since the last frame
    // (0: a still), w = aspect (width / height).
    view: vec4<f32>,
    // x = fade-in, y = fade-out rate (visibility per second, 0 = at once); z = 1 for a
    // standard-Z depth buffer (near 0, nothing drawn 1), 0 for reversed-Z.
    fade: vec4<f32>,
}
