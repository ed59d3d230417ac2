// atmosphere/multiscattering_lut.wgsl — one order of the multiple-scattering LUT: Hillaire 2020's
// Ψ_ms ("A Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020,
// section 5.2), summed order by order instead of his geometric series.
//
// Conventions: as atmosphere/common.wgsl. Texel (u, v) ↦ mu_s = unit_to_mu_s(u) (crowded at the
// horizon), h = v · atmosphere height, on the LUT sphere. Ψ(h, mu_s) is the mean, over all
// directions, of the radiance of every order ≥ 1 arriving at the point for a unit sun: the light
// of order ≥ 2 that the point scatters is then σ_s · Ψ (Hillaire's assumption: that light is
// scattered isotropically). Ψ_k, the light arriving after exactly k scattering or reflection
// events, is marched along DIRECTIONS rays of STEPS samples from the point, with the sources
//   order 1 (FIRST_ORDER):  σ_s · phase(ν) · T_sun, and the ground at the ray's end lit by the sun;
//   order k > 1:           σ_s · Ψ_{k−1}(h', mu_s') scattered by its moments, and the ground lit by
//                          E_{k−1}, the sky irradiance order k − 1 brings to the ground.
// Order by order rather than by fixed-point iteration (each iterate adding every order again) so
// that order 1, whose light has the true phase's structure, is marched once, later orders need no
// sun, and the orders beyond the last marched one can be summed as a geometric series from the
// last two (multiscattering_sum.wgsl) instead of marched: docs/ATMOSPHERE.md, "Multiple
// scattering". Hillaire's 1/(1 − f_ms) series instead assumes every point sees the same light,
// which is low near the ground, where the sky near the horizon is brightest.
//
// A compute pass with one workgroup per texel and one invocation per direction (the directions'
// sums are reduced in workgroup memory): a texel's rays in one thread left a
// data-centre GPU latency-bound (docs/PERFORMANCE.md). Workgroups (x, y) with y < 32 write order
// k's moments (moments_out.wgsl) of texel (x, y) of MULTISCATTERING_LUT_SIZE and add them, and
// the sky irradiance on a horizontal surface there, to the texel's `OrderSums`; row y = 32 writes E_k, the sky irradiance on the ground per unit sun at
// mu_s(x) (the same u mapping), which the next order's ground reflects. Ψ_k and E_k are stored
// as their logarithms, the other moments over Ψ_k (see `Moments` in luts.wgsl), as Rgba16Float
// texels packed into `multiscattering_out` (passes/atmosphere/multiscattering.rs copies them into
// the textures the next order reads).

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/moments_out

// Whether this pipeline marches order 1 (sunlight scattered once) rather than a later order.
override FIRST_ORDER: bool = true;

// Whether order 1 splits off the phase functions' delta-M forward peaks (a thick air,
// gpu_types::medium::THICK_AIR_DEPTH). A peak as narrow as a thick cloud's or Titan's haze's
// falls between the directions (with the Sun at the zenith the nearest lay 33° from it, 11° now),
// and Venus's subsolar cloud top came out 40 % dark, with the Sun 30° down 10 % bright. Split,
// the directions march the band-limited rest (bands 0–4 with a_l − f, as the later orders
// scatter), and the peak's light, which arrives from the sun's direction alone, is marched along
// that one direction and added to the moments exactly (`peak_light`).
override SPLIT_PEAK: bool = false;

// Directions: ZENITHS strata of the cosine by AZIMUTHS of the half circle towards +y. The light is
// mirror-symmetric about the sun's vertical plane (the x–z plane) and every moment summed is even
// in y (luts.wgsl), so each direction stands for its mirror image too: the 144 directions of
// 12 × 12 over the whole sphere for the price of 72.
const ZENITHS: u32 = 12u;
const AZIMUTHS: u32 = 6u;
const DIRECTIONS: u32 = ZENITHS * AZIMUTHS;
const STEPS: i32 = 20;

