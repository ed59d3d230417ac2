// classic_lighting.wgsl — objects lit by the OpenGL 2.1 fixed-function equations (seeds 001, 004).
//
// Conventions: every lighting vector is in GL *eye space* (camera at the origin looking down -z),
// as the GL specification states the equations; `n` is the unit normal, `to_light` the unit
// vector from the point to the light. Colours are GL RGBA, clamped to [0, 1] where GL clamps.
// The f64 references are `firmament_core::classic::{lighting::Lighting::shade, fog}`; keep them in
// step. Depth is firmament's reversed-Z: the projection maps near to 1.
// Shading (`frame.mode.x`): SHADING_GOURAUD (lit per vertex, colours interpolated),
// SHADING_PHONG (lit per fragment), SHADING_UNLIT (the front diffuse colour). Flat shading is
// Gouraud over a mesh whose vertices carry their triangle's provoking (GL: last) vertex as
// `shade_*` (see `GpuMesh`), so all three light the same point and no flat interpolation
// qualifier (WGSL's takes the first vertex) is involved.
// Under a physical sky (`mode.z` = 1) three things go past GL, all off in classic scenes: sun
// shadows (shadow/sampling.wgsl; per fragment, so Phong only), the clouds' shadows on the suns'
// beams (`cloud_visibility`, per vertex or fragment as the shading) and, with a ground
// (`ground_mode.x` = 1), an ambient term by view factors — the sky's light over (1 + n·up)/2,
// the ground's bounce over (1 − n·up)/2 (`firmament_core::classic::ground`).

#import generated/constants
#import shadow/sampling

const MAX_LIGHTS: u32 = 8u;

struct ClassicLight {
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    specular: vec4<f32>,
    position: vec4<f32>,       // eye space; w = 0 directional
    spot_direction: vec4<f32>, // xyz eye space; w = cos(cutoff), or -2 for no spot (cutoff 180)
    // x = spot exponent, y/z/w = constant/linear/quadratic attenuation
    spot_attenuation: vec4<f32>,
}

struct ClassicMaterial {
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    specular: vec4<f32>,
    emission: vec4<f32>,
    shininess: vec4<f32>, // x = shininess; yzw unused
}

struct ClassicFrame {
    projection: mat4x4<f32>,
    scene_ambient: vec4<f32>,
    // x = light count, y = local viewer, z = two-sided, w = separate specular
    model_flags: vec4<u32>,
    // x = shading (SHADING_*), y = specular model (SPECULAR_*), z = 1: radiance under a physical
    // sky, never clamped to [0, 1], w = 1: vertex colours are not clamped (GL_CLAMP_VERTEX_COLOR
    // off): Gouraud interpolates them as lit, and only the fragment stage clamps
    mode: vec4<u32>,
    // Fog: x = equation (FOG_*: GL 2.1 §3.10's, or height fog), y = coordinate (FOG_COORDINATE_*:
    // eye-plane depth |z_eye|, eye distance, or the vertex's own fog coordinate, GL_FOG_COORD),
    // computed per vertex and interpolated; the factor is computed per fragment, as GL
    // implementations do. z = 1: height fog in-scatters `fog_sun`.
    fog_mode: vec4<u32>,
    // Linear/exp/exp2: x = start, y = end, z = density.
    // Height fog: x = extinction at the camera (1/m), y = falloff (1/m).
    fog_params: vec4<f32>,
    fog_color: vec4<f32>,
    // World +z in eye space (for height fog); w unused.
    eye_up: vec4<f32>,
    // Height fog's sun: xyz = unit direction to it (eye space), w = lobe exponent.
    fog_sun: vec4<f32>,
    fog_sun_color: vec4<f32>,
    // World up in eye space; w = the camera's height above the ground patch (m).
    ground_up: vec4<f32>,
    // The ground's radiance from the suns (unshadowed) and from the sky (cd/m², linear sRGB).
    bounced_sun: vec4<f32>,
    bounced_sky: vec4<f32>,
    // x = 1: the view-factor ambient (scene_ambient is the sky's part on a horizontal surface)
    ground_mode: vec4<u32>,
    lights: array<ClassicLight, MAX_LIGHTS>,
}

