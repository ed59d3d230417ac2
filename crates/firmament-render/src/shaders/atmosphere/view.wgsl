// atmosphere/view.wgsl — shared by the view-dependent atmosphere passes: the camera, the suns,
// the sky-view LUT mapping and the ray march.
//
// Conventions: as atmosphere/common.wgsl; every position and direction is in the planet frame,
// positions relative to the planet centre. The camera position is f32 (its altitude and its
// ellipsoid terms come exactly from f64); a camera far away never appears in a position at all
// (see common/view_ray.wgsl).

#import common/ellipsoid
#import common/view_ray
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/eclipse
#import atmosphere/surface
#import atmosphere/rings

const HDR_MAX: f32 = 65504.0; // largest half float (firmament_render::HDR_MAX)

const SKY_VIEW_LUT_SIZE: vec2<f32> = vec2<f32>(192.0, 108.0);

// Sun i's sky-view tile holds its radiance over 2^k, k = this (stored in the tile's alpha, an
// integer, so filtering keeps it exact): about 1/64 of the sky's mean radiance at the camera,
// sun i's brightest irradiance channel times the mean Ψ of the multiple-scattering LUT. So neither
// a dim light (the Moon, a millionth of the Sun) nor a sun far below the horizon (the sky falls
// ~e^70 per unit of mu_s) lets the half-float LUT's values fall among its subnormals, and the
// brightest sky (~100 × its mean, towards the sun) stays far below its largest value.
//
// An eclipse dims the sky by about the share of the sun the camera still sees; in totality the
// light comes from the air outside the shadow, ~1/4096 of the uneclipsed sky or more.
fn sky_view_exponent(i: u32) -> f32 {
    let e = view.suns[i].irradiance.rgb * max(sun_visible_fraction(view.camera.xyz, i), 1.0 / 4096.0);
    let mu_s = dot(view.local_up.xyz, view.suns[i].direction.xyz);
    let uv = mu_s_h_to_uv(mu_s, max(view.camera.w, 0.0), MULTISCATTERING_LUT_SIZE);
    let psi = decode_log(textureSampleLevel(multiscattering_lut, lut_sampler, uv, 0, 0.0).rgb);
    let mean = max(max(e.r, max(e.g, e.b)) * max(psi.r, max(psi.g, psi.b)), 1e-30);
    return round(log2(mean)) - 6.0;
}

// The sky-view LUT's frame for sun `i` at the camera: up, towards the sun's azimuth, and across.
struct SunFrame {
    up: vec3<f32>,
    toward: vec3<f32>,
    across: vec3<f32>,
}

fn sun_frame(i: u32) -> SunFrame {
    let up = view.local_up.xyz;
    let s = view.suns[i].direction.xyz;
    var toward = s - dot(s, up) * up;
    if dot(toward, toward) < 1e-12 {
        // The sun at the zenith or nadir: every azimuth is alike.
        toward = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(up.x) > 0.9);
        toward = toward - dot(toward, up) * up;
    }
    toward = normalize(toward);
    var f: SunFrame;
    f.up = up;
    f.toward = toward;
    f.across = cross(up, toward);
    return f;
}

// The zenith angle of the horizon seen from the camera, on the LUT sphere.
fn horizon_zenith_angle() -> vec2<f32> {
    let r = atmosphere.lut.x + max(view.camera.w, 0.01);
    let cos_beta = safe_sqrt(r * r - atmosphere.lut.x * atmosphere.lut.x) / r;
    let beta = acos(clamp(cos_beta, -1.0, 1.0));
    return vec2<f32>(PI - beta, beta); // (zenith angle of the horizon, angle below it to the nadir)
}

// Hillaire 2020's non-linear latitude mapping: v = 0.5 at the horizon, texels crowded there.
// u = relative azimuth to the sun / π (the sky is mirror-symmetric about the sun's vertical), or,
// with eclipsing bodies (`view.sun_count.z` = 1: their shadow need not be symmetric), the signed
// azimuth over the whole circle, (azimuth / π + 1) / 2.
fn full_circle_azimuth() -> bool {
    return view.sun_count.z == 1u;
}

fn sky_view_uv(d: vec3<f32>, frame: SunFrame) -> vec2<f32> {
    let horizon = horizon_zenith_angle();
    let zenith = acos(clamp(dot(d, frame.up), -1.0, 1.0));
    var v: f32;
    if zenith < horizon.x {
        v = (1.0 - sqrt(max(1.0 - zenith / horizon.x, 0.0))) * 0.5;
    } else {
        v = sqrt(clamp((zenith - horizon.x) / horizon.y, 0.0, 1.0)) * 0.5 + 0.5;
    }
    var u: f32;
    if full_circle_azimuth() {
        u = 0.5 * (atan2(dot(d, frame.across), dot(d, frame.toward)) / PI + 1.0);
    } else {
        u = atan2(abs(dot(d, frame.across)), dot(d, frame.toward)) / PI;
    }
    return vec2<f32>(unit_to_texel_coord(u, SKY_VIEW_LUT_SIZE.x), unit_to_texel_coord(v, SKY_VIEW_LUT_SIZE.y));
}