var<workgroup> partial: array<vec4<f32>, DIRECTIONS>;

// The sum of `v` over the workgroup's invocations (a tree in workgroup memory). Called by every
// invocation in uniform control flow.
fn sum_directions(v: vec4<f32>, lane: u32) -> vec4<f32> {
    partial[lane] = v;
    workgroupBarrier();
    for (var stride = 64u; stride > 0u; stride = stride >> 1u) {
        if lane < stride && lane + stride < DIRECTIONS {
            partial[lane] += partial[lane + stride];
        }
        workgroupBarrier();
    }
    return partial[0];
}

// The previous order's ground irradiance row E_{k−1} at mu_s.
fn previous_irradiance(mu_s: f32) -> vec3<f32> {
    let u = unit_to_texel_coord(mu_s_to_unit(mu_s), MULTISCATTERING_LUT_SIZE.x);
    return decode_log(textureSampleLevel(previous_ground_irradiance, lut_sampler, vec2<f32>(u, 0.5), 0.0).rgb);
}

// Step k of STEPS along a ray of `ray_length`: its middle (x) and length (y), spread
// quadratically, short near the point: a grazing ray from the ground is ~1000 km long but meets
// most of its air in the first kilometres.
fn quadratic_step(k: i32, ray_length: f32) -> vec2<f32> {
    let a = f32(k) / f32(STEPS);
    let b = f32(k + 1) / f32(STEPS);
    return vec2<f32>(0.5 * (a * a + b * b) * ray_length, (b * b - a * a) * ray_length);
}

// Σ σ_s·p of the terms' delta-M phase functions without their peaks: bands 0–4 with a_l − f, as
// `scatter_moments` in luts.wgsl scatters the later orders' light, each term's clamped at 0.
fn band_limited_scattering_phase(c: Coefficients, nu: f32) -> vec3<f32> {
    let p2 = 0.5 * (3.0 * nu * nu - 1.0);
    let p3 = 0.5 * nu * (5.0 * nu * nu - 3.0);
    let p4 = (35.0 * nu * nu * nu * nu - 30.0 * nu * nu + 3.0) / 8.0;
    var total = vec3<f32>(0.0);
    for (var i = 0u; i < term_count(); i++) {
        let f = atmosphere.terms[i].phase.w;
        let a = atmosphere.terms[i].legendre - f;
        let value = (1.0 - f) + 3.0 * a.x * nu + 5.0 * a.y * p2 + 7.0 * a.z * p3 + 9.0 * a.w * p4;
        total += term_scattering(c, i) * max(value, 0.0) / (4.0 * PI);
    }
    return total;
}

// The radiance of the forward peaks' light arriving at radius r from the sun's direction, per
// unit sun: Σ f_i·σ_i·T_sun along that direction, meeting the diffuse extinction on its way back.
fn peak_light(r: f32, sun: vec3<f32>) -> vec3<f32> {
    if ray_hits_ground(r, sun.z) {
        return vec3<f32>(0.0);
    }
    let ray_length = distance_to_top(r, sun.z);
    let origin = vec3<f32>(0.0, 0.0, r);
    var throughput = vec3<f32>(1.0);
    var light = vec3<f32>(0.0);
    for (var k = 0; k < STEPS; k++) {
        let step = quadratic_step(k, ray_length);
        let dt = step.y;
        let p = origin + sun * step.x;
        let r_t = length(p);
        let h_t = r_t - atmosphere.lut.x;
        let c = coefficients_at(h_t);
        var peak = vec3<f32>(0.0);
        for (var i = 0u; i < term_count(); i++) {
            peak += atmosphere.terms[i].phase.w * term_scattering(c, i);
        }
        let step_transmittance = exp(-c.diffuse_extinction * dt);
        let source = peak * transmittance_to_sun(h_t, dot(p, sun) / r_t, 0.0);
        light += throughput * integrate_step(source, c.diffuse_extinction, step_transmittance, dt);
        throughput *= step_transmittance;
    }
    return light;
}

