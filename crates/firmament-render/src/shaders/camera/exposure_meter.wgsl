// camera/exposure_meter.wgsl — auto-exposure, step 1: the histogram of the HDR image's luminance
// in cells of METERING_CELL² pixels, each cell's mean over its pixels off the suns' discs
// (firmament_core::auto_exposure is the reference).
//
// Conventions: as camera/bindings.wgsl. One invocation per cell, one workgroup of 16 × 16 cells per
// METERING_TILE² pixels, binned in workgroup memory, then added to the global histogram (which
// the adapt step reads and clears).

#import camera/bindings

var<workgroup> tile_counts: array<atomic<u32>, METERING_BINS>;
var<workgroup> tile_fractions: array<atomic<u32>, METERING_BINS>;

// The view ray through a point of the image, in pixels from its top left.
fn view_direction(at: vec2<f32>, size: vec2<u32>) -> vec3<f32> {
    let uv = at / vec2<f32>(size);
    let p = metering.clip_to_world * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 1.0, 1.0);
    return normalize(p.xyz / p.w);
}

// Whether the pixel's view ray falls within a masked sun disc.
fn on_a_disc(pixel: vec2<u32>, size: vec2<u32>) -> bool {
    let direction = view_direction(vec2<f32>(pixel) + 0.5, size);
    for (var i = 0u; i < metering.counts.x; i += 1u) {
        let disc = metering.discs[i];
        if dot(direction, disc.xyz) >= disc.w {
            return true;
        }
    }
    return false;
}

// Whether any pixel of the cell at `corner` may fall within a masked disc: its centre within
// the masked radius plus the cell's (`ev.w`, an upper bound) of one.
fn near_a_disc(corner: vec2<u32>, size: vec2<u32>) -> bool {
    let direction = view_direction(vec2<f32>(corner) + 0.5 * f32(METERING_CELL), size);
    for (var i = 0u; i < metering.counts.x; i += 1u) {
        let disc = metering.discs[i];
        let reach = acos(clamp(disc.w, -1.0, 1.0)) + metering.ev.w;
        if dot(direction, disc.xyz) >= cos(min(reach, 3.14159265)) {
            return true;
        }
    }
    return false;
}

// Bins the mean luminance of the cell whose top-left pixel is `corner`.
fn meter_cell(corner: vec2<u32>, size: vec2<u32>) {
    var sum = 0.0;
    var count = 0u;
    let masking = near_a_disc(corner, size);
    for (var dy = 0u; dy < METERING_CELL; dy += 1u) {
        for (var dx = 0u; dx < METERING_CELL; dx += 1u) {
            let pixel = corner + vec2<u32>(dx, dy);
            if pixel.x < size.x && pixel.y < size.y && !(masking && on_a_disc(pixel, size)) {
                let rgb = textureLoad(hdr_in, vec2<i32>(pixel), 0).rgb;
                sum += dot(rgb, vec3<f32>(0.2126, 0.7152, 0.0722));
                count += 1u;
            }
        }
    }
    if count == 0u {
        return;
    }
    let y = sum / f32(count);
    // Below the range (and NaN, for which the test is false): no light to meter.
    if !(y >= exp2(metering.range.x)) {
        return;
    }
    let place = min((log2(y) - metering.range.x) / (metering.range.y - metering.range.x), 1.0)
        * f32(METERING_BINS);
    let bin = min(u32(place), METERING_BINS - 1u);
    let fraction = min(u32((place - f32(bin)) * f32(METERING_FRACTION_STEPS)), METERING_FRACTION_STEPS - 1u);
    atomicAdd(&tile_counts[bin], 1u);
    atomicAdd(&tile_fractions[bin], fraction);
}

// One dimension of 256 (16 × 16 cells, row by row): firmament's limits allow 8 in y.
@compute @workgroup_size(256)
fn cs_main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) index: u32) {
    atomicStore(&tile_counts[index], 0u);
    atomicStore(&tile_fractions[index], 0u);
    workgroupBarrier();
    let cell = vec2<u32>(index % 16u, index / 16u);
    meter_cell(group.xy * METERING_TILE + cell * METERING_CELL, metering.counts.yz);
    workgroupBarrier();
    let count = atomicLoad(&tile_counts[index]);
    if count > 0u {
        atomicAdd(&histogram.counts[index], count);
        atomicAdd(&histogram.fractions[index], atomicLoad(&tile_fractions[index]));
    }
}
