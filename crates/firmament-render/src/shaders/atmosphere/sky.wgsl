// atmosphere/sky.wgsl — the atmosphere seen by the camera: sky, lit ground and sun discs, as
// linear sRGB radiance (Y in cd/m²) into the HDR target, drawn at the far plane behind whatever
// is already in the depth buffer.
//
// Conventions: as atmosphere/view.wgsl. Inside the atmosphere each pixel sums the sky-view LUT
// tiles of the suns; above it each pixel marches its own ray (Hillaire 2020 does the same);
// across the top of the atmosphere the two are blended by `view.local_up.w`, so crossing it does
// not pop. `SKY_MODE` picks the path.
//
// Two entry points: `fs_main`, a full-screen draw depth-tested against the far plane (for
// callers' render passes), and `cs_main`, a compute pass for the renderer's own targets that
// writes `sky_out` where `scene_depth` holds the far plane (`view.aerial.w`) — data-centre GPUs
// run fragment work on a few of their SMs and compute on all (docs/PERFORMANCE.md).

#import common/fullscreen
#import common/ellipsoid
#import common/view_ray
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/view
#import atmosphere/eclipse
#import atmosphere/rings
#import atmosphere/body_hits
#import atmosphere/bodies
#import atmosphere/body_air
#import atmosphere/sky_view
#import generated/constants

// A SKY_MODE_* (the LUT, the march, or both blended by `view.local_up.w`). A pipeline constant,
// so each pipeline holds only the path it takes.
override SKY_MODE: u32 = SKY_MODE_BLEND;

const MARCH_STEPS: i32 = 64;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

struct SkySample {
    radiance: vec3<f32>,     // scattered light and lit ground
    transmittance: vec3<f32>, // to space along the ray (0 when it ends on the ground)
}

fn marched_sky(ray: ViewRay) -> SkySample {
    var out: SkySample;
    out.radiance = vec3<f32>(0.0);
    out.transmittance = vec3<f32>(1.0);
    let top = ellipsoid_hits(ray.origin, ray.direction, top_radii(), ray.c_top);
    if top.x > top.y || top.y <= ray.near {
        return out; // misses the atmosphere
    }
    let ground = ellipsoid_hits(ray.origin, ray.direction, atmosphere.radii.xyz, ray.c_surface);
    let hits_ground = ground.x <= ground.y && ground.x > ray.near;
    let t0 = max(top.x, ray.near);
    let t1 = select(top.y, ground.x, hits_ground);
    let inside = ray.near > top.x;
    let result = march(ray.origin, ray.direction, t0, t1, hits_ground, 0u, view.sun_count.x, MARCH_STEPS, inside);
    out.radiance = result.radiance;
    out.transmittance = select(result.transmittance, vec3<f32>(0.0), hits_ground);
    return out;
}

// Transmittance from the camera along d to space, from the transmittance LUT.
fn lut_transmittance(d: vec3<f32>) -> vec3<f32> {
    let ground = ellipsoid_hits(view.camera.xyz, d, atmosphere.radii.xyz, view.camera_shape.x);
    if ground.x > 0.0 && ground.x <= ground.y {
        return vec3<f32>(0.0);
    }
    let r = atmosphere.lut.x + max(view.camera.w, 0.0);
    return transmittance_to_top(r, dot(d, view.local_up.xyz));
}

// Every sun's limb-darkened disc seen along d, above the atmosphere (zero off the discs, for a
// sun whose disc is not drawn and where an eclipsing body stands in front), and, while there are
// eclipsers, its corona, drawn with or without the disc (firmament_core Sun::corona_radiance:
// Baumbach 1937; by day the sky near the sun outshines it).
fn sun_discs(d: vec3<f32>) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    if meets_eclipser(d) {
        return radiance;
    }
    for (var i = 0u; i < view.sun_count.x; i++) {
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        // A negative radius: the disc is not drawn.
        let alpha = abs(sun.direction.w);
        let disc = sun.direction.w > 0.0;
        // atan2 keeps the precision acos loses for small angles.
        let angle = atan2(length(cross(d, s)), dot(d, s));
        let r = angle / alpha;
        if view.sun_count.y > 0u && alpha > 0.0 && r >= 1.0 && r < CORONA_MAX_RADII {
            let half = sin(0.5 * alpha);
            let mean = sun.irradiance.rgb / (4.0 * PI * half * half);
            radiance += mean * 1e-6 * (0.0532 * pow(r, -2.5) + 1.425 * pow(r, -7.0) + 2.565 * pow(r, -17.0));
        }
        if disc && angle < alpha {
            let x = angle / alpha;
            let mu = sqrt(max(1.0 - x * x, 0.0));
            let u = sun.irradiance.w;
            // 2π(1 − cos α), written so f32 keeps its precision for small discs.
            let half = sin(0.5 * alpha);
            let solid_angle = 4.0 * PI * half * half;
            let center = sun.irradiance.rgb / (solid_angle * (1.0 - u / 3.0));
            radiance += center * (1.0 - u * (1.0 - mu));
        }
    }
    return radiance;
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    // A pixel's height in NDC, from the screen-space derivatives (uniform control flow here).
    return sky_color(in.ndc, abs(dpdy(in.ndc.y)));
}

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(sky_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    if !at_far_plane(textureLoad(scene_depth, id.xy, 0).r) {
        return; // geometry stands here
    }
    textureStore(sky_out, id.xy, sky_color(pixel_ndc(id.xy, size), 2.0 / f32(size.y)));
}

