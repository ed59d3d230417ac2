// common/view_ray.wgsl — shared: a pixel's view ray in the planet frame, precise from the street
// to 100 AU.
//
// Conventions: planet frame, metres; `ndc` the pixel in normalised device coordinates. The four
// fields of `PlanetView` are the first four of both passes' view uniforms (Rust:
// `gpu_types::planet_view`), passed in by each pass's own `view_ray`.

#import common/ellipsoid

struct PlanetView {
    view_to_planet: mat4x4<f32>, // rotation: view-space direction → planet frame
    camera: vec4<f32>,           // xyz camera position (m)
    camera_shape: vec4<f32>,     // |o/a|² − 1 against the surface and the top; tan of half fov x, y
    center: vec4<f32>,           // far camera: centre's view x, y over depth; depth (m); 1 if far
}

// A view ray in the planet frame, as the part of the line that lies in front of the camera.
struct ViewRay {
    origin: vec3<f32>,
    direction: vec3<f32>,
    near: f32,         // smallest t in front of the camera
    c_surface: f32,    // |origin/a|² − 1 against the surface and the top
    c_top: f32,
}

// Far from the planet the camera's own position is useless in f32 (at 100 AU its rounding is a
// sizeable fraction of the planet), so the ray starts at its closest approach to the centre,
// computed from the small, exact offset between the pixel and the centre on the image plane:
// with dn = (x·tan_x, y·tan_y, −1), the centre at s·cn (s its depth, cn = (cx, cy, −1)) and
// δ = dn − cn, the closest point is s·(δ − (δ·d̂)d̂) and the camera sits at t = −s·(|dn| − δ·d̂).
// `surface` and `top` are the semi-axes of the ground and of the top of the atmosphere.
fn planet_view_ray(ndc: vec2<f32>, view: PlanetView, surface: vec3<f32>, top: vec3<f32>) -> ViewRay {
    let tangent = ndc * view.camera_shape.zw;
    let dn = vec3<f32>(tangent, -1.0);
    let d_view = normalize(dn);
    let rotation = mat3x3<f32>(view.view_to_planet[0].xyz, view.view_to_planet[1].xyz, view.view_to_planet[2].xyz);
    var ray: ViewRay;
    ray.direction = normalize(rotation * d_view);
    if view.center.w > 0.5 {
        let delta = vec3<f32>(tangent - view.center.xy, 0.0);
        let along = dot(delta, d_view);
        ray.origin = rotation * (view.center.z * (delta - along * d_view));
        ray.near = -view.center.z * (length(dn) - along);
        ray.c_surface = ellipsoid_c(ray.origin, surface);
        ray.c_top = ellipsoid_c(ray.origin, top);
    } else {
        ray.origin = view.camera.xyz;
        ray.near = 0.0;
        ray.c_surface = view.camera_shape.x;
        ray.c_top = view.camera_shape.y;
    }
    return ray;
}
