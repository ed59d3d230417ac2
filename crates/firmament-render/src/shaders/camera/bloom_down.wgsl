// camera/bloom_down.wgsl — bloom, the way down from the first level: each level half the size of
// the one before, by the dual filter's downsample (Bjørge, "Bandwidth-Efficient Rendering",
// SIGGRAPH 2015): four times the centre and once each the four diagonal neighbours one source
// texel away, over eight. The weights sum to one, so every level keeps the image's mean radiance.
//
// Conventions: as camera/bindings.wgsl; one invocation per output texel. The source level is
// sampled bilinearly at the output texel's place (clamped at the edges), so levels of odd sizes
// stay registered with the image.

#import camera/bindings

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(bloom_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let uv = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(size);
    let d = 1.0 / vec2<f32>(textureDimensions(bloom_in));
    var sum = 4.0 * textureSampleLevel(bloom_in, bloom_sampler, uv, 0.0).rgb;
    sum += textureSampleLevel(bloom_in, bloom_sampler, uv + vec2<f32>(-d.x, -d.y), 0.0).rgb;
    sum += textureSampleLevel(bloom_in, bloom_sampler, uv + vec2<f32>(d.x, -d.y), 0.0).rgb;
    sum += textureSampleLevel(bloom_in, bloom_sampler, uv + vec2<f32>(-d.x, d.y), 0.0).rgb;
    sum += textureSampleLevel(bloom_in, bloom_sampler, uv + vec2<f32>(d.x, d.y), 0.0).rgb;
    textureStore(bloom_out, vec2<i32>(id.xy), vec4<f32>(sum / 8.0, 1.0));
}
