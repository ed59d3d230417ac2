// atmosphere/aerial_perspective_volume.wgsl — Hillaire 2020's aerial-perspective volume, a
// compute pass.
//
// Conventions: as atmosphere/view.wgsl. One invocation per froxel column: it marches the column's
// view ray through the air once and stores, at each slice, the scattered light so far (spectral
// radiance, all suns) and the transmittance so far — O(N) per column instead of O(N²). Slices and
// their distances: see `AERIAL_PERSPECTIVE_SIZE` in view.wgsl. Two midpoint samples per slice. A
// column that passes under the ground goes on through ground-level air (`aerial_span`,
// `aerial_sample_point`).
//
// The volume is a 2D atlas of its slices side by side (slice k at x ∈ [32k, 32k + 32)): GL
// binds a 3D storage texture one layer at a time, so a 3D volume would only get its first slice.

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/view

const SAMPLES_PER_SLICE: u32 = 2u;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= AERIAL_PERSPECTIVE_SIZE.xy) {
        return;
    }
    let uv = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(AERIAL_PERSPECTIVE_SIZE.xy);
    let ray = view_ray(vec2<f32>(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y));
    let span = aerial_span(ray);
    let air = span.y - span.x;
    var radiance = vec3<f32>(0.0);
    var transmittance = vec3<f32>(1.0);
    var diffuse_transmittance = vec3<f32>(1.0); // what scattered light meets (view.wgsl's march)
    var previous = 0.0;
    let slices = AERIAL_PERSPECTIVE_SIZE.z;
    for (var k = 0u; k < slices; k++) {
        let w = (f32(k) + 0.5) / f32(slices);
        let distance = view.aerial.x * w * w;
        for (var s = 0u; s < SAMPLES_PER_SLICE; s++) {
            let a = min(mix(previous, distance, f32(s) / f32(SAMPLES_PER_SLICE)), air);
            let b = min(mix(previous, distance, f32(s + 1u) / f32(SAMPLES_PER_SLICE)), air);
            let dt = b - a;
            if dt > 0.0 {
                let p = aerial_sample_point(ray.origin + ray.direction * (span.x + 0.5 * (a + b)));
                let here = medium_sample(p, ray.direction, 0u, view.sun_count.x);
                let diffuse_step = exp(-here.diffuse_extinction * dt);
                radiance += diffuse_transmittance * integrate_step(here.source, here.diffuse_extinction, diffuse_step, dt);
                diffuse_transmittance *= diffuse_step;
                transmittance *= exp(-here.extinction * dt);
            }
        }
        previous = distance;
        let texel = vec2<u32>(id.x + k * AERIAL_PERSPECTIVE_SIZE.x, id.y);
        textureStore(aerial_scattering_out, texel, vec4<f32>(radiance, 1.0));
        textureStore(aerial_transmittance_out, texel, vec4<f32>(transmittance, 1.0));
    }
}
