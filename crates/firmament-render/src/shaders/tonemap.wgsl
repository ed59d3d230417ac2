// tonemap.wgsl — HDR radiance → display: bloom, night vision, exposure, tone curve, sRGB encoding.
//
// Conventions: the input texture holds linear scene radiance (Rgba16Float; cd/m² for the physical
// sky), read texel for texel (same size as the output). Curves, night vision and exposure are the
// f64 references in `firmament_core::display`, `night_vision` and `auto_exposure`; keep them in
// step. `transfer` (TRANSFER_*): encode applies the sRGB encoding here (the output format does
// not); decode applies its inverse so that an `*Srgb` output's own encoding cancels (display
// encoding "none": the stored bytes are round(255·v)); none leaves values as they are.

#import common/fullscreen
#import generated/constants

struct Tonemap {
    exposure: f32,     // the scene's exposure multiplier (when not metered)
    curve: u32,        // TONE_CURVE_*
    transfer: u32,     // TRANSFER_*
    metered: u32,      // 1: the exposure is the meter's, from `metered_exposure`
    bloom: f32,        // bloom's share of each pixel, [0, 1]
    night_vision: u32, // 1: the eye's night vision
    _pad: vec2<u32>,
}

@group(0) @binding(0) var<uniform> params: Tonemap;
@group(0) @binding(1) var hdr: texture_2d<f32>;
@group(0) @binding(2) var metered_exposure: texture_2d<f32>; // 1 × 1: the multiplier
@group(0) @binding(3) var bloom_image: texture_2d<f32>;     // half size, sampled bilinearly
@group(0) @binding(4) var bloom_sampler: sampler;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

// Stephen Hill's ACES fit (BakingLab). WGSL matrices are column-major: these constructors list
// the published rows as columns, so `v * M` multiplies by the published row-major matrix.
fn aces_fitted(c: vec3<f32>) -> vec3<f32> {
    let input = mat3x3<f32>(
        vec3<f32>(0.59719, 0.35458, 0.04823),
        vec3<f32>(0.07600, 0.90834, 0.01566),
        vec3<f32>(0.02840, 0.13383, 0.83777),
    );
    let output = mat3x3<f32>(
        vec3<f32>(1.60475, -0.53108, -0.07367),
        vec3<f32>(-0.10208, 1.10813, -0.00605),
        vec3<f32>(-0.00327, -0.07276, 1.07602),
    );
    let v = c * input;
    let a = v * (v + 0.0245786) - 0.000090537;
    let b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return (a / b) * output;
}

// Khronos PBR Neutral, as in the specification.
fn pbr_neutral(color: vec3<f32>) -> vec3<f32> {
    let start_compression = 0.8 - 0.04;
    let desaturation = 0.15;
    let x = min(color.r, min(color.g, color.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    var c = color - offset;
    let peak = max(c.r, max(c.g, c.b));
    if peak < start_compression {
        return c;
    }
    let d = 1.0 - start_compression;
    let new_peak = 1.0 - d * d / (peak + d - start_compression);
    c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(c, vec3<f32>(new_peak), g);
}

// AgX (Sobotka), as `firmament_core::display::agx`: inset, log2 over [AGX_MIN_EV, AGX_MAX_EV],
// the base sigmoid in closed form, outset (the inset's inverse), the curve's 2.2 power.
fn agx_sigmoid(x: vec3<f32>) -> vec3<f32> {
    let pivot = 20.0 / 33.0;
    let below = x <= vec3<f32>(pivot);
    let a = select(vec3<f32>(69.86278913545539), vec3<f32>(59.507875), below);
    let b = select(vec3<f32>(13.0 / 4.0), vec3<f32>(3.0), below);
    let d = x - pivot;
    return 0.5 + 2.0 * d * pow(1.0 + a * pow(abs(d), b), -1.0 / b);
}

fn agx(c: vec3<f32>) -> vec3<f32> {
    let inset = mat3x3<f32>(
        vec3<f32>(0.842479062253094, 0.0784335999999992, 0.0792237451477643),
        vec3<f32>(0.0423282422610123, 0.878468636469772, 0.0791661274605434),
        vec3<f32>(0.0423756549057051, 0.0784336, 0.879142973793104),
    );
    let outset = mat3x3<f32>(
        vec3<f32>(1.1968790051, -0.0980208811, -0.0990297441),
        vec3<f32>(-0.0528968518, 1.1519031299, -0.0989611768),
        vec3<f32>(-0.0529716355, -0.0980434501, 1.1510736726),
    );
    let min_ev = -12.47393;
    let max_ev = 4.026069;
    let stops = clamp(log2(max(c * inset, vec3<f32>(1e-30))), vec3<f32>(min_ev), vec3<f32>(max_ev));
    let display = agx_sigmoid((stops - min_ev) / (max_ev - min_ev)) * outset;
    return pow(max(display, vec3<f32>(0.0)), vec3<f32>(2.2));
}

// Night vision (Krawczyk, Myszkowski & Seidel 2005): the rods' luminance (Larson et al. 1997) in
// a bluish grey, mixed with the colour by the rods' share σ = σ_b / (σ_b + Y).
fn night_vision(c: vec3<f32>) -> vec3<f32> {
    let to_xyz = mat3x3<f32>(
        vec3<f32>(0.4124, 0.3576, 0.1805),
        vec3<f32>(0.2126, 0.7152, 0.0722),
        vec3<f32>(0.0193, 0.1192, 0.9505),
    );
    let xyz = c * to_xyz;
    let v = select(0.0, max(xyz.y * (1.33 * (1.0 + (xyz.y + xyz.z) / xyz.x) - 1.68), 0.0), xyz.x > 0.0);
    let half_luminance = 0.4;
    let sigma = half_luminance / (half_luminance + max(xyz.y, 0.0));
    return (1.0 - sigma) * c + sigma * v * vec3<f32>(1.05, 0.97, 1.27);
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let texel = vec2<i32>(floor(in.clip.xy));
    var scene = textureLoad(hdr, texel, 0).rgb;
    if params.bloom > 0.0 {
        let uv = in.clip.xy / vec2<f32>(textureDimensions(hdr));
        let spread = textureSampleLevel(bloom_image, bloom_sampler, uv, 0.0).rgb;
        scene = mix(scene, spread, params.bloom);
    }
    if params.night_vision != 0u {
        scene = night_vision(scene);
    }
    var exposure = params.exposure;
    if params.metered != 0u {
        exposure = textureLoad(metered_exposure, vec2<i32>(0, 0), 0).r;
    }
    let radiance = scene * exposure;
    var c = radiance;
    if params.curve == TONE_CURVE_ACES_FITTED {
        c = aces_fitted(radiance);
    } else if params.curve == TONE_CURVE_PBR_NEUTRAL {
        c = pbr_neutral(radiance);
    } else if params.curve == TONE_CURVE_AGX {
        c = agx(radiance);
    }
    // NaN-safe clamp: max/min with a NaN operand may return either, so test explicitly.
    c = select(clamp(c, vec3<f32>(0.0), vec3<f32>(1.0)), vec3<f32>(0.0), c != c);
    if params.transfer == TRANSFER_ENCODE_SRGB {
        c = linear_to_srgb(c);
    } else if params.transfer == TRANSFER_DECODE_SRGB {
        c = srgb_to_linear(c);
    }
    return vec4<f32>(c, 1.0);
}
