// include/firmament_lighting.wgsl — firmament's per-frame lighting for your own shaders: each sun's
// direction and colour at the camera, and the sky's irradiance as spherical harmonics.
//
// Use: put this file before your shader's code (`firmament_render::FIRMAMENT_LIGHTING_WGSL` binds
// the buffer at @group(1) @binding(0); `firmament_render::firmament_lighting_wgsl(group, binding)`
// gives the same text at your own group and binding). Bind the atmosphere pass's
// `sky_lighting_buffer()` there as a uniform buffer; its bind group layout entry is
// `firmament_render::sky_lighting_layout_entry(binding)` (a uniform buffer of 416 bytes seen by
// the vertex, fragment and compute stages). It imports nothing, and every name here starts with
// `firmament_`, `Firmament` or `FIRMAMENT_`.
//
// The values are the camera's, written each frame by the atmosphere pass's `record_luts` (so use
// them in commands encoded after it). Conventions (frames and units):
// - Directions are unit vectors in the world frame (the frame of firmament's camera and suns).
// - Colours are linear sRGB whose Y is the photometric quantity: the sky's radiance in cd/m², an
//   irradiance in lux (lm/m² = cd·sr/m²) — the units of the sky firmament draws, so one exposure
//   serves both. A Lambertian surface of albedo ρ and normal n then has the radiance (cd/m²)
//   ρ/π · firmament_irradiance(n).
// - The sky is the sky-view LUT's radiance (sky and lit ground, all orders, no sun discs) projected
//   onto the real spherical harmonics of bands 0–2 in the world frame (Ramamoorthi & Hanrahan 2001,
//   "An Efficient Representation for Irradiance Environment Maps"): `sky_sh[l(l + 1) + m]` holds
//   L_lm (rgb; w = 0), the basis being Y_00 = 1/(2√π), Y_1m = √(3/4π)·(y, z, x), Y_2m =
//   √(15/4π)·(xy, yz), √(5/16π)·(3z² − 1), √(15/4π)·xz, √(15/16π)·(x² − y²) for m = −l … l.
//   Irradiance from bands 0–2 approximates the exact cosine integral; how closely:
//   docs/ATMOSPHERE.md, "Lighting your own materials".

const FIRMAMENT_MAX_SUNS: u32 = 8u;

struct FirmamentSun {
    direction: vec4<f32>, // xyz unit direction towards the sun, world frame; w = angular radius (rad)
    color: vec4<f32>,     // rgb irradiance at the camera on a surface facing the sun, E·T (lux); w = 0
}

struct FirmamentSkyLighting {
    sun_count: vec4<u32>,                          // x = number of suns; yzw = 0
    suns: array<FirmamentSun, FIRMAMENT_MAX_SUNS>, // the first sun_count.x are set, the rest zero
    sky_sh: array<vec4<f32>, 9>,                   // sky radiance L_lm at l(l + 1) + m (cd/m²)
}

@group(1) @binding(0) var<uniform> firmament_sky_lighting: FirmamentSkyLighting;

// How many suns light the scene (0 to FIRMAMENT_MAX_SUNS).
fn firmament_sun_count() -> u32 {
    return min(firmament_sky_lighting.sun_count.x, FIRMAMENT_MAX_SUNS);
}

// Unit direction towards sun i, world frame.
fn firmament_sun_direction(i: u32) -> vec3<f32> {
    return firmament_sky_lighting.suns[min(i, FIRMAMENT_MAX_SUNS - 1u)].direction.xyz;
}

// Sun i's irradiance at the camera on a surface facing it, after the atmosphere's transmittance
// (E·T, linear sRGB, lux): zero when it is set.
fn firmament_sun_color(i: u32) -> vec3<f32> {
    return firmament_sky_lighting.suns[min(i, FIRMAMENT_MAX_SUNS - 1u)].color.rgb;
}

// The sky's irradiance (lux, linear sRGB) on a surface of unit world normal n: the cosine-weighted
// integral of the sky radiance over n's hemisphere, by Ramamoorthi & Hanrahan 2001, eq. 13
// (c1 = Â₂·√(15/16π), c2 = Â₁·√(3/4π)/2, c3 = 3·Â₂·√(5/16π), c4 = Â₀/(2√π), c5 = Â₂·√(5/16π),
// with Â₀ = π, Â₁ = 2π/3, Â₂ = π/4). Clamped at zero against the bands' ringing.
fn firmament_sky_irradiance(n: vec3<f32>) -> vec3<f32> {
    let c1 = 0.429043;
    let c2 = 0.511664;
    let c3 = 0.743125;
    let c4 = 0.886227;
    let c5 = 0.247708;
    let l = firmament_sky_lighting.sky_sh;
    let e = c1 * l[8].rgb * (n.x * n.x - n.y * n.y)
        + c3 * l[6].rgb * n.z * n.z
        + c4 * l[0].rgb
        - c5 * l[6].rgb
        + 2.0 * c1 * (l[4].rgb * n.x * n.y + l[7].rgb * n.x * n.z + l[5].rgb * n.y * n.z)
        + 2.0 * c2 * (l[3].rgb * n.x + l[1].rgb * n.y + l[2].rgb * n.z);
    return max(e, vec3<f32>(0.0));
}

// Everything firmament's lights give a surface of unit world normal n (lux, linear sRGB): each
// sun's E·T·max(n·l, 0) plus the sky's irradiance. A Lambertian albedo ρ reflects ρ/π times this
// (cd/m²). The suns are not shadowed here: that is your renderer's.
fn firmament_irradiance(n: vec3<f32>) -> vec3<f32> {
    var e = firmament_sky_irradiance(n);
    for (var i = 0u; i < firmament_sun_count(); i++) {
        e += firmament_sun_color(i) * max(dot(n, firmament_sun_direction(i)), 0.0);
    }
    return e;
}
