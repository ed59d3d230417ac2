// camera/exposure_adapt.wgsl — auto-exposure, step 2: the metered luminance from the histogram
// (the darkest and brightest shares dropped, fractions of a bin at the cuts), the EV100 that puts
// it on middle grey, the step towards it, and the exposure multiplier the output pass reads.
// Clears the histogram for the next frame.
//
// Conventions: as camera/bindings.wgsl; firmament_core::auto_exposure is the reference. One
// workgroup of METERING_BINS invocations, one per bin; the sums run in one invocation, in bin
// order, so every run gives the same bits.

#import camera/bindings

var<workgroup> bin_counts: array<f32, METERING_BINS>;
var<workgroup> bin_means: array<f32, METERING_BINS>; // mean log2 luminance of the bin's pixels

@compute @workgroup_size(256)
fn cs_main(@builtin(local_invocation_index) bin: u32) {
    let count = atomicLoad(&histogram.counts[bin]);
    let fractions = atomicLoad(&histogram.fractions[bin]);
    atomicStore(&histogram.counts[bin], 0u);
    atomicStore(&histogram.fractions[bin], 0u);
    let lo = metering.range.x;
    let width = (metering.range.y - lo) / f32(METERING_BINS);
    bin_counts[bin] = f32(count);
    // A step's pixels lie anywhere in it: their mean place is its middle.
    let place = (f32(fractions) / max(f32(count), 1.0) + 0.5) / f32(METERING_FRACTION_STEPS);
    bin_means[bin] = lo + width * (f32(bin) + place);
    workgroupBarrier();
    if bin != 0u {
        return;
    }
    var state = exposure_state;
    var total = 0.0;
    for (var i = 0u; i < METERING_BINS; i += 1u) {
        total += bin_counts[i];
    }
    // Nothing metered: the exposure opens up to its lowest EV100.
    state.target_ev100 = metering.ev.x;
    if total > 0.0 {
        let low = metering.range.z * total;
        let high = (1.0 - metering.range.w) * total;
        var below = 0.0;
        var weight = 0.0;
        var sum = 0.0;
        for (var i = 0u; i < METERING_BINS; i += 1u) {
            let kept = max(min(below + bin_counts[i], high) - max(below, low), 0.0);
            weight += kept;
            sum += kept * bin_means[i];
            below += bin_counts[i];
        }
        state.metered_log2 = sum / max(weight, 1e-30);
        state.target_ev100 = clamp(
            state.metered_log2 + metering.ev.z,
            metering.ev.x,
            metering.ev.y,
        );
    }
    // Within reach the exposure arrives exactly (ev + (target − ev) can miss by a rounding), so
    // a frame that adapts within its step equals one metered afresh (the core's `adapt`).
    let change = state.target_ev100 - state.ev100;
    if state.frames == 0u || metering.step.z > 0.5 || (change >= -metering.step.y && change <= metering.step.x) {
        state.ev100 = state.target_ev100;
    } else {
        state.ev100 += clamp(change, -metering.step.y, metering.step.x);
    }
    state.frames += 1u;
    exposure_state = state;
    // Lagarde & de Rousiers 2014: exposure = 1 / (1.2 · 2^EV100).
    textureStore(exposure_out, vec2<i32>(0, 0), vec4<f32>(1.0 / (1.2 * exp2(state.ev100)), 0.0, 0.0, 1.0));
}
