// camera/bloom_from_image.wgsl — bloom, the first step down: from the HDR image (any float
// format, filterable or not) to half its size, by the dual filter's downsample (Bjørge,
// "Bandwidth-Efficient Rendering", SIGGRAPH 2015) as camera/bloom_down.wgsl, read texel for
// texel: the output texel's centre is the corner of four source texels, so each of the five taps
// is the mean of four, clamped at the edges as a bilinear tap would be.
//
// Conventions: as camera/bindings.wgsl; one invocation per output texel.

#import camera/bindings

fn source_texel(p: vec2<i32>) -> vec3<f32> {
    let last = vec2<i32>(textureDimensions(bloom_in)) - 1;
    return textureLoad(bloom_in, clamp(p, vec2<i32>(0), last), 0).rgb;
}

// The mean of the four texels that share the corner at the top left of texel `corner`.
fn corner_mean(corner: vec2<i32>) -> vec3<f32> {
    return 0.25 * (source_texel(corner - vec2<i32>(1, 1)) + source_texel(corner - vec2<i32>(0, 1))
        + source_texel(corner - vec2<i32>(1, 0)) + source_texel(corner));
}

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(bloom_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    // The output texel's centre is the corner between source texels 2·id and 2·id + 1.
    let c = 2 * vec2<i32>(id.xy) + 1;
    var sum = 4.0 * corner_mean(c);
    sum += corner_mean(c + vec2<i32>(-1, -1));
    sum += corner_mean(c + vec2<i32>(1, -1));
    sum += corner_mean(c + vec2<i32>(-1, 1));
    sum += corner_mean(c + vec2<i32>(1, 1));
    // Half floats end at 65504: keep the levels finite.
    textureStore(bloom_out, vec2<i32>(id.xy), vec4<f32>(min(sum / 8.0, vec3<f32>(65504.0)), 1.0));
}
