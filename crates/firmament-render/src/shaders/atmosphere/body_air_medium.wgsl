// atmosphere/body_air_medium.wgsl — what the air of a body beside the planet is made of and how
// much of a sun's light crosses it: altitude over the body, extinction, scattering, the
// transmittance towards a sun and the tables of its light scattered more than once and of its
// sky's light on the ground (firmament_core::atmosphere::body::air, whose docs give the model).
// The light the air scatters to the camera is atmosphere/body_air.wgsl.
//
// Conventions: as atmosphere/common.wgsl, but positions and directions here are in body i's
// axes, from its centre (`local`, as atmosphere/body_hits.wgsl gives them). Body i has air where
// `view.bodies[i].air.x` (its height, m) > 0; its terms are `view.body_air[i]`: molecules,
// aerosols, the absorbing gas. Altitude over a body is (|q| − 1)·R, q the point over its
// semi-axes and R its volumetric mean radius (`air.y`). A path through the air is summed at
// nodes crowded about its point nearest the centre (t = t_c ± L·u², u at midpoints), where the
// density peaks: a grazing path 4 000 km long holds the air of a few hundred km about it.

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common
#import generated/constants

// Nodes on each side of a sun path's nearest point.
const BODY_AIR_SUN_NODES: u32 = 6u;

fn body_has_air(i: u32) -> bool {
    return view.bodies[i].air.x > 0.0;
}

// The semi-axes of the top of body i's air.
fn body_air_top_radii(i: u32) -> vec3<f32> {
    let body = view.bodies[i];
    return body.radii.xyz * (1.0 + body.air.x / body.air.y);
}

// Altitude over body i of the point `local` (m).
fn body_air_altitude(i: u32, local: vec3<f32>) -> f32 {
    let body = view.bodies[i];
    return (length(local / body.radii.xyz) - 1.0) * body.air.y;
}

// Body i's air's extinction at altitude h (m⁻¹).
fn body_air_extinction(i: u32, h: f32) -> vec3<f32> {
    var total = vec3<f32>(0.0);
    for (var k = 0u; k < BODY_AIR_TERMS; k++) {
        let term = view.body_air[i][k];
        total += term.extinction.rgb * profile_density(term.profile, h);
    }
    return total;
}

// Body i's air's Σ σ_s·p at altitude h (m⁻¹·sr⁻¹), nu the cosine between the view ray and the
// direction to the sun: molecules by Rayleigh's phase, aerosols by theirs (Cornette–Shanks or
// Henyey–Greenstein; the gas does not scatter).
fn body_air_scattering_phase(i: u32, h: f32, nu: f32) -> vec3<f32> {
    let molecules = view.body_air[i][0];
    let aerosols = view.body_air[i][1];
    let g = aerosols.phase.x;
    let aerosol_phase = select(henyey_greenstein(g, nu), cornette_shanks(g, nu), u32(aerosols.scattering.w) == PHASE_CORNETTE_SHANKS);
    return molecules.scattering.rgb * (profile_density(molecules.profile, h) * rayleigh_phase(nu))
        + aerosols.scattering.rgb * (profile_density(aerosols.profile, h) * aerosol_phase);
}

// Body i's air's scattering coefficient at altitude h, every scatterer without its phase (m⁻¹).
fn body_air_scattering(i: u32, h: f32) -> vec3<f32> {
    let molecules = view.body_air[i][0];
    let aerosols = view.body_air[i][1];
    return molecules.scattering.rgb * profile_density(molecules.profile, h)
        + aerosols.scattering.rgb * profile_density(aerosols.profile, h);
}

// Body i's table `layer` (0: Ψ, 1: the sky's light on the ground) at the sun's zenith cosine
// mu_s and the altitude h: its nodes lie at texel centres (bindings.wgsl `body_air_light`).
fn body_air_light_at(i: u32, layer: u32, mu_s: f32, h: f32) -> vec3<f32> {
    let size = vec2<f32>(textureDimensions(body_air_light));
    let x = clamp(vec2<f32>(0.5 * (mu_s + 1.0), h / view.bodies[i].air.x), vec2<f32>(0.0), vec2<f32>(1.0));
    let uv = (0.5 + x * (size - 1.0)) / size;
    return textureSampleLevel(body_air_light, lut_sampler, uv, i32(2u * i + layer), 0.0).rgb;
}

// The light body i's air scatters more than once at altitude h under a sun at zenith cosine
// mu_s, per unit irradiance (sr⁻¹): Hillaire 2020's Ψ (firmament_core::atmosphere::body::AirLight).
fn body_air_multiple(i: u32, h: f32, mu_s: f32) -> vec3<f32> {
    return body_air_light_at(i, 0u, mu_s, h);
}

// The irradiance body i's sky casts on its horizontal ground under a sun at zenith cosine mu_s,
// per unit irradiance of that sun.
fn body_air_sky(i: u32, mu_s: f32) -> vec3<f32> {
    return body_air_light_at(i, 1u, mu_s, 0.0);
}

// Node k of 2n along [t0, t1] crowded about t_c (within it), near to far: its t and its length.
fn body_air_node(t0: f32, tc: f32, t1: f32, k: u32, n: u32) -> vec2<f32> {
    let before = k < n;
    let j = select(k - n, n - 1u - k, before);
    let u = (f32(j) + 0.5) / f32(n);
    let span = select(t1 - tc, tc - t0, before);
    let t = tc + select(1.0, -1.0, before) * span * u * u;
    return vec2<f32>(t, 2.0 * span * u / f32(n));
}

// Where along the line local + t·d the point nearest body i's centre (over its semi-axes) lies.
fn body_air_nearest(i: u32, local: vec3<f32>, d: vec3<f32>) -> f32 {
    let radii = view.bodies[i].radii.xyz;
    let q = local / radii;
    let e = d / radii;
    return -dot(q, e) / dot(e, e);
}

// The transmittance of body i's air from `local` along the unit `d` (body axes) to its top: 0
// where the path meets the body (the core's Body::air_transmittance).
fn body_air_transmittance(i: u32, local: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if !body_has_air(i) {
        return vec3<f32>(1.0);
    }
    let radii = view.bodies[i].radii.xyz;
    let ground = ellipsoid_hits(local, d, radii, ellipsoid_c(local, radii));
    if ground.x <= ground.y && ground.x > 0.0 {
        return vec3<f32>(0.0);
    }
    let top_radii = body_air_top_radii(i);
    let top = ellipsoid_hits(local, d, top_radii, ellipsoid_c(local, top_radii));
    let t0 = max(top.x, 0.0);
    if top.x > top.y || top.y <= t0 {
        return vec3<f32>(1.0);
    }
    let tc = clamp(body_air_nearest(i, local, d), t0, top.y);
    var depth = vec3<f32>(0.0);
    for (var k = 0u; k < 2u * BODY_AIR_SUN_NODES; k++) {
        let node = body_air_node(t0, tc, top.y, k, BODY_AIR_SUN_NODES);
        depth += body_air_extinction(i, body_air_altitude(i, local + node.x * d)) * node.y;
    }
    return exp(-depth);
}
