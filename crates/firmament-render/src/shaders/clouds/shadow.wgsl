// clouds/shadow.wgsl — the clouds' shadow map: for each sun, the cloud layers' optical depth
// along its rays through a square of CLOUD_SHADOW_SIZE² texels across them, 2·CLOUD_SHADOW_REACH
// metres wide and centred on the camera, the suns' squares side by side (sun i at columns
// i·CLOUD_SHADOW_SIZE …). Written each cloudy frame by clouds/shadow_map.wgsl; read by the light
// shafts (clouds/march.wgsl) and the objects' sunlight (shadow/sampling.wgsl). No bindings: the
// readers pass the map.
//
// Conventions: metres, in any frame the axes are given in (the planet frame here; the readers'
// eye space for objects, whose camera is at the origin). A texel holds, for its ray (a line along
// the sun's direction s, t metres along it from the plane through the camera across the rays, t
// growing towards the sun): x the t where the last cloud towards the sun ends, y the mean
// extinction between where the first begins and there (m⁻¹), z the whole optical depth, w 1 where
// any cloud was found. A point at t on the ray sees min(y·(x − t), z) of it between it and the
// sun, clamped at zero (Unreal's cloud shadow map keeps the same three; Hillaire 2016).

// Texels across one sun's square.
const CLOUD_SHADOW_SIZE: u32 = 256u;
// Half the square's width, metres: the air and the objects within this distance of the camera
// get the clouds' shadows.
const CLOUD_SHADOW_REACH: f32 = 20000.0;

// Two unit vectors across the sun's direction s (and s itself, the third column), planet frame:
// the same for the writer and the readers (gpu_types::shadow::cloud_shadow_axes for objects).
fn cloud_shadow_axes(s: vec3<f32>) -> mat3x3<f32> {
    let helper = select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(s.z) > 0.9);
    let across = normalize(cross(s, helper));
    return mat3x3<f32>(across, cross(s, across), s);
}

// The clouds' optical depth towards sun `sun` in `map` from the point `across` metres from the
// camera across the sun's rays (along the first two axes) and `t` metres along them, bilinear
// between the four texels about it; zero outside the square.
fn cloud_shadow_lookup(map: texture_2d<f32>, across: vec2<f32>, t: f32, sun: u32) -> f32 {
    let size = f32(CLOUD_SHADOW_SIZE);
    let texel = (across / CLOUD_SHADOW_REACH * 0.5 + 0.5) * size - 0.5;
    if any(texel < vec2<f32>(0.0)) || any(texel > vec2<f32>(size - 1.0)) {
        return 0.0;
    }
    let base = vec2<i32>(floor(texel));
    let f = texel - floor(texel);
    let column = i32(sun * CLOUD_SHADOW_SIZE);
    var depth = array<f32, 4>();
    for (var k = 0; k < 4; k++) {
        let at = min(base + vec2<i32>(k & 1, k >> 1u), vec2<i32>(i32(CLOUD_SHADOW_SIZE) - 1));
        let texel_value = textureLoad(map, vec2<i32>(column + at.x, at.y), 0);
        depth[k] = clamp(texel_value.y * (texel_value.x - t), 0.0, texel_value.z);
    }
    return mix(mix(depth[0], depth[1], f.x), mix(depth[2], depth[3], f.x), f.y);
}