struct ClassicObject {
    model_view: mat4x4<f32>,
    // Inverse transpose of the model-view's upper 3×3, as three columns (GL's normal matrix).
    normal_matrix: mat3x3<f32>,
    front: ClassicMaterial,
    back: ClassicMaterial,
    // x = textured (GL_MODULATE), y = the mesh has per-vertex fog coordinates, z = how many
    // `light_colors` replace the lights' diffuse and specular colours (suns at this object)
    flags: vec4<u32>,
    // x = the object's current fog coordinate (glFogCoord), for meshes without their own
    fog_coord: vec4<f32>,
    light_colors: array<vec4<f32>, MAX_LIGHTS>,
}

@group(0) @binding(0) var<uniform> frame: ClassicFrame;
@group(0) @binding(1) var<uniform> object: ClassicObject;
@group(0) @binding(2) var object_texture: texture_2d<f32>;
@group(0) @binding(3) var object_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) tex_coord: vec2<f32>,
    // The point lit for this vertex: itself, or its triangle's provoking vertex (flat shading).
    @location(3) shade_position: vec3<f32>,
    @location(4) shade_normal: vec3<f32>,
    // GL_FOG_COORD from the mesh (0 where it has none; `object.flags.y` says which).
    @location(5) fog_coord: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) eye_position: vec3<f32>,
    @location(1) eye_normal: vec3<f32>,
    // Gouraud: the lit colours of both sides (GL lights front and back per vertex).
    @location(2) front_primary: vec4<f32>,
    @location(3) front_secondary: vec4<f32>,
    @location(4) back_primary: vec4<f32>,
    @location(5) back_secondary: vec4<f32>,
    @location(6) fog_coordinate: f32,
    @location(7) tex_coord: vec2<f32>,
}

struct Lit {
    primary: vec4<f32>,
    secondary: vec4<f32>,
}

// The ambient light on a surface of unit eye-space normal n at eye-space point p: GL's scene
// ambient, or under a physical sky with a ground the sky and the ground by their view factors,
// the ground's sunlit part shadowed as at the ground point below p (`shadowed`: per fragment).
fn ambient_light(p: vec3<f32>, n: vec3<f32>, shadowed: bool) -> vec4<f32> {
    if frame.ground_mode.x == 0u {
        return frame.scene_ambient;
    }
    let up = frame.ground_up.xyz;
    let up_facing = 0.5 * (1.0 + dot(n, up));
    var sun = 1.0;
    if shadowed && frame.model_flags.x > 0u {
        // The point of the ground plane straight below p (the plane lies camera height below
        // the eye), lit by the first sun as that ground sees it.
        let below = p - up * (dot(p, up) + frame.ground_up.w);
        sun = shadow_visibility(0u, below, up, normalize(frame.lights[0].position.xyz));
    }
    if frame.model_flags.x > 0u {
        sun *= cloud_visibility(0u, p - up * (dot(p, up) + frame.ground_up.w));
    }
    let ground = frame.bounced_sky.rgb + frame.bounced_sun.rgb * sun;
    return vec4<f32>(frame.scene_ambient.rgb * up_facing + ground * (1.0 - up_facing), 1.0);
}

