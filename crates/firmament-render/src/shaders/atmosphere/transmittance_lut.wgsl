// atmosphere/transmittance_lut.wgsl — the transmittance LUT: for each (r, mu) of the LUT sphere,
// exp(−optical depth) to the top of the atmosphere (Bruneton 2017,
// ComputeTransmittanceToTopAtmosphereBoundary).
//
// Conventions: as atmosphere/common.wgsl. A compute pass (GL cannot render to Rgba32Float, but
// can store to it): one invocation per texel of TRANSMITTANCE_LUT_SIZE; rgb = transmittance per
// wavelength, a = 1.

#import atmosphere/bindings
#import atmosphere/common

// The trapezoid rule with this many intervals: the integrand is smooth, so the error is far
// below the LUT's 0.1 % budget (measured against the f64 reference by the GPU tests).
const STEPS: i32 = 500;

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = TRANSMITTANCE_LUT_SIZE;
    if f32(id.x) >= size.x || f32(id.y) >= size.y {
        return;
    }
    let uv = (vec2<f32>(id.xy) + 0.5) / size;
    let r_mu = transmittance_lut_r_mu(uv);
    let r = r_mu.x;
    let mu = r_mu.y;
    let dx = distance_to_top(r, mu) / f32(STEPS);
    var depth = vec3<f32>(0.0);
    for (var i = 0; i <= STEPS; i++) {
        let t = f32(i) * dx;
        // Altitude along the ray, in the cancellation-free form r_t − R = (t² + 2 r mu t) / (r_t + r) + (r − R).
        let r_t = sqrt(t * t + 2.0 * r * mu * t + r * r);
        let h = (t * t + 2.0 * r * mu * t) / (r_t + r) + (r - atmosphere.lut.x);
        let weight = select(1.0, 0.5, i == 0 || i == STEPS);
        depth += coefficients_at(h).extinction * weight;
    }
    textureStore(transmittance_out, id.xy, vec4<f32>(exp(-depth * dx), 1.0));
}
