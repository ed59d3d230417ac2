// atmosphere/luts.wgsl — shared include: the precomputed tables and their lookups.
// Needs atmosphere/common.wgsl. Conventions as there; the LUT layouts are documented in
// passes/atmosphere/luts.rs.
//
// The transmittance LUT is Rgba32Float (0.1 % accuracy needs more than half floats), which is not
// filterable everywhere, so it is read with textureLoad and filtered here.

@group(0) @binding(2) var transmittance_lut: texture_2d<f32>;
@group(0) @binding(3) var multiscattering_lut: texture_2d<f32>;
@group(0) @binding(5) var lut_sampler: sampler;
@group(0) @binding(7) var irradiance_lut: texture_2d<f32>;
@group(0) @binding(15) var multiscattering_zz_lut: texture_2d<f32>;
@group(0) @binding(17) var multiscattering_xx_lut: texture_2d<f32>;
@group(0) @binding(18) var multiscattering_xz_lut: texture_2d<f32>;
@group(0) @binding(21) var multiscattering_x_lut: texture_2d<f32>;
@group(0) @binding(22) var multiscattering_z_lut: texture_2d<f32>;

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
// ground).
fn transmittance_to_top(r: f32, mu: f32) -> vec3<f32> {
    return load_bilinear(transmittance_lut, transmittance_lut_uv(r, mu)).rgb;
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
// mean(L·ωz), and bands 3 and 4 about the up axis and about the sun (`zonal`).
//
// Stored as ln(psi) and the other moments over psi (`zonal` over psi summed over wavelengths:
// one shape for all three, in the alphas of four textures). Below the horizon psi falls by ~e^70 per unit
// of mu_s (docs/ATMOSPHERE.md): linear filtering between texels that differ 16-fold overshot the
// twilight sky by up to 50 %, and half floats lost it altogether from the sun 10° down. ln(psi)
// is nearly linear there, the ratios are bounded (|x/psi| ≤ 1) and smooth.
struct Moments {
    psi: vec3<f32>,
    zz: vec3<f32>,
    xx: vec3<f32>,
    xz: vec3<f32>,
    x: vec3<f32>,
    z: vec3<f32>,
    // Bands 3 and 4 about the up axis u and about the sun s, summed over wavelengths and over
    // the summed psi: (mean(L·P_3(ω·u)), mean(L·P_4(ω·u)), mean(L·P_3(ω·s)), mean(L·P_4(ω·s))).
    zonal: vec4<f32>,
}

// The light such a field scatters per unit length towards a direction ω with components
// (`toward`, ·, `up`) in that frame, the sun at mu_s. A phase function with Legendre coefficients
// a_l scatters Σ a_l L_l(ω), L_l the field's degree-l spherical-harmonic band; the moments hold
// bands 0 to 2: L_0 = psi, L_1(ω) = 3 ω·m (m the first moments) and L_2(ω) = 5·(3/2 ωᵀQω −
// psi/2), Q the second-moment matrix. Rayleigh's phase (3/16π)(1 + cos²) has a_2 = 1/10 and
// nothing else, so its part is exact: ¾(psi + ωᵀQω). Mie's is truncated after band 4, with the
// medium's own a_l (`atmosphere.mie_legendre`, from firmament_core's
// MiePhase::legendre_coefficient) less its forward peak f (delta-M, see `Coefficients` in
// common.wgsl: the peak's light goes straight on, which the marches account for by
// `diffuse_extinction`). Bands 3 and 4 are known only along two axes — the up axis, for the
// bright band of sky at the horizon, and the sun's, for the aureole a dusty sky (Mars) scatters
// around it — and are taken in their span (`zonal_band`). Isotropic light (m = 0, Q = psi/3 on
// the diagonal) gives (σ_R + (1 − f)·σ_M)·psi.
fn scatter_moments(c: Coefficients, m: Moments, up: f32, toward: f32, mu_s: f32) -> vec3<f32> {
    let yy = m.psi - m.xx - m.zz;
    let across2 = max(1.0 - up * up - toward * toward, 0.0);
    let second = m.zz * up * up + m.xx * toward * toward + yy * across2 + 2.0 * m.xz * toward * up;
    let f = atmosphere.mie_forward_peak.x;
    let a = atmosphere.mie_legendre - f;
    let band1 = 3.0 * (m.x * toward + m.z * up);
    let band2 = 5.0 * (1.5 * second - 0.5 * m.psi);
    let d_sun = toward * safe_sqrt(1.0 - mu_s * mu_s) + up * mu_s;
    let band3 = 7.0 * zonal_band(m.zonal.x, m.zonal.z, legendre_3(mu_s), legendre_3(up), legendre_3(d_sun));
    let band4 = 9.0 * zonal_band(m.zonal.y, m.zonal.w, legendre_4(mu_s), legendre_4(up), legendre_4(d_sun));
    let higher = (a.z * band3 + a.w * band4) * m.psi;
    let mie = max((1.0 - f) * m.psi + a.x * band1 + a.y * band2 + higher, vec3<f32>(0.0));
    return c.rayleigh * 0.75 * (m.psi + second) + c.mie * mie;
}

fn legendre_3(x: f32) -> f32 {
    return 0.5 * x * (5.0 * x * x - 3.0);
}

fn legendre_4(x: f32) -> f32 {
    let x2 = x * x;
    return (35.0 * x2 * x2 - 30.0 * x2 + 3.0) / 8.0;
}

// A band l along ω, over psi and over 2l + 1, from the field's projections b_u = mean(L·P_l(ω·u))
// and b_s = mean(L·P_l(ω·s)) (over psi) onto the zonal harmonics about u and s, whose overlap is
// P_l(u·s): the band taken in their span, c_u·P_l(ω·u) + c_s·P_l(ω·s) with c solving the Gram
// system. Ridge-regularised by 2 %, so the sun at the zenith (u = s) splits the band evenly
// instead of dividing by zero.
fn zonal_band(b_u: f32, b_s: f32, overlap: f32, p_u: f32, p_s: f32) -> f32 {
    let diagonal = 1.02;
    let determinant = diagonal * diagonal - overlap * overlap;
    let c_u = (diagonal * b_u - overlap * b_s) / determinant;
    let c_s = (diagonal * b_s - overlap * b_u) / determinant;
    return c_u * p_u + c_s * p_s;
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
    let m = sample_moments(
        multiscattering_lut, multiscattering_zz_lut, multiscattering_xx_lut,
        multiscattering_xz_lut, multiscattering_x_lut, multiscattering_z_lut,
        mu_s_h_to_uv(dot(up, s), h, MULTISCATTERING_LUT_SIZE),
    );
    return scatter_moments(c, m, dot(d, up), toward_sun_cosine(d, up, s), dot(up, s));
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

// The moments stored in six LUTs (in `Moments` order; the zonal ones in the alphas of the
// first four after psi) at uv, filtered.
fn sample_moments(
    psi: texture_2d<f32>, zz: texture_2d<f32>, xx: texture_2d<f32>,
    xz: texture_2d<f32>, x: texture_2d<f32>, z: texture_2d<f32>, uv: vec2<f32>,
) -> Moments {
    let t_psi = textureSampleLevel(psi, lut_sampler, uv, 0.0);
    let t_zz = textureSampleLevel(zz, lut_sampler, uv, 0.0);
    let t_xx = textureSampleLevel(xx, lut_sampler, uv, 0.0);
    let t_xz = textureSampleLevel(xz, lut_sampler, uv, 0.0);
    let t_x = textureSampleLevel(x, lut_sampler, uv, 0.0);
    let t_z = textureSampleLevel(z, lut_sampler, uv, 0.0);
    var m: Moments;
    m.psi = decode_log(t_psi.rgb);
    m.zz = t_zz.rgb * m.psi;
    m.xx = t_xx.rgb * m.psi;
    m.xz = t_xz.rgb * m.psi;
    m.x = t_x.rgb * m.psi;
    m.z = t_z.rgb * m.psi;
    m.zonal = vec4<f32>(t_zz.a, t_xx.a, t_xz.a, t_x.a);
    return m;
}

const IRRADIANCE_LUT_SIZE: vec2<f32> = vec2<f32>(64.0, 16.0);

// Sky irradiance on a horizontal surface at altitude h for a unit sun at mu_s (W·m⁻²·nm⁻¹ per
// W·m⁻²·nm⁻¹ of sun).
fn sky_irradiance(h: f32, mu_s: f32) -> vec3<f32> {
    return decode_log(textureSampleLevel(irradiance_lut, lut_sampler, mu_s_h_to_uv(mu_s, h, IRRADIANCE_LUT_SIZE), 0.0).rgb);
}