fn shade(position: vec3<f32>, normal: vec3<f32>, back: bool, shadowed: bool) -> Lit {
    var m = object.front;
    var n = normalize(normal);
    if back {
        m = object.back;
        n = -n;
    }
    var color = m.emission + m.ambient * ambient_light(position, n, shadowed);
    var specular_sum = vec4<f32>(0.0);
    let to_eye = normalize(-position);
    let local_viewer = frame.model_flags.y != 0u;
    let eye = select(vec3<f32>(0.0, 0.0, 1.0), to_eye, local_viewer);
    let count = min(frame.model_flags.x, MAX_LIGHTS);
    for (var i = 0u; i < count; i = i + 1u) {
        var light = frame.lights[i];
        if i < object.flags.z {
            light.diffuse = object.light_colors[i];
            light.specular = object.light_colors[i];
        }
        var to_light: vec3<f32>;
        var attenuation = 1.0;
        if light.position.w == 0.0 {
            to_light = normalize(light.position.xyz);
        } else {
            let d = light.position.xyz / light.position.w - position;
            let dist = length(d);
            to_light = d / dist;
            let k = light.spot_attenuation.y + light.spot_attenuation.z * dist + light.spot_attenuation.w * dist * dist;
            attenuation = select(0.0, 1.0 / k, k > 0.0);
        }
        var spot = 1.0;
        if light.spot_direction.w > -1.5 {
            let cos_angle = dot(-to_light, normalize(light.spot_direction.xyz));
            spot = select(0.0, pow(max(cos_angle, 0.0), light.spot_attenuation.x), cos_angle >= light.spot_direction.w);
        }
        let factor = attenuation * spot;
        // A shadow hides the light's direct part (diffuse and specular), not its ambient term.
        // The clouds' shadow hides a sun's beam on every object (its colour is the beam through
        // the clear air).
        var direct = factor * cloud_visibility(i, position);
        if shadowed {
            direct *= shadow_visibility(i, position, n, to_light);
        }
        let n_dot_l = max(dot(n, to_light), 0.0);
        color = color + factor * m.ambient * light.ambient + direct * n_dot_l * m.diffuse * light.diffuse;
        if n_dot_l != 0.0 {
            var s: f32;
            if frame.mode.y == SPECULAR_BLINN {
                s = max(dot(n, normalize(to_light + eye)), 0.0);
            } else {
                s = max(dot(reflect(-to_light, n), eye), 0.0);
            }
            let power = select(pow(s, m.shininess.x), 1.0, m.shininess.x == 0.0);
            specular_sum = specular_sum + direct * power * m.specular * light.specular;
        }
    }
    let spec = vec4<f32>(specular_sum.rgb, 0.0);
    var out: Lit;
    if frame.model_flags.w != 0u {
        out.primary = vec4<f32>(color.rgb, m.diffuse.a);
        out.secondary = spec;
    } else {
        out.primary = vec4<f32>(color.rgb + spec.rgb, m.diffuse.a);
        out.secondary = vec4<f32>(0.0);
    }
    return out;
}

