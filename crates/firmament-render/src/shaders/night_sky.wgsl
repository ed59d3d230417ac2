// night_sky.wgsl — the stars and the Moon, added to the HDR target over the sky.
//
// Conventions:
// - Directions are camera-relative world directions (`w` = 0 through `view_proj`: only the view
//   rotation and the projection). Both primitives are put at the far plane (reversed-Z clip
//   depth 0) so a `GreaterEqual` depth test against the cleared depth 0 keeps them behind
//   everything drawn.
// - Pixel coordinates `px` run from the top-left corner of the target, x right, y down, pixel
//   centres at half-integers; they are computed in the vertex stage and interpolated (never read
//   from the fragment position), so they mean the same on every backend.
// - Radiance is linear RGB in the frame's units; a star's `color` is an irradiance (units × sr).
//   Output is additive (blend One, One), alpha 0, clamped to the half-float maximum.
//
// Stars: an instanced quad per star around its projected centre. The star's light goes to the
// 5 × 5 pixels whose centres lie within `star.y` (2.5) pixels of its centre along each axis,
// weighted by a Gaussian of σ = `star.x` (0.6) pixels sampled at the pixel centres and
// normalised over those 25 pixels, then divided by each pixel's solid angle
// (du dv / (1 + u² + v²)^{3/2}, u, v the tangent-plane coordinates), so that the radiance summed
// over the footprint times each pixel's solid angle is the star's colour.
//
// The Moon: one quad in the plane tangent to the sky at the Moon's centre `d`, spanned by `e1`
// and `e2`, of half size h = tan α plus two pixels (α its angular radius). A fragment's view ray
// is d + h (uv.x e1 + uv.y e2) — exact, as the quad is planar and uv interpolates perspective-
// correctly — so the ray is θ from the centre with tan θ = h |uv|. With the Moon 1/sin α
// radii away, the ray passes b = sin θ / sin α radii from its centre (a hit when b ≤ 1); where
// it enters the sphere the normal is n = −d (μ cos θ + b sin θ) + ŵ (b cos θ − μ sin θ), with
// μ = √(1 − b²) the cosine of the emergence angle and ŵ the ray's offset direction, and
// μ₀ = n · s (s the Sun seen from the Moon, in the (e1, e2, d) basis). The radiance is
// `moon_radiance` × 2 μ₀ / (μ₀ + μ): Lommel–Seeliger, 1 at normal incidence and emergence.
// Each pixel averages n × n such rays on a regular grid over its square (n = `moon_sun.w`: 4 for a
// Moon 8 pixels or more in radius, up to 16 for a smaller one; for n = 4 the offsets are ±1/8 and
// ±3/8 of a pixel), taken through the uv derivatives, so the rim and the terminator are
// antialiased and the disc's light is kept. (A Moon under two pixels in radius is drawn as a star
// instead.) In a lunar eclipse each point's radiance is also times its share of the sunlight,
// read from a table by its distance from the planet's shadow axis (firmament_core MoonShadow).

const HDR_MAX: f32 = 65504.0;
// The far plane's clip depth: 0 for reversed-Z (firmament's), overridden with 1 for a
// standard-Z depth buffer (an embedder's).
override FAR_DEPTH: f32 = 0.0;

