// atmosphere/bodies.wgsl — the bodies beside the planet: where a view ray meets one and the
// light its ground sends back (its air: atmosphere/body_air.wgsl); the GPU twin of
// firmament_core::atmosphere::body, whose docs give the model (an opaque ellipsoid, Lambert or
// Lommel–Seeliger, its albedo uniform or patterned by the Moon's maria, lit through its own air
// and by its sky, shadowed by the planet as a ball of its volumetric mean radius or by the light
// of its shadow's table (a lunar eclipse's red), by the rings and by the other bodies; lit by
// the planet's sunlit face too, planet-shine; a map's albedo:
// firmament_core::atmosphere::body::map).
//
// Conventions: as atmosphere/common.wgsl. `view.bodies[i]` for i < `view.sun_count.w`; body i is
// also eclipser i (`view.eclipsers`), which its own shading skips. Radiance is spectral, per
// model wavelength, like the sky's.

#import atmosphere/bindings
#import atmosphere/body_hits
#import atmosphere/body_air_medium
#import atmosphere/common
#import common/ellipsoid
#import atmosphere/eclipse
#import atmosphere/rings
#import generated/constants

// What a view ray meets of the bodies: the nearest surface ahead and its radiance.
struct BodySample {
    hit: bool,
    t: f32,                // along the ray (m)
    radiance: vec3<f32>,
}

// The nearest body the ray o + t·d meets at t > near, lit; the ray's pixel spans `pixel_rad`
// radians (how sharp a body's map is read).
fn body_sample(o: vec3<f32>, d: vec3<f32>, near: f32, pixel_rad: f32) -> BodySample {
    let hit = nearest_body_hit(o, d, near);
    var out = BodySample(hit.hit, hit.t, vec3<f32>(0.0));
    if hit.hit {
        let p = o + hit.t * d;
        // From the camera: a far camera's rays start at their closest approach to the planet.
        out.radiance = body_radiance(hit.index, p, hit.local, d, pixel_rad * distance(p, view.camera.xyz));
    }
    return out;
}

// The radiance body i's surface point p (planet frame; `local` in the body's axes, from its
// centre) sends back along −d; the pixel there spans `pixel_m` metres across the ray.
fn body_radiance(i: u32, p: vec3<f32>, local: vec3<f32>, d: vec3<f32>, pixel_m: f32) -> vec3<f32> {
    let body = view.bodies[i];
    let to_local = body_from_planet(i);
    let radii = body.radii.xyz;
    let n_local = normalize(local / (radii * radii));
    let n = transpose(to_local) * n_local;
    let mu = max(dot(n, -d), 0.0);
    let law_code = u32(body.center.w);
    let air = body_has_air(i);
    var received = vec3<f32>(0.0);
    for (var s = 0u; s < view.sun_count.x; s++) {
        let to_sun = view.suns[s].direction.xyz;
        let mu0 = dot(n, to_sun);
        // Below the horizon only the sky of an air still lights the ground (twilight).
        if mu0 <= 0.0 && !air {
            continue;
        }
        let shadows = view.suns[s].irradiance.rgb * body_shadows_share(p, s, i) * ring_transmittance(p, to_sun);
        if mu0 > 0.0 {
            let law = body_law(law_code, mu0, mu, dot(to_sun, -d));
            received += shadows * body_air_transmittance(i, local, to_local * to_sun) * law;
        }
        if air {
            // The sky's light, taken as Lambertian (firmament_core's Body::skylight_radiance).
            received += shadows * body_air_sky(i, mu0);
        }
    }
    received += planetshine(p, n, -d, law_code);
    var albedo = body.albedo.rgb;
    let surface = u32(body.radii.w);
    if surface == BODY_SURFACE_LUNAR_MARIA {
        albedo *= lunar_albedo_factor(n_local);
    } else if surface == BODY_SURFACE_MAP {
        // The pixel's footprint on the ground, stretched by the slant (the geometric mean of its
        // two axes, 1 and 1/μ), in texels: the mip level whose texels match it.
        let footprint = pixel_m / sqrt(max(mu, 1.0 / 64.0)) / body.air.z;
        let lod = log2(max(footprint, 1.0));
        let texel = textureSampleLevel(body_maps, map_sampler, equirect_uv(n_local), i32(i), lod).rgb;
        albedo = min(albedo * texel, vec3<f32>(1.0));
    }
    return received * albedo / PI;
}

// The maria's factor on the albedo at the point with unit normal `n` in the body's axes
// (firmament_core::atmosphere::body::maria::albedo_factor).
fn lunar_albedo_factor(n: vec3<f32>) -> f32 {
    var mare = 0.0;
    for (var i = 0u; i < LUNAR_MARIA_COUNT; i++) {
        let mare_patch = LUNAR_MARIA[i];
        // atan2 keeps the precision acos loses for small angles.
        let angle = atan2(length(cross(n, mare_patch.xyz)), dot(n, mare_patch.xyz)) / mare_patch.w;
        mare = max(mare, 1.0 - smoothstep(LUNAR_EDGE_INNER, LUNAR_EDGE_OUTER, angle));
    }
    return mix(LUNAR_HIGHLAND_FACTOR, LUNAR_MARE_FACTOR, mare);
}

