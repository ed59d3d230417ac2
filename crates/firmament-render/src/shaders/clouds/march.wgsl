// clouds/march.wgsl — the cloud layers laid over the finished HDR image (sky, objects and their
// aerial perspective): each pixel's ray is marched through the shells of every layer in front of
// its geometry, and the cloud's light and transmittance are composited with the air in front.
//
// Conventions: as atmosphere/view.wgsl (planet frame, metres, spectra per model wavelength, HDR
// colour linear sRGB with Y in cd/m²); the density field is clouds/density.wgsl's, the mirror of
// firmament_core::atmosphere::clouds. Cloud extinction is grey: one transmittance for every
// channel. Shells are the ellipsoid's semi-axes plus the altitude (within metres of the true
// offset surface below 20 km on Earth; the density itself takes the sample's own altitude).
//
// Lighting of a sample (docs/CLOUDS.md, "How clouds are drawn"), δ-scaled: the cloud's own light
// fades along the view over (1 − ω·g²)·σ, and what it scatters is the source function of a
// plane-parallel slab in scaled optical depth (`cloud_source`):
// - each sun: E · T_air (transmittance LUT) times, with τ' the cloud's scaled optical depth
//   towards the sun (a short march, LIGHT_STEPS), the beam p(ν)·e^(−τ') and the Eddington
//   diffuse field scattered once more (`eddington_beam`);
// - the sky's light from above (the sky-irradiance LUT) and the ground's bounce from below,
//   diffuse light entering the slab's faces (`eddington_diffuse`).
// What lies behind fades over the scaled extinction too, but a sun's disc over the whole
// (`behind_transmittance`).
// From afar, where a pixel spans many of a layer's columns, the march, the light's way to the sun
// and the ground's shadow take the columns as independent: a share of the rays meets cloud, the
// rest none (march_stretch; docs/CLOUDS.md, "Level of detail").
// The clouds' shadow on the ground: the sky draws the ground lit by the suns unshadowed, so where
// a pixel's ray ends on the ground the sunlight the clouds take off it is subtracted first
// (`ground_shadow`: the layers' optical depth towards each sun from the ground point, the
// detail's mean, GROUND_SHADOW_STEPS samples per layer; the air's transmittance between camera and
// ground from the transmittance LUT). The sky's light on the ground keeps no cloud shadow.
// Likewise the air's single scattering where the clouds shadow it (`air_shadow`: light shafts),
// from the shadow map (clouds/shadow.wgsl), within its reach of the camera.
// Compositing (Hillaire 2016, "Physically based sky, atmosphere and cloud rendering in
// Frostbite"): the air in front of the cloud is the aerial-perspective volume's at the cloud's
// transmittance-weighted depth; the image behind keeps its own air:
// out = A + T_air · L_cloud + T_cloud · (in − A).
//
// Into a caller's target (`CLOUD_LAYER`), which a compute pass cannot read and write, cs_main
// writes the clouds as a layer instead, (A·(1 − T_cloud) + T_air · L_cloud, T_cloud), and
// vs_main/fs_main lay it over the caller's colour with the blend `src + dst · src.a`: the same
// sum wherever the image behind is brighter than the air in front (`in ≥ A`; the renderer's own
// targets clamp `in − A` at zero).

#import common/fullscreen
#import common/ellipsoid
#import common/view_ray
#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/view
#import atmosphere/eclipse
#import atmosphere/surface
#import atmosphere/aerial_lookup
#import atmosphere/body_hits
#import clouds/density
#import clouds/extinction
#import clouds/shadow

// Samples of the air's single scattering in the clouds' shadows along a view ray (air_shadow).
const SHAFT_STEPS: u32 = 24u;
// Samples along each layer's stretch of a ray from the ground towards a sun (ground_shadow).
const GROUND_SHADOW_STEPS: u32 = 12u;
// Most coarse and fine samples along one layer's stretch of a ray (march_stretch).
const COARSE_STEPS: u32 = 64u;
const FINE_STEPS: u32 = 128u;
// Fine samples in a row without cloud that send the march back to coarse steps.
const FINE_TO_COARSE: u32 = 8u;
// Samples along the way towards each sun, each twice as long as the one before.
const LIGHT_STEPS: u32 = 6u;
// Below this (the scaled transmittance, which the cloud's own light fades by) the cloud hides
// everything behind it: the march stops.
const OPAQUE: f32 = 1e-3;

