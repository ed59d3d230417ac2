// atmosphere/moments_out.wgsl — shared by the multiple-scattering LUT's stages: writing moments
// into `multiscattering_out`, the packed Rgba16Float texels that passes/atmosphere/multiscattering.rs
// copies into the moment textures.
//
// Conventions: as atmosphere/luts.wgsl (`Moments`: Ψ stored as its logarithm, the other moments
// over Ψ). `multiscattering_out` holds the seven moment textures of MULTISCATTERING_LUT_SIZE one
// after another, then the ground row and the sky irradiance (multiscattering.rs).

#import atmosphere/bindings
#import atmosphere/luts

// The texels of one moment texture; the ground row follows the seven, then the sky irradiance
// LUT (IRRADIANCE_LUT_SIZE, the same texels).
const MOMENT_TEXELS: u32 = 32u * 32u;
const GROUND_ROW_START: u32 = 7u * MOMENT_TEXELS;
const IRRADIANCE_START: u32 = GROUND_ROW_START + 32u;

// A texel's moments before they are stored: seven sums over directions (means over the sphere,
// per unit sun) — Ψ, zz, xx, xz, x, z per wavelength in rgb, and bands 3 and 4 (summed over
// wavelengths) in the w components and the seventh: (Ψ, band 4 m = 4), (zz, band 3 m = 0),
// (xx, band 3 m = 1), (xz, band 3 m = 2), (x, band 3 m = 3), (z, band 4 m = 0),
// (band 4 m = 1 … 3, 0). `OrderSums` (bindings.wgsl) keeps them per order.
const ORDER_SUMS: u32 = 7u;

fn store_texel(index: u32, v: vec4<f32>) {
    multiscattering_out[index] = vec2<u32>(pack2x16float(v.xy), pack2x16float(v.zw));
}

// Writes texel `index` of the seven moment textures from its sums.
fn store_moments(index: u32, sums: array<vec4<f32>, ORDER_SUMS>) {
    let psi = sums[0];
    let band3 = vec4<f32>(sums[1].w, sums[2].w, sums[3].w, sums[4].w);
    let band4 = vec4<f32>(sums[5].w, sums[6].xyz);
    let psi_sum = psi.r + psi.g + psi.b;
    let none = psi_sum <= 1e-30;
    let band3_ratio = select(band3 / psi_sum, vec4<f32>(0.0), none);
    let band4_ratio = select(band4 / psi_sum, vec4<f32>(0.0), none);
    let band4_m4 = select(psi.w / psi_sum, 0.0, none);
    store_texel(index, vec4<f32>(encode_log(psi.rgb), 0.0));
    store_texel(index + MOMENT_TEXELS, vec4<f32>(moment_ratio(sums[1].rgb, psi.rgb), band4_ratio.x));
    store_texel(index + 2u * MOMENT_TEXELS, vec4<f32>(moment_ratio(sums[2].rgb, psi.rgb), band4_ratio.y));
    store_texel(index + 3u * MOMENT_TEXELS, vec4<f32>(moment_ratio(sums[3].rgb, psi.rgb), band4_ratio.z));
    store_texel(index + 4u * MOMENT_TEXELS, vec4<f32>(moment_ratio(sums[4].rgb, psi.rgb), band4_ratio.w));
    store_texel(index + 5u * MOMENT_TEXELS, vec4<f32>(moment_ratio(sums[5].rgb, psi.rgb), band4_m4));
    store_texel(index + 6u * MOMENT_TEXELS, band3_ratio);
}
