// sky_gradient.wgsl — the keyframed gradient sky of seed 002, with a sun disc and glow.
//
// Conventions: world frame is local East-North-Up (+z up); `dir` is a unit world-space view
// direction; `elevation` is asin(dir.z) in radians; every colour is linear RGB radiance. The f64
// reference is `firmament_core::gradient_sky::GradientSkyState::radiance`; keep the two in step.
// Drawn at the far plane (reversed-Z depth 0) with depth writes off, so anything already drawn
// stays in front.

#import common/fullscreen
#import generated/constants

struct GradientSky {
    // Clip space → camera-relative world position (inverse of projection × view rotation).
    clip_to_world: mat4x4<f32>,
    zenith: vec4<f32>,        // rgb; a unused
    upper: vec4<f32>,
    horizon: vec4<f32>,
    lower: vec4<f32>,
    ground: vec4<f32>,
    sun_direction: vec4<f32>, // xyz unit direction to the sun; w = angular radius (rad)
    sun_disc: vec4<f32>,      // rgb disc radiance; w = edge softness (fraction of radius)
    sun_glow: vec4<f32>,      // rgb glow radiance at the centre; w = glow falloff angle (rad)
    // x = zenith_start, y = horizon_half_width, z = ground_start (all elevations, rad);
    // w = blend (GRADIENT_BLEND_*)
    shape: vec4<f32>,
    // x = upper_exponent, y = lower_exponent, z = sun horizon fade half-width (rad), w unused
    exponents: vec4<f32>,
}

@group(0) @binding(0) var<uniform> sky: GradientSky;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

fn shape_weight(t: f32) -> f32 {
    let c = clamp(t, 0.0, 1.0);
    return select(c, c * c * (3.0 - 2.0 * c), u32(sky.shape.w) == GRADIENT_BLEND_SMOOTH);
}

fn band_color(elevation: f32) -> vec3<f32> {
    let zenith_start = sky.shape.x;
    let hw = sky.shape.y;
    let ground_start = sky.shape.z;
    if elevation >= zenith_start {
        return sky.zenith.rgb;
    }
    if elevation >= hw {
        let t = (elevation - hw) / (zenith_start - hw);
        return mix(sky.upper.rgb, sky.zenith.rgb, shape_weight(pow(t, sky.exponents.x)));
    }
    if elevation >= 0.0 {
        return mix(sky.horizon.rgb, sky.upper.rgb, shape_weight(elevation / hw));
    }
    if elevation >= -hw {
        return mix(sky.horizon.rgb, sky.lower.rgb, shape_weight(-elevation / hw));
    }
    if elevation > ground_start {
        let t = (-hw - elevation) / (-hw - ground_start);
        return mix(sky.lower.rgb, sky.ground.rgb, shape_weight(pow(t, sky.exponents.y)));
    }
    return sky.ground.rgb;
}

fn sun_radiance(dir: vec3<f32>, elevation: f32) -> vec3<f32> {
    // acos loses precision near 0; the sun is tiny, so measure the angle with atan2 instead.
    let s = sky.sun_direction.xyz;
    let angle = atan2(length(cross(dir, s)), dot(dir, s));
    let radius = sky.sun_direction.w;
    let coverage = 1.0 - smoothstep(radius * (1.0 - sky.sun_disc.w), radius, angle);
    let glow = exp(-angle / sky.sun_glow.w);
    let fade = sky.exponents.z;
    let above = smoothstep(-fade, fade, elevation);
    return (sky.sun_disc.rgb * coverage + sky.sun_glow.rgb * glow) * above;
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    // A point on the near plane (reversed-Z depth 1): finite even with an infinite far plane.
    let p = sky.clip_to_world * vec4<f32>(in.ndc, 1.0, 1.0);
    let dir = normalize(p.xyz / p.w);
    let elevation = asin(clamp(dir.z, -1.0, 1.0));
    return vec4<f32>(band_color(elevation) + sun_radiance(dir, elevation), 1.0);
}
