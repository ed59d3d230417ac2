// atmosphere/sky_view_lut.wgsl — Hillaire 2020's sky-view LUT, one tile per sun.
//
// Conventions: as atmosphere/view.wgsl. The target is SKY_VIEW_LUT_SIZE.x · MAX_SUNS wide: tile i
// (x in [i·W, (i+1)·W)) holds the light scattered towards the camera from sun i alone (all
// orders, and the ground that sun lights), over (azimuth relative to the sun, non-linear zenith
// angle) — see `sky_view_uv`. Only the first `sun_count` tiles are drawn (the viewport is
// narrowed on the Rust side). rgb = spectral radiance over 2^a, a = `sky_view_exponent(sun)` (so
// dim suns and deep twilight keep their precision).

#import common/fullscreen
#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/view

const STEPS: i32 = 32;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let sun = u32(in.clip.x / SKY_VIEW_LUT_SIZE.x);
    let uv = vec2<f32>(in.clip.x - f32(sun) * SKY_VIEW_LUT_SIZE.x, in.clip.y) / SKY_VIEW_LUT_SIZE;
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
    let result = march(o, d, t0, max(t1, t0), hits_ground, sun, 1u, STEPS, inside);
    let k = sky_view_exponent(sun);
    return vec4<f32>(result.radiance * exp2(-k), k);
}
