// atmosphere/eclipse.wgsl — how much of each sun the eclipsing bodies (the Moon at a real date)
// and the rings' shadow leave at a point: the GPU twin of firmament_core::atmosphere::eclipse, whose docs
// give the model (two flat discs, the sun limb-darkened, the partly covered rings by
// Gauss–Legendre after r = a + (b − a)(1 − cos φ)/2).
//
// Conventions: as atmosphere/common.wgsl. Bodies are `view.eclipsers[i]`: xyz = centre in the
// planet frame (m), w = radius (m); `view.sun_count.y` of them. Angles in radians; the discs'
// sizes and distances in units of the sun's angular radius.

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/rings
#import generated/constants

// How far from a point in an eclipse's umbra the light scattered into it is taken from at most
// (m): `multiple_scattering_visible_fraction`'s fitted reach.
const MULTIPLE_SCATTERING_REACH_M: f32 = 1.0e5;
// The visible fraction above which that average is the fraction at the point itself.
const MULTIPLE_SCATTERING_AVERAGED_BELOW: f32 = 0.2;

// The fraction of a limb-darkened disc (radius 1, linear limb darkening u) hidden by a disc of
// radius k whose centre lies d from its centre.
fn eclipse_hidden_fraction(d: f32, k: f32, u: f32) -> f32 {
    if k <= 0.0 || d >= 1.0 + k {
        return 0.0;
    }
    if k >= 1.0 + d {
        return 1.0;
    }
    let total = PI * (1.0 - u / 3.0);
    // The core every ring of which the body covers, in closed form.
    let core = clamp(k - d, 0.0, 1.0);
    let rim = 1.0 - core * core;
    let covered = PI * (1.0 - u) * core * core + 2.0 * PI * u / 3.0 * (1.0 - rim * sqrt(rim));
    let a = abs(d - k);
    let b = min(d + k, 1.0);
    var partial = 0.0;
    if b > a && d > 0.0 {
        for (var n = 0u; n < ECLIPSE_QUADRATURE_POINTS; n++) {
            let phi = 0.5 * PI * (ECLIPSE_NODES[n] + 1.0);
            let r = a + 0.5 * (b - a) * (1.0 - cos(phi));
            let jacobian = 0.25 * PI * (b - a) * sin(phi);
            let cos_theta = clamp((r * r + d * d - k * k) / (2.0 * r * d), -1.0, 1.0);
            let intensity = 1.0 - u * (1.0 - sqrt(max(1.0 - r * r, 0.0)));
            partial += ECLIPSE_WEIGHTS[n] * jacobian * intensity * 2.0 * acos(cos_theta) * r;
        }
    }
    return clamp((covered + partial) / total, 0.0, 1.0);
}

// The fraction of sun i's light that reaches planet-frame point p past the ball `body` (xyz
// centre, planet frame (m); w = radius (m)): 1 in full sunlight, 0 in the umbra or inside it.
fn eclipser_visible_fraction(p: vec3<f32>, i: u32, body: vec4<f32>) -> f32 {
    let s = view.suns[i].direction.xyz;
    let alpha = abs(view.suns[i].direction.w);
    let to_body = body.xyz - p;
    let distance = length(to_body);
    if distance <= body.w {
        return 0.0;
    }
    // atan2 keeps the precision acos loses for small angles.
    let separation = atan2(length(cross(to_body, s)), dot(to_body, s));
    let beta = asin(body.w / distance);
    if separation >= alpha + beta {
        return 1.0;
    }
    return 1.0 - eclipse_hidden_fraction(separation / alpha, beta / alpha, view.suns[i].irradiance.w);
}

// Whether eclipser (and body) e is the source of sun i's light, which it does not hide.
fn eclipser_is_source(e: u32, i: u32) -> bool {
    return view.suns[i].source.x == e + 1u;
}

