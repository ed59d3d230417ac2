// atmosphere/multiscattering_sum.wgsl — the multiple-scattering LUTs and the sky irradiance LUT
// from the orders multiscattering_lut.wgsl marched: their sum, and (TAIL) the orders after the
// last as a geometric series.
//
// Conventions: as atmosphere/luts.wgsl. One invocation per texel of MULTISCATTERING_LUT_SIZE
// (index y · 32 + x), reading its `OrderSums` and writing its moments and sky irradiance into
// `multiscattering_out` (moments_out.wgsl), which passes/atmosphere/multiscattering.rs copies into
// the LUTs. Each workgroup also sums Ψ of the last two orders over every texel for the tail (the
// same sums in every workgroup: 1024 texels' two vec4s are cheaper to read again than a pass of
// their own).
//
// The tail: successive orders of light in a medium shrink by a ratio that settles after a few
// orders (the Neumann series of the scattering operator, whose spectral radius it tends to;
// Hillaire's 1/(1 − f_ms) is such a series with one transfer factor for every order). Per texel
// and wavelength the orders after the last one marched, n, add Ψ_n · r / (1 − r), and each
// moment its own last order times the same factor (bands 3 and 4, one shape for all wavelengths,
// take the factor of Ψ summed over them). r is the texel's own Ψ_n / Ψ_{n−1}, but no more than the
// same ratio of Ψ summed over every texel: in the shadow, where light arrives from lit air far
// off, a texel's orders may still grow at n, and its own ratio would sum them as if they never
// stopped. Measured against more orders marched in docs/ATMOSPHERE.md, "Multiple scattering".
// In a thick air (Venus, Titan) the ratio has not settled after the orders marched: there
// multiscattering_ordinates.wgsl and one more order marched add the tail to the sums and this
// runs without TAIL.

#import atmosphere/bindings
#import atmosphere/luts
#import atmosphere/moments_out

// Whether to add the geometric tail (off: the LUTs hold exactly the orders marched, for
// `firmament sky-sample`'s radiance by order).
override TAIL: bool = true;

const SUM_INVOCATIONS: u32 = 256u;

// The largest ratio of successive orders the tail trusts (at most 19 more orders' worth).
const MAX_ORDER_RATIO: f32 = 0.95;

var<workgroup> last_total: array<vec4<f32>, SUM_INVOCATIONS>;
var<workgroup> previous_total: array<vec4<f32>, SUM_INVOCATIONS>;

// Ψ per wavelength (rgb) and summed over them (w).
fn with_sum(psi: vec3<f32>) -> vec4<f32> {
    return vec4<f32>(psi, psi.r + psi.g + psi.b);
}

// r / (1 − r) for the ratio r of successive orders, per wavelength (and w: summed).
fn tail_factor(last: vec4<f32>, before: vec4<f32>, global_ratio: vec4<f32>) -> vec4<f32> {
    let own = last / max(before, vec4<f32>(1e-30));
    let ratio = select(vec4<f32>(0.0), min(own, global_ratio), before > vec4<f32>(1e-30));
    return ratio / (1.0 - ratio);
}

// Ψ of the last order over Ψ of the one before, over every texel (0 without the tail).
fn global_ratio(lane: u32) -> vec4<f32> {
    if !TAIL {
        return vec4<f32>(0.0);
    }
    var last = vec4<f32>(0.0);
    var before = vec4<f32>(0.0);
    for (var index = lane; index < MOMENT_TEXELS; index += SUM_INVOCATIONS) {
        last += with_sum(multiscattering_orders[index].last[0].rgb);
        before += multiscattering_orders[index].previous_psi;
    }
    last_total[lane] = last;
    previous_total[lane] = before;
    workgroupBarrier();
    for (var stride = SUM_INVOCATIONS / 2u; stride > 0u; stride = stride >> 1u) {
        if lane < stride {
            last_total[lane] += last_total[lane + stride];
            previous_total[lane] += previous_total[lane + stride];
        }
        workgroupBarrier();
    }
    // Below 1: the series must converge (a medium that scatters without loss, in the limit).
    let total_before = previous_total[0];
    return select(
        vec4<f32>(0.0),
        min(last_total[0] / max(total_before, vec4<f32>(1e-30)), vec4<f32>(MAX_ORDER_RATIO)),
        total_before > vec4<f32>(1e-30),
    );
}

@compute @workgroup_size(256)
fn cs_main(
    @builtin(local_invocation_index) lane: u32,
    @builtin(global_invocation_id) id: vec3<u32>,
) {
    let ratio = global_ratio(lane);
    let index = id.x;
    if index >= MOMENT_TEXELS {
        return;
    }
    let orders = multiscattering_orders[index];
    let factor = tail_factor(with_sum(orders.last[0].rgb), orders.previous_psi, ratio);
    // Per wavelength in rgb; the bands (w, and the seventh sum) by the summed factor.
    var sums = orders.sum;
    for (var m = 0u; m < ORDER_SUMS - 1u; m++) {
        sums[m] += orders.last[m] * factor;
    }
    sums[ORDER_SUMS - 1u] += orders.last[ORDER_SUMS - 1u] * factor.w;
    store_moments(index, sums);
    // The sky irradiance LUT: the irradiance of every order, its tail by Ψ's factor.
    let irradiance = orders.irradiance.rgb + orders.last_irradiance.rgb * factor.rgb;
    store_texel(IRRADIANCE_START + index, vec4<f32>(encode_log(irradiance), 1.0));
}
