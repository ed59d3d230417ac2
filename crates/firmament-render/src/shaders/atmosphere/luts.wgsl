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

// Hillaire 2020's Ψ_ms at altitude h for a sun at mu_s: radiance of all orders ≥ 2 per unit
// irradiance, to be multiplied by the total scattering coefficient.
fn multiscattering(h: f32, mu_s: f32) -> vec3<f32> {
    return textureSampleLevel(multiscattering_lut, lut_sampler, mu_s_h_to_uv(mu_s, h, MULTISCATTERING_LUT_SIZE), 0.0).rgb;
}

const IRRADIANCE_LUT_SIZE: vec2<f32> = vec2<f32>(64.0, 16.0);

// Sky irradiance on a horizontal surface at altitude h for a unit sun at mu_s (W·m⁻²·nm⁻¹ per
// W·m⁻²·nm⁻¹ of sun).
fn sky_irradiance(h: f32, mu_s: f32) -> vec3<f32> {
    return textureSampleLevel(irradiance_lut, lut_sampler, mu_s_h_to_uv(mu_s, h, IRRADIANCE_LUT_SIZE), 0.0).rgb;
}