// A body's reflectance law `code` (BODY_REFLECTANCE_*) for incidence cosine mu0 (> 0), emergence
// cosine mu and the cosine of the phase angle between the light and the viewer: 1 at normal
// incidence seen face-on (firmament_core's Reflectance::factor times ::phase_factor).
fn body_law(code: u32, mu0: f32, mu: f32, cos_alpha: f32) -> f32 {
    if code == BODY_REFLECTANCE_LAMBERT {
        return mu0;
    }
    let lommel_seeliger = 2.0 * mu0 / (mu0 + mu);
    if code == BODY_REFLECTANCE_LUNAR {
        return lommel_seeliger * lunar_phase_factor(cos_alpha);
    }
    return lommel_seeliger;
}

// The Moon's factor on the Lommel–Seeliger law at the phase angle whose cosine is `cos_alpha`:
// its measured phase curve (Krisciunas & Schaefer 1991) over a Lommel–Seeliger ball's, held
// past LUNAR_PHASE_MAX_RAD (firmament_core::atmosphere::body::phase).
fn lunar_phase_factor(cos_alpha: f32) -> f32 {
    let alpha = min(acos(clamp(cos_alpha, -1.0, 1.0)), LUNAR_PHASE_MAX_RAD);
    let phi = degrees(alpha);
    let measured = pow(10.0, -0.4 * (0.026 * phi + 4e-9 * phi * phi * phi * phi));
    var ball = 1.0;
    if alpha >= 1e-6 {
        let half = 0.5 * alpha;
        ball = 1.0 - sin(half) * tan(half) * log(1.0 / tan(0.25 * alpha));
    }
    return measured / ball;
}

// The irradiance the planet's sunlit face casts at planet-frame point p, reflected by the law
// `law_code` at normal n towards `to_viewer`, per unit albedo: a point of light of geometric
// albedo `view.surface.z`, phase law of a Lambert sphere
// (firmament_core::atmosphere::body::planetshine).
fn planetshine(p: vec3<f32>, n: vec3<f32>, to_viewer: vec3<f32>, law_code: u32) -> vec3<f32> {
    let distance = length(p);
    let to_planet = -p / distance;
    let mu0 = dot(n, to_planet);
    if view.surface.z <= 0.0 || mu0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let law = body_law(law_code, mu0, max(dot(n, to_viewer), 0.0), dot(to_planet, to_viewer));
    let size = view.surface.w / distance;
    var received = vec3<f32>(0.0);
    for (var s = 0u; s < view.sun_count.x; s++) {
        let cos_alpha = clamp(dot(view.suns[s].direction.xyz, -to_planet), -1.0, 1.0);
        let alpha = acos(cos_alpha);
        let phase = (sin(alpha) + (PI - alpha) * cos_alpha) / PI;
        received += view.suns[s].irradiance.rgb * (view.surface.z * size * size * phase);
    }
    return received * law;
}

// The share of sun s's light that reaches point p of body `own`, per model wavelength: past the
// planet (a ball of its volumetric mean radius, or the light of its shadow's table where the body
// has one for this sun) and every other eclipser but the light's source; not the rings, which
// the callers take (firmament_core::atmosphere::body::shadows_share). Zero for the body's own
// light.
fn body_shadows_share(p: vec3<f32>, s: u32, own: u32) -> vec3<f32> {
    if eclipser_is_source(own, s) {
        return vec3<f32>(0.0);
    }
    var share = 1.0;
    for (var e = 0u; e < min(view.sun_count.y, MAX_ECLIPSERS); e++) {
        if e != own && !eclipser_is_source(e, s) {
            share *= eclipser_visible_fraction(p, s, view.eclipsers[e]);
        }
    }
    if u32(view.bodies[own].albedo.w) == s + 1u {
        return share * planet_shadow_light(own, p);
    }
    return vec3<f32>(share * eclipser_visible_fraction(p, s, vec4<f32>(0.0, 0.0, 0.0, view.surface.w)));
}

// The light body i's table of the planet's shadow gives at point p: linear between entries by
// the distance from the shadow's axis, 1 before the planet and beyond the last entry
// (firmament_core::atmosphere::body::BodyInShadow::light_at).
fn planet_shadow_light(i: u32, p: vec3<f32>) -> vec3<f32> {
    let shadow = view.bodies[i].shadow;
    let behind = dot(p, shadow.xyz);
    if behind <= 0.0 {
        return vec3<f32>(1.0);
    }
    let x = length(p - shadow.xyz * behind) / shadow.w;
    let k = u32(x);
    if k + 1u >= BODY_SHADOW_ENTRIES {
        return vec3<f32>(1.0);
    }
    return mix(view.body_shadows[i][k].rgb, view.body_shadows[i][k + 1u].rgb, x - f32(k));
}
