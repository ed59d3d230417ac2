// common/ellipsoid.wgsl — shared: ray/ellipsoid intersection, and where an equirectangular map
// is read.
//
// Conventions: any frame whose axes are the ellipsoid's (the planet frame), metres; `a` the
// semi-axes; `c` = |o/a|² − 1 of the ray origin o (negative inside, positive outside).

// Entry and exit parameters of the line o + t·d (t may be negative) through the ellipsoid with
// semi-axes `a`, or (1, 0) when it misses. `c` is passed in so callers can give a value computed
// more exactly (the camera's, from f64). The numerically stable pair of roots (geometry.rs does
// the same in f64).
fn ellipsoid_hits(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, c: f32) -> vec2<f32> {
    let os = o / a;
    let ds = d / a;
    let qa = dot(ds, ds);
    let qb = dot(os, ds);
    let disc = qb * qb - qa * c;
    if disc < 0.0 {
        return vec2<f32>(1.0, 0.0);
    }
    let s = sqrt(disc);
    let q = -(qb + select(-s, s, qb >= 0.0));
    if q == 0.0 {
        return vec2<f32>(0.0, 0.0);
    }
    let t0 = q / qa;
    let t1 = c / q;
    return vec2<f32>(min(t0, t1), max(t0, t1));
}

fn ellipsoid_c(o: vec3<f32>, a: vec3<f32>) -> f32 {
    let os = o / a;
    return dot(os, os) - 1.0;
}

// Where an equirectangular map over the planet (a cloud layer's coverage, the surface) is read
// for the point whose geodetic up is `up` (planet frame, unit): u = (longitude + π)/2π,
// v = (π/2 − latitude)/π, for a sampler with linear filtering, Repeat in u and ClampToEdge in v
// (the core's CoverageMap and SurfaceMap: texel centres, wrapping in longitude).
fn equirect_uv(up: vec3<f32>) -> vec2<f32> {
    let latitude = asin(clamp(up.z, -1.0, 1.0));
    let longitude = atan2(up.y, up.x);
    return vec2<f32>(longitude * 0.15915494 + 0.5, 0.5 - latitude * 0.31830989);
}
