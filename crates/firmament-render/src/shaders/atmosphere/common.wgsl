// atmosphere/common.wgsl — shared by every atmosphere pass: the medium, the phase functions,
// altitudes and the LUT parameterisations.
//
// Conventions (those of firmament_core::atmosphere):
// - Planet frame: metres, centred on the planet, axes along the ellipsoid's semi-axes.
// - `h`: altitude above the ellipsoid surface (m). `r`: distance from the centre of the *LUT
//   sphere* (radius `lut.x`, m). `mu`: cosine of the view zenith angle, `mu_s`: of the sun zenith
//   angle, `nu`: of the angle between the view and sun directions.
// - Spectra are vec3: one value per model wavelength (x = the longest). Coefficients m⁻¹,
//   radiance W·m⁻²·sr⁻¹·nm⁻¹, irradiance W·m⁻²·nm⁻¹.
// - The transmittance and multiple-scattering LUTs are built for a sphere. On an ellipsoid a
//   lookup takes the sample's true altitude and local up, `r = lut.x + h` (the LUT sphere
//   touches the ellipsoid where the sample is; see passes/atmosphere/mod.rs for the error).
// The f64 reference is firmament_core::atmosphere::reference; keep the models in step.

#import atmosphere/bindings
#import generated/constants

const PI: f32 = 3.14159265358979;

fn layer_density(layer: vec4<f32>, h: f32) -> f32 {
    return clamp(layer.x * exp(layer.y * h) + layer.z * h + layer.w, 0.0, 1.0);
}

fn profile_density(profile: DensityProfile, h: f32) -> f32 {
    return select(layer_density(profile.layer1, h), layer_density(profile.layer0, h), h < profile.width.x);
}

fn term_count() -> u32 {
    return min(u32(atmosphere.lut.z), MAX_MEDIUM_TERMS);
}

// Where x in [0, 1] falls in row `row` of a table of `samples` values per row: the index of the
// value before it (tables hold four values to a vector) and the fraction towards the next.
struct TableSpot {
    at: u32,
    t: f32,
}

fn table_spot(row: u32, samples: u32, x: f32) -> TableSpot {
    let position = clamp(x, 0.0, 1.0) * f32(samples - 1u);
    let k = min(u32(position), samples - 2u);
    return TableSpot(row * samples + k, position - f32(k));
}

// Linear interpolation in a term's row of the density tables (x: altitude over the height) and
// of the phase tables (x: scattering angle over π).
fn density_table_value(row: u32, x: f32) -> f32 {
    let s = table_spot(row, DENSITY_TABLE_SAMPLES, x);
    let b = s.at + 1u;
    return mix(atmosphere.density_tables[s.at / 4u][s.at % 4u], atmosphere.density_tables[b / 4u][b % 4u], s.t);
}

fn phase_table_value(row: u32, x: f32) -> f32 {
    let s = table_spot(row, PHASE_TABLE_SAMPLES, x);
    let b = s.at + 1u;
    return mix(atmosphere.phase_tables[s.at / 4u][s.at % 4u], atmosphere.phase_tables[b / 4u][b % 4u], s.t);
}

// The terms whose density is a table, and those whose phase function is one (their indices).
// Tables are read in loops of their own so that an air without them pays nothing for them: a
// shader compiler that runs both sides of a branch (llvmpipe does) would otherwise read the
// tables for every term.
fn density_table_term(k: u32) -> u32 {
    return atmosphere.density_table_terms[k / 4u][k % 4u];
}

fn phase_table_term(k: u32) -> u32 {
    return atmosphere.phase_table_terms[k / 4u][k % 4u];
}

