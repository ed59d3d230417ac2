// atmosphere/body_hits.wgsl — where a view ray meets the bodies beside the planet: the geometry
// alone, for the sky pass's shading (atmosphere/bodies.wgsl) and for the passes that must stop
// at a body (the clouds' march), without the lighting's imports.
//
// Conventions: as atmosphere/common.wgsl. `view.bodies[i]` for i < `view.sun_count.w`.

#import common/ellipsoid
#import atmosphere/bindings

// A `far` along a ray that meets no body (nothing opaque).
const NO_BODY_T: f32 = 3.0e38;

// The nearest body along a ray: where, which, and the point in its axes from its centre.
struct BodyHit {
    hit: bool,
    t: f32,             // along the ray (m)
    index: u32,
    local: vec3<f32>,   // the hit in the body's axes (m)
}

// Rotation from the planet frame into body i's axes (the transpose of its axis columns).
fn body_from_planet(i: u32) -> mat3x3<f32> {
    let body = view.bodies[i];
    return transpose(mat3x3<f32>(body.axis_x.xyz, body.axis_y.xyz, body.axis_z.xyz));
}

// Where the ray o + t·d meets body i at t > near (`hit` false: it does not).
fn body_hit(i: u32, o: vec3<f32>, d: vec3<f32>, near: f32) -> BodyHit {
    let body = view.bodies[i];
    let to_local = body_from_planet(i);
    // Solved from the ray's closest approach to the body's centre: from afar, |o − c|² and
    // the quadratic's other terms cancel to far less than f32 holds (km on the Moon).
    let closest = dot(body.center.xyz - o, d);
    let local = to_local * ((o - body.center.xyz) + closest * d);
    let from_closest = ellipsoid_hits(local, to_local * d, body.radii.xyz, ellipsoid_c(local, body.radii.xyz));
    // Tested before `closest` is added: far away (1, 0), the miss, rounds to a point.
    let t = closest + from_closest.x;
    let hit = from_closest.x <= from_closest.y && t > near;
    return BodyHit(hit, t, i, local + from_closest.x * (to_local * d));
}

// The nearest body the ray o + t·d meets at t > near.
fn nearest_body_hit(o: vec3<f32>, d: vec3<f32>, near: f32) -> BodyHit {
    var out = BodyHit(false, 0.0, 0u, vec3<f32>(0.0));
    for (var i = 0u; i < min(view.sun_count.w, MAX_BODIES); i++) {
        let hit = body_hit(i, o, d, near);
        if hit.hit && (!out.hit || hit.t < out.t) {
            out = hit;
        }
    }
    return out;
}