// The fraction of sun i's light that reaches planet-frame point p past every eclipsing body but
// its source (their fractions multiply): 1 in full sunlight, 0 in the umbra.
fn sun_visible_fraction(p: vec3<f32>, i: u32) -> f32 {
    var visible = 1.0;
    for (var e = 0u; e < min(view.sun_count.y, MAX_ECLIPSERS); e++) {
        if eclipser_is_source(e, i) {
            continue;
        }
        visible *= eclipser_visible_fraction(p, i, view.eclipsers[e]);
        if visible == 0.0 {
            return 0.0;
        }
    }
    return visible;
}

// Sun i's spectral irradiance at the top of the atmosphere above p, after the eclipsing bodies
// and through the planet's rings (their shadow) (W·m⁻²·nm⁻¹).
fn sun_irradiance_at(p: vec3<f32>, i: u32) -> vec3<f32> {
    let past_rings = sun_irradiance_past_rings(p, i);
    if view.sun_count.y == 0u {
        return past_rings;
    }
    return past_rings * sun_visible_fraction(p, i);
}

// Sun i's spectral irradiance at the top of the atmosphere above p through the planet's rings
// (their shadow), before any eclipse (W·m⁻²·nm⁻¹).
fn sun_irradiance_past_rings(p: vec3<f32>, i: u32) -> vec3<f32> {
    return view.suns[i].irradiance.rgb * ring_transmittance(p, view.suns[i].direction.xyz);
}

// The share of sun i the light scattered more than once at p has seen, per model wavelength. In
// the umbra that light comes from the sunlit air around, so the visible fraction is averaged
// over points displaced horizontally from p in three directions, at the 2-point Gauss–Laguerre
// distances of an exponential law whose mean is the air's mean free path at p (1/`extinction`,
// m), each capped at MULTIPLE_SCATTERING_REACH_M. An empirical model, fitted and checked against
// the reference path tracer (docs/ATMOSPHERE.md, "Eclipses"). Where `here`, the visible fraction
// at p (sun_visible_fraction; 1 without eclipsers), exceeds MULTIPLE_SCATTERING_AVERAGED_BELOW,
// the penumbra is nearly linear over the reach and the average is `here` itself (blended in over
// the half below).
fn multiple_scattering_visible_fraction(p: vec3<f32>, i: u32, here: f32, extinction: vec3<f32>) -> vec3<f32> {
    if here >= MULTIPLE_SCATTERING_AVERAGED_BELOW {
        return vec3<f32>(here);
    }
    let up = normalize(p);
    let e1 = normalize(cross(up, select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(up.z) > 0.9)));
    let e2 = cross(up, e1);
    let nodes = array<f32, 2>(0.58578644, 3.41421356);
    let weights = array<f32, 2>(0.85355339, 0.14644661);
    let free_path = 1.0 / max(extinction, vec3<f32>(1e-9));
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < 2u; k++) {
        // The channels' distances, most often the same once capped: each ring is taken once.
        var last_r = -1.0;
        var ring = 0.0;
        for (var c = 0u; c < 3u; c++) {
            let r = min(nodes[k] * free_path[c], MULTIPLE_SCATTERING_REACH_M);
            if r != last_r {
                ring = 0.0;
                for (var a = 0u; a < 3u; a++) {
                    let angle = 2.0 * PI / 3.0 * f32(a);
                    ring += sun_visible_fraction(p + r * (cos(angle) * e1 + sin(angle) * e2), i) / 3.0;
                }
                last_r = r;
            }
            sum[c] += weights[k] * ring;
        }
    }
    let blend = smoothstep(0.5 * MULTIPLE_SCATTERING_AVERAGED_BELOW, MULTIPLE_SCATTERING_AVERAGED_BELOW, here);
    return mix(sum, vec3<f32>(here), blend);
}

// Whether the view ray from the camera along d meets an eclipsing body (which hides the suns'
// discs behind it).
fn meets_eclipser(d: vec3<f32>) -> bool {
    for (var e = 0u; e < min(view.sun_count.y, MAX_ECLIPSERS); e++) {
        let body = view.eclipsers[e];
        let to_body = body.xyz - view.camera.xyz;
        let along = dot(to_body, d);
        // The ray's closest approach to the centre.
        let off = length(cross(to_body, d));
        if along > 0.0 && off < body.w {
            return true;
        }
    }
    return false;
}