fn sky_view_direction(uv: vec2<f32>, frame: SunFrame) -> vec3<f32> {
    let horizon = horizon_zenith_angle();
    let u = texel_coord_to_unit(uv.x, SKY_VIEW_LUT_SIZE.x);
    let v = texel_coord_to_unit(uv.y, SKY_VIEW_LUT_SIZE.y);
    var zenith: f32;
    if v < 0.5 {
        let x = 1.0 - 2.0 * v;
        zenith = horizon.x * (1.0 - x * x);
    } else {
        let x = 2.0 * v - 1.0;
        zenith = horizon.x + horizon.y * x * x;
    }
    let azimuth = select(u * PI, (2.0 * u - 1.0) * PI, full_circle_azimuth());
    let horizontal = frame.toward * cos(azimuth) + frame.across * sin(azimuth);
    return frame.up * cos(zenith) + horizontal * sin(zenith);
}

// Whether a depth-buffer value is the far plane: 0 (reversed-Z) or 1 (standard), as
// `view.aerial.w` says.
fn at_far_plane(depth: f32) -> bool {
    return select(depth <= 0.0, depth >= 1.0, view.aerial.w > 0.5);
}

// The normalised device coordinates (x right, y up) of the centre of pixel `id` of a `size`-pixel
// image, for the compute passes (a full-screen draw gets them from common/fullscreen).
fn pixel_ndc(id: vec2<u32>, size: vec2<u32>) -> vec2<f32> {
    let uv = (vec2<f32>(id) + 0.5) / vec2<f32>(size);
    return vec2<f32>(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y);
}

// This pass's view ray (common/view_ray.wgsl).
fn view_ray(ndc: vec2<f32>) -> ViewRay {
    let planet = PlanetView(view.view_to_planet, view.camera, view.camera_shape, view.center);
    return planet_view_ray(ndc, planet, atmosphere.radii.xyz, top_radii());
}

// The radiance the lit ground at p (altitude h, normal `up`) sends towards `to_eye` from suns
// [first, first + count): direct sunlight and sky light on its Lambertian albedo, and each sun's
// glint on its water (atmosphere/surface.wgsl), all dimmed by any eclipse at p (the sky light by
// the share the air around has seen, as multiple scattering is), and the rings' light
// (atmosphere/rings.wgsl).
fn ground_radiance(p: vec3<f32>, h: f32, up: vec3<f32>, to_eye: vec3<f32>, first: u32, count: u32) -> vec3<f32> {
    let ground = ground_at(up);
    // The air's extinction only an eclipse needs (its mean free path).
    var extinction = vec3<f32>(0.0);
    if view.sun_count.y > 0u {
        extinction = coefficients_at(h).extinction;
    }
    var irradiance = vec3<f32>(0.0);
    var glint = vec3<f32>(0.0);
    for (var i = first; i < first + count; i++) {
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        let mu_s = dot(up, s);
        let beam = transmittance_to_sun(h, mu_s, abs(sun.direction.w));
        let direct = beam * max(mu_s, 0.0);
        let top = sun_irradiance_past_rings(p, i);
        let seen = sun_visible_fraction(p, i);
        let around = multiple_scattering_visible_fraction(p, i, seen, extinction);
        irradiance += top * (seen * direct + around * sky_irradiance(h, mu_s));
        glint += top * seen * beam * glint_factor(ground, up, s, to_eye);
        if has_rings() {
            irradiance += sun.irradiance.rgb * ring_light_irradiance(up, i);
        }
    }
    return ground.albedo / PI * irradiance + glint;
}

// The air's transmittance along a view ray from `start` (a point of it in the air: the camera,
// or where it enters the air from outside) to the ground point `ground` (altitude and up
// `at_ground`): Bruneton 2017's ratio of two transmittances to the top, both looking back up
// the ray.
fn transmittance_to_ground(d: vec3<f32>, start: vec3<f32>, at_ground: AltitudeUp) -> vec3<f32> {
    let entry = altitude_up(start);
    let r_start = atmosphere.lut.x + clamp(entry.h, 0.0, atmosphere.lut.y - atmosphere.lut.x);
    let through = transmittance_to_top(atmosphere.lut.x + max(at_ground.h, 0.0), dot(at_ground.up, -d))
        / max(transmittance_to_top(r_start, dot(entry.up, -d)), vec3<f32>(1e-30));
    return min(through, vec3<f32>(1.0));
}

// The medium at one point of a view ray along d: its extinction, the extinction scattered light
// meets (delta-M, see `Coefficients` in common.wgsl) and the light it scatters towards −d per unit
// length (all orders) from suns [first, first + count).
struct MediumSample {
    extinction: vec3<f32>,
    diffuse_extinction: vec3<f32>,
    source: vec3<f32>,
}