// Whether cs_main writes the clouds as a layer to blend (a caller's target) rather than the
// image with the clouds over it (the renderer's own).
override CLOUD_LAYER: bool = false;

// One stretch of a ray inside one layer.
struct Stretch {
    t0: f32,
    t1: f32,
    layer: u32,
}

// Where a pixel's ray meets the ground and the top of the air (common/ellipsoid's hits: x > y
// when it misses), found once per pixel for the march and the shadows.
struct RayHits {
    ground: vec2<f32>,
    top: vec2<f32>,
}

fn ray_hits(ray: ViewRay) -> RayHits {
    return RayHits(
        ellipsoid_hits(ray.origin, ray.direction, atmosphere.radii.xyz, ray.c_surface),
        ellipsoid_hits(ray.origin, ray.direction, top_radii(), ray.c_top),
    );
}

// What the march gathers: the cloud's light reaching the camera's side of it (spectral radiance,
// before the air in front), its transmittance (of what lies behind), the transmittance of its own
// light (δ-scaled: cloud_source), and its transmittance-weighted distance.
struct CloudSample {
    radiance: vec3<f32>,
    transmittance: f32,
    scaled_transmittance: f32,
    depth_sum: f32,
    weight_sum: f32,
}

// The two lobes' Henyey–Greenstein mixture with both asymmetries scaled by `scale` (sr⁻¹).
fn dual_henyey_greenstein(phase: vec4<f32>, nu: f32, scale: f32) -> f32 {
    return phase.z * henyey_greenstein_phase(phase.x * scale, nu)
        + (1.0 - phase.z) * henyey_greenstein_phase(phase.y * scale, nu);
}

fn henyey_greenstein_phase(g: f32, nu: f32) -> f32 {
    let g2 = g * g;
    let denominator = max(1.0 + g2 - 2.0 * g * nu, 1e-6);
    return (1.0 - g2) / (4.0 * PI * denominator * sqrt(denominator));
}

// Where the ray meets the layer: up to two stretches, [t0, t1] inside the top shell and outside
// the bottom one, cut to [near, far]. Empty stretches have t1 <= t0.
fn layer_stretches(ray: ViewRay, bottom: f32, top: f32, near: f32, far: f32) -> array<vec2<f32>, 2> {
    var out = array<vec2<f32>, 2>(vec2<f32>(0.0), vec2<f32>(0.0));
    let outer = cloud_shell_hits(ray.origin, ray.direction, top);
    if outer.x > outer.y {
        return out;
    }
    let inner = cloud_shell_hits(ray.origin, ray.direction, bottom);
    if inner.x > inner.y {
        out[0] = vec2<f32>(max(outer.x, near), min(outer.y, far));
    } else {
        out[0] = vec2<f32>(max(outer.x, near), min(inner.x, far));
        out[1] = vec2<f32>(max(inner.y, near), min(outer.y, far));
    }
    return out;
}

// Optical depth from p (geodetic up `up`) towards the sun along s through `layer`: LIGHT_STEPS
// samples over stretches doubling in length, out to where the ray leaves the layer's top. From
// afar (`lod`) the columns' average counts over the share of such ways that meet cloud
// (cloud_cover_along): the view's sample lies in a cloud, and so does the start of its way out.
fn optical_depth_to_sun(layer: CloudLayerGpu, p: vec3<f32>, up: vec3<f32>, s: vec3<f32>, lod: f32) -> f32 {
    let top = layer.shell.y;
    let exit = cloud_shell_hits(p, s, top).y;
    let length_out = max(exit, 0.0);
    let cover = cloud_cover_along(layer, up, s, length_out, lod);
    // Steps of 1, 2, 4, … units, summing to the way out.
    let unit = length_out / f32((1u << LIGHT_STEPS) - 1u);
    var depth = 0.0;
    var t = 0.0;
    var dt = unit;
    for (var k = 0u; k < LIGHT_STEPS; k++) {
        let q = p + s * (t + 0.5 * dt);
        let here = altitude_up(q);
        depth += cloud_extinction_lod(layer, q, here.h, here.up, false, lod, cover) * dt;
        t += dt;
        dt *= 2.0;
    }
    return depth;
}

