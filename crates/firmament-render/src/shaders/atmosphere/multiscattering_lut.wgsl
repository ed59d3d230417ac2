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
// A compute pass with one workgroup per texel and one invocation per direction (the directions'
// sums are reduced in workgroup memory): a texel's 144 rays × 20 samples in one thread left a
// data-centre GPU latency-bound (docs/PERFORMANCE.md). Workgroups (x, y) with y < 32 write the
// moments (Ψ, zz, xx, xz, x, z, bands 3 and 4) of texel (x, y) of MULTISCATTERING_LUT_SIZE; row
// y = 32 writes E, the sky irradiance on the ground per unit sun at mu_s(x) (the same u mapping),
// needed by the next iterate's ground. Ψ and E are stored as their logarithms, the other moments
// over Ψ (see `Moments` in luts.wgsl), as Rgba16Float texels packed into `multiscattering_out`
// (MOMENT_TEXELS, GROUND_ROW_START below; passes/atmosphere/multiscattering.rs copies them into the
// textures the next iterate reads). The iteration starts from textures holding (LOG_FLOOR, 0, …),
// i.e. zero.

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts

const DIRECTIONS_SQRT: u32 = 12u;
const DIRECTIONS: u32 = DIRECTIONS_SQRT * DIRECTIONS_SQRT;
const STEPS: i32 = 20;

// The texels of one moment texture in `multiscattering_out`; the ground row follows the seven
// moments (MULTISCATTERING_MOMENTS in passes/atmosphere/luts.rs).
const MOMENT_TEXELS: u32 = 32u * 32u;
const GROUND_ROW_START: u32 = 7u * MOMENT_TEXELS;

var<workgroup> partial: array<vec4<f32>, DIRECTIONS>;

// The sum of `v` over the workgroup's invocations (a tree in workgroup memory). Called by every
// invocation in uniform control flow.
fn sum_directions(v: vec4<f32>, lane: u32) -> vec4<f32> {
    partial[lane] = v;
    workgroupBarrier();
    for (var stride = 128u; stride > 0u; stride = stride >> 1u) {
        if lane < stride && lane + stride < DIRECTIONS {
            partial[lane] += partial[lane + stride];
        }
        workgroupBarrier();
    }
    return partial[0];
}

fn store_texel(index: u32, v: vec4<f32>) {
    multiscattering_out[index] = vec2<u32>(pack2x16float(v.xy), pack2x16float(v.zw));
}

// The previous iterate's ground irradiance row E at mu_s.
fn previous_irradiance(mu_s: f32) -> vec3<f32> {
    let u = unit_to_texel_coord(mu_s_to_unit(mu_s), MULTISCATTERING_LUT_SIZE.x);
    return decode_log(textureSampleLevel(previous_ground_irradiance, lut_sampler, vec2<f32>(u, 0.5), 0.0).rgb);
}

// What one direction brings: its light (weighted for the sphere) and the direction.
struct DirectionLight {
    light: vec3<f32>,
    dir: vec3<f32>,
}

// The light of every order ≥ 1 arriving at radius r along direction `lane` with the sun at mu_s,
// from the previous iterate (`multiple_scattering` reads the moments being built).
fn direction_light(lane: u32, r: f32, sun: vec3<f32>) -> DirectionLight {
    let origin = vec3<f32>(0.0, 0.0, r);
    let albedo = atmosphere.ground_albedo.rgb;
    // Stratified over the sphere, crowded at the horizon: cos θ = x·|x| for x stratified in
    // [−1, 1], each direction weighted by dcosθ/dx = 2|x| (its weights average 1). At twilight a
    // shadowed point's light comes from a thin band of lit air near the horizon, which uniform
    // strata (cos θ = ±0.125 nearest) stepped over.
    let i = lane / DIRECTIONS_SQRT;
    let j = lane % DIRECTIONS_SQRT;
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
        // Steps spread quadratically, short near the point: a grazing ray from the ground is
        // ~1000 km long but meets most of its air in the first kilometres.
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
        let again = multiple_scattering(c, h_t, p / r_t, sun, dir);
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
    var out: DirectionLight;
    out.light = light * weight;
    out.dir = dir;
    return out;
}

