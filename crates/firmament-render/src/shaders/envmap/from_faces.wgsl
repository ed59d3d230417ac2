// envmap/from_faces.wgsl — the environment-map pass's lookups: the six faces' atlas sampled as a cube layer's texel or an equirectangular pixel, and a texel's disc pieces.
//
// Conventions:
// - `faces` is an atlas of the six face cameras' HDR images (3 × 2 faces: face k at columns
//   (k mod 3)·size…, rows (k / 3)·size…), as the cameras drew them: each is the OpenGL face
//   mirrored left to right, so face texel (i, j) is the atlas texel `size − 1 − i` across, row `j`.
// - Directions are world ENU (x east, y north, z up); the faces follow OpenGL's cube-map
//   convention in the Y-up frame (x east, y up, z south), as `firmament_core::envmap::projection`
//   (`cube_position`); the equirectangular layout is its `equirect_direction`: azimuth
//   2π(x/width − 1/4) clockwise from north, zenith angle π·y/height. The bilinear lookup is
//   `envmap/resample.rs`'s (between the four texel centres around the point, clamped to the
//   face's outer texel centres), here in f32.
// - Texel coordinates run from the output's top-left corner, texel (i, j) centred at
//   (i + ½, j + ½).
// - Radiance is linear RGB in the map's units (cd/m² for the physical atmosphere). A disc piece
//   holds its irradiance over its texel's solid angle (rounded to f32 on the CPU, listed in the
//   CPU's order); a texel adds its run of pieces onto its sky one by one, as the CPU path does.

struct EnvmapParams {
    face: u32,   // the cube layer written (0 for an equirectangular map)
    size: u32,   // the faces' side, texels
    width: u32,  // the output's width, texels
    height: u32, // the output's height, texels
}

// A texel that disc pieces fall in: where, and its run `first` … `first + count − 1` of pieces.
struct DiscTexel {
    x: u32,
    y: u32,
    face: u32,
    first: u32,
    count: u32,
}

@group(0) @binding(0) var<uniform> params: EnvmapParams;
@group(0) @binding(1) var faces: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> pieces: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> disc_texels: array<DiscTexel>;

const ENVMAP_PI: f32 = 3.14159265358979;
const ENVMAP_TAU: f32 = 6.28318530717959;

// Face `face`'s texel (i, j) (OpenGL's orientation), RGBA.
fn face_texel(face: u32, i: u32, j: u32) -> vec4<f32> {
    let size = params.size;
    let corner = vec2<u32>((face % 3u) * size, (face / 3u) * size);
    return textureLoad(faces, corner + vec2<u32>(size - 1u - i, j), 0);
}

// The radiance along unit ENU `d`: bilinear between the four texel centres around it on its face.
fn cube_radiance(d: vec3<f32>) -> vec3<f32> {
    let r = vec3<f32>(d.x, d.z, -d.y); // the Y-up frame
    let a = abs(r);
    var face = 0u;
    var st = vec2<f32>(0.0);
    var ma = 1.0;
    if a.x >= a.y && a.x >= a.z {
        ma = a.x;
        if r.x >= 0.0 {
            face = 0u;
            st = vec2<f32>(-r.z, -r.y);
        } else {
            face = 1u;
            st = vec2<f32>(r.z, -r.y);
        }
    } else if a.y >= a.z {
        ma = a.y;
        if r.y >= 0.0 {
            face = 2u;
            st = vec2<f32>(r.x, r.z);
        } else {
            face = 3u;
            st = vec2<f32>(r.x, -r.z);
        }
    } else {
        ma = a.z;
        if r.z >= 0.0 {
            face = 4u;
            st = vec2<f32>(r.x, -r.y);
        } else {
            face = 5u;
            st = vec2<f32>(-r.x, -r.y);
        }
    }
    let s = f32(params.size);
    let p = (st / ma + 1.0) * 0.5 * s;
    let xy = clamp(p - 0.5, vec2<f32>(0.0), vec2<f32>(s - 1.0));
    let lo = vec2<u32>(floor(xy));
    let hi = min(lo + 1u, vec2<u32>(params.size - 1u));
    let f = xy - floor(xy);
    let c00 = face_texel(face, lo.x, lo.y).rgb;
    let c10 = face_texel(face, hi.x, lo.y).rgb;
    let c01 = face_texel(face, lo.x, hi.y).rgb;
    let c11 = face_texel(face, hi.x, hi.y).rgb;
    let top = c00 + (c10 - c00) * f.x;
    let bottom = c01 + (c11 - c01) * f.x;
    return top + (bottom - top) * f.y;
}

// The unit ENU direction at continuous texel coordinates `p` of the equirectangular map.
fn equirect_direction(p: vec2<f32>) -> vec3<f32> {
    let azimuth = ENVMAP_TAU * (p.x / f32(params.width) - 0.25);
    let zenith = ENVMAP_PI * p.y / f32(params.height);
    let sin_z = sin(zenith);
    return vec3<f32>(sin_z * sin(azimuth), sin_z * cos(azimuth), cos(zenith));
}

// Texel `texel` of cube layer `params.face`, RGBA as the face holds it.
fn cube_sky(texel: vec2<u32>) -> vec4<f32> {
    return face_texel(params.face, texel.x, texel.y);
}

// Texel `texel` of the equirectangular map (sampled at its centre), alpha 1.
fn equirect_sky(texel: vec2<u32>) -> vec4<f32> {
    return vec4<f32>(cube_radiance(equirect_direction(vec2<f32>(texel) + 0.5)), 1.0);
}

// Whether `texel` lies inside the output.
fn inside(texel: vec2<u32>) -> bool {
    return texel.x < params.width && texel.y < params.height;
}

// `sky` with the run of pieces of `disc` added, one by one.
fn add_pieces(sky: vec4<f32>, disc: DiscTexel) -> vec4<f32> {
    var rgb = sky.rgb;
    for (var k = disc.first; k < disc.first + disc.count; k++) {
        rgb += pieces[k].rgb;
    }
    return vec4<f32>(rgb, sky.a);
}