// The light a unit of cloud extinction at p (altitude h, up `up`) scatters towards −d (spectral,
// per metre per unit extinction: multiply by the extinction), from every sun, the sky and the
// ground; the way to each sun through the field at the view sample's level of detail `lod`.
// δ-scaled (Joseph, Wiscombe & Weinman 1976): the droplets' forward peak f = g² goes on with the
// light it scattered, so the march dims this light by the scaled extinction (1 − ω·f)·σ
// (`delta_scale`), and the diffuse light is the Eddington solution of a conservative
// plane-parallel slab in scaled optical depth (`eddington_beam`, `eddington_diffuse`), the slab
// guessed from the local extinction and the sun's way out; the once-scattered beam keeps the whole
// phase function (Nakajima & Tanaka 1988's TMS correction).
fn cloud_source(layer: CloudLayerGpu, p: vec3<f32>, h: f32, up: vec3<f32>, d: vec3<f32>, extinction: f32, lod: f32) -> vec3<f32> {
    let albedo = layer.coverage.w;
    let g = mean_cosine(layer.phase);
    let f = g * g;
    // The δ-scaled asymmetry of what is left, (g − f)/(1 − f).
    let g_scaled = g / (1.0 + g);
    let mu_out = dot(-d, up);
    // The slab around the sample, in scaled optical depth: above and below it, straight up and down
    // (conservative, as the Eddington solutions below take it: an albedo below 1 scales the result).
    let scaled = (1.0 - f) * extinction;
    let above = scaled * max(layer.shell.y - h, 0.0);
    let below = scaled * max(h - layer.shell.x, 0.0);
    var source = vec3<f32>(0.0);
    var ground_irradiance = vec3<f32>(0.0);
    var sky_light = vec3<f32>(0.0);
    for (var i = 0u; i < view.sun_count.x; i++) {
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        let mu_s = dot(up, s);
        let air = transmittance_to_sun(h, mu_s, abs(sun.direction.w));
        let irradiance = sun_irradiance_at(p, i);
        sky_light += irradiance * sky_irradiance(h, mu_s);
        ground_irradiance += irradiance
            * (transmittance_to_sun(0.0, mu_s, abs(sun.direction.w)) * max(mu_s, 0.0) + sky_irradiance(0.0, mu_s));
        if all(air <= vec3<f32>(0.0)) {
            continue;
        }
        // The beam's scaled optical depth to the sun, and the same straight up (the slab's depth
        // of the sample, exact in a uniform slab).
        let tau = (1.0 - f) * optical_depth_to_sun(layer, p, up, s, lod);
        let single = dual_henyey_greenstein(layer.phase, dot(d, s), 1.0) * exp(-tau);
        let diffuse = (1.0 - f) * eddington_beam(max(mu_s, 0.0), max(mu_s, 0.0) * tau, below, g_scaled, mu_out);
        source += irradiance * air * (single + diffuse);
    }
    // The sky's light from above and the ground's from below, each isotropic radiance (irradiance
    // over π) entering its face of the slab.
    let sky = eddington_diffuse(above, below, g_scaled, -mu_out);
    let ground = eddington_diffuse(below, above, g_scaled, mu_out);
    source += (1.0 - f) * (sky_light * sky + atmosphere.ground_albedo.rgb * ground_irradiance * ground) / PI;
    return albedo * source;
}

// The share of a layer's extinction that dims the cloud's own light, 1 − ω·f (see cloud_source).
fn delta_scale(layer: CloudLayerGpu) -> f32 {
    let g = mean_cosine(layer.phase);
    return 1.0 - layer.coverage.w * g * g;
}

