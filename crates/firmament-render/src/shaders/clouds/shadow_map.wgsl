// clouds/shadow_map.wgsl — writes the clouds' shadow map (clouds/shadow.wgsl): one invocation per
// texel of each sun's square, marching its ray through every layer.
//
// Conventions: as clouds/shadow.wgsl. A texel's ray is marched over each layer's stretch on the
// sun's side of the square's plane, from CLOUD_SHADOW_REACH behind it (what lies farther behind
// shadows nothing the map serves), SHADOW_MAP_STEPS midpoint samples per stretch, with the
// detail's mean (the light march's field, clouds/march.wgsl).

#import atmosphere/bindings
#import atmosphere/common
#import clouds/extinction
#import clouds/shadow

// Samples over each layer's stretch of a texel's ray.
const SHADOW_MAP_STEPS: u32 = 24u;

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let sun = id.x / CLOUD_SHADOW_SIZE;
    if sun >= view.sun_count.x || id.y >= CLOUD_SHADOW_SIZE {
        return;
    }
    let s = view.suns[sun].direction.xyz;
    let axes = cloud_shadow_axes(s);
    let across = (vec2<f32>(f32(id.x % CLOUD_SHADOW_SIZE), f32(id.y)) + 0.5) / f32(CLOUD_SHADOW_SIZE) * 2.0 - 1.0;
    let o = view.camera.xyz + (axes[0] * across.x + axes[1] * across.y) * CLOUD_SHADOW_REACH;
    var depth = 0.0;
    var first = 3.0e38;
    var last = -3.0e38;
    for (var i = 0u; i < clouds.count.x; i++) {
        let layer = clouds.layers[i];
        let outer = cloud_shell_hits(o, s, layer.shell.y);
        if !(outer.x <= outer.y) {
            continue;
        }
        let inner = cloud_shell_hits(o, s, layer.shell.x);
        // The stretches inside the top shell and outside the bottom one.
        var stretches = array<vec2<f32>, 2>(outer, vec2<f32>(0.0));
        if inner.x <= inner.y {
            stretches[0] = vec2<f32>(outer.x, inner.x);
            stretches[1] = vec2<f32>(inner.y, outer.y);
        }
        for (var j = 0u; j < 2u; j++) {
            let a = max(stretches[j].x, -CLOUD_SHADOW_REACH);
            let b = stretches[j].y;
            if b <= a {
                continue;
            }
            let dt = (b - a) / f32(SHADOW_MAP_STEPS);
            for (var k = 0u; k < SHADOW_MAP_STEPS; k++) {
                let t = a + (f32(k) + 0.5) * dt;
                let p = o + s * t;
                let here = altitude_up(p);
                let extinction = cloud_extinction(layer, p, here.h, here.up, false);
                if extinction > 0.0 {
                    depth += extinction * dt;
                    first = min(first, t - 0.5 * dt);
                    last = max(last, t + 0.5 * dt);
                }
            }
        }
    }
    var texel = vec4<f32>(-3.0e38, 0.0, 0.0, 0.0);
    if depth > 0.0 {
        texel = vec4<f32>(last, depth / max(last - first, 1e-3), depth, 1.0);
    }
    textureStore(cloud_shadow_out, vec2<i32>(id.xy), texel);
}