fn medium_sample(p: vec3<f32>, d: vec3<f32>, first: u32, count: u32) -> MediumSample {
    let here = altitude_up(p);
    let c = coefficients_at(here.h);
    var out: MediumSample;
    out.extinction = c.extinction;
    out.diffuse_extinction = c.diffuse_extinction;
    out.source = vec3<f32>(0.0);
    for (var i = first; i < first + count; i++) {
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        let mu_s = dot(here.up, s);
        let direct = transmittance_to_sun(here.h, mu_s, abs(sun.direction.w)) * scattering_phase(c, dot(d, s));
        // An eclipse dims the direct light by the share of the sun seen here, the light scattered
        // more than once by the share the air around has seen (docs/ATMOSPHERE.md, "Eclipses").
        let top = sun_irradiance_past_rings(p, i);
        let seen = sun_visible_fraction(p, i);
        let around = multiple_scattering_visible_fraction(p, i, seen, c.extinction);
        out.source += top * (seen * direct + around * multiple_scattering(c, here.h, here.up, s, d));
    }
    return out;
}

// `radiance`: the scattered light (and lit ground) reaching the start of a march; `transmittance`:
// the air's over the march, for what lies behind it (the sun's disc, space, the user's geometry).
struct MarchResult {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// Light scattered towards the start of o + t·d over t in [t0, t1] from suns [first, first + count),
// with `steps` midpoint samples (spread quadratically, denser at t0, when `dense_near`), plus the
// lit ground at t1 when `ground`. Scattered light and the ground's meet the diffuse extinction.
fn march(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, ground: bool, first: u32, count: u32, steps: i32, dense_near: bool) -> MarchResult {
    var result: MarchResult;
    result.radiance = vec3<f32>(0.0);
    result.transmittance = vec3<f32>(1.0);
    var diffuse_transmittance = vec3<f32>(1.0);
    let span = max(t1 - t0, 0.0);
    for (var k = 0; k < steps; k++) {
        var a = f32(k) / f32(steps);
        var b = f32(k + 1) / f32(steps);
        if dense_near {
            a = a * a;
            b = b * b;
        }
        let dt = (b - a) * span;
        let t = t0 + (a + b) * 0.5 * span;
        let here = medium_sample(o + d * t, d, first, count);
        let diffuse_step = exp(-here.diffuse_extinction * dt);
        result.radiance += diffuse_transmittance * integrate_step(here.source, here.diffuse_extinction, diffuse_step, dt);
        diffuse_transmittance *= diffuse_step;
        result.transmittance *= exp(-here.extinction * dt);
    }
    if ground {
        let end = o + d * t1;
        let here = altitude_up(end);
        result.radiance += diffuse_transmittance * ground_radiance(end, max(here.h, 0.0), here.up, -d, first, count);
    }
    return result;
}

// Linear sRGB (Y in cd/m²) of a spectral radiance.
fn to_linear_srgb(radiance: vec3<f32>) -> vec3<f32> {
    return mat3x3<f32>(view.to_srgb0.xyz, view.to_srgb1.xyz, view.to_srgb2.xyz) * radiance;
}

// ---- Aerial perspective ----
// The volume (Hillaire 2020, section 5.3) covers the view frustum: x, y as the screen (u right,
// v down), z the distance travelled through the air from where the pixel's ray enters it,
// `range · w²` for w in [0, 1] (slices crowd near the camera, where distances are short). Slice k
// holds the light scattered towards the camera over the first `range · ((k + ½)/N)²` metres and
// the transmittance over them, so a texel centre is exactly where its value was integrated.
// Stored as a 2D atlas of the slices side by side (see aerial_perspective_volume.wgsl).

const AERIAL_PERSPECTIVE_SIZE: vec3<u32> = vec3<u32>(32u, 32u, 32u);

// Where a view ray's air starts and ends for aerial perspective (t along the ray): equal when the
// ray misses the atmosphere. The ground does not end it: a froxel column just below the horizon
// meets the ground ~100 m out from a street, yet geometry on the ground kilometres away lies
// between it and the column above, and is filtered from both. Past the ground the column goes on
// through ground-level air (see `aerial_sample_point`), as Hillaire 2020's volume does by moving
// voxels under the ground up onto it.
fn aerial_span(ray: ViewRay) -> vec2<f32> {
    let top = ellipsoid_hits(ray.origin, ray.direction, top_radii(), ray.c_top);
    if top.x > top.y || top.y <= ray.near {
        return vec2<f32>(ray.near);
    }
    let start = max(top.x, ray.near);
    return vec2<f32>(start, max(top.y, start));
}

// Where the aerial-perspective volume samples the air for a point p of a column: p itself, or,
// under the ground, the point of the surface above it.
fn aerial_sample_point(p: vec3<f32>) -> vec3<f32> {
    let here = altitude_up(p);
    return select(p, p - here.up * here.h, here.h < 0.0);
}
