// atmosphere/irradiance_lut.wgsl — sky irradiance on a horizontal surface, per unit sun
// irradiance (the ground's sky light; Bruneton 2017's irradiance texture, computed in one pass
// from single scattering plus Hillaire's multiple-scattering term).
//
// Conventions: as atmosphere/common.wgsl. Texel (u, v) ↦ mu_s = unit_to_mu_s(u) (crowded at the
// horizon), h = v · atmosphere height, on the LUT sphere (IRRADIANCE_LUT_SIZE). For each it
// integrates the sky's radiance over the upper hemisphere (cos θ-weighted), with DIRECTIONS
// directions of STEPS samples. Light reflected by the ground below is left out (second order in
// the albedo). rgb = ln(irradiance / sun irradiance), as `encode_log` stores it: below the horizon
// it falls ~e^70 per unit of mu_s like Ψ, so filtering it linearly would brighten the twilight
// ground (docs/ATMOSPHERE.md, "The GPU pipeline"); a = 1.
//
// A compute pass with one workgroup per texel and one invocation per direction, summed in
// workgroup memory (as multiscattering_lut.wgsl, for the same reason).

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts

// Directions: ZENITHS strata by AZIMUTHS of the half circle towards +y, each standing for its
// mirror image about the sun's vertical plane too (the sky is symmetric about it): the 256
// directions of 16 × 16 over the hemisphere for the price of 128.
const ZENITHS: u32 = 16u;
const AZIMUTHS: u32 = 8u;
const DIRECTIONS: u32 = ZENITHS * AZIMUTHS;
const STEPS: i32 = 16;

var<workgroup> partial: array<vec3<f32>, DIRECTIONS>;

// The cos θ-weighted sky radiance along direction `lane` of the upper hemisphere, at radius r
// with the sun towards `sun` (zero where the ray meets the ground).
fn direction_irradiance(lane: u32, r: f32, sun: vec3<f32>) -> vec3<f32> {
    let origin = vec3<f32>(0.0, 0.0, r);
    let i = lane / ZENITHS;
    let j = lane % ZENITHS;
    // Crowded at the horizon: cos θ = x² for x stratified in (0, 1), so ∫ L cos θ dω =
    // ∫∫ L·x²·2x dx dφ and each direction carries 2x³ of 2π/N. At twilight the ground's
    // light comes from a band of lit sky a few degrees high, which cosine-weighted strata
    // (the lowest 10° up) step over.
    let phi = PI * (f32(i) + 0.5) / f32(AZIMUTHS);
    let x = (f32(j) + 0.5) / f32(ZENITHS);
    let mu = x * x;
    let weight = 2.0 * x * x * x;
    let sin_theta = safe_sqrt(1.0 - mu * mu);
    let dir = vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), mu);
    if ray_hits_ground(r, mu) {
        return vec3<f32>(0.0);
    }
    let ray_length = distance_to_top(r, mu);
    let nu = dot(dir, sun);
    var throughput = vec3<f32>(1.0);
    var radiance = vec3<f32>(0.0);
    for (var k = 0; k < STEPS; k++) {
        // Quadratic steps, short near the point (see multiscattering_lut.wgsl).
        let a = f32(k) / f32(STEPS);
        let b = f32(k + 1) / f32(STEPS);
        let dt = (b * b - a * a) * ray_length;
        let p = origin + dir * (0.5 * (a * a + b * b) * ray_length);
        let r_t = length(p);
        let h_t = r_t - atmosphere.lut.x;
        let c = coefficients_at(h_t);
        let mu_s_t = dot(p, sun) / r_t;
        let direct = transmittance_to_sun(h_t, mu_s_t, 0.0) * scattering_phase(c, nu);
        let source = direct + multiple_scattering(c, h_t, p / r_t, sun, dir);
        // Sky light meets the diffuse extinction (delta-M, common.wgsl).
        let step_transmittance = exp(-c.diffuse_extinction * dt);
        radiance += throughput * integrate_step(source, c.diffuse_extinction, step_transmittance, dt);
        throughput *= step_transmittance;
    }
    return radiance * weight;
}

@compute @workgroup_size(128)
fn cs_main(@builtin(workgroup_id) texel: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let uv = (vec2<f32>(texel.xy) + 0.5) / IRRADIANCE_LUT_SIZE;
    let mu_s_h = uv_to_mu_s_h(uv, IRRADIANCE_LUT_SIZE);
    let mu_s = mu_s_h.x;
    let sun = vec3<f32>(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    partial[lane] = direction_irradiance(lane, atmosphere.lut.x + mu_s_h.y, sun);
    workgroupBarrier();
    for (var stride = DIRECTIONS / 2u; stride > 0u; stride = stride >> 1u) {
        if lane < stride {
            partial[lane] += partial[lane + stride];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        let total = partial[0] * 2.0 * PI / f32(DIRECTIONS);
        textureStore(irradiance_out, texel.xy, vec4<f32>(encode_log(total), 1.0));
    }
}