// The diffuse radiance a unit of scaled extinction scatters towards direction cosine `mu_out` (to
// the local up) at scaled optical depth `t` below the top of a conservative slab reaching
// `t_below` further down, scaled asymmetry `g`, lit at cosine `mu0` by a sun of unit irradiance
// (normal to the beam), per steradian: the Eddington solution I = I0 + μ·I1 (Shettle & Weinman
// 1970; Joseph, Wiscombe & Weinman 1976) with Marshak's conditions (no diffuse light entering
// at the top, a black ground below), scattered by the Eddington phase 1 + 3g·cos Θ:
// I0 + g·mu_out·I1. Its reflectance I0(0) + 2/3·I1(0) over μ0/π is δ-Eddington's,
// (γτ + (½ − ¾μ0)(1 − e^(−τ/μ0)))/(1 + γτ), γ = ¾(1 − g).
fn eddington_beam(mu0: f32, t: f32, t_below: f32, g: f32, mu_out: f32) -> f32 {
    if mu0 <= 0.0 {
        return 0.0;
    }
    let f0 = 1.0 / PI;
    let total = t + t_below;
    let beam = exp(-t / mu0);
    let beam_bottom = exp(-total / mu0);
    let c1 = -f0 * (0.5 * mu0 + 0.75 * mu0 * mu0 + beam_bottom * (0.5 * mu0 - 0.75 * mu0 * mu0))
        / (4.0 / 3.0 + (1.0 - g) * total);
    let c2 = 2.0 / 3.0 * c1 + 0.75 * f0 * mu0 * mu0 + 0.5 * f0 * mu0;
    let i1 = c1 + 0.75 * f0 * mu0 * beam;
    let i0 = c2 + (1.0 - g) * c1 * t - 0.75 * f0 * mu0 * mu0 * beam;
    return max(i0 + g * mu_out * i1, 0.0);
}

// The same for diffuse light of unit radiance entering one face of the slab, `t` into it and
// `t_beyond` short of the other face (black, as Marshak's conditions take it), towards
// `mu_in`, the cosine to the axis pointing into the slab: I0 = 1 − (⅔ + (1 − g)·t)/D and
// I1 = 1/D along that axis, D = 4/3 + (1 − g)·(t + t_beyond), scattered as above.
fn eddington_diffuse(t: f32, t_beyond: f32, g: f32, mu_in: f32) -> f32 {
    let d = 4.0 / 3.0 + (1.0 - g) * (t + t_beyond);
    let i0 = 1.0 - (2.0 / 3.0 + (1.0 - g) * t) / d;
    return max(i0 + g * mu_in / d, 0.0);
}

// The phase function's mean cosine g.
fn mean_cosine(phase: vec4<f32>) -> f32 {
    return phase.z * phase.x + (1.0 - phase.z) * phase.y;
}

// The layers' transmittance (grey) from the ground point p towards the sun along s, up to where
// the ray leaves each layer's top, with the detail's mean. From afar (a pixel spanning `span`
// metres there) each layer's columns are independent: a share `cover` of the ways meets cloud
// of optical depth τ/cover (cloud_cover_along), so the layer lets 1 − cover + cover·e^(−τ/cover)
// through.
fn cloud_transmittance_to_sun(p: vec3<f32>, s: vec3<f32>, span: f32) -> f32 {
    var transmittance = 1.0;
    for (var i = 0u; i < clouds.count.x; i++) {
        let layer = clouds.layers[i];
        let outer = cloud_shell_hits(p, s, layer.shell.y);
        let inner = cloud_shell_hits(p, s, layer.shell.x);
        // From where the ray leaves the layer's bottom (it starts below it) to where it leaves the top.
        let a = select(0.0, max(inner.y, 0.0), inner.x <= inner.y && inner.y > 0.0);
        let b = outer.y;
        if !(outer.x <= outer.y) || b <= a {
            continue;
        }
        let lod = cloud_lod(layer, span);
        let cover = cloud_cover_along(layer, altitude_up(p + s * (0.5 * (a + b))).up, s, b - a, lod);
        let dt = (b - a) / f32(GROUND_SHADOW_STEPS);
        var depth = 0.0;
        for (var k = 0u; k < GROUND_SHADOW_STEPS; k++) {
            depth += cloud_extinction_at(layer, p + s * (a + (f32(k) + 0.5) * dt), false, lod, cover) * dt;
        }
        transmittance *= 1.0 - cover + cover * exp(-depth);
    }
    return transmittance;
}

