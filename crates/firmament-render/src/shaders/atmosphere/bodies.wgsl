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

// A body whose disc's angular radius is under this many pixels is drawn by the share of each
// pixel it covers (`bodies_seen`), not where the pixel's ray meets it: a Moon a pixel or two
// across then neither vanishes between pixel centres nor flickers as it moves.
const SMALL_BODY_RADIUS_PIXELS: f32 = 2.0;

// The points of a disc at which a small body's mean radiance is taken: a sunflower of this many,
// equal areas apart.
const SMALL_BODY_SAMPLES: u32 = 64u;

// Body i's disc seen from the camera: its angular radius (rad) and the distance to its centre
// (m), from the bounding sphere of its largest semi-axis.
fn body_disc(i: u32) -> vec2<f32> {
    let body = view.bodies[i];
    // From the camera: a far camera's rays start at their closest approach to the planet.
    let distance = length(body.center.xyz - view.camera.xyz);
    let reach = max(body.radii.x, max(body.radii.y, body.radii.z));
    return vec2<f32>(asin(min(reach / distance, 1.0)), distance);
}

fn is_small_body(i: u32, pixel_rad: f32) -> bool {
    return body_disc(i).x < SMALL_BODY_RADIUS_PIXELS * pixel_rad;
}

// The signed area of the disc of radius r about the origin within the quadrant between the axes
// and (x, y): the disc's area in any axis-aligned box is four of them, signed by the corners.
// For x, y ≥ 0: y·m + G(x) − G(m), m where the disc's chord height falls to y, G(t) = ∫₀ᵗ √(r² − u²) du.
fn disc_corner_area(x: f32, y: f32, r: f32) -> f32 {
    let ax = min(abs(x), r);
    let ay = min(abs(y), r);
    let m = min(ax, sqrt(max(r * r - ay * ay, 0.0)));
    let g_x = 0.5 * (ax * sqrt(max(r * r - ax * ax, 0.0)) + r * r * asin(clamp(ax / r, -1.0, 1.0)));
    let g_m = 0.5 * (m * sqrt(max(r * r - m * m, 0.0)) + r * r * asin(clamp(m / r, -1.0, 1.0)));
    return sign(x) * sign(y) * (ay * m + g_x - g_m);
}

// What a pixel sees of the bodies: the nearest large one its ray meets, and the nearest small one
// whose disc overlaps it (in front of the large one).
struct BodiesSeen {
    body: BodySample,
    small: SmallBody,
}

// A small body in a pixel: its mean radiance over its disc times the share of the pixel it covers
// (`radiance`), that share (`coverage`; 0: none), and the distance to its centre along the ray.
struct SmallBody {
    radiance: vec3<f32>,
    coverage: f32,
    t: f32,
}

// The bodies seen through the pixel whose ray is o + t·d (t > near) and which spans `pixel_rad`
// radians (how sharp a body's map is read). A large body is drawn where the ray meets it. A small
// one (SMALL_BODY_RADIUS_PIXELS) covers the exact area of the pixel's square its disc overlaps —
// the shares of neighbouring pixels add up to the disc's area wherever it stands, so its light is
// whole at any sub-pixel position — with its disc's mean radiance: rays along d through a
// sunflower of points on it. Both are shaded in one loop, so the shader holds one copy of a
// body's lighting (software rasterizers pay for every copy).
fn bodies_seen(o: vec3<f32>, d: vec3<f32>, near: f32, pixel_rad: f32) -> BodiesSeen {
    var hit = BodyHit(false, 0.0, 0u, vec3<f32>(0.0));
    for (var i = 0u; i < min(view.sun_count.w, MAX_BODIES); i++) {
        let candidate = body_hit(i, o, d, near);
        if candidate.hit && (!hit.hit || candidate.t < hit.t) && !is_small_body(i, pixel_rad) {
            hit = candidate;
        }
    }
    var out = BodiesSeen(BodySample(hit.hit, hit.t, vec3<f32>(0.0)), SmallBody(vec3<f32>(0.0), 0.0, 0.0));
    // The nearest small body whose disc overlaps the pixel, in front of the large one.
    var small = MAX_BODIES;
    var small_t = select(NO_BODY_T, hit.t, hit.hit);
    var off_ray = vec3<f32>(0.0);
    var reach = 0.0;
    let right = view.view_to_planet[0].xyz;
    let up = view.view_to_planet[1].xyz;
    for (var i = 0u; i < min(view.sun_count.w, MAX_BODIES); i++) {
        let disc = body_disc(i);
        if disc.x >= SMALL_BODY_RADIUS_PIXELS * pixel_rad {
            continue;
        }
        let body = view.bodies[i];
        let to_center = body.center.xyz - o;
        let along = dot(to_center, d);
        let off = to_center - along * d;
        // The disc's centre and radius in pixels from this pixel's centre.
        let pixels = 1.0 / (disc.y * pixel_rad);
        let offset = vec2<f32>(dot(off, right), dot(off, up)) * pixels;
        let radius = max(body.radii.x, max(body.radii.y, body.radii.z));
        let r = radius * pixels;
        if along <= near || along >= small_t || any(abs(offset) >= vec2<f32>(r + 0.5)) {
            continue; // behind, or the disc misses the pixel
        }
        // The pixel's square from the disc's centre, in pixels.
        let low = vec2<f32>(-0.5) - offset;
        let high = vec2<f32>(0.5) - offset;
        let overlap = disc_corner_area(high.x, high.y, r) - disc_corner_area(low.x, high.y, r)
            - disc_corner_area(high.x, low.y, r) + disc_corner_area(low.x, low.y, r);
        if overlap > 0.0 {
            small = i;
            small_t = along;
            off_ray = off;
            reach = radius;
            out.small.coverage = min(overlap, 1.0);
            out.small.t = along;
        }
    }
    let small_samples = select(0u, SMALL_BODY_SAMPLES, small < MAX_BODIES);
    let across = normalize(cross(d, select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(d.x) > 0.9)));
    let other = cross(d, across);
    var sum = vec3<f32>(0.0);
    var hits = 0u;
    // The small body's sunflower first, then the large body's hit.
    for (var k = 0u; k < small_samples + select(0u, 1u, hit.hit); k++) {
        var seen = hit;
        var start = o;
        if k < small_samples {
            let r = sqrt((f32(k) + 0.5) / f32(SMALL_BODY_SAMPLES)) * reach;
            let angle = f32(k) * 2.39996323; // the golden angle
            start = o + off_ray + (cos(angle) * across + sin(angle) * other) * r;
            seen = body_hit(small, start, d, near);
            if !seen.hit {
                continue;
            }
        }
        let p = start + seen.t * d;
        // From the camera: a far camera's rays start at their closest approach to the planet.
        let radiance = body_radiance(seen.index, p, seen.local, d, pixel_rad * distance(p, view.camera.xyz));
        if k < small_samples {
            sum += radiance;
            hits += 1u;
        } else {
            out.body.radiance = radiance;
        }
    }
    if hits > 0u {
        // An ellipsoid fills only the share of its bounding disc that the rays met.
        out.small.coverage *= f32(hits) / f32(SMALL_BODY_SAMPLES);
        out.small.radiance = sum / f32(hits) * out.small.coverage;
    } else {
        out.small.coverage = 0.0;
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
