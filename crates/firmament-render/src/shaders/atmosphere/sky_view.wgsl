// atmosphere/sky_view.wgsl — shared: reading the sky-view LUT (sky_view_lut.wgsl writes it), for
// the sky pass and the sky-lighting stage.
//
// Conventions: as atmosphere/view.wgsl; radiance spectral (W·m⁻²·sr⁻¹·nm⁻¹).

#import atmosphere/bindings
#import atmosphere/view

// The spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) reaching the camera from direction d (planet frame):
// every sun's tile at d, each times the power of two it was stored over (its alpha). Sky and lit
// ground, no sun discs.
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
