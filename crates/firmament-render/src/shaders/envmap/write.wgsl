// envmap/write.wgsl — the environment-map pass's kernels: a cube layer or the equirectangular map into the pass's own storage texture, then the texels the suns' discs fall in.
//
// Conventions: as `envmap/from_faces`. The output is the pass's plain 2D storage texture of the
// caller's format (the pass copies it into the caller's texture): `rgba16float` here, and Rust
// builds the `rgba32float` variant by replacing that one word of the `output` declaration. The
// `*_sky` kernels write every texel (8 × 8 per workgroup); the `*_disc` kernels, dispatched after
// them, one texel of `disc_texels` per invocation (those of other layers skipped), overwriting its
// sky with the sky plus its pieces.

#import envmap/from_faces

@group(0) @binding(4) var output: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn cube_sky_kernel(@builtin(global_invocation_id) id: vec3<u32>) {
    if inside(id.xy) {
        textureStore(output, id.xy, cube_sky(id.xy));
    }
}

@compute @workgroup_size(8, 8)
fn equirect_sky_kernel(@builtin(global_invocation_id) id: vec3<u32>) {
    if inside(id.xy) {
        textureStore(output, id.xy, equirect_sky(id.xy));
    }
}

@compute @workgroup_size(64)
fn cube_disc_kernel(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&disc_texels) {
        let disc = disc_texels[id.x];
        let texel = vec2<u32>(disc.x, disc.y);
        if disc.face == params.face && disc.count > 0u {
            textureStore(output, texel, add_pieces(cube_sky(texel), disc));
        }
    }
}

@compute @workgroup_size(64)
fn equirect_disc_kernel(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&disc_texels) {
        let disc = disc_texels[id.x];
        let texel = vec2<u32>(disc.x, disc.y);
        if disc.count > 0u {
            textureStore(output, texel, add_pieces(equirect_sky(texel), disc));
        }
    }
}
