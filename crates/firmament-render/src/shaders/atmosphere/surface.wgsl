// atmosphere/surface.wgsl — shared: the planet's ground, what it is made of and how it reflects
// the suns (firmament_core::atmosphere::surface, its f32 mirror).
//
// Conventions: as atmosphere/common.wgsl. Without a surface (`view.surface.x` = 0) the ground is
// the medium's `ground_albedo` everywhere, with no water: everything here then reduces to the
// Lambertian ground the atmosphere passes had before surfaces.

#import common/ellipsoid
#import atmosphere/bindings
#import atmosphere/common

// Water's refractive index (firmament_core glint::WATER_REFRACTIVE_INDEX).
const WATER_REFRACTIVE_INDEX: f32 = 1.34;

// The ground at one point: its Lambertian albedo (rgb) and the share of it that is water.
struct Ground {
    albedo: vec3<f32>,
    water: f32,
}

fn has_surface() -> bool {
    return view.surface.x > 0.5;
}

// The ground at the point whose geodetic up is `up` (the core's Surface::at).
fn ground_at(up: vec3<f32>) -> Ground {
    if !has_surface() {
        return Ground(atmosphere.ground_albedo.rgb, 0.0);
    }
    let texel = textureSampleLevel(surface_map, map_sampler, equirect_uv(up), 0.0);
    return Ground(texel.rgb, texel.a);
}

// Fresnel's unpolarised reflectance from air into index n at incidence cosine c (the core's
// glint::fresnel_reflectance).
fn fresnel_reflectance(cos_incidence: f32, n: f32) -> f32 {
    let c = clamp(cos_incidence, 0.0, 1.0);
    let g = sqrt(n * n - 1.0 + c * c);
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

// Smith's share of facets seen at zenith cosine mu (the core's glint::smith_visible).
fn smith_visible(mu: f32, sigma2: f32) -> f32 {
    if mu <= 0.0 {
        return 0.0;
    }
    let a = mu / (sqrt(sigma2) * sqrt(max(1.0 - mu * mu, 1e-12)));
    if a >= 1.6 {
        return 1.0;
    }
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// The sea's glint BRDF (sr⁻¹) for light from `s` seen from `v` over mean normal `up`, mean square
// slope `sigma2`: Cox–Munk slopes as Beckmann facets, Fresnel, Smith (the core's glint::brdf).
fn glint_brdf(up: vec3<f32>, s: vec3<f32>, v: vec3<f32>, sigma2: f32) -> f32 {
    let mu_s = dot(up, s);
    let mu_v = dot(up, v);
    if mu_s <= 0.0 || mu_v <= 0.0 {
        return 0.0;
    }
    let half = normalize(s + v);
    let c = max(dot(up, half), 1e-6);
    let c2 = c * c;
    let tan2 = (1.0 - c2) / c2;
    let facets = exp(-tan2 / sigma2) / (PI * sigma2 * c2 * c2);
    let fresnel = fresnel_reflectance(dot(s, half), WATER_REFRACTIVE_INDEX);
    let shadowing = smith_visible(mu_s, sigma2) * smith_visible(mu_v, sigma2);
    return fresnel * facets * shadowing / (4.0 * mu_s * mu_v);
}

// The glint's radiance towards `to_eye` per unit of a sun's beam irradiance (normal to the beam)
// from `s`: water share × BRDF × μ_s (0 without water).
fn glint_factor(ground: Ground, up: vec3<f32>, s: vec3<f32>, to_eye: vec3<f32>) -> f32 {
    if ground.water <= 0.0 {
        return 0.0;
    }
    return ground.water * glint_brdf(up, s, to_eye, view.surface.y) * max(dot(up, s), 0.0);
}
