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

// The layer's coverage where the geodetic up is `up`, 0–1: its own, times its coverage map there
// if it has one.
fn cloud_coverage_here(layer: CloudLayerGpu, up: vec3<f32>) -> f32 {
    if layer.codes.z == 0u {
        return layer.coverage.x;
    }
    let map = textureSampleLevel(cloud_coverage_maps, map_sampler, equirect_uv(up), i32(layer.codes.w), 0.0).r;
    return layer.coverage.x * map;
}

// The layer's extinction at p (altitude h, geodetic up `up`), m⁻¹, with its coverage map if it has
// one; with its detail noise when `detailed`, else the detail's mean (cloud_density_detailed);
// and seen from afar by `lod`: 0 the field itself, 1 its average over the columns at that
// altitude (cloud_mean_density_at) over `cover`, the share of the rays that meet cloud
// (cloud_cover_seen: the density inside the clouds those rays meet; 1 for the plain average),
// linear between (cloud_lod).
fn cloud_extinction_lod(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, detailed: bool, lod: f32, cover: f32) -> f32 {
    var coverage = layer.coverage.x;
    var t = layer.coverage.y;
    var t_core = layer.coverage.z;
    if layer.codes.z != 0u {
        coverage = cloud_coverage_here(layer, up);
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
    return mix(field, mean / max(cover, 1e-6), lod);
}

// The field itself (level of detail 0).
fn cloud_extinction(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, detailed: bool) -> f32 {
    return cloud_extinction_lod(layer, p, h, up, detailed, 0.0, 1.0);
}

fn cloud_extinction_at(layer: CloudLayerGpu, p: vec3<f32>, detailed: bool, lod: f32, cover: f32) -> f32 {
    let here = altitude_up(p);
    return cloud_extinction_lod(layer, p, here.h, here.up, detailed, lod, cover);
}

// The level of detail where a pixel spans `span` metres: 0 up to a quarter of the layer's column
// cell, 1 from a whole cell on, where the columns' structure is finer than the pixel and a sample
// of it would alias (the speckle of a layer seen from orbit); smooth between.
fn cloud_lod(layer: CloudLayerGpu, span: f32) -> f32 {
    return smoothstep(0.25, 1.0, span / cloud_column_cell(layer));
}

// The share of the rays that meet cloud, as the march divides and weights the columns' average at
// level of detail `lod` (cloud_extinction_lod's `cover`), for a way through the layer along `d`
// over `way` metres where the geodetic up is `up`: cloud_cover_seen from afar, 1 (the field) up
// close, linear between.
fn cloud_cover_along(layer: CloudLayerGpu, up: vec3<f32>, d: vec3<f32>, way: f32, lod: f32) -> f32 {
    if lod <= 0.0 {
        return 1.0;
    }
    let along_up = dot(d, up);
    let horizontal = way * sqrt(max(1.0 - along_up * along_up, 0.0));
    return mix(1.0, cloud_cover_seen(layer, cloud_coverage_here(layer, up), horizontal), lod);
}