// The sunlight the clouds take off the ground where the ray meets it before `far` (spectral
// radiance towards the camera; zero when it meets no ground, or geometry first): for each sun,
// what the ground there reflects of it towards the camera (albedo over π, and the glint on its
// water) times its irradiance after the air, times 1 − e^(−τ) of the clouds towards it, dimmed
// by the air between the camera and the ground.
fn ground_shadow(ray: ViewRay, hits: RayHits, far: f32, footprint: f32) -> vec3<f32> {
    let ground = hits.ground;
    if !(ground.x <= ground.y && ground.x > ray.near && ground.x < far) {
        return vec3<f32>(0.0);
    }
    let g = ray.origin + ray.direction * ground.x;
    let at_ground = altitude_up(g);
    let h = max(at_ground.h, 0.0);
    let surface = ground_at(at_ground.up);
    var lost = vec3<f32>(0.0);
    var lost_glint = vec3<f32>(0.0);
    for (var i = 0u; i < view.sun_count.x; i++) {
        let sun = view.suns[i];
        let s = sun.direction.xyz;
        let mu_s = dot(at_ground.up, s);
        if mu_s <= 0.0 {
            continue;
        }
        let shade = 1.0 - cloud_transmittance_to_sun(g, s, ground.x * footprint);
        if shade > 0.0 {
            let beam = sun_irradiance_at(g, i) * transmittance_to_sun(h, mu_s, abs(sun.direction.w));
            lost += beam * (mu_s * shade);
            lost_glint += beam * (shade * glint_factor(surface, at_ground.up, s, -ray.direction));
        }
    }
    if all(lost <= vec3<f32>(0.0)) {
        return lost;
    }
    // The air between: from where the air starts (the top of the air from outside).
    let start = ray.origin + ray.direction * max(hits.top.x, ray.near);
    let through_air = transmittance_to_ground(ray.direction, start, at_ground);
    return (surface.albedo / PI * lost + lost_glint) * through_air;
}

// The clouds' optical depth between planet-frame point p and sun `sun` (direction s), from the
// shadow map.
fn cloud_shadow_depth(p: vec3<f32>, sun: u32, s: vec3<f32>) -> f32 {
    let axes = cloud_shadow_axes(s);
    let offset = p - view.camera.xyz;
    return cloud_shadow_lookup(cloud_shadow_map, vec2<f32>(dot(offset, axes[0]), dot(offset, axes[1])), dot(offset, s), sun);
}

// The sunlight the air scatters once towards the camera from where the clouds shadow it, along
// the ray from where the air starts to `t_end` (at most CLOUD_SHADOW_REACH from the camera, where
// the shadow map ends; spectral radiance): for each sun, σ_s·p(ν)·E·T_sun·T_view·(1 − e^(−τ)),
// τ the clouds' optical depth towards it from the map, in SHAFT_STEPS steps offset by the
// pixel's `jitter`. Light shafts and the shadows' darkening of the air; none from far away.
fn air_shadow(ray: ViewRay, hits: RayHits, t_end: f32, jitter: f32) -> vec3<f32> {
    if view.center.w > 0.5 {
        return vec3<f32>(0.0);
    }
    let top = hits.top;
    let t0 = max(top.x, ray.near);
    let t1 = min(min(t_end, top.y), ray.near + CLOUD_SHADOW_REACH);
    if !(top.x <= top.y) || t1 <= t0 {
        return vec3<f32>(0.0);
    }
    let dt = (t1 - t0) / f32(SHAFT_STEPS);
    var lost = vec3<f32>(0.0);
    var transmittance = vec3<f32>(1.0);
    // Up to the first step, from t0 (the jitter's share of a step).
    var previous = t0;
    for (var k = 0u; k < SHAFT_STEPS; k++) {
        let t = t0 + (f32(k) + jitter) * dt;
        let p = ray.origin + ray.direction * t;
        let here = altitude_up(p);
        let air = coefficients_at(here.h);
        transmittance *= exp(-air.extinction * (t - previous));
        previous = t;
        for (var i = 0u; i < view.sun_count.x; i++) {
            let sun = view.suns[i];
            let s = sun.direction.xyz;
            let shade = 1.0 - exp(-cloud_shadow_depth(p, i, s));
            if shade > 0.0 {
                let sunlight = sun_irradiance_at(p, i) * transmittance_to_sun(here.h, dot(here.up, s), abs(sun.direction.w));
                lost += shade * transmittance * scattering_phase(air, dot(ray.direction, s)) * sunlight * dt;
            }
        }
    }
    return lost;
}