struct NightSky {
    // Camera-relative world direction (w = 0) → clip space.
    view_proj: mat4x4<f32>,
    // Target width and height (pixels), tan of half the horizontal and vertical field of view.
    pixels: vec4<f32>,
    // x = Gaussian σ (pixels), y = half window (pixels).
    star: vec4<f32>,
    // xyz = d, w = sin α.
    moon_center: vec4<f32>,
    // xyz = e1, w = h, the quad's half size in the tangent plane (tan α plus two pixels).
    moon_e1: vec4<f32>,
    // xyz = e2 = d × e1, w = cos α.
    moon_e2: vec4<f32>,
    // xyz = the Sun seen from the Moon in the (e1, e2, d) basis, w = rays per pixel along each axis.
    moon_sun: vec4<f32>,
    // rgb = radiance at normal incidence and emergence.
    moon_radiance: vec4<f32>,
    // In a lunar eclipse: xyz = the planet's shadow axis in the (e1, e2, d) basis, w = the
    // distance between entries of `moon_shadow` in Moon radii (0: no eclipse).
    moon_shadow_axis: vec4<f32>,
    // xyz = from the axis to the Moon's centre across it, Moon radii, same basis.
    moon_shadow_offset: vec4<f32>,
    // rgb = the sunlight's share k·step from the axis (1 beyond the last entry).
    moon_shadow: array<vec4<f32>, MOON_SHADOW_ENTRIES>,
}

// Entries of the shadow table (firmament_core::atmosphere::planet_shadow::SHADOW_ENTRIES).
const MOON_SHADOW_ENTRIES: u32 = 64u;

// The sunlight's share at the point of the Moon with normal n (in the (e1, e2, d) basis).
fn moon_shadow_light(n: vec3<f32>) -> vec3<f32> {
    let step = night.moon_shadow_axis.w;
    if step <= 0.0 {
        return vec3<f32>(1.0);
    }
    let axis = night.moon_shadow_axis.xyz;
    let across = night.moon_shadow_offset.xyz + n - axis * dot(n, axis);
    let x = length(across) / step;
    let i = u32(floor(x));
    if i + 1u >= MOON_SHADOW_ENTRIES {
        return vec3<f32>(1.0);
    }
    return mix(night.moon_shadow[i].rgb, night.moon_shadow[i + 1u].rgb, x - f32(i));
}

@group(0) @binding(0) var<uniform> night: NightSky;

// A triangle strip over the corners (-1,-1), (1,-1), (-1,1), (1,1).
fn quad_corner(v: u32) -> vec2<f32> {
    return vec2<f32>(f32(v & 1u) * 2.0 - 1.0, f32((v >> 1u) & 1u) * 2.0 - 1.0);
}

// NDC (y up) → pixel coordinates (y down).
fn ndc_to_px(ndc: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * night.pixels.xy;
}

// The solid angle of the pixel centred at `px`, steradians.
fn pixel_solid_angle(px: vec2<f32>) -> f32 {
    let ndc = vec2<f32>(px.x / night.pixels.x * 2.0 - 1.0, 1.0 - px.y / night.pixels.y * 2.0);
    let t = ndc * night.pixels.zw;
    let step = 2.0 * night.pixels.zw / night.pixels.xy;
    let q = 1.0 + dot(t, t);
    return step.x * step.y / (q * sqrt(q));
}

struct StarIn {
    // xyz = unit direction
    @location(0) direction: vec4<f32>,
    // rgb = irradiance (units × sr)
    @location(1) color: vec4<f32>,
}

struct StarOut {
    @builtin(position) clip: vec4<f32>,
    // This fragment's pixel coordinates.
    @location(0) px: vec2<f32>,
    // The star's centre, pixel coordinates.
    @location(1) @interpolate(flat) center: vec2<f32>,
    @location(2) @interpolate(flat) color: vec3<f32>,
}

@vertex
fn vs_star(@builtin(vertex_index) v: u32, star: StarIn) -> StarOut {
    var out: StarOut;
    out.color = star.color.rgb;
    let clip = night.view_proj * vec4<f32>(star.direction.xyz, 0.0);
    if clip.w <= 0.0 {
        // Behind the camera: outside the clip volume (z < 0), nothing rasterised.
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        out.px = vec2<f32>(0.0);
        out.center = vec2<f32>(0.0);
        return out;
    }
    let ndc = clip.xy / clip.w;
    // Half a pixel beyond the footprint's outermost pixel centres.
    let reach = (night.star.y + 1.0) * 2.0 / night.pixels.xy;
    let corner_ndc = ndc + quad_corner(v) * reach;
    out.clip = vec4<f32>(corner_ndc, FAR_DEPTH, 1.0);
    out.px = ndc_to_px(corner_ndc);
    out.center = ndc_to_px(ndc);
    return out;
}

