// flare/bindings.wgsl — the lens-flare passes' interface with Rust: the frame uniforms and the
// source records (mirrored by `gpu_types/flare.rs`, checked by the layout tests in
// `shaders/mod.rs`) and every group-0 binding of both pipelines, in one place (mirrored by the
// `binding` module of `passes/flare.rs`, checked by its tests).
//
// Conventions: NDC x right and y up in [-1, 1]; view space has the camera at the origin looking
// down -z; reversed-Z depth (near = 1, nothing drawn = 0) unless `fade.z` says standard; the
// planet frame in metres. Each pipeline's layout holds only the bindings its entry points use.

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
    // x = fade-in, y = fade-out rate (visibility per second, 0 = at once); z = the depth buffer's
    // convention (DEPTH_*, generated/constants).
    fade: vec4<f32>,
}

struct FlareSource {
    // xy = disc centre (NDC), zw = disc radii (NDC x, y).
    disc: vec4<f32>,
    // x = the source's depth in the buffer's convention (the far plane's for a sun), y = its
    // distance (m).
    depth: vec4<f32>,
}

// ---- Both passes ----
@group(0) @binding(0) var<uniform> frame: FlareFrame;

// ---- The occlusion pass (flare_occlusion.wgsl) ----
@group(0) @binding(1) var<storage, read> sources: array<FlareSource>;
// Each source's visible share, kept between frames for smoothing.
@group(0) @binding(2) var<storage, read_write> visibility: array<f32>;
// A depth view, read as unfilterable float.
@group(0) @binding(3) var depth_buffer: texture_2d<f32>;

// ---- The element pass (flare.wgsl) ----
// The same buffer as `visibility`, read only.
@group(0) @binding(4) var<storage, read> element_visibility: array<f32>;
// One layer per element image.
@group(0) @binding(5) var images: texture_2d_array<f32>;
@group(0) @binding(6) var image_sampler: sampler;
