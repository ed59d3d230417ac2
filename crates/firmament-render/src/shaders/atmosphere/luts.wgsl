// atmosphere/luts.wgsl — shared: the precomputed tables and their lookups.
//
// Conventions: as atmosphere/common.wgsl; the LUT layouts are documented in
// passes/atmosphere/luts.rs. The transmittance LUT is Rgba32Float (0.1 % accuracy needs more
// than half floats), which is not filterable everywhere, so it is read with textureLoad and
// filtered here.

#import atmosphere/bindings
#import atmosphere/common

fn load_bilinear(lut: texture_2d<f32>, uv: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(lut));
    let texel = clamp(uv * size - 0.5, vec2<f32>(0.0), size - 1.0);
    let i = vec2<i32>(floor(texel));
    let f = texel - floor(texel);
    let j = min(i + 1, vec2<i32>(size) - 1);
    let a = textureLoad(lut, i, 0);
    let b = textureLoad(lut, vec2<i32>(j.x, i.y), 0);
    let c = textureLoad(lut, vec2<i32>(i.x, j.y), 0);
    let d = textureLoad(lut, j, 0);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// Transmittance from radius r along mu to the top of the atmosphere (the ray must not hit the
// ground). The LUT holds the optical depth, which varies linearly along each of its rows in a
// uniform air, so filtering it rather than its exponential stays exact where a texel spans
// several optical depths (a thick air's slant paths).
fn transmittance_to_top(r: f32, mu: f32) -> vec3<f32> {
    return exp(-load_bilinear(transmittance_lut, transmittance_lut_uv(r, mu)).rgb);
}

// Transmittance to a sun of angular radius `alpha` (> 0) seen at altitude h with cosine mu_s:
// zero below the horizon, and the visible fraction of the disc while it sets (Bruneton 2017).
fn transmittance_to_sun(h: f32, mu_s: f32, alpha: f32) -> vec3<f32> {
    let r = atmosphere.lut.x + max(h, 0.0);
    let sin_h = atmosphere.lut.x / r;
    let cos_h = -safe_sqrt(1.0 - sin_h * sin_h);
    let edge = max(sin_h * alpha, 1e-6);
    let visible = smoothstep(-edge, edge, mu_s - cos_h);
    if visible <= 0.0 {
        return vec3<f32>(0.0);
    }
    return transmittance_to_top(r, mu_s) * visible;
}

const MULTISCATTERING_LUT_SIZE: vec2<f32> = vec2<f32>(32.0, 32.0);

// A radiance field at a point known by its moments over directions ω, in the frame x = towards
// the sun's azimuth, z = up (y across; the field is mirror-symmetric in y): psi = mean(L) and the
// second moments mean(L·ωz²), mean(L·ωx²), mean(L·ωx·ωz), the first moments mean(L·ωx),
// mean(L·ωz) — bands 0 to 2 per wavelength — and bands 3 and 4 whole, as their projections
// mean(L·Y) on the real spherical harmonics Y of `band3_basis` and `band4_basis`.
//
// Stored as ln(psi) and the other moments over psi (bands 3 and 4 over psi summed over
// wavelengths: one shape for all three, in the alphas of five textures and a seventh's rgba).
// Below the horizon psi falls by ~e^70 per unit of mu_s: filtered linearly it overshoots the
// twilight sky, and half floats lose it altogether (docs/ATMOSPHERE.md, "The GPU pipeline").
// ln(psi) is nearly linear there, the ratios are bounded (|x/psi| ≤ 1, |band/psi| ≤ 3) and
// smooth.
struct Moments {
    psi: vec3<f32>,
    zz: vec3<f32>,
    xx: vec3<f32>,
    xz: vec3<f32>,
    x: vec3<f32>,
    z: vec3<f32>,
    // Band 3 (m = 0…3) and band 4 (m = 0…3, then m = 4), summed over wavelengths, over the summed psi.
    band3: vec4<f32>,
    band4: vec4<f32>,
    band4_m4: f32,
}

