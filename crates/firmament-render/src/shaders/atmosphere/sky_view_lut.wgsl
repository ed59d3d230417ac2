// atmosphere/sky_view_lut.wgsl — Hillaire 2020's sky-view LUT, one tile per sun.
//
// Conventions: as atmosphere/view.wgsl. The target is SKY_VIEW_LUT_SIZE.x · MAX_SUNS wide: tile i
// (x in [i·W, (i+1)·W)) holds the light scattered towards the camera from sun i alone (all
// orders, and the ground that sun lights unless the planet has a surface: sky_view.wgsl's
// sky_radiance reads that per ray), over (azimuth relative to the sun, non-linear zenith
// angle) — see `sky_view_uv`. A compute pass, one invocation per texel; only the first
// `sun_count` tiles are dispatched (on the Rust side). rgb = spectral radiance over 2^a, a = `sky_view_exponent(sun)` (so
// dim suns and deep twilight keep their precision).

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/view
#import atmosphere/surface

const STEPS: i32 = 32;

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let tile = vec2<u32>(SKY_VIEW_LUT_SIZE);
    let sun = id.x / tile.x;
    if id.y >= tile.y || sun >= MAX_SUNS {
        return;
    }
    let uv = (vec2<f32>(f32(id.x - sun * tile.x), f32(id.y)) + 0.5) / SKY_VIEW_LUT_SIZE;
    let d = sky_view_direction(uv, sun_frame(sun));
    let o = view.camera.xyz;
    let top = ellipsoid_hits(o, d, top_radii(), view.camera_shape.y);
    let ground = ellipsoid_hits(o, d, atmosphere.radii.xyz, view.camera_shape.x);
    let hits_ground = ground.x > 0.0 && ground.x <= ground.y;
    // From above the atmosphere (the sky-lighting stage reads the LUT there) the march starts
    // where the ray enters the air; inside it starts at the camera, denser near it.
    let inside = top.x <= 0.0;
    let t0 = max(top.x, 0.0);
    let t1 = select(max(top.y, 0.0), ground.x, hits_ground);
    let result = march(o, d, t0, max(t1, t0), hits_ground && !has_surface(), sun, 1u, STEPS, inside);
    let k = sky_view_exponent(sun);
    textureStore(sky_view_out, id.xy, vec4<f32>(result.radiance * exp2(-k), k));
}