// Interleaved gradient noise (Jimenez 2014): a fixed fraction per pixel, so neighbours' samples
// interleave and reruns are identical.
fn pixel_jitter(pixel: vec2<f32>) -> f32 {
    return fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
}

// Marches one stretch of a layer from t0 to t1, adding to `acc`. Up close this is the field
// (march_field); from afar, where a pixel spans many of the layer's columns, the columns are
// independent (Cahalan et al. 1994's independent-pixel approximation): a share `cover` of the
// rays meets cloud (cloud_cover_along: the layer's coverage looking down, nearly all of them at
// a grazing look), of the columns' mean density over that share, and the rest meet none. So a
// broken layer from orbit keeps the light of its gaps — the columns' mean transmittance, not the
// transmittance of their mean optical depth (an even veil).
fn march_stretch(ray: ViewRay, layer: CloudLayerGpu, t0: f32, t1: f32, jitter: f32, footprint: f32, acc: ptr<function, CloudSample>) {
    if (*acc).scaled_transmittance < OPAQUE {
        return;
    }
    let middle = 0.5 * (t0 + t1);
    let up = altitude_up(ray.origin + ray.direction * middle).up;
    let cover = cloud_cover_along(layer, up, ray.direction, t1 - t0, cloud_lod(layer, middle * footprint));
    if cover >= 1.0 {
        march_field(ray, layer, t0, t1, jitter, footprint, 1.0, acc);
        return;
    }
    var part = CloudSample(vec3<f32>(0.0), 1.0, 1.0, 0.0, 0.0);
    march_field(ray, layer, t0, t1, jitter, footprint, cover, &part);
    let seen = (*acc).transmittance * cover;
    (*acc).radiance += (*acc).scaled_transmittance * cover * part.radiance;
    (*acc).depth_sum += seen * part.depth_sum;
    (*acc).weight_sum += seen * part.weight_sum;
    (*acc).transmittance *= 1.0 - cover + cover * part.transmittance;
    (*acc).scaled_transmittance *= 1.0 - cover + cover * part.scaled_transmittance;
}

