// camera/bloom_up.wgsl — bloom, the way up: each level is its own downsampled image mixed with the
// coarser level's bloom, upsampled by the dual filter's tent (Bjørge 2015: four axial taps two
// finer texels out, weight 1, four diagonal taps one out, weight 2, over twelve). The mix is
// (1 − k) · own + k · coarser, k = BLOOM_SPREAD, so the finest level's bloom is a blur of the
// image whose weights sum to one: spreading light, never adding or losing it.
//
// Conventions: as camera/bindings.wgsl; `bloom_in` is this level of the way down (read texel for
// texel), `bloom_coarser` the coarser level's bloom (sampled bilinearly, clamped at the edges).

#import camera/bindings

// k: the coarser level's share; larger spreads the light wider (Rust: `bloom::BLOOM_SPREAD`).
override BLOOM_SPREAD: f32 = 0.6;

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(bloom_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let uv = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(size);
    let d = 1.0 / vec2<f32>(size);
    var sum = vec3<f32>(0.0);
    sum += textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(-2.0 * d.x, 0.0), 0.0).rgb;
    sum += textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(2.0 * d.x, 0.0), 0.0).rgb;
    sum += textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(0.0, -2.0 * d.y), 0.0).rgb;
    sum += textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(0.0, 2.0 * d.y), 0.0).rgb;
    sum += 2.0 * textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(-d.x, -d.y), 0.0).rgb;
    sum += 2.0 * textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(d.x, -d.y), 0.0).rgb;
    sum += 2.0 * textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(-d.x, d.y), 0.0).rgb;
    sum += 2.0 * textureSampleLevel(bloom_coarser, bloom_sampler, uv + vec2<f32>(d.x, d.y), 0.0).rgb;
    let own = textureLoad(bloom_in, vec2<i32>(id.xy), 0).rgb;
    textureStore(bloom_out, vec2<i32>(id.xy), vec4<f32>(mix(own, sum / 12.0, BLOOM_SPREAD), 1.0));
}
