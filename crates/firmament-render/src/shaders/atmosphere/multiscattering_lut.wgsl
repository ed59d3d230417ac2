// atmosphere/multiscattering_lut.wgsl — the multiple-scattering LUT: Hillaire 2020's Ψ_ms ("A
// Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020, section 5.2),
// solved by fixed-point iteration instead of his geometric series.
//
// Conventions: as atmosphere/common.wgsl. Texel (u, v) ↦ mu_s = unit_to_mu_s(u) (crowded at the
// horizon), h = v · atmosphere height, on the LUT sphere. Ψ(h, mu_s) is the mean, over all
// directions, of the radiance of every order ≥ 1 arriving at the point for a unit sun: the light
// of order ≥ 2 that the point scatters is then σ_s · Ψ (Hillaire's assumption: that light is
// scattered isotropically). Each iteration marches DIRECTIONS_SQRT² rays of STEPS samples from the
// point, with the sources
//   σ_s · phase(ν) · T_sun        (sunlight scattered once, with the true phase) and
//   σ_s · Ψ_prev(h', mu_s')       (light scattered again, from the previous iterate),
// plus the ground at each ray's end lit by the sun and by the previous iterate's sky irradiance
// E_prev. Starting from zero, iterate k holds every order up to k exactly under that assumption;
// Hillaire's 1/(1 − f_ms) series instead assumes every point sees the same light, which is low
// near the ground, where the sky near the horizon is brightest (measured in docs/ATMOSPHERE.md).
//
// `OUTPUT` picks the targets: MULTISCATTERING_OUTPUT_MOMENTS = the moments (Ψ, zz, xx, xz, x, z,
// bands 3 and 4) over MULTISCATTERING_LUT_SIZE; MULTISCATTERING_OUTPUT_GROUND_IRRADIANCE = (E,
// unused…), E the sky irradiance on the ground per unit sun, one row over mu_s (the same u
// mapping), needed by the next iterate's ground. Ψ and E are stored as their logarithms, the
// other moments over Ψ (see `Moments` in luts.wgsl); the iteration starts from targets cleared to
// (LOG_FLOOR, 0, …), i.e. zero.

#import common/fullscreen
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import generated/constants

struct Targets {
    @location(0) psi: vec4<f32>,
    @location(1) zz: vec4<f32>,
    @location(2) xx: vec4<f32>,
    @location(3) xz: vec4<f32>,
    @location(4) x: vec4<f32>,
    @location(5) z: vec4<f32>,
    @location(6) band3: vec4<f32>,
}

// A MULTISCATTERING_OUTPUT_*: which targets the draw writes.
override OUTPUT: u32 = MULTISCATTERING_OUTPUT_MOMENTS;

const DIRECTIONS_SQRT: i32 = 12;
const STEPS: i32 = 20;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

// The previous iterate's `multiple_scattering` (luts.wgsl).
fn previous_multiple_scattering(c: Coefficients, h: f32, up: vec3<f32>, s: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let m = sample_moments(
        previous_multiscattering, previous_multiscattering_zz, previous_multiscattering_xx,
        previous_multiscattering_xz, previous_multiscattering_x, previous_multiscattering_z,
        previous_multiscattering_band3, moments_uv(h, up, s),
    );
    return scatter_moments(c, m, up, s, d);
}

fn previous_irradiance(mu_s: f32) -> vec3<f32> {
    let u = unit_to_texel_coord(mu_s_to_unit(mu_s), MULTISCATTERING_LUT_SIZE.x);
    return decode_log(textureSampleLevel(previous_ground_irradiance, lut_sampler, vec2<f32>(u, 0.5), 0.0).rgb);
}

