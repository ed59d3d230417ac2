// atmosphere/aerial_perspective_volume.wgsl — Hillaire 2020's aerial-perspective volume, a
// compute pass.
//
// Conventions: as atmosphere/view.wgsl. One workgroup per froxel column, one invocation per
// sample: two midpoint samples per slice, each invocation integrating its own stretch of the
// column's view ray through the air (its scattered light, and what its stretch lets through), and
// a prefix sum over the workgroup (Hillis & Steele 1986) chaining the stretches, so each slice
// holds the scattered light and the transmittance from the camera to it. The column's samples run
// side by side rather than one after another: 32 × 32 columns are too few invocations to fill a
// data-centre GPU, 64 × 32 × 32 samples are not (docs/PERFORMANCE.md). Slices and their distances:
// see `AERIAL_PERSPECTIVE_SIZE` in view.wgsl. A column that passes under the ground goes on
// through ground-level air (`aerial_span`, `aerial_sample_point`).
//
// The volume is a 2D atlas of its slices side by side (slice k at x ∈ [32k, 32k + 32)): GL
// binds a 3D storage texture one layer at a time, so a 3D volume would only get its first slice.

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/view

const SAMPLES_PER_SLICE: u32 = 2u;
// Samples per column: the workgroup's size.
const SAMPLES: u32 = 64u; // AERIAL_PERSPECTIVE_SIZE.z * SAMPLES_PER_SLICE

// A stretch of the ray, or the chain of stretches from the camera: the light it scatters towards
// its start, the transmittance scattered light meets over it (delta-M's, see view.wgsl's march)
// and the transmittance over it.
struct Stretch {
    radiance: vec3<f32>,
    diffuse_transmittance: vec3<f32>,
    transmittance: vec3<f32>,
}

var<workgroup> chain: array<Stretch, SAMPLES>;

// `near` followed by `far`.
fn then(near: Stretch, far: Stretch) -> Stretch {
    return Stretch(
        near.radiance + near.diffuse_transmittance * far.radiance,
        near.diffuse_transmittance * far.diffuse_transmittance,
        near.transmittance * far.transmittance,
    );
}

// Distance through the air to the far end of slice k's region: the slice's centre (view.wgsl).
fn slice_distance(k: u32) -> f32 {
    let w = (f32(k) + 0.5) / f32(AERIAL_PERSPECTIVE_SIZE.z);
    return view.aerial.x * w * w;
}

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(workgroup_id) column: vec3<u32>, @builtin(local_invocation_index) sample: u32) {
    let uv = (vec2<f32>(column.xy) + 0.5) / vec2<f32>(AERIAL_PERSPECTIVE_SIZE.xy);
    let ray = view_ray(vec2<f32>(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y));
    let span = aerial_span(ray);
    let air = span.y - span.x;
    let k = sample / SAMPLES_PER_SLICE;
    let s = sample % SAMPLES_PER_SLICE;
    let previous = select(0.0, slice_distance(k - 1u), k > 0u);
    let distance = slice_distance(k);
    let a = min(mix(previous, distance, f32(s) / f32(SAMPLES_PER_SLICE)), air);
    let b = min(mix(previous, distance, f32(s + 1u) / f32(SAMPLES_PER_SLICE)), air);
    let dt = b - a;
    var own = Stretch(vec3<f32>(0.0), vec3<f32>(1.0), vec3<f32>(1.0));
    if dt > 0.0 {
        let p = aerial_sample_point(ray.origin + ray.direction * (span.x + 0.5 * (a + b)));
        let here = medium_sample(p, ray.direction, 0u, view.sun_count.x);
        own.diffuse_transmittance = exp(-here.diffuse_extinction * dt);
        own.radiance = integrate_step(here.source, here.diffuse_extinction, own.diffuse_transmittance, dt);
        own.transmittance = exp(-here.extinction * dt);
    }
    // Inclusive prefix: after the step of offset o, each invocation holds the chain of the 2o
    // stretches ending at its own (or all from the camera).
    chain[sample] = own;
    for (var offset = 1u; offset < SAMPLES; offset *= 2u) {
        workgroupBarrier();
        var combined = chain[sample];
        if sample >= offset {
            combined = then(chain[sample - offset], combined);
        }
        workgroupBarrier();
        chain[sample] = combined;
    }
    if s == SAMPLES_PER_SLICE - 1u {
        let total = chain[sample];
        let texel = vec2<u32>(column.x + k * AERIAL_PERSPECTIVE_SIZE.x, column.y);
        textureStore(aerial_scattering_out, texel, vec4<f32>(total.radiance, 1.0));
        textureStore(aerial_transmittance_out, texel, vec4<f32>(total.transmittance, 1.0));
    }
}