// GL's clamp of both colours to [0, 1]: after lighting (vertex colour clamping) and as the
// fragment stage takes them (fragment colour clamping, on for fixed-point framebuffers).
fn clamped(lit: Lit) -> Lit {
    var out: Lit;
    out.primary = clamp(lit.primary, vec4<f32>(0.0), vec4<f32>(1.0));
    out.secondary = clamp(lit.secondary, vec4<f32>(0.0), vec4<f32>(1.0));
    return out;
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    let eye = object.model_view * vec4<f32>(in.position, 1.0);
    var out: VertexOut;
    out.clip = frame.projection * eye;
    out.eye_position = eye.xyz / eye.w;
    out.eye_normal = object.normal_matrix * in.normal;
    out.tex_coord = in.tex_coord;
    if frame.fog_mode.y == FOG_COORDINATE_VERTEX {
        out.fog_coordinate = select(object.fog_coord.x, in.fog_coord, object.flags.y != 0u);
    } else {
        out.fog_coordinate = select(
            abs(out.eye_position.z),
            length(out.eye_position),
            frame.fog_mode.y == FOG_COORDINATE_EYE_DISTANCE,
        );
    }
    if frame.mode.x == SHADING_GOURAUD {
        let shade_eye = object.model_view * vec4<f32>(in.shade_position, 1.0);
        let p = shade_eye.xyz / shade_eye.w;
        let n = object.normal_matrix * in.shade_normal;
        let clamp_vertex = frame.mode.z == 0u && frame.mode.w == 0u;
        var front = shade(p, n, false, false);
        if clamp_vertex {
            front = clamped(front);
        }
        out.front_primary = front.primary;
        out.front_secondary = front.secondary;
        // The back colours are only read with two-sided lighting; don't pay for them otherwise.
        if frame.model_flags.z != 0u {
            var back = shade(p, n, true, false);
            if clamp_vertex {
                back = clamped(back);
            }
            out.back_primary = back.primary;
            out.back_secondary = back.secondary;
        } else {
            out.back_primary = front.primary;
            out.back_secondary = front.secondary;
        }
    }
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let back = frame.model_flags.z != 0u && !front_facing;
    var lit: Lit;
    if frame.mode.x == SHADING_GOURAUD {
        lit.primary = select(in.front_primary, in.back_primary, back);
        lit.secondary = select(in.front_secondary, in.back_secondary, back);
    } else if frame.mode.x == SHADING_PHONG {
        lit = shade(in.eye_position, in.eye_normal, back, shadows.counts.w != 0u);
    } else {
        // Lighting off: the current colour (clamped below); no secondary colour.
        lit.primary = object.front.diffuse;
        lit.secondary = vec4<f32>(0.0);
    }
    // The fragment stage's clamp; for Gouraud colours it only acts when the vertices left them
    // unclamped (GL_CLAMP_VERTEX_COLOR off), so values above 1 took full part in interpolation.
    if frame.mode.z == 0u {
        lit = clamped(lit);
    }
    // Sampled unconditionally (uniform control flow), used only when textured.
    let texel = textureSample(object_texture, object_sampler, in.tex_coord);
    var primary = lit.primary;
    if object.flags.x != 0u {
        primary = primary * texel; // GL_MODULATE
    }
    // GL's colour sum: the secondary (separate specular) colour added after texturing, clamped
    // (radiance under a physical sky is not).
    var color = vec4<f32>(primary.rgb + lit.secondary.rgb, clamp(primary.a, 0.0, 1.0));
    if frame.mode.z == 0u {
        color = clamp(color, vec4<f32>(0.0), vec4<f32>(1.0));
    }
    return apply_fog(color, in.fog_coordinate, in.eye_position);
}

// GL 2.1 eq. 3.16–3.18 (f keeps the fragment colour; alpha untouched), or height fog: the
// transmittance exp(-τ) of the eye ray through density σ(h) = σ_cam·exp(-k·(h - h_cam)),
// τ = σ_cam·L·(1 - exp(-k·Δh))/(k·Δh) in closed form (`HeightFog::optical_depth`), in-scattering
// the fog colour plus the sun's lobe `FogSun::inscattered`.
fn apply_fog(color: vec4<f32>, c: f32, eye_position: vec3<f32>) -> vec4<f32> {
    let mode = frame.fog_mode.x;
    if mode == FOG_NONE {
        return color;
    }
    let start = frame.fog_params.x;
    let end = frame.fog_params.y;
    let density = frame.fog_params.z;
    var f: f32;
    if mode == FOG_LINEAR {
        f = select((end - c) / (end - start), select(0.0, 1.0, c < end), end == start);
    } else if mode == FOG_EXP {
        f = exp(-density * c);
    } else if mode == FOG_EXP2 {
        f = exp(-(density * c) * (density * c));
    } else {
        let length_m = length(eye_position);
        let x = frame.fog_params.y * dot(eye_position, frame.eye_up.xyz);
        // (1 - e^-x)/x, with its series near 0 where the division cancels (error < 1e-9 there;
        // the f32 quotient's relative error beyond is < 1e-5).
        let ratio = select((1.0 - exp(-x)) / x, 1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0, abs(x) < 1e-2);
        f = exp(-frame.fog_params.x * length_m * ratio);
    }
    f = clamp(f, 0.0, 1.0);
    var fog_color = frame.fog_color.rgb;
    if mode == FOG_HEIGHT && frame.fog_mode.z != 0u {
        let lobe = pow(max(dot(normalize(eye_position), frame.fog_sun.xyz), 0.0), frame.fog_sun.w);
        fog_color = fog_color + frame.fog_sun_color.rgb * lobe;
    }
    return vec4<f32>(mix(fog_color, color.rgb, f), color.a);
}