// The local coefficients at altitude h: each term's density, the extinction, and the extinction
// that light already scattered once meets, `diffuse_extinction`.
//
// That is the delta-M method (Wiscombe 1977, "The Delta-M Method: Rapid Yet Accurate Radiative
// Flux Calculations for Strongly Asymmetric Phase Functions", J. Atmos. Sci. 34): multiple
// scattering sees each phase function only through bands 0–4 (`scatter_moments` in luts.wgsl),
// and a forward peak reaches far beyond them (a_5 = 0.37 for Cornette–Shanks with g = 0.8).
// So a share f of each term's scattering is split off as light that goes straight on — it lowers
// the extinction scattered light meets by f·σ_s — and the rest, with coefficients a_l − f, is
// left to bands 0–4. Delta-M takes f = a_5; firmament takes at most 0.19 (MIE_FORWARD_PEAK_MAX in
// gpu_types/medium.rs: Earth's horizon light is a band narrower than its haze's wide peak).
// Cutting the series off after band 4 instead leaves the sky dark near the horizon
// (docs/ATMOSPHERE.md, "Mie's forward peak").
// Sunlight itself keeps the full extinction and the exact phase functions: single scattering, the
// sun's disc and whatever stands behind the air (whose transmittance is `extinction`'s) are exact.
struct Coefficients {
    density: array<f32, MAX_MEDIUM_TERMS>,
    extinction: vec3<f32>,
    diffuse_extinction: vec3<f32>,
}

// A term's profile density; 0 for a term whose density is a table (its profile is all zeros).
fn term_profile_density(i: u32, h: f32) -> f32 {
    return profile_density(atmosphere.terms[i].profile, h);
}

fn term_table_density(i: u32, h: f32) -> f32 {
    return density_table_value(i, h / atmosphere.radii.w);
}

// Adds term i at `density` to c's extinction and to the share of it delta-M sends straight on.
fn add_term(c: ptr<function, Coefficients>, forward: ptr<function, vec3<f32>>, i: u32, density: f32) {
    (*c).density[i] = density;
    (*c).extinction += atmosphere.terms[i].extinction.rgb * density;
    *forward += atmosphere.terms[i].phase.w * (atmosphere.terms[i].scattering.rgb * density);
}

fn coefficients_at(h: f32) -> Coefficients {
    var c: Coefficients;
    var forward = vec3<f32>(0.0);
    for (var i = 0u; i < term_count(); i++) {
        add_term(&c, &forward, i, term_profile_density(i, h));
    }
    for (var k = 0u; k < atmosphere.table_counts.x; k++) {
        let i = density_table_term(k);
        add_term(&c, &forward, i, term_table_density(i, h));
    }
    c.diffuse_extinction = c.extinction - forward;
    return c;
}

// Term i's scattering at a point of coefficients c, m⁻¹.
fn term_scattering(c: Coefficients, i: u32) -> vec3<f32> {
    return atmosphere.terms[i].scattering.rgb * c.density[i];
}

fn rayleigh_phase(nu: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

fn henyey_greenstein(g: f32, nu: f32) -> f32 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    return (1.0 - g * g) / (4.0 * PI * denominator * sqrt(denominator));
}

fn cornette_shanks(g: f32, nu: f32) -> f32 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    return 3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + nu * nu) / ((2.0 + g * g) * denominator * sqrt(denominator));
}

// Term i's analytic phase function at nu, sr⁻¹ (0 for a table: see `scattering_phase`). Every
// kind is computed and one selected, without branches.
fn analytic_phase(i: u32, nu: f32) -> f32 {
    let kind = u32(atmosphere.terms[i].scattering.w);
    let p = atmosphere.terms[i].phase;
    let hg = henyey_greenstein(p.x, nu);
    var value = rayleigh_phase(nu);
    value = select(value, cornette_shanks(p.x, nu), kind == PHASE_CORNETTE_SHANKS);
    value = select(value, hg, kind == PHASE_HENYEY_GREENSTEIN);
    value = select(value, p.z * hg + (1.0 - p.z) * henyey_greenstein(p.y, nu), kind == PHASE_DUAL_HENYEY_GREENSTEIN);
    return select(value, 0.0, kind == PHASE_TABLE);
}

// Σ σ_s·p over the terms for light travelling along the sun direction scattered into the view:
// nu = dot(view, sun).
fn scattering_phase(c: Coefficients, nu: f32) -> vec3<f32> {
    var total = vec3<f32>(0.0);
    for (var i = 0u; i < term_count(); i++) {
        total += term_scattering(c, i) * analytic_phase(i, nu);
    }
    if atmosphere.table_counts.y > 0u {
        let x = acos(clamp(nu, -1.0, 1.0)) / PI;
        for (var k = 0u; k < atmosphere.table_counts.y; k++) {
            let i = phase_table_term(k);
            total += term_scattering(c, i) * phase_table_value(i, x);
        }
    }
    return total;
}