// Marches the field of one stretch of a layer from t0 to t1, adding to `acc`, the columns'
// average (from afar) over `cover`. Empty air is crossed in coarse steps (a sixteenth of the
// layer's thickness, or of the stretch over COARSE_STEPS when that is longer); the first coarse
// sample that finds cloud steps back and the cloud is marched in fine steps, an eighth of a coarse
// one (or the stretch over FINE_STEPS), until FINE_TO_COARSE fine samples in a row find none
// (Schneider & Vos 2015). Both counts are bounded by construction.
fn march_field(ray: ViewRay, layer: CloudLayerGpu, t0: f32, t1: f32, jitter: f32, footprint: f32, cover: f32, acc: ptr<function, CloudSample>) {
    // Where a pixel spans more than a detail cell the detail is taken as its mean (a filter, and
    // cheaper): the light march always does.
    let detail_cell = 1.0 / layer.detail.x;
    let length_in = t1 - t0;
    let thickness = max(layer.shell.y - layer.shell.x, 1.0);
    let coarse = max(thickness / 16.0, length_in / f32(COARSE_STEPS));
    let fine = max(coarse / 8.0, length_in / f32(FINE_STEPS));
    let scale = delta_scale(layer);
    var t = t0 + jitter * coarse;
    var fine_mode = false;
    var empty = 0u;
    for (var guard = 0u; guard < COARSE_STEPS + 2u * FINE_STEPS && t < t1; guard++) {
        if (*acc).scaled_transmittance < OPAQUE {
            return;
        }
        if !fine_mode {
            let p = ray.origin + ray.direction * t;
            if cloud_extinction_at(layer, p, t * footprint < detail_cell, cloud_lod(layer, t * footprint), cover) > 0.0 {
                fine_mode = true;
                empty = 0u;
                t = max(t - coarse, t0);
            } else {
                t += coarse;
            }
            continue;
        }
        let dt = min(fine, t1 - t);
        let tm = t + 0.5 * dt;
        let p = ray.origin + ray.direction * tm;
        let here = altitude_up(p);
        let lod = cloud_lod(layer, tm * footprint);
        let extinction = cloud_extinction_lod(layer, p, here.h, here.up, tm * footprint < detail_cell, lod, cover);
        t += dt;
        if extinction <= 0.0 {
            empty += 1u;
            fine_mode = empty < FINE_TO_COARSE;
            continue;
        }
        empty = 0u;
        let source = cloud_source(layer, p, here.h, here.up, ray.direction, extinction, lod) * extinction;
        // The cloud's own light fades over the scaled extinction, what lies behind over the whole.
        let scaled = extinction * scale;
        let step = exp(-extinction * dt);
        let scaled_step = exp(-scaled * dt);
        let scattered = select((source - source * scaled_step) / scaled, source * dt, scaled * dt < 1e-4);
        (*acc).radiance += (*acc).scaled_transmittance * scattered;
        let lost = (*acc).transmittance * (1.0 - step);
        (*acc).depth_sum += lost * tm;
        (*acc).weight_sum += lost;
        (*acc).transmittance *= step;
        (*acc).scaled_transmittance *= scaled_step;
    }
}

// The clouds along the ray of pixel `id` up to `far` (metres along the ray).
fn march_clouds(ray: ViewRay, hits: RayHits, far: f32, jitter: f32, footprint: f32) -> CloudSample {
    var acc: CloudSample;
    acc.radiance = vec3<f32>(0.0);
    acc.transmittance = 1.0;
    acc.scaled_transmittance = 1.0;
    acc.depth_sum = 0.0;
    acc.weight_sum = 0.0;
    // The ground ends every ray that meets it.
    let ground = hits.ground;
    var end = far;
    if ground.x <= ground.y && ground.y > ray.near {
        end = min(end, max(ground.x, ray.near));
    }
    // Every layer's stretches, marched nearest first.
    var stretches: array<Stretch, 16>;
    var count = 0u;
    for (var i = 0u; i < clouds.count.x; i++) {
        let layer = clouds.layers[i];
        let found = layer_stretches(ray, layer.shell.x, layer.shell.y, ray.near, end);
        for (var j = 0u; j < 2u; j++) {
            if found[j].y > found[j].x {
                stretches[count] = Stretch(found[j].x, found[j].y, i);
                count += 1u;
            }
        }
    }
    var done = 0u;
    var marched = 0u; // one bit per stretch already marched
    while done < count {
        var next = 0u;
        var nearest = 3.0e38;
        for (var k = 0u; k < count; k++) {
            if (marched & (1u << k)) == 0u && stretches[k].t0 < nearest {
                nearest = stretches[k].t0;
                next = k;
            }
        }
        marched |= 1u << next;
        done += 1u;
        let stretch = stretches[next];
        march_stretch(ray, clouds.layers[stretch.layer], stretch.t0, stretch.t1, jitter, footprint, &acc);
    }
    return acc;
}

// The transmittance of the clouds for what lies behind them along d, for a pixel `footprint`
// radians across: the δ-scaled one (cloud_source) — the light the droplets' forward peak scatters
// goes on as if unscattered, so a sky, a ground or an object behind keeps it — except on a sun's
// disc, which that peak spreads into the aureole the march draws (the phase function's peak in
// cloud_source), so the disc itself fades over the whole extinction.
fn behind_transmittance(cloud: CloudSample, d: vec3<f32>, footprint: f32) -> f32 {
    for (var i = 0u; i < view.sun_count.x; i++) {
        let sun = view.suns[i];
        let angle = atan2(length(cross(d, sun.direction.xyz)), dot(d, sun.direction.xyz));
        if sun.direction.w > 0.0 && angle < sun.direction.w + footprint {
            return cloud.transmittance;
        }
    }
    return cloud.scaled_transmittance;
}