// The light such a field, at a point of local up `up_axis` with the sun towards s, scatters per
// unit length towards the ray direction d, whose components in the field's frame are
// ω = (`toward`, ·, `up`). A phase function with Legendre coefficients a_l scatters
// Σ a_l L_l(ω), L_l the field's degree-l spherical-harmonic band; L_0 = psi, L_1(ω) = 3 ω·m (m the
// first moments), L_2(ω) = 5·(3/2 ωᵀQω − psi/2) (Q the second-moment matrix), and L_3, L_4 the
// stored projections times their harmonics. Each term's phase function enters with its own a_l
// (`legendre`, from firmament_core's Phase::legendre_coefficient) less its forward peak f
// (delta-M, see `Coefficients` in common.wgsl: the peak's light goes straight on, which the
// marches account for by `diffuse_extinction`). Rayleigh's phase (3/16π)(1 + cos²) has
// a_2 = 1/10 and nothing else, so its part is exact: ¾(psi + ωᵀQω); the others are truncated
// after band 4, and each is clamped at 0 where its truncation would go negative. Bands 3 and 4 matter for a dusty sky (Mars, g = 0.63), whole and not
// only about the up and sun axes (docs/ATMOSPHERE.md, "The GPU pipeline"). Isotropic light (m = 0, Q = psi/3 on the diagonal, no bands 3–4) gives
// Σ (1 − f_i)·σ_i·psi.
fn scatter_moments(c: Coefficients, m: Moments, up_axis: vec3<f32>, s: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let up = dot(d, up_axis);
    let toward = toward_sun_cosine(d, up_axis, s);
    let yy = m.psi - m.xx - m.zz;
    let across2 = max(1.0 - up * up - toward * toward, 0.0);
    let second = m.zz * up * up + m.xx * toward * toward + yy * across2 + 2.0 * m.xz * toward * up;
    let band1 = 3.0 * (m.x * toward + m.z * up);
    let band2 = 5.0 * (1.5 * second - 0.5 * m.psi);
    let band3 = dot(m.band3, band3_basis(toward, across2, up));
    let b4 = band4_basis(toward, across2, up);
    let band4 = dot(m.band4, b4.low) + m.band4_m4 * b4.m4;
    var scattered = vec3<f32>(0.0);
    for (var i = 0u; i < term_count(); i++) {
        let sigma = term_scattering(c, i);
        let f = atmosphere.terms[i].phase.w;
        let a = atmosphere.terms[i].legendre - f;
        let higher = (a.z * band3 + a.w * band4) * m.psi;
        scattered += sigma * max((1.0 - f) * m.psi + a.x * band1 + a.y * band2 + higher, vec3<f32>(0.0));
    }
    return scattered;
}

// The field's band-3 harmonics at the unit direction (x, y, z), y given as y²: the real spherical
// harmonics even in y, P_3^m(z)·cos(mφ) for m = 0…3, scaled so each has mean square 1 over the
// sphere (then a band is Σ mean(L·Y)·Y).
fn band3_basis(x: f32, y2: f32, z: f32) -> vec4<f32> {
    let x2 = x * x;
    let z2 = z * z;
    return vec4<f32>(
        2.6457513 * 0.5 * z * (5.0 * z2 - 3.0), // √7
        1.6201852 * x * (5.0 * z2 - 1.0),       // √(21/8)
        5.1234754 * z * (x2 - y2),              // √(105/4)
        2.0916501 * x * (x2 - 3.0 * y2),        // √(35/8)
    );
}

// The same for band 4, m = 0…3 in `low` and m = 4.
struct Band4 {
    low: vec4<f32>,
    m4: f32,
}

fn band4_basis(x: f32, y2: f32, z: f32) -> Band4 {
    let x2 = x * x;
    let z2 = z * z;
    var out: Band4;
    out.low = vec4<f32>(
        3.0 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0) / 8.0, // 3 = √9
        2.3717082 * x * z * (7.0 * z2 - 3.0),           // √(45/8)
        1.6770510 * (x2 - y2) * (7.0 * z2 - 1.0),       // √(45/16)
        6.2749502 * z * x * (x2 - 3.0 * y2),            // √(315/8)
    );
    out.m4 = 2.2185299 * (x2 * x2 - 6.0 * x2 * y2 + y2 * y2); // √(315/64)
    return out;
}

// The cosine between d and the horizontal direction towards the sun s at a point of up `up` (0
// when the sun is at the zenith or nadir, where every azimuth is alike).
fn toward_sun_cosine(d: vec3<f32>, up: vec3<f32>, s: vec3<f32>) -> f32 {
    let horizontal = s - dot(s, up) * up;
    let length2 = dot(horizontal, horizontal);
    return select(0.0, dot(d, horizontal) * inverseSqrt(length2), length2 > 1e-12);
}

