// atmosphere/body_air.wgsl — the light the airs of the bodies beside the planet scatter towards
// the camera along a view ray, and their transmittance along it: every sun's light scattered
// once, reaching a point of the air through it (atmosphere/body_air_medium.wgsl), and more than
// once (the air's Ψ table), past the shadows of the planet, its rings and the other bodies
// (atmosphere/bodies.wgsl); the GPU twin of firmament_core::atmosphere::body::Body::air_along.
//
// Conventions: as atmosphere/body_air_medium.wgsl. The airs of different bodies never overlap
// (the core's validate_bodies), so each is one segment of the ray.

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/body_hits
#import atmosphere/body_air_medium
#import atmosphere/bodies
#import atmosphere/rings

// Nodes on each side of a view path's nearest point.
const BODY_AIR_VIEW_NODES: u32 = 16u;

// What the bodies' airs do to a view ray.
struct BodyAirSample {
    hit: bool,               // the ray crosses some air
    entry: f32,              // where it enters the nearest (m along the ray)
    radiance: vec3<f32>,     // scattered towards the camera
    transmittance: vec3<f32>, // through all of them
}

// One body's segment of a view ray.
struct BodyAirSegment {
    hit: bool,
    entry: f32,
    exit: f32,
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// The airs along o + t·d for near < t < far (far: where something opaque stands), composited in
// the order they lie along the ray: exact for up to two airs on one ray (the next is then in
// front of or behind the first); a third between two others counts as behind them.
fn body_air_sample(o: vec3<f32>, d: vec3<f32>, near: f32, far: f32) -> BodyAirSample {
    var out = BodyAirSample(false, 0.0, vec3<f32>(0.0), vec3<f32>(1.0));
    for (var i = 0u; i < min(view.sun_count.w, MAX_BODIES); i++) {
        if !body_has_air(i) {
            continue;
        }
        let segment = body_air_segment(i, o, d, near, far);
        if !segment.hit {
            continue;
        }
        if out.hit && segment.exit <= out.entry {
            // In front of the airs so far.
            out.radiance = segment.radiance + segment.transmittance * out.radiance;
            out.entry = segment.entry;
        } else {
            out.radiance += out.transmittance * segment.radiance;
            out.entry = select(segment.entry, out.entry, out.hit);
        }
        out.transmittance *= segment.transmittance;
        out.hit = true;
    }
    return out;
}

// Body i's air along o + t·d for near < t < far.
fn body_air_segment(i: u32, o: vec3<f32>, d: vec3<f32>, near: f32, far: f32) -> BodyAirSegment {
    var out = BodyAirSegment(false, 0.0, 0.0, vec3<f32>(0.0), vec3<f32>(1.0));
    let body = view.bodies[i];
    let to_local = body_from_planet(i);
    // From the ray's closest approach to the centre, as body_hits.wgsl does, for precision.
    let closest = dot(body.center.xyz - o, d);
    let local = to_local * ((o - body.center.xyz) + closest * d);
    let local_d = to_local * d;
    let top_radii = body_air_top_radii(i);
    let top = ellipsoid_hits(local, local_d, top_radii, ellipsoid_c(local, top_radii));
    let s0 = max(top.x, near - closest);
    let s1 = min(top.y, far - closest);
    if top.x > top.y || s1 <= s0 {
        return out;
    }
    out.hit = true;
    out.entry = closest + s0;
    out.exit = closest + s1;
    let sc = clamp(body_air_nearest(i, local, local_d), s0, s1);
    var depth = vec3<f32>(0.0);
    for (var k = 0u; k < 2u * BODY_AIR_VIEW_NODES; k++) {
        let node = body_air_node(s0, sc, s1, k, BODY_AIR_VIEW_NODES);
        let x = local + node.x * local_d;
        let h = body_air_altitude(i, x);
        let extinction = body_air_extinction(i, h);
        let step = exp(-extinction * node.y);
        let p = o + (closest + node.x) * d;
        let up = normalize(x / (body.radii.xyz * body.radii.xyz));
        let scattering = body_air_scattering(i, h);
        var source = vec3<f32>(0.0);
        for (var s = 0u; s < view.sun_count.x; s++) {
            let to_sun = view.suns[s].direction.xyz;
            let local_sun = to_local * to_sun;
            let shadows = body_shadows_share(p, s, i) * ring_transmittance(p, to_sun);
            if all(shadows <= vec3<f32>(0.0)) {
                continue;
            }
            let once = body_air_transmittance(i, x, local_sun) * body_air_scattering_phase(i, h, dot(d, to_sun));
            let again = scattering * body_air_multiple(i, h, dot(up, local_sun));
            source += view.suns[s].irradiance.rgb * shadows * (once + again);
        }
        out.radiance += out.transmittance * integrate_step(source, extinction, step, node.y);
        out.transmittance *= step;
    }
    return out;
}
