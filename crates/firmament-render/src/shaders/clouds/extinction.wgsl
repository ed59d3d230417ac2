// clouds/extinction.wgsl — a cloud layer's extinction where the passes sample it: the density
// field (clouds/density.wgsl) with the layer's coverage map read at the point.
//
// Conventions: as clouds/density.wgsl (planet frame, metres, extinction in m⁻¹, grey).

#import atmosphere/bindings
#import atmosphere/common
#import clouds/density

// The layer's extinction at p (altitude h, geodetic up `up`), m⁻¹, with its coverage map if it has
// one; with its detail noise when `detailed`, else the detail's mean (cloud_density_detailed).
fn cloud_extinction(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, detailed: bool) -> f32 {
    var coverage = layer.coverage.x;
    var t = layer.coverage.y;
    var t_core = layer.coverage.z;
    if layer.codes.z != 0u {
        let map = textureSampleLevel(cloud_coverage_maps, cloud_map_sampler, cloud_coverage_map_uv(up), i32(layer.codes.w), 0.0).r;
        coverage *= map;
        t = cloud_coverage_threshold(layer, coverage);
        t_core = cloud_coverage_threshold(layer, coverage * layer.column.w);
    }
    return cloud_density_detailed(layer, p, h, coverage, t, t_core, detailed);
}

fn cloud_extinction_at(layer: CloudLayerGpu, p: vec3<f32>, detailed: bool) -> f32 {
    let here = altitude_up(p);
    return cloud_extinction(layer, p, here.h, here.up, detailed);
}
