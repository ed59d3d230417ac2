// flare/bindings.wgsl — the lens-flare passes' interface with Rust: the frame uniforms, the
// source and element records (mirrored by `gpu_types/flare.rs`, checked by the layout tests in
// `shaders/mod.rs`), the state the compute passes leave for the later ones (offsets mirrored by
// `passes/flare.rs`, checked by its tests) and every group-0 binding of the four pipelines, in
// one place (mirrored by the `binding` module of `passes/flare.rs`, checked by its tests).
//
// Conventions: NDC x right and y up in [-1, 1]; pixels x right and y down from the top-left
// corner, rectangles [x0, x1) x [y0, y1) packed as x | y << 16; view space has the camera at the
// origin looking down -z; reversed-Z depth (near = 1, nothing drawn = 0) unless `fade.z` says
// standard; the planet frame in metres. Each pipeline's layout holds only the bindings its entry
// points use.

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
    // convention (DEPTH_*, generated/constants); w = the element count.
    fade: vec4<f32>,
}

struct FlareSource {
    // xy = disc centre (NDC), zw = disc radii (NDC x, y).
    disc: vec4<f32>,
    // x = the source's depth in the buffer's convention (the far plane's for a sun), y = its
    // distance (m); z/w = the pixel rectangle its elements cover, corners (x0, y0) and (x1, y1)
    // packed, as f32 bits (bitcast<u32>).
    depth: vec4<f32>,
}

// One element (named for the vertex input it was; `shaders/mod.rs` checks it by this name).
struct InstanceIn {
    // xy = centre (NDC), z = radius (units of half the screen height), w = horizontal stretch.
    placement: vec4<f32>,
    // rgb = colour at full visibility, a = the source's edge fade.
    color: vec4<f32>,
    // x = shape (FLARE_*, generated/constants), yzw = its parameters.
    shape: vec4<f32>,
    // x = source index; y/z = the pixel rectangle it may light, corners (x0, y0) and (x1, y1)
    // packed; w = the radius (uv units) beyond which its light is negligible, as f32 bits.
    source: vec4<u32>,
}

// The element pass's tile side (pixels): a workgroup lights FLARE_TILE x FLARE_TILE pixels.
const FLARE_TILE: u32 = 16u;
// Most elements in a frame (MAX_FLARE_SOURCES x MAX_FLARE_ELEMENTS).
const MAX_INSTANCES: u32 = 4096u;

// Everything `prepare` uploads but the frame uniforms.
struct FlareRecords {
    // The kept sources (MAX_FLARE_SOURCES).
    sources: array<FlareSource, 64>,
    // Their elements that can light the target, `fade.w` of them.
    elements: array<InstanceIn>,
}

// What the occlusion and binning passes leave for the element and composite passes of the same
// frame.
struct FlareState {
    // Each source's visible share, kept between frames for smoothing (MAX_FLARE_SOURCES).
    visibility: array<f32, 64>,
    // The element pass's workgroups (x, y, z; w unused): FLARE_TILE-pixel tiles over `rect`,
    // none when no source is seen.
    dispatch: vec4<u32>,
    // The composite draw (vertex count, instance count, first vertex, first instance): one quad
    // over `rect`, none when no source is seen.
    draw: vec4<u32>,
    // The pixels the seen sources' elements may light: x0, y0 (multiples of FLARE_TILE), x1, y1.
    rect: vec4<u32>,
    // The bins (written by `prepare`): side (pixels, a power of two >= FLARE_TILE), bins across,
    // bins down, words per bin.
    grid: vec4<u32>,
    // Which elements are images, as a bin's bit set (written by `prepare`).
    images: array<u32, 128>,
    // Per bin, row by row, a bit set of the elements that may light it (bit k % 32 of word
    // k / 32 for element k).
    bins: array<atomic<u32>>,
}

// FlareState as the element pass reads it: read-only storage cannot hold atomics, so the bins
// are plain words here (the layouts are the same).
struct FlareStateView {
    visibility: array<f32, 64>,
    dispatch: vec4<u32>,
    draw: vec4<u32>,
    rect: vec4<u32>,
    grid: vec4<u32>,
    images: array<u32, 128>,
    bins: array<u32>,
}

fn corner(packed: u32) -> vec2<u32> {
    return vec2<u32>(packed & 0xffffu, packed >> 16u);
}

// ---- All passes ----
@group(0) @binding(0) var<uniform> frame: FlareFrame;

// ---- The compute passes ----
@group(0) @binding(1) var<storage, read> records: FlareRecords;

// ---- The occlusion and binning passes (flare_occlusion.wgsl) ----
@group(0) @binding(2) var<storage, read_write> state: FlareState;
// A depth view, read as unfilterable float.
@group(0) @binding(3) var depth_buffer: texture_2d<f32>;

// ---- The element pass (flare.wgsl, cs_elements) ----
// The same buffer as `state`, read only.
@group(0) @binding(4) var<storage, read> element_state: FlareStateView;
// One layer per element image.
@group(0) @binding(5) var images: texture_2d_array<f32>;
@group(0) @binding(6) var image_sampler: sampler;
// The elements' light, summed per pixel over `rect` (the flare's own target).
@group(0) @binding(7) var accumulated_out: texture_storage_2d<rgba16float, write>;

// ---- The composite pass (flare.wgsl, vs_composite and fs_composite; also `frame`) ----
// The same texture as `accumulated_out`, read unfiltered.
@group(0) @binding(8) var accumulated: texture_2d<f32>;