// The sky's colour (linear sRGB, Y in cd/m²; alpha 1) seen through the pixel at `ndc`: the air
// (and lit ground), and behind it the suns' discs or a body (atmosphere/bodies.wgsl) seen
// through the bodies' airs (atmosphere/body_air.wgsl); the rings in front of the air or between
// it and what lies behind (atmosphere/rings.wgsl). A body, or its air, in front of the planet's
// air comes before it; a body under a few pixels across covers its share of the pixel (in front of
// the rings and of its own air, which it leaves out). `pixel_height_ndc` is a pixel's height in
// NDC.
fn sky_color(ndc: vec2<f32>, pixel_height_ndc: f32) -> vec4<f32> {
    let ray = view_ray(ndc);
    let discs = sun_discs(ray.direction);
    // The angle the pixel spans (at the image's centre: tan θ ≈ θ over one pixel).
    let pixel_rad = pixel_height_ndc * view.camera_shape.w;
    let seen = bodies_seen(ray.origin, ray.direction, ray.near, pixel_rad);
    let body = seen.body;
    // A body under a few pixels across, in front of the nearest large one, by its share of the pixel.
    let small = seen.small;
    let body_air = body_air_sample(ray.origin, ray.direction, ray.near, select(NO_BODY_T, body.t, body.hit));
    // What lies beyond the bodies' airs: a body, or else the discs (hidden by the bodies).
    let behind_body_air = select(discs, body.radiance, body.hit);
    var beyond = body_air.radiance + body_air.transmittance * behind_body_air;
    var rings = ring_sample(ray.origin, ray.direction, ray.near);
    // Rings behind a body are hidden by it.
    rings.hit = rings.hit && !(body.hit && body.t < rings.t);
    let behind_air = rings.hit || body.hit || body_air.hit || small.coverage > 0.0 || any(discs > vec3<f32>(0.0));
    var radiance: vec3<f32>;
    // The air's transmittance along the ray, where something lies behind it.
    var through = vec3<f32>(0.0);
    if SKY_MODE == SKY_MODE_LUT {
        radiance = sky_radiance(ray.direction);
        // The transmittance only matters behind the air: most pixels skip its lookups.
        if behind_air {
            through = lut_transmittance(ray.direction);
        }
    } else if SKY_MODE == SKY_MODE_MARCH {
        let marched = marched_sky(ray);
        radiance = marched.radiance;
        through = marched.transmittance;
    } else {
        let blend = view.local_up.w;
        let marched = marched_sky(ray);
        radiance = mix(sky_radiance(ray.direction), marched.radiance, blend);
        if behind_air {
            through = mix(lut_transmittance(ray.direction), marched.transmittance, blend);
        }
    }
    // Where the ray enters and leaves the air: only a body, its air or the rings need it.
    var top = vec2<f32>(1.0, 0.0);
    if body.hit || body_air.hit || rings.hit {
        top = ellipsoid_hits(ray.origin, ray.direction, top_radii(), ray.c_top);
    }
    let misses_air = top.x > top.y || top.y <= ray.near;
    if body.hit && (misses_air || body.t < top.x) {
        // The body stands between the camera and the air: none of the air shows.
        radiance = vec3<f32>(0.0);
        through = vec3<f32>(1.0);
    } else if body_air.hit && (misses_air || body_air.entry < top.x) {
        // A body's air stands in front of the planet's, its body (or the discs) behind both.
        radiance = body_air.radiance + body_air.transmittance * radiance;
        through *= body_air.transmittance;
        beyond = behind_body_air;
    }
    if rings.hit {
        let ground = ellipsoid_hits(ray.origin, ray.direction, atmosphere.radii.xyz, ray.c_surface);
        let blocked = ground.x <= ground.y && ground.x > ray.near && ground.x < rings.t;
        let in_front = top.x > top.y || rings.t < top.x;
        if in_front {
            // The rings first, the air (and the ground, a body or the discs) behind them.
            radiance = rings.radiance + rings.transmittance * (radiance + beyond * through);
        } else if !blocked {
            radiance += through * (rings.radiance + rings.transmittance * beyond);
        } else {
            radiance += beyond * through;
        }
    } else {
        radiance += beyond * through;
    }
    if small.coverage > 0.0 {
        let air = ellipsoid_hits(ray.origin, ray.direction, top_radii(), ray.c_top);
        if air.x > air.y || air.y <= ray.near || small.t < air.x {
            // In front of the air: over everything.
            radiance = small.radiance + (1.0 - small.coverage) * radiance;
        } else {
            // Behind the air, hiding their share of what lies behind them.
            radiance += through * (small.radiance - small.coverage * beyond);
        }
    }
    // The half-float HDR target ends at 65504; a sun disc in cd/m² is far beyond.
    return vec4<f32>(min(to_linear_srgb(radiance), vec3<f32>(HDR_MAX)), 1.0);
}