@compute @workgroup_size(144)
fn cs_main(@builtin(workgroup_id) texel: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let size = vec2<u32>(MULTISCATTERING_LUT_SIZE);
    let ground_row = texel.y == size.y;
    let uv = (vec2<f32>(texel.xy) + 0.5) / MULTISCATTERING_LUT_SIZE;
    let mu_s_h = uv_to_mu_s_h(uv, MULTISCATTERING_LUT_SIZE);
    let mu_s = mu_s_h.x;
    let h = select(mu_s_h.y, 0.0, ground_row);
    let sun = vec3<f32>(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    let one = direction_light(lane, atmosphere.lut.x + h, sun);
    let light = one.light;
    let dir = one.dir;
    let n = f32(DIRECTIONS);

    if ground_row {
        // ∫ L cos⁺ dω over the sphere, by uniform sampling: 4π/n per direction.
        let irradiance = sum_directions(vec4<f32>(light * max(dir.z, 0.0), 0.0), lane).rgb;
        if lane == 0u {
            store_texel(GROUND_ROW_START + texel.x, vec4<f32>(encode_log(irradiance * (4.0 * PI / n)), 1.0));
        }
        return;
    }

    // The sun is in the x–z plane: x is towards its azimuth.
    let light_sum = light.r + light.g + light.b;
    let y2 = dir.y * dir.y;
    let b3 = light_sum * band3_basis(dir.x, y2, dir.z);
    let b4 = band4_basis(dir.x, y2, dir.z);
    // 27 sums in seven vec4s: the bands' coefficients ride in the spare w components.
    let b4_low = light_sum * b4.low;
    let psi = sum_directions(vec4<f32>(light, b4.m4 * light_sum), lane) / n;
    let zz = sum_directions(vec4<f32>(light * dir.z * dir.z, b3.x), lane) / n;
    let xx = sum_directions(vec4<f32>(light * dir.x * dir.x, b3.y), lane) / n;
    let xz = sum_directions(vec4<f32>(light * dir.x * dir.z, b3.z), lane) / n;
    let x = sum_directions(vec4<f32>(light * dir.x, b3.w), lane) / n;
    let z = sum_directions(vec4<f32>(light * dir.z, b4_low.x), lane) / n;
    let b4_rest = sum_directions(vec4<f32>(b4_low.yzw, 0.0), lane) / n;
    let band3 = vec4<f32>(zz.w, xx.w, xz.w, x.w);
    let band4 = vec4<f32>(z.w, b4_rest.xyz);
    if lane != 0u {
        return;
    }
    let psi_sum = psi.r + psi.g + psi.b;
    let none = psi_sum <= 1e-30;
    let band3_ratio = select(band3 / psi_sum, vec4<f32>(0.0), none);
    let band4_ratio = select(band4 / psi_sum, vec4<f32>(0.0), none);
    let band4_m4 = select(psi.w / psi_sum, 0.0, none);
    let index = texel.y * size.x + texel.x;
    store_texel(index, vec4<f32>(encode_log(psi.rgb), 0.0));
    store_texel(index + MOMENT_TEXELS, vec4<f32>(moment_ratio(zz.rgb, psi.rgb), band4_ratio.x));
    store_texel(index + 2u * MOMENT_TEXELS, vec4<f32>(moment_ratio(xx.rgb, psi.rgb), band4_ratio.y));
    store_texel(index + 3u * MOMENT_TEXELS, vec4<f32>(moment_ratio(xz.rgb, psi.rgb), band4_ratio.z));
    store_texel(index + 4u * MOMENT_TEXELS, vec4<f32>(moment_ratio(x.rgb, psi.rgb), band4_ratio.w));
    store_texel(index + 5u * MOMENT_TEXELS, vec4<f32>(moment_ratio(z.rgb, psi.rgb), band4_m4));
    store_texel(index + 6u * MOMENT_TEXELS, band3_ratio);
}