// ---- Sphere geometry of the LUTs (Bruneton 2017, functions.glsl) ----

fn safe_sqrt(x: f32) -> f32 {
    return sqrt(max(x, 0.0));
}

// Distance from radius r along mu to the top of the LUT sphere (the ray starts inside).
fn distance_to_top(r: f32, mu: f32) -> f32 {
    let top = atmosphere.lut.y;
    return max(-r * mu + safe_sqrt(r * r * (mu * mu - 1.0) + top * top), 0.0);
}

fn ray_hits_ground(r: f32, mu: f32) -> bool {
    let bottom = atmosphere.lut.x;
    return mu < 0.0 && r * r * (mu * mu - 1.0) + bottom * bottom >= 0.0;
}

// Texel-centre mapping of x in [0, 1] onto a texture of `size` texels, and back.
fn unit_to_texel_coord(x: f32, size: f32) -> f32 {
    return 0.5 / size + x * (1.0 - 1.0 / size);
}

fn texel_coord_to_unit(u: f32, size: f32) -> f32 {
    return (u - 0.5 / size) / (1.0 - 1.0 / size);
}

// The mu_s axis of the multiple-scattering and irradiance LUTs: u = (1 + sign(mu_s)·√|mu_s|) / 2,
// so texels crowd around the horizon (mu_s = 0), where twilight changes fastest.
fn mu_s_to_unit(mu_s: f32) -> f32 {
    return 0.5 + 0.5 * sign(mu_s) * sqrt(abs(mu_s));
}

fn unit_to_mu_s(u: f32) -> f32 {
    let x = 2.0 * u - 1.0;
    return sign(x) * x * x;
}

// Whether the air is thick (table_counts.z; gpu_types::medium::is_thick_air): its multiple-
// scattering LUTs' rows stand at atmosphere.lut_rows and their directions crowd at the poles.
fn thick_air() -> bool {
    return atmosphere.table_counts.z != 0u;
}

// The h axis of the multiple-scattering and irradiance LUTs, LUT_ROWS rows from the ground to
// lut.w: evenly spread in a thin air; in a thick one at the altitudes of atmosphere.lut_rows
// (gpu_types::medium::multiscattering_lut_rows), with h linear between them.
const LUT_ROWS: u32 = 32u;

fn lut_row_altitude(i: u32) -> f32 {
    return atmosphere.lut_rows[i / 4u][i % 4u];
}

// The altitude at (fractional) row `row`.
fn lut_row_to_h(row: f32) -> f32 {
    if !thick_air() {
        return row / f32(LUT_ROWS - 1u) * atmosphere.lut.w;
    }
    let i = min(u32(max(row, 0.0)), LUT_ROWS - 2u);
    return mix(lut_row_altitude(i), lut_row_altitude(i + 1u), clamp(row - f32(i), 0.0, 1.0));
}

