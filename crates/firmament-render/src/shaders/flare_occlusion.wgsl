// flare_occlusion.wgsl — how much of each lens-flare source can be seen, on the GPU, with no
// read-back (NeHe lesson 44's to-do; Unity's SRP lens flare samples a disc the same way).
//
// Conventions: as flare/bindings.wgsl. One invocation per source: `counts.y` points of Vogel's
// golden-angle spiral over its disc (r = sqrt((k + 1/2)/n), theta = k * golden angle:
// `firmament_core::flare::sample_pattern`), each hidden when the depth buffer holds something
// nearer than the source, or when the planet lies in front of it along that view ray (a sun
// setting behind the limb). Samples off the screen count as seen (the edge fade handles those
// sources). The visible share, moved towards at the fade rates
// (`firmament_core::flare::smoothed_visibility`), is written to `visibility`, where the flare
// pass reads it in the same frame.

#import common/ellipsoid
#import flare/bindings
#import generated/constants

const GOLDEN_ANGLE: f32 = 2.3999632;

// Whether the planet hides the view ray through `ndc` before `distance` metres.
fn planet_hides(ndc: vec2<f32>, distance: f32) -> bool {
    if frame.planet_radii.w == 0.0 {
        return false;
    }
    let d_view = normalize(vec3<f32>(ndc.x * frame.view.x, ndc.y * frame.view.y, -1.0));
    let d = (frame.view_to_planet * vec4<f32>(d_view, 0.0)).xyz;
    let t = ellipsoid_hits(frame.planet_origin.xyz, d, frame.planet_radii.xyz, frame.planet_origin.w);
    return t.x <= t.y && t.y > 0.0 && max(t.x, 0.0) < distance;
}

@compute @workgroup_size(64)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= frame.counts.x {
        return;
    }
    let source = sources[i];
    let n = max(frame.counts.y, 1u);
    let size = vec2<f32>(f32(frame.counts.z), f32(frame.counts.w));
    var seen = 0u;
    for (var k = 0u; k < n; k = k + 1u) {
        let r = sqrt((f32(k) + 0.5) / f32(n));
        let theta = f32(k) * GOLDEN_ANGLE;
        let p = source.disc.xy + vec2<f32>(r * cos(theta), r * sin(theta)) * source.disc.zw;
        var hidden = planet_hides(p, source.depth.y);
        let pixel = vec2<f32>((p.x * 0.5 + 0.5) * size.x, (0.5 - p.y * 0.5) * size.y);
        if !hidden && all(pixel >= vec2<f32>(0.0)) && all(pixel < size) {
            let depth = textureLoad(depth_buffer, vec2<i32>(pixel), 0).x;
            hidden = select((depth > source.depth.x), (depth < source.depth.x), (u32(frame.fade.z) == DEPTH_STANDARD));
        }
        if !hidden {
            seen = seen + 1u;
        }
    }
    let target_share = f32(seen) / f32(n);
    var v = target_share;
    let dt = frame.view.z;
    if dt > 0.0 {
        let previous = visibility[i];
        let step = target_share - previous;
        let limit = select(frame.fade.y, frame.fade.x, step >= 0.0);
        if limit > 0.0 {
            v = previous + clamp(step, -limit * dt, limit * dt);
        }
    }
    visibility[i] = v;
}
