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

// The fraction of sun i's light that reaches planet-frame point p past every eclipsing body
// (their fractions multiply): 1 in full sunlight, 0 in the umbra.
fn sun_visible_fraction(p: vec3<f32>, i: u32) -> f32 {
    var visible = 1.0;
    for (var e = 0u; e < min(view.sun_count.y, MAX_ECLIPSERS); e++) {
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
    let rings = ring_transmittance(p, view.suns[i].direction.xyz);
    if view.sun_count.y == 0u {
        return view.suns[i].irradiance.rgb * rings;
    }
    return view.suns[i].irradiance.rgb * (rings * sun_visible_fraction(p, i));
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
