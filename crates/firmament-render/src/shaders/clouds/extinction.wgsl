// clouds/extinction.wgsl — a cloud layer's extinction where the passes sample it: the density
// field (clouds/density.wgsl) with the layer's coverage map read at the point, at a level of
// detail; and where a ray meets the layers' shells.
//
// Conventions: as clouds/density.wgsl (planet frame, metres, extinction in m⁻¹, grey).

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import clouds/density

// Where the ray o + t·d meets the shell at altitude h (the ellipsoid's semi-axes plus h): the
// two t of common/ellipsoid's ellipsoid_hits (x > y when it misses).
fn cloud_shell_hits(o: vec3<f32>, d: vec3<f32>, h: f32) -> vec2<f32> {
    let radii = atmosphere.radii.xyz + vec3<f32>(h);
    return ellipsoid_hits(o, d, radii, ellipsoid_c(o, radii));
}

// The layer's extinction at p (altitude h, geodetic up `up`), m⁻¹, with its coverage map if it has
// one; with its detail noise when `detailed`, else the detail's mean (cloud_density_detailed);
// and seen from afar by `lod`: 0 the field itself, 1 its average over the columns at that
// altitude (cloud_mean_density_at), linear between (cloud_lod).
fn cloud_extinction_lod(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, detailed: bool, lod: f32) -> f32 {
    var coverage = layer.coverage.x;
    var t = layer.coverage.y;
    var t_core = layer.coverage.z;
    if layer.codes.z != 0u {
        let map = textureSampleLevel(cloud_coverage_maps, map_sampler, equirect_uv(up), i32(layer.codes.w), 0.0).r;
        coverage *= map;
        t = cloud_coverage_threshold(layer, coverage);
        t_core = cloud_coverage_threshold(layer, coverage * layer.column.w);
    }
    var field = 0.0;
    if lod < 1.0 {
        field = cloud_density_detailed(layer, p, h, coverage, t, t_core, detailed);
    }
    if lod <= 0.0 {
        return field;
    }
    // Without a map the average is the layer's tabulated profile; with one, at the map's coverage.
    var mean: f32;
    if layer.codes.z == 0u {
        mean = cloud_mean_density(layer, h);
    } else {
        mean = cloud_mean_density_at(layer, h, coverage, t, t_core);
    }
    return mix(field, mean, lod);
}

// The field itself (level of detail 0).
fn cloud_extinction(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, detailed: bool) -> f32 {
    return cloud_extinction_lod(layer, p, h, up, detailed, 0.0);
}

fn cloud_extinction_at(layer: CloudLayerGpu, p: vec3<f32>, detailed: bool, lod: f32) -> f32 {
    let here = altitude_up(p);
    return cloud_extinction_lod(layer, p, here.h, here.up, detailed, lod);
}

// The level of detail where a pixel spans `span` metres: 0 up to a quarter of the layer's column
// cell (its Worley cell, or its gradient noise's without Worley), 1 from a whole cell on, where
// the columns' structure is finer than the pixel and a sample of it would alias (the speckle of
// a layer seen from orbit); smooth between.
fn cloud_lod(layer: CloudLayerGpu, span: f32) -> f32 {
    let cell = 1.0 / select(layer.column_scale.x, layer.column.x, layer.column.y > 0.0);
    return smoothstep(0.25, 1.0, span / cell);
}