// The image at pixel `id` with the clouds laid over it, or with CLOUD_LAYER the clouds alone as a
// layer to blend.
@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(scene_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    var color = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if !CLOUD_LAYER {
        color = textureLoad(hdr_in, id.xy, 0);
    }
    let ndc = pixel_ndc(id.xy, size);
    let ray = view_ray(ndc);
    let depth = textureLoad(scene_depth, id.xy, 0).x;
    var far = 3.0e38;
    if !at_far_plane(depth) {
        let view_depth = view.aerial.z / (depth + view.aerial.y);
        far = ray.near + view_depth * length(vec3<f32>(ndc * view.camera_shape.zw, -1.0));
    }
    // A body beside the planet hides the clouds behind it.
    let body = nearest_body_hit(ray.origin, ray.direction, ray.near);
    if body.hit {
        far = min(far, body.t);
    }
    let pixel = vec2<f32>(id.xy) + 0.5;
    // A pixel's width per metre along its ray (the vertical field of view over the rows).
    let footprint = 2.0 * view.camera_shape.w / f32(size.y);
    let jitter = pixel_jitter(pixel);
    let hits = ray_hits(ray);
    let cloud = march_clouds(ray, hits, far, jitter, footprint);
    // The clouds' shadows: on the ground behind (before the cloud's own transmittance), and in
    // the air in front of the cloud or of the ray's end (a layer subtracts both through the
    // blend, starting from nothing: `color` is then −ground).
    var air_end = far;
    if cloud.weight_sum > 0.0 {
        air_end = cloud.depth_sum / cloud.weight_sum;
    }
    let air_shade = to_linear_srgb(air_shadow(ray, hits, air_end, jitter));
    color = vec4<f32>(color.rgb - to_linear_srgb(ground_shadow(ray, hits, far, footprint)), color.a);
    if cloud.weight_sum <= 0.0 {
        // No cloud: the image less the shadows, or a layer that takes them off it.
        var rgb = color.rgb - air_shade;
        if !CLOUD_LAYER {
            rgb = max(rgb, vec3<f32>(0.0));
        }
        textureStore(hdr_out, id.xy, vec4<f32>(rgb, color.a));
        return;
    }
    // The air in front of the cloud, at its transmittance-weighted depth (none from far away,
    // where the volume is not built: see aerial_perspective.wgsl).
    var air_transmittance = vec3<f32>(1.0);
    var air_light = vec3<f32>(0.0);
    if view.center.w < 0.5 {
        let t_front = cloud.depth_sum / cloud.weight_sum;
        let span = aerial_span(ray);
        let through_air = clamp(t_front, span.x, span.y) - span.x;
        let coordinates = firmament_aerial_coordinates(pixel / vec2<f32>(size), through_air, view.aerial.x);
        air_transmittance = firmament_aerial_transmittance_at(aerial_transmittance, lut_sampler, coordinates);
        air_light = min(to_linear_srgb(firmament_aerial_scattering_at(aerial_scattering, lut_sampler, coordinates)), vec3<f32>(HDR_MAX));
    }
    let cloud_light = to_linear_srgb(cloud.radiance) * air_transmittance;
    let through = behind_transmittance(cloud, ray.direction, footprint);
    if CLOUD_LAYER {
        let layer = air_light * (1.0 - through) - air_shade + cloud_light + through * color.rgb;
        textureStore(hdr_out, id.xy, vec4<f32>(min(layer, vec3<f32>(HDR_MAX)), through));
        return;
    }
    let behind = max(color.rgb - air_light, vec3<f32>(0.0));
    let out = max(air_light - air_shade, vec3<f32>(0.0)) + cloud_light + through * behind;
    textureStore(hdr_out, id.xy, vec4<f32>(min(out, vec3<f32>(HDR_MAX)), color.a));
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

// The layer cs_main wrote with CLOUD_LAYER (bound as `hdr_in`), to blend `src + dst · src.a`.
@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    return textureLoad(hdr_in, vec2<i32>(in.clip.xy), 0);
}