// The unit coordinate of altitude h on the h axis (clamped to [0, 1]).
fn h_to_lut_unit(h: f32) -> f32 {
    if !thick_air() {
        return clamp(h / atmosphere.lut.w, 0.0, 1.0);
    }
    // The rows lo and hi = lo + 1 around h, by bisection.
    var lo = 0u;
    var hi = LUT_ROWS - 1u;
    while hi - lo > 1u {
        let mid = (lo + hi) / 2u;
        if lut_row_altitude(mid) <= h {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let below = lut_row_altitude(lo);
    let t = clamp((h - below) / max(lut_row_altitude(hi) - below, 1e-3), 0.0, 1.0);
    return (f32(lo) + t) / f32(LUT_ROWS - 1u);
}

// The (mu_s, h) tables (multiple scattering, irradiance): texel coordinates of a lookup, and the
// (mu_s, h) a texel at `uv` stands for, on a table of `size` texels (size.y = LUT_ROWS).
fn mu_s_h_to_uv(mu_s: f32, h: f32, size: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(
        unit_to_texel_coord(mu_s_to_unit(mu_s), size.x),
        unit_to_texel_coord(h_to_lut_unit(h), size.y),
    );
}

fn uv_to_mu_s_h(uv: vec2<f32>, size: vec2<f32>) -> vec2<f32> {
    let unit = texel_coord_to_unit(uv.y, size.y);
    var h = unit * atmosphere.lut.w;
    if thick_air() {
        h = lut_row_to_h(unit * f32(LUT_ROWS - 1u));
    }
    return vec2<f32>(unit_to_mu_s(texel_coord_to_unit(uv.x, size.x)), h);
}

const TRANSMITTANCE_LUT_SIZE: vec2<f32> = vec2<f32>(256.0, 64.0);

// Bruneton's transmittance parameterisation: x_mu spreads the distance to the top between its
// bounds, x_r = rho / H, so the horizon is resolved at every altitude.
fn transmittance_lut_uv(r: f32, mu: f32) -> vec2<f32> {
    let bottom = atmosphere.lut.x;
    let top = atmosphere.lut.y;
    let big_h = sqrt(top * top - bottom * bottom);
    let rho = safe_sqrt(r * r - bottom * bottom);
    let d = distance_to_top(r, mu);
    let d_min = top - r;
    let d_max = rho + big_h;
    let x_mu = (d - d_min) / max(d_max - d_min, 1e-3);
    let x_r = rho / big_h;
    return vec2<f32>(unit_to_texel_coord(x_mu, TRANSMITTANCE_LUT_SIZE.x), unit_to_texel_coord(x_r, TRANSMITTANCE_LUT_SIZE.y));
}

fn transmittance_lut_r_mu(uv: vec2<f32>) -> vec2<f32> {
    let bottom = atmosphere.lut.x;
    let top = atmosphere.lut.y;
    let x_mu = texel_coord_to_unit(uv.x, TRANSMITTANCE_LUT_SIZE.x);
    let x_r = texel_coord_to_unit(uv.y, TRANSMITTANCE_LUT_SIZE.y);
    let big_h = sqrt(top * top - bottom * bottom);
    let rho = big_h * x_r;
    let r = sqrt(rho * rho + bottom * bottom);
    let d_min = top - r;
    let d_max = rho + big_h;
    let d = d_min + x_mu * (d_max - d_min);
    var mu = 1.0;
    if d > 0.0 {
        mu = clamp((big_h * big_h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    }
    return vec2<f32>(r, mu);
}

// ---- Ellipsoids ----

// Altitude above the ellipsoid surface: f/|∇f| for f(p) = |p/a| − 1, refined once at the point
// that distance down along ∇f (firmament_core Planet::approximate_altitude; < 2 mm below 100 km
// at flattening 0.1). Returns the altitude and the outward unit normal (local up).
struct AltitudeUp {
    h: f32,
    up: vec3<f32>,
}

fn first_order_altitude(p: vec3<f32>) -> AltitudeUp {
    let a = atmosphere.radii.xyz;
    let q = p / a;
    let q_len = length(q);
    let gradient = p / (a * a) / max(q_len, 1e-30);
    let gradient_len = length(gradient);
    var out: AltitudeUp;
    out.h = (q_len - 1.0) / max(gradient_len, 1e-30);
    out.up = gradient / max(gradient_len, 1e-30);
    return out;
}

fn altitude_up(p: vec3<f32>) -> AltitudeUp {
    let first = first_order_altitude(p);
    let second = first_order_altitude(p - first.up * first.h);
    var out: AltitudeUp;
    out.h = first.h + second.h;
    out.up = second.up;
    return out;
}

fn top_radii() -> vec3<f32> {
    return atmosphere.radii.xyz + vec3<f32>(atmosphere.radii.w);
}

// Hillaire's energy-conserving step: ∫₀^dt S·e^(−σ_t·s) ds = S·(1 − T)/σ_t for a source S and
// extinction σ_t constant over the step (T = e^(−σ_t·dt)); S·dt where σ_t vanishes.
fn integrate_step(source: vec3<f32>, extinction: vec3<f32>, step_transmittance: vec3<f32>, dt: f32) -> vec3<f32> {
    let thin = extinction * dt < vec3<f32>(1e-4);
    return select((source - source * step_transmittance) / max(extinction, vec3<f32>(1e-30)), source * dt, thin);
}
