// atmosphere/rings.wgsl — a planet's rings: their optical depth, the light they let through and
// the light they scatter; the GPU twin of firmament_core::atmosphere::rings, whose docs give the
// model (a thin slab in the planet frame's z = 0 plane; single scattering, Henyey–Greenstein).
//
// Conventions: as atmosphere/common.wgsl. `view.rings`: x, y = inner and outer radius (m),
// z = g, w = 1 with rings; `view.ring_depth`: the normal optical depth table, linear between
// entries. `ring_light`: their light on the ground per sun, a table over the globe (bindings.wgsl).

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common

fn has_rings() -> bool {
    return view.rings.w > 0.5;
}

// The normal optical depth at radius r (m) in the plane: 0 off the rings.
fn ring_optical_depth(r: f32) -> f32 {
    let inner = view.rings.x;
    let outer = view.rings.y;
    if r < inner || r >= outer {
        return 0.0;
    }
    let x = (r - inner) / (outer - inner) * f32(RING_TABLE_ENTRIES - 1u);
    let i = min(u32(floor(x)), RING_TABLE_ENTRIES - 2u);
    let a = view.ring_depth[i / 4u][i % 4u];
    let b = view.ring_depth[(i + 1u) / 4u][(i + 1u) % 4u];
    return mix(a, b, x - f32(i));
}

// Where the ray o + t·d crosses the ring plane: (t, r), t < 0 when it does not ahead of o.
fn ring_crossing(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    if d.z == 0.0 {
        return vec2<f32>(-1.0, 0.0);
    }
    let t = -o.z / d.z;
    return vec2<f32>(t, length((o + d * t).xy));
}

// The share of light the rings let through along the ray from o along d (1 off the rings).
fn ring_transmittance(o: vec3<f32>, d: vec3<f32>) -> f32 {
    if !has_rings() {
        return 1.0;
    }
    let hit = ring_crossing(o, d);
    if hit.x <= 0.0 {
        return 1.0;
    }
    return exp(-ring_optical_depth(hit.y) / abs(d.z));
}

fn ring_henyey_greenstein(g: f32, nu: f32) -> f32 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    return (1.0 - g * g) / (4.0 * PI * denominator * sqrt(denominator));
}

// The rings seen along a view ray: the light they scatter towards the viewer, the share of what
// lies behind them they let through, and where the ray crosses them (`hit` false: it does not).
struct RingSample {
    radiance: vec3<f32>,
    transmittance: f32,
    t: f32,
    hit: bool,
}

// The rings where the ray o + t·d crosses them at t > near (o need not be the camera: far away
// it is the ray's closest approach to the centre, `near` < 0): lit by every sun the globe does not
// hide from that point, each sun's light E times ϖ·p·(the slab's single scattering).
fn ring_sample(o: vec3<f32>, d: vec3<f32>, near: f32) -> RingSample {
    var out: RingSample;
    out.radiance = vec3<f32>(0.0);
    out.transmittance = 1.0;
    out.t = 0.0;
    out.hit = false;
    if !has_rings() {
        return out;
    }
    let hit = ring_crossing(o, d);
    let tau = ring_optical_depth(hit.y);
    if hit.x <= near || tau <= 0.0 {
        return out;
    }
    out.t = hit.x;
    out.hit = true;
    let mu = abs(d.z);
    out.transmittance = exp(-tau / mu);
    let x = o + d * hit.x;
    let c = ellipsoid_c(x, atmosphere.radii.xyz);
    for (var i = 0u; i < view.sun_count.x; i++) {
        let s = view.suns[i].direction.xyz;
        let mu0 = abs(s.z);
        let globe = ellipsoid_hits(x, s, atmosphere.radii.xyz, c);
        if mu0 <= 0.0 || (globe.x <= globe.y && globe.y > 0.0) {
            continue; // in the globe's shadow
        }
        var slab: f32;
        if (d.z > 0.0) != (s.z > 0.0) {
            slab = mu0 / (mu0 + mu) * (1.0 - exp(-tau * (1.0 / mu + 1.0 / mu0)));
        } else if abs(mu0 - mu) < 1e-6 {
            slab = mu0 * tau / (mu * mu) * exp(-tau / mu);
        } else {
            slab = mu0 / (mu0 - mu) * (exp(-tau / mu0) - exp(-tau / mu));
        }
        let phase = ring_henyey_greenstein(view.rings.z, dot(s, d));
        out.radiance += view.suns[i].irradiance.rgb * view.ring_albedo.rgb * (phase * slab);
    }
    return out;
}

// The light the rings scatter from sun i onto the ground with geodetic normal `up`, through the
// air (irradiance per unit of the sun's): the core's Rings::light_table, relative to the sun's
// azimuth.
fn ring_light_irradiance(up: vec3<f32>, i: u32) -> vec3<f32> {
    let s = view.suns[i].direction.xyz;
    let azimuth = abs(atan2(up.x * s.y - up.y * s.x, up.x * s.x + up.y * s.y));
    // Rows crowd at the equator: v − ½ goes as the square root of the latitude.
    let latitude = asin(clamp(up.z, -1.0, 1.0));
    let uv = vec2<f32>(azimuth / PI, 0.5 + 0.5 * sign(latitude) * sqrt(abs(latitude) / (0.5 * PI)));
    return textureSampleLevel(ring_light, lut_sampler, uv, i, 0.0).rgb;
}