// The light of order ≥ 2 scattered per unit length at altitude h, sun s at mu_s, towards the ray
// direction d at a point of up `up`, per unit sun irradiance (multiscattering_lut.wgsl).
fn multiple_scattering(c: Coefficients, h: f32, up: vec3<f32>, s: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let m = sample_moments(multiscattering_lut, moments_uv(h, up, s));
    return scatter_moments(c, m, up, s, d);
}

// Where the moments of a point at altitude h, local up `up`, sun towards s lie in the
// multiple-scattering LUTs.
fn moments_uv(h: f32, up: vec3<f32>, s: vec3<f32>) -> vec2<f32> {
    return mu_s_h_to_uv(dot(up, s), h, MULTISCATTERING_LUT_SIZE);
}

// The smallest psi (or ground irradiance) the LUTs hold: ln of it is what "none" is stored as.
const LOG_FLOOR: f32 = -69.0; // ≈ ln(1e-30)

// The stored form of psi or of the ground irradiance row, and back.
fn encode_log(v: vec3<f32>) -> vec3<f32> {
    return max(log(max(v, vec3<f32>(1e-30))), vec3<f32>(LOG_FLOOR));
}

fn decode_log(v: vec3<f32>) -> vec3<f32> {
    return select(exp(v), vec3<f32>(0.0), v <= vec3<f32>(LOG_FLOOR));
}

// A moment over psi, as stored (0 where psi is none).
fn moment_ratio(moment: vec3<f32>, psi: vec3<f32>) -> vec3<f32> {
    return select(moment / psi, vec3<f32>(0.0), psi <= vec3<f32>(1e-30));
}

// The moments stored in the seven layers of `moments` (in `Moments` order; band 4 in the alphas
// of the five after psi, band 3 in the seventh, ln Ψ's curvature in psi's alpha) at uv, filtered.
fn sample_moments(moments: texture_2d_array<f32>, uv: vec2<f32>) -> Moments {
    let t_psi = textureSampleLevel(moments, lut_sampler, uv, 0, 0.0);
    let t_zz = textureSampleLevel(moments, lut_sampler, uv, 1, 0.0);
    let t_xx = textureSampleLevel(moments, lut_sampler, uv, 2, 0.0);
    let t_xz = textureSampleLevel(moments, lut_sampler, uv, 3, 0.0);
    let t_x = textureSampleLevel(moments, lut_sampler, uv, 4, 0.0);
    let t_z = textureSampleLevel(moments, lut_sampler, uv, 5, 0.0);
    var m: Moments;
    // Between two rows ln Ψ follows a quadratic: the alpha holds its second difference in a thick
    // air (multiscattering_curvature.wgsl), 0 in a thin one.
    let row = fract(max(uv.y * MULTISCATTERING_LUT_SIZE.y - 0.5, 0.0));
    m.psi = decode_log(t_psi.rgb - 0.5 * row * (1.0 - row) * t_psi.a);
    m.zz = t_zz.rgb * m.psi;
    m.xx = t_xx.rgb * m.psi;
    m.xz = t_xz.rgb * m.psi;
    m.x = t_x.rgb * m.psi;
    m.z = t_z.rgb * m.psi;
    m.band3 = textureSampleLevel(moments, lut_sampler, uv, 6, 0.0);
    m.band4 = vec4<f32>(t_zz.a, t_xx.a, t_xz.a, t_x.a);
    m.band4_m4 = t_z.a;
    return m;
}

// The same texels as the multiple-scattering LUT's (multiscattering_sum.wgsl writes both).
const IRRADIANCE_LUT_SIZE: vec2<f32> = MULTISCATTERING_LUT_SIZE;

// Sky irradiance on a horizontal surface at altitude h for a unit sun at mu_s (W·m⁻²·nm⁻¹ per
// W·m⁻²·nm⁻¹ of sun).
fn sky_irradiance(h: f32, mu_s: f32) -> vec3<f32> {
    return decode_log(textureSampleLevel(irradiance_lut, lut_sampler, mu_s_h_to_uv(mu_s, h, IRRADIANCE_LUT_SIZE), 0.0).rgb);
}
