// atmosphere/sky_view.wgsl — shared: reading the sky-view LUT (sky_view_lut.wgsl writes it), for
// the sky pass and the sky-lighting stage.
//
// Conventions: as atmosphere/view.wgsl; radiance spectral (W·m⁻²·sr⁻¹·nm⁻¹).

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/view
#import atmosphere/surface

// The spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) reaching the camera from direction d (planet frame):
// every sun's tile at d, each times the power of two it was stored over (its alpha). Sky and lit
// ground (with a surface, the ground the LUT leaves out: see `sky_radiance`), no sun discs.
fn lut_radiance(d: vec3<f32>) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    for (var i = 0u; i < view.sun_count.x; i++) {
        let uv = sky_view_uv(d, sun_frame(i));
        let atlas_uv = vec2<f32>((uv.x + f32(i)) / f32(MAX_SUNS), uv.y);
        let texel = textureSampleLevel(sky_view_lut, lut_sampler, atlas_uv, 0.0);
        radiance += texel.rgb * exp2(texel.a);
    }
    return radiance;
}

// The sky and the lit ground seen from the camera along d, as the sky-view LUT gives them: the
// LUT's radiance and, with a surface, the ground read along this very ray — its albedo and water
// vary faster than the LUT's texels, so the LUT is built without the ground then
// (sky_view_lut.wgsl) and the ground is added here, dimmed by the air between.
fn sky_radiance(d: vec3<f32>) -> vec3<f32> {
    var radiance = lut_radiance(d);
    if has_surface() {
        let o = view.camera.xyz;
        let ground = ellipsoid_hits(o, d, atmosphere.radii.xyz, view.camera_shape.x);
        if ground.x > 0.0 && ground.x <= ground.y {
            let p = o + d * ground.x;
            let here = altitude_up(p);
            let through = transmittance_to_ground(d, o, here);
            radiance += through * ground_radiance(p, max(here.h, 0.0), here.up, -d, 0u, view.sun_count.x);
        }
    }
    return radiance;
}