fn star_gauss(x: f32) -> f32 {
    let s = night.star.x;
    return exp(-0.5 * x * x / (s * s));
}

@fragment
fn fs_star(in: StarOut) -> @location(0) vec4<f32> {
    let c = in.center;
    let half_window = night.star.y;
    let count = i32(round(2.0 * half_window));
    // The first pixel centre at or after c − half_window, per axis.
    let first = ceil(c - half_window - 0.5) + 0.5;
    let index = round(in.px - first);
    if any(index < vec2<f32>(0.0)) || any(index > vec2<f32>(f32(count - 1))) {
        discard;
    }
    var sum = vec2<f32>(0.0);
    for (var j = 0; j < count; j++) {
        let o = first + f32(j) - c;
        sum += vec2<f32>(star_gauss(o.x), star_gauss(o.y));
    }
    let p = first + index;
    let weight = star_gauss(p.x - c.x) * star_gauss(p.y - c.y) / (sum.x * sum.y);
    let radiance = in.color * (weight / pixel_solid_angle(p));
    return vec4<f32>(min(radiance, vec3<f32>(HDR_MAX)), 0.0);
}

struct MoonOut {
    @builtin(position) clip: vec4<f32>,
    // The tangent-plane offset in units of tan α.
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_moon(@builtin(vertex_index) v: u32) -> MoonOut {
    let corner = quad_corner(v);
    let offset = corner.x * night.moon_e1.xyz + corner.y * night.moon_e2.xyz;
    let direction = night.moon_center.xyz + night.moon_e1.w * offset;
    let clip = night.view_proj * vec4<f32>(direction, 0.0);
    var out: MoonOut;
    out.clip = vec4<f32>(clip.x, clip.y, FAR_DEPTH * clip.w, clip.w);
    out.uv = corner;
    return out;
}

// The Moon's radiance along the ray at tangent-plane offset `uv` (units of the quad's half size):
// zero off the disc and on the night side.
fn moon_radiance_at(uv: vec2<f32>) -> vec3<f32> {
    let r = length(uv);
    let tan_t = r * night.moon_e1.w;
    let cos_t = inverseSqrt(1.0 + tan_t * tan_t);
    let sin_t = tan_t * cos_t;
    let b = sin_t / night.moon_center.w;
    if b > 1.0 {
        return vec3<f32>(0.0);
    }
    let mu = sqrt(max(1.0 - b * b, 0.0));
    var w_hat = vec2<f32>(0.0);
    if r > 0.0 {
        w_hat = uv / r;
    }
    let n_across = b * cos_t - mu * sin_t;
    let n_along = -(mu * cos_t + b * sin_t);
    let mu0 = dot(w_hat, night.moon_sun.xy) * n_across + night.moon_sun.z * n_along;
    if mu0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let shade = moon_shadow_light(vec3<f32>(w_hat * n_across, n_along));
    return night.moon_radiance.rgb * shade * (2.0 * mu0 / (mu0 + mu));
}

@fragment
fn fs_moon(in: MoonOut) -> @location(0) vec4<f32> {
    // uv per pixel across and down the target (taken first, in uniform control flow).
    let across = dpdxFine(in.uv);
    let down = dpdyFine(in.uv);
    let n = i32(night.moon_sun.w);
    let step = 1.0 / f32(n);
    var sum = vec3<f32>(0.0);
    for (var j = 0; j < n; j++) {
        for (var i = 0; i < n; i++) {
            let o = (vec2<f32>(f32(i), f32(j)) + 0.5) * step - 0.5;
            sum += moon_radiance_at(in.uv + across * o.x + down * o.y);
        }
    }
    return vec4<f32>(min(sum * (step * step), vec3<f32>(HDR_MAX)), 0.0);
}
