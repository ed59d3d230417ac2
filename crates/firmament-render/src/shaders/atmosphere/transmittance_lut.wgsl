// atmosphere/transmittance_lut.wgsl — the transmittance LUT: for each (r, mu) of the LUT sphere,
// the optical depth to the top of the atmosphere (Bruneton 2017,
// ComputeTransmittanceToTopAtmosphereBoundary, which stores its exponential instead).
//
// Conventions: as atmosphere/common.wgsl. A compute pass (GL cannot render to Rgba32Float, but
// can store to it): LANES invocations per texel of TRANSMITTANCE_LUT_SIZE, each summing every
// LANES-th point of the integral, TEXELS texels per workgroup (texel index = row · width +
// column); rgb = optical depth per wavelength, a = 0. luts.wgsl's `transmittance_to_top` filters
// the depth and takes its exponential: filtered linearly, the transmittance itself overshoots
// wherever a texel spans more than a fraction of an optical depth (a thick air's slant paths).
// One invocation per texel, 500 points in a row, left a data-centre GPU waiting on one long
// chain per thread.

#import atmosphere/bindings
#import atmosphere/common

// The trapezoid rule with this many intervals: the integrand is smooth, so the error is far
// below the LUT's 0.1 % budget (measured against the f64 reference by the GPU tests).
const STEPS: i32 = 500;

const LANES: u32 = 8u;
const TEXELS: u32 = 32u;

var<workgroup> partial: array<vec3<f32>, LANES * TEXELS>;

@compute @workgroup_size(256)
fn cs_main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) invocation: u32) {
    let size = vec2<u32>(TRANSMITTANCE_LUT_SIZE);
    let lane = invocation % LANES;
    let slot = invocation / LANES;
    let texel_index = group.x * TEXELS + slot;
    let texel = vec2<u32>(texel_index % size.x, texel_index / size.x);
    let inside = texel.y < size.y;
    let uv = (vec2<f32>(texel) + 0.5) / TRANSMITTANCE_LUT_SIZE;
    let r_mu = transmittance_lut_r_mu(uv);
    let r = r_mu.x;
    let mu = r_mu.y;
    let dx = distance_to_top(r, mu) / f32(STEPS);
    var depth = vec3<f32>(0.0);
    for (var i = i32(lane); i <= STEPS; i += i32(LANES)) {
        let t = f32(i) * dx;
        // Altitude along the ray, in the cancellation-free form r_t − R = (t² + 2 r mu t) / (r_t + r) + (r − R).
        let r_t = sqrt(t * t + 2.0 * r * mu * t + r * r);
        let h = (t * t + 2.0 * r * mu * t) / (r_t + r) + (r - atmosphere.lut.x);
        let weight = select(1.0, 0.5, i == 0 || i == STEPS);
        depth += coefficients_at(h).extinction * weight;
    }
    partial[invocation] = depth;
    workgroupBarrier();
    if lane == 0u && inside {
        var total = vec3<f32>(0.0);
        for (var k = 0u; k < LANES; k++) {
            total += partial[slot * LANES + k];
        }
        textureStore(transmittance_out, texel, vec4<f32>(total * dx, 0.0));
    }
}
