// camera/bindings.wgsl — the camera passes' interface with Rust (auto-exposure and bloom): the
// uniform and storage structs (mirrored by `gpu_types/camera.rs`, checked by the layout tests in
// `shaders/mod.rs`) and every group-0 binding of every camera pipeline (mirrored by the `binding`
// module of `passes/camera/mod.rs`, checked by its tests).
//
// Conventions: the HDR input is linear scene radiance (cd/m² for the physical sky), read texel for
// texel; luminance is Rec. 709's Y; exposure values are EV100. Each pipeline's layout holds only
// the bindings its entry points use.

// The meter's histogram: bins over log2 luminance (firmament_core::auto_exposure's range).
const METERING_BINS: u32 = 256u;
// Each bin also sums where in the bin its pixels fell, in 1/METERING_FRACTION_STEPS of a bin, so
// the mean is not limited by the bin width.
const METERING_FRACTION_STEPS: u32 = 64u;
// How many sun discs the meter leaves out (firmament_core::frame::MAX_SUNS).
const METERING_MAX_DISCS: u32 = 8u;
// The meter's cells: METERING_CELL² pixels each (firmament_core::auto_exposure::METERING_CELL),
// 16 × 16 cells per workgroup, which so covers METERING_TILE² pixels.
const METERING_CELL: u32 = 4u;
const METERING_TILE: u32 = 64u;

struct Metering {
    clip_to_world: mat4x4<f32>,                 // clip → camera-relative world (directions)
    discs: array<vec4<f32>, METERING_MAX_DISCS>, // xyz unit direction to a sun; w = cos of the masked radius
    range: vec4<f32>,                           // log2 luminance (cd/m²) of the lowest and highest bin's edges; dark and bright shares dropped
    ev: vec4<f32>,                              // EV100 bounds (min, max); z = EV100 − log2(L): log2(100 / K) less the compensation; w = a bound on a cell's angular radius (rad)
    step: vec4<f32>,                            // largest rise and fall this frame (EV); z = 1: jump to the target; unused
    counts: vec4<u32>,                          // discs; image width, height (pixels); unused
}

struct Histogram {
    counts: array<atomic<u32>, METERING_BINS>,
    fractions: array<atomic<u32>, METERING_BINS>, // sums of the pixels' places in their bins
}

struct ExposureState {
    ev100: f32,        // the exposure in use
    target_ev100: f32, // what the meter asked for this frame
    metered_log2: f32, // log2 of the metered luminance (cd/m²)
    frames: u32,       // frames metered since the state was made (0: none yet)
}

@group(0) @binding(0) var<uniform> metering: Metering;
@group(0) @binding(1) var hdr_in: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> histogram: Histogram;
@group(0) @binding(3) var<storage, read_write> exposure_state: ExposureState;
@group(0) @binding(4) var exposure_out: texture_storage_2d<r32float, write>;
@group(0) @binding(5) var bloom_in: texture_2d<f32>;
@group(0) @binding(6) var bloom_coarser: texture_2d<f32>;
@group(0) @binding(7) var bloom_sampler: sampler;
@group(0) @binding(8) var bloom_out: texture_storage_2d<rgba16float, write>;