@fragment
fn fs_main(in: FullscreenVertex) -> Targets {
    let uv = in.clip.xy / MULTISCATTERING_LUT_SIZE;
    let mu_s_h = uv_to_mu_s_h(uv, MULTISCATTERING_LUT_SIZE);
    let mu_s = mu_s_h.x;
    let h = select(mu_s_h.y, 0.0, OUTPUT == MULTISCATTERING_OUTPUT_GROUND_IRRADIANCE);
    let r = atmosphere.lut.x + h;
    let origin = vec3<f32>(0.0, 0.0, r);
    let sun = vec3<f32>(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    let albedo = atmosphere.ground_albedo.rgb;

    var moments: Moments;
    moments.psi = vec3<f32>(0.0);
    moments.zz = vec3<f32>(0.0);
    moments.xx = vec3<f32>(0.0);
    moments.xz = vec3<f32>(0.0);
    moments.x = vec3<f32>(0.0);
    moments.z = vec3<f32>(0.0);
    moments.band3 = vec4<f32>(0.0);
    moments.band4 = vec4<f32>(0.0);
    moments.band4_m4 = 0.0;
    var irradiance = vec3<f32>(0.0);
    for (var i = 0; i < DIRECTIONS_SQRT; i++) {
        for (var j = 0; j < DIRECTIONS_SQRT; j++) {
            // Stratified over the sphere, crowded at the horizon: cos θ = x·|x| for x stratified
            // in [−1, 1], each direction weighted by dcosθ/dx = 2|x| (its weights average 1). At
            // twilight a shadowed point's light comes from a thin band of lit air near the
            // horizon, which uniform strata (cos θ = ±0.125 nearest) stepped over.
            let phi = 2.0 * PI * (f32(i) + 0.5) / f32(DIRECTIONS_SQRT);
            let x = 1.0 - 2.0 * (f32(j) + 0.5) / f32(DIRECTIONS_SQRT);
            let cos_theta = x * abs(x);
            let weight = 2.0 * abs(x);
            let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
            let dir = vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
            let mu = cos_theta;
            let ground = ray_hits_ground(r, mu);
            var ray_length = distance_to_top(r, mu);
            if ground {
                let bottom = atmosphere.lut.x;
                ray_length = max(-r * mu - safe_sqrt(r * r * (mu * mu - 1.0) + bottom * bottom), 0.0);
            }

            let nu = dot(dir, sun);
            var throughput = vec3<f32>(1.0);
            var light = vec3<f32>(0.0);
            for (var k = 0; k < STEPS; k++) {
                // Steps spread quadratically, short near the point: a grazing ray from the
                // ground is ~1000 km long but meets most of its air in the first kilometres.
                let a = f32(k) / f32(STEPS);
                let b = f32(k + 1) / f32(STEPS);
                let dt = (b * b - a * a) * ray_length;
                let t = 0.5 * (a * a + b * b) * ray_length;
                let p = origin + dir * t;
                let r_t = length(p);
                let h_t = r_t - atmosphere.lut.x;
                let mu_s_t = dot(p, sun) / r_t;
                let c = coefficients_at(h_t);
                // Scattered light meets the diffuse extinction (delta-M, common.wgsl).
                let step_transmittance = exp(-c.diffuse_extinction * dt);
                let sun_transmittance = transmittance_to_sun(h_t, mu_s_t, 0.0);
                let again = previous_multiple_scattering(c, h_t, p / r_t, sun, dir);
                let source = scattering_phase(c, nu) * sun_transmittance + again;
                light += throughput * integrate_step(source, c.diffuse_extinction, step_transmittance, dt);
                throughput *= step_transmittance;
            }
            if ground {
                let p = origin + dir * ray_length;
                let mu_ground = dot(normalize(p), sun);
                let direct = transmittance_to_sun(0.0, mu_ground, 0.0) * max(mu_ground, 0.0);
                light += throughput * albedo / PI * (direct + previous_irradiance(mu_ground));
            }
            // The sun is in the x–z plane: x is towards its azimuth.
            light *= weight;
            moments.psi += light;
            moments.zz += light * dir.z * dir.z;
            moments.xx += light * dir.x * dir.x;
            moments.xz += light * dir.x * dir.z;
            moments.x += light * dir.x;
            moments.z += light * dir.z;
            let light_sum = light.r + light.g + light.b;
            let y2 = dir.y * dir.y;
            moments.band3 += light_sum * band3_basis(dir.x, y2, dir.z);
            let b4 = band4_basis(dir.x, y2, dir.z);
            moments.band4 += light_sum * b4.low;
            moments.band4_m4 += light_sum * b4.m4;
            irradiance += light * max(mu, 0.0);
        }
    }
    let n = f32(DIRECTIONS_SQRT * DIRECTIONS_SQRT);
    var out: Targets;
    if OUTPUT == MULTISCATTERING_OUTPUT_GROUND_IRRADIANCE {
        // ∫ L cos⁺ dω over the sphere, by uniform sampling: 4π/n per direction.
        out.psi = vec4<f32>(encode_log(irradiance * (4.0 * PI / n)), 1.0);
        return out;
    }
    let psi = moments.psi / n;
    let psi_sum = psi.r + psi.g + psi.b;
    let none = psi_sum <= 1e-30;
    let band3 = select(moments.band3 / n / psi_sum, vec4<f32>(0.0), none);
    let band4 = select(moments.band4 / n / psi_sum, vec4<f32>(0.0), none);
    let band4_m4 = select(moments.band4_m4 / n / psi_sum, 0.0, none);
    out.psi = vec4<f32>(encode_log(psi), 0.0);
    out.zz = vec4<f32>(moment_ratio(moments.zz / n, psi), band4.x);
    out.xx = vec4<f32>(moment_ratio(moments.xx / n, psi), band4.y);
    out.xz = vec4<f32>(moment_ratio(moments.xz / n, psi), band4.z);
    out.x = vec4<f32>(moment_ratio(moments.x / n, psi), band4.w);
    out.z = vec4<f32>(moment_ratio(moments.z / n, psi), band4_m4);
    out.band3 = band3;
    return out;
}