// The moments of light `peak` arriving from the single direction s alone (as `cs_main` sums
// them over directions: means over the sphere).
fn peak_moments(peak: vec3<f32>, s: vec3<f32>) -> array<vec4<f32>, ORDER_SUMS> {
    let m = peak / (4.0 * PI);
    let m_sum = m.r + m.g + m.b;
    let b3 = m_sum * band3_basis(s.x, s.y * s.y, s.z);
    let b4 = band4_basis(s.x, s.y * s.y, s.z);
    let b4_low = m_sum * b4.low;
    return array<vec4<f32>, ORDER_SUMS>(
        vec4<f32>(m, b4.m4 * m_sum),
        vec4<f32>(m * s.z * s.z, b3.x),
        vec4<f32>(m * s.x * s.x, b3.y),
        vec4<f32>(m * s.x * s.z, b3.z),
        vec4<f32>(m * s.x, b3.w),
        vec4<f32>(m * s.z, b4_low.x),
        vec4<f32>(b4_low.yzw, 0.0),
    );
}

// What one direction brings: its light (weighted for the sphere) and the direction.
struct DirectionLight {
    light: vec3<f32>,
    dir: vec3<f32>,
}

// The light of this pipeline's order arriving at radius r along direction `lane` with the sun
// towards `sun` (`multiple_scattering` reads the previous order's moments).
fn direction_light(lane: u32, r: f32, sun: vec3<f32>) -> DirectionLight {
    let origin = vec3<f32>(0.0, 0.0, r);
    let albedo = atmosphere.ground_albedo.rgb;
    // Stratified over the sphere, crowded at the horizon: cos θ = x·|x| for x stratified in
    // [−1, 1], each direction weighted by dcosθ/dx = 2|x| (its weights average 1). At twilight a
    // shadowed point's light comes from a thin band of lit air near the horizon, which uniform
    // strata (cos θ = ±0.125 nearest) stepped over. Deep in a thick air the light arrives from
    // near the zenith, 33° from the nearest of these: there the poles are crowded too.
    let i = lane / ZENITHS;
    let j = lane % ZENITHS;
    let phi = PI * (f32(i) + 0.5) / f32(AZIMUTHS);
    let x = 1.0 - 2.0 * (f32(j) + 0.5) / f32(ZENITHS);
    var cos_theta = x * abs(x);
    var weight = 2.0 * abs(x);
    if thick_air() {
        // cos θ = sign(x)·(1 − cos πx)/2, weighted by its stratum's width in cos θ over its
        // width in x, sin π|x|·sin(π/ZENITHS)·ZENITHS/2 (the derivative π/2·sin π|x| at the
        // stratum's middle would weigh isotropic light 1.15 % high, and each order again).
        cos_theta = sign(x) * 0.5 * (1.0 - cos(PI * x));
        weight = 0.5 * f32(ZENITHS) * sin(PI / f32(ZENITHS)) * sin(PI * abs(x));
    }
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
        let step = quadratic_step(k, ray_length);
        let dt = step.y;
        let p = origin + dir * step.x;
        let r_t = length(p);
        let h_t = r_t - atmosphere.lut.x;
        let mu_s_t = dot(p, sun) / r_t;
        let c = coefficients_at(h_t);
        // Scattered light meets the diffuse extinction (delta-M, common.wgsl).
        let step_transmittance = exp(-c.diffuse_extinction * dt);
        var source: vec3<f32>;
        if FIRST_ORDER && SPLIT_PEAK {
            source = band_limited_scattering_phase(c, nu) * transmittance_to_sun(h_t, mu_s_t, 0.0);
        } else if FIRST_ORDER {
            source = scattering_phase(c, nu) * transmittance_to_sun(h_t, mu_s_t, 0.0);
        } else {
            source = multiple_scattering(c, h_t, p / r_t, sun, dir);
        }
        light += throughput * integrate_step(source, c.diffuse_extinction, step_transmittance, dt);
        throughput *= step_transmittance;
    }
    if ground {
        let p = origin + dir * ray_length;
        let mu_ground = dot(normalize(p), sun);
        var irradiance: vec3<f32>;
        if FIRST_ORDER {
            irradiance = transmittance_to_sun(0.0, mu_ground, 0.0) * max(mu_ground, 0.0);
        } else {
            irradiance = previous_irradiance(mu_ground);
        }
        light += throughput * albedo / PI * irradiance;
    }
    var out: DirectionLight;
    out.light = light * weight;
    out.dir = dir;
    return out;
}

@compute @workgroup_size(72)
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

    // The sky irradiance on a horizontal surface: ∫ L cos⁺ dω, 4π/n per direction. On the ground
    // row it is E_k, which the next order's ground reflects.
    var irradiance = sum_directions(vec4<f32>(light * max(dir.z, 0.0), 0.0), lane) * (4.0 * PI / n);
    // Order 1's forward peaks, from the sun's direction alone (lane 0 keeps the sums).
    var peak = vec3<f32>(0.0);
    if FIRST_ORDER && SPLIT_PEAK && lane == 0u {
        peak = peak_light(atmosphere.lut.x + h, sun);
        irradiance += vec4<f32>(peak * max(sun.z, 0.0), 0.0);
    }
    if ground_row {
        if lane == 0u {
            store_texel(GROUND_ROW_START + texel.x, vec4<f32>(encode_log(irradiance.rgb), 1.0));
        }
        return;
    }

    // The sun is in the x–z plane: x is towards its azimuth.
    let light_sum = light.r + light.g + light.b;
    let y2 = dir.y * dir.y;
    let b3 = light_sum * band3_basis(dir.x, y2, dir.z);
    let b4 = band4_basis(dir.x, y2, dir.z);
    // 27 sums in seven vec4s (moments_out.wgsl).
    let b4_low = light_sum * b4.low;
    var order = array<vec4<f32>, ORDER_SUMS>(
        sum_directions(vec4<f32>(light, b4.m4 * light_sum), lane) / n,
        sum_directions(vec4<f32>(light * dir.z * dir.z, b3.x), lane) / n,
        sum_directions(vec4<f32>(light * dir.x * dir.x, b3.y), lane) / n,
        sum_directions(vec4<f32>(light * dir.x * dir.z, b3.z), lane) / n,
        sum_directions(vec4<f32>(light * dir.x, b3.w), lane) / n,
        sum_directions(vec4<f32>(light * dir.z, b4_low.x), lane) / n,
        sum_directions(vec4<f32>(b4_low.yzw, 0.0), lane) / n,
    );
    if lane != 0u {
        return;
    }
    if FIRST_ORDER && SPLIT_PEAK {
        let from_peak = peak_moments(peak, sun);
        for (var m = 0u; m < ORDER_SUMS; m++) {
            order[m] += from_peak[m];
        }
    }
    let index = texel.y * size.x + texel.x;
    store_moments(index, order);
    // The orders so far, in f32 (multiscattering_sum.wgsl writes the LUTs from them).
    if FIRST_ORDER {
        multiscattering_orders[index].sum = order;
        multiscattering_orders[index].previous_psi = vec4<f32>(0.0);
        multiscattering_orders[index].irradiance = irradiance;
    } else {
        multiscattering_orders[index].irradiance += irradiance;
        let before = multiscattering_orders[index].last[0].rgb;
        multiscattering_orders[index].previous_psi = vec4<f32>(before, before.r + before.g + before.b);
        for (var m = 0u; m < ORDER_SUMS; m++) {
            multiscattering_orders[index].sum[m] += order[m];
        }
    }
    multiscattering_orders[index].last = order;
    multiscattering_orders[index].last_irradiance = irradiance;
}
