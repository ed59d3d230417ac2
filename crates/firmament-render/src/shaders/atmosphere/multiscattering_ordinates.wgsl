// atmosphere/multiscattering_ordinates.wgsl — the orders of light after the last one marched in
// a thick air (Venus, Titan), by discrete ordinates, as the field one more order marches from.
//
// Conventions: as atmosphere/luts.wgsl. One invocation per column x of MULTISCATTERING_LUT_SIZE
// (one mu_s), each wavelength in turn. Row y of the LUT lies at h = lut_row_to_h(y)
// (common.wgsl: a thick air's rows, crowded where its light changes fast). Here μ is the cosine
// of the direction light travels in, up positive (the LUT's moments take the direction it
// arrives from: its z moment is −m₁).
//
// Where the air is optically thick, light diffuses through hundreds of orders before it reaches
// the ground, and the ratio of successive orders has not settled after the few marched
// (multiscattering_sum.wgsl's geometric tail then leaves Venus's ground black). The light L of
// the orders after the last marched one, n, solves the transport equation whose source is order
// n scattered once, which is solved here in a plane-parallel column at this mu_s, azimuthally
// averaged, by discrete ordinates (Chandrasekhar 1950, "Radiative Transfer", ch. II; Stamnes et
// al. 1988, "Numerically stable algorithm for discrete-ordinate-method radiative transfer in
// multiple scattering and emitting layered media", Appl. Opt. 27, 2502) on STREAMS double-Gauss
// directions per hemisphere (Sykes 1951), in the even-parity form of Vladimirov (1963):
// with ψ = (L(μ) + L(−μ))/2 and φ = (L(μ) − L(−μ))/2 at the STREAMS cosines μ > 0,
//   μ·dφ/dz = −B·ψ + Q⁺,    B = σ'·1 − S⁺·W     (the even Legendre bands)
//   μ·dψ/dz = −A·φ + Q⁻,    A = σ'·1 − S⁻·W     (the odd bands)
// σ' = σ_t − Σ_i f_i·σ_s,i the extinction without the delta-M peaks, S±_jk = Σ_l (2l + 1)·s_l·
// P_l(μ_j)·P_l(μ_k) over the even (odd) bands l ≤ 4, s_l = Σ_i (a_l,i − f_i)·σ_s,i (the phase
// functions as the later orders scatter them, multiscattering_lut.wgsl), W the weights, and
// Q± the even and odd parts of order n scattered, Σ_l (2l + 1)·s_l·P_l(μ)·m_l from its Legendre
// moments m_l about the vertical. Eliminating φ = A⁻¹·(Q⁻ − μ·dψ/dz) leaves a second-order
// system in ψ, solved by finite volumes on NODES altitudes (REFINE evenly spread between rows;
// order n interpolated between rows as the LUT is, Ψ_n log-linearly) and the block Thomas
// algorithm. Boundaries: no light comes down at the top (φ = ψ); the Lambertian ground of
// albedo A sends up A/π times the irradiance from above, the tail's own and order n's E_n.
// Against the exact solution of a uniform isotropic slab, four streams a hemisphere are within
// 0.1 % at every depth; the Eddington (P1) approximation that stood here was −7 … +18 % off
// (docs/ATMOSPHERE.md, "Thick airs").
//
// This writes order n plus the tail (its moments Ψ, zz, xx, z and the m = 0 parts of bands 3
// and 4; its irradiance to the ground row) as the moments an order reads, and
// passes/atmosphere/multiscattering.rs marches one more order from them — a transport sweep in
// the sphere, whose light, the orders after n scattered once more from this field, stands for
// them all and brings back what the column's azimuthal mean left out. It runs instead of the
// geometric tail in a thick air (gpu_types::medium::THICK_AIR_DEPTH).

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/moments_out

const ROWS: u32 = LUT_ROWS;
const REFINE: u32 = 8u;
const NODES: u32 = (ROWS - 1u) * REFINE + 1u;

// The directions per hemisphere and their cosines and weights: Gauss–Legendre on [0, 1] (the
// weights of each hemisphere add up to 1, so a mean over the sphere is Σ w·ψ).
const STREAMS: u32 = 4u;
const MU: vec4<f32> = vec4<f32>(0.069431844, 0.33000948, 0.66999052, 0.93056816);
const WEIGHT: vec4<f32> = vec4<f32>(0.17392742, 0.32607258, 0.32607258, 0.17392742);

// The smallest extinction the column's odd system uses, m⁻¹: where the air all but ends (the top
// of Titan's 600 km) light streams freely; 10⁻⁹ m⁻¹ keeps A invertible there.
const MIN_EXTINCTION: f32 = 1e-9;

// The Legendre polynomials P_0 … P_4 at the four cosines.
struct Legendre {
    p: array<vec4<f32>, 5>,
}

fn legendre_at_streams() -> Legendre {
    let m2 = MU * MU;
    var out: Legendre;
    out.p[0] = vec4<f32>(1.0);
    out.p[1] = MU;
    out.p[2] = 0.5 * (3.0 * m2 - 1.0);
    out.p[3] = 0.5 * MU * (5.0 * m2 - 3.0);
    out.p[4] = (35.0 * m2 * m2 - 30.0 * m2 + 3.0) / 8.0;
    return out;
}

fn outer(a: vec4<f32>, b: vec4<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(a * b.x, a * b.y, a * b.z, a * b.w);
}

fn diagonal(v: vec4<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(
        vec4<f32>(v.x, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, v.y, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, v.z, 0.0),
        vec4<f32>(0.0, 0.0, 0.0, v.w),
    );
}

// X and x with a·X = b and a·x = v, by Gauss–Jordan elimination with partial pivoting.
struct Solved {
    m: mat4x4<f32>,
    v: vec4<f32>,
}

fn solve4(a: mat4x4<f32>, b: mat4x4<f32>, v: vec4<f32>) -> Solved {
    // Rows of [a | b | v].
    var ra = transpose(a);
    var rb = transpose(b);
    var rv = v;
    for (var k = 0u; k < 4u; k++) {
        var p = k;
        for (var i = k + 1u; i < 4u; i++) {
            if abs(ra[i][k]) > abs(ra[p][k]) {
                p = i;
            }
        }
        let swap_a = ra[k];
        ra[k] = ra[p];
        ra[p] = swap_a;
        let swap_b = rb[k];
        rb[k] = rb[p];
        rb[p] = swap_b;
        let swap_v = rv[k];
        rv[k] = rv[p];
        rv[p] = swap_v;
        let inverse = 1.0 / ra[k][k];
        ra[k] *= inverse;
        rb[k] *= inverse;
        rv[k] *= inverse;
        for (var i = 0u; i < 4u; i++) {
            if i != k {
                let factor = ra[i][k];
                ra[i] -= factor * ra[k];
                rb[i] -= factor * rb[k];
                rv[i] -= factor * rv[k];
            }
        }
    }
    return Solved(transpose(rb), rv);
}

// The column's coefficients at one altitude, at one wavelength.
struct Column {
    extinction: f32,         // σ' = σ_t − Σ f_i·σ_s,i
    bands: array<f32, 5>,    // s_l = Σ (a_l,i − f_i)·σ_s,i
}

fn column_at(h: f32, channel: u32) -> Column {
    let c = coefficients_at(h);
    var out: Column;
    out.extinction = c.diffuse_extinction[channel];
    for (var i = 0u; i < term_count(); i++) {
        let sigma = term_scattering(c, i)[channel];
        let f = atmosphere.terms[i].phase.w;
        let a = atmosphere.terms[i].legendre;
        out.bands[0] += (1.0 - f) * sigma;
        out.bands[1] += (a.x - f) * sigma;
        out.bands[2] += (a.y - f) * sigma;
        out.bands[3] += (a.z - f) * sigma;
        out.bands[4] += (a.w - f) * sigma;
    }
    return out;
}

// B (even) or A (odd): σ'·1 − Σ_l (2l + 1)·s_l·P_l·P_lᵀ·W over the bands of that parity.
fn column_matrix(column: Column, legendre: Legendre, odd: bool) -> mat4x4<f32> {
    var m = diagonal(vec4<f32>(column.extinction));
    if odd {
        m = diagonal(vec4<f32>(max(column.extinction, MIN_EXTINCTION)));
    }
    for (var l = select(0u, 1u, odd); l < 5u; l += 2u) {
        let p = legendre.p[l];
        m -= outer(p, p * WEIGHT) * (f32(2u * l + 1u) * column.bands[l]);
    }
    return m;
}

// Order n's Legendre moments m_0 … m_4 about the vertical (travel directions) at fine node j of
// column x, at one wavelength: Ψ log-linear between rows, the others' ratios to Ψ linear (the
// LUT's reads bend ln Ψ, multiscattering_curvature.wgsl; reading three more rows here stalled
// llvmpipe's compiler). Bands 3 and 4 are kept summed over wavelengths and share Ψ's spectrum.
fn last_order_at(x: u32, j: u32, channel: u32) -> array<f32, 5> {
    let y0 = min(j / REFINE, ROWS - 2u);
    let t = f32(j - y0 * REFINE) / f32(REFINE);
    let a = multiscattering_orders[y0 * ROWS + x].last;
    let b = multiscattering_orders[(y0 + 1u) * ROWS + x].last;
    let psi0 = a[0][channel];
    let psi1 = b[0][channel];
    var psi = mix(psi0, psi1, t);
    if psi0 > 1e-30 && psi1 > 1e-30 {
        psi = exp(mix(log(psi0), log(psi1), t));
    }
    let sum0 = max(a[0].r + a[0].g + a[0].b, 1e-30);
    let sum1 = max(b[0].r + b[0].g + b[0].b, 1e-30);
    let z = mix(a[5][channel] / max(psi0, 1e-30), b[5][channel] / max(psi1, 1e-30), t) * psi;
    let zz = mix(a[1][channel] / max(psi0, 1e-30), b[1][channel] / max(psi1, 1e-30), t) * psi;
    let band3 = mix(a[1].w / sum0, b[1].w / sum1, t) * psi;
    let band4 = mix(a[5].w / sum0, b[5].w / sum1, t) * psi;
    // The LUT's band 3 and 4 m = 0 sums are √7·P_3 and 3·P_4 of the arrival direction.
    return array<f32, 5>(psi, -z, 0.5 * (3.0 * zz - psi), -band3 / 2.6457513, band4 / 3.0);
}

// Q⁺ (even bands) or Q⁻ (odd): order n scattered once, Σ_l (2l + 1)·s_l·P_l(μ)·m_l.
fn source(column: Column, legendre: Legendre, moments: array<f32, 5>, odd: bool) -> vec4<f32> {
    var q = vec4<f32>(0.0);
    for (var l = select(0u, 1u, odd); l < 5u; l += 2u) {
        q += legendre.p[l] * (f32(2u * l + 1u) * column.bands[l] * moments[l]);
    }
    return q;
}

// The altitude of fine node j.
fn node_h(j: u32) -> f32 {
    return lut_row_to_h(f32(j) / f32(REFINE));
}

// Between nodes j and j + 1: μ·φ = e − D·(ψ_{j+1} − ψ_j), D = μ·A⁻¹·μ/dz and e = μ·A⁻¹·Q⁻.
struct Flux {
    d: mat4x4<f32>,
    e: vec4<f32>,
    // A⁻¹·Q⁻ and A⁻¹·μ/dz, for φ itself.
    phi_source: vec4<f32>,
    phi_gradient: mat4x4<f32>,
}

fn flux_between(x: u32, j: u32, channel: u32, legendre: Legendre) -> Flux {
    let dz = node_h(j + 1u) - node_h(j);
    let column = column_at(0.5 * (node_h(j) + node_h(j + 1u)), channel);
    let q_below = source(column, legendre, last_order_at(x, j, channel), true);
    let q_above = source(column, legendre, last_order_at(x, j + 1u, channel), true);
    let mu = diagonal(MU);
    let solved = solve4(column_matrix(column, legendre, true), mu * (1.0 / dz), 0.5 * (q_below + q_above));
    var out: Flux;
    out.d = mu * solved.m;
    out.e = MU * solved.v;
    out.phi_source = solved.v;
    out.phi_gradient = solved.m;
    return out;
}

// The block Thomas algorithm's forward sweep: ψ_j = solve_d[j] − solve_c[j]·ψ_{j+1}.
var<private> solve_c: array<mat4x4<f32>, NODES>;
var<private> solve_d: array<vec4<f32>, NODES>;

// Order n plus the tail at each row, as `OrderSums` (moments_out.wgsl) before they are stored.
var<private> rows: array<array<vec4<f32>, ORDER_SUMS>, ROWS>;

@compute @workgroup_size(32)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = id.x;
    if x >= ROWS {
        return;
    }
    let legendre = legendre_at_streams();
    let mu = diagonal(MU);
    let identity = diagonal(vec4<f32>(1.0));
    let ground_light = decode_log(textureLoad(previous_ground_irradiance, vec2<i32>(i32(x), 0), 0).rgb);
    for (var y = 0u; y < ROWS; y++) {
        rows[y] = multiscattering_orders[y * ROWS + x].last;
    }
    var ground_tail = vec3<f32>(0.0);

    for (var channel = 0u; channel < 3u; channel++) {
        let albedo = atmosphere.ground_albedo[channel];
        // The ground: ψ + φ = A/π·(E_n + 2π·Σ w·μ·(ψ − φ)), solved for φ = P·ψ + p.
        let reflect = outer(vec4<f32>(1.0), WEIGHT * MU) * (2.0 * albedo);
        let ground = solve4(identity + reflect, reflect - identity, vec4<f32>(albedo / PI * ground_light[channel]));

        // Node j's balance, μ·(φ_{j+½} − φ_{j−½}) + w·B·ψ_j = w·Q⁺_j with w its cell's length,
        // as lower·ψ_{j−1} + middle·ψ_j + upper·ψ_{j+1} = rhs.
        var below: Flux;
        for (var j = 0u; j < NODES; j++) {
            let column = column_at(node_h(j), channel);
            let w = 0.5 * (node_h(min(j + 1u, NODES - 1u)) - node_h(max(j, 1u) - 1u));
            var middle = column_matrix(column, legendre, false) * w;
            var rhs = source(column, legendre, last_order_at(x, j, channel), false) * w;
            var lower = mat4x4<f32>();
            var upper = mat4x4<f32>();
            if j > 0u {
                middle += below.d;
                lower = below.d * -1.0;
                rhs += below.e;
            }
            var above: Flux;
            if j + 1u < NODES {
                above = flux_between(x, j, channel, legendre);
                middle += above.d;
                upper = above.d * -1.0;
                rhs -= above.e;
            }
            if j == 0u {
                middle -= mu * ground.m;
                rhs += MU * ground.v;
            }
            if j == NODES - 1u {
                middle += mu;
            }
            if j > 0u {
                middle -= lower * solve_c[j - 1u];
                rhs -= lower * solve_d[j - 1u];
            }
            let solved = solve4(middle, upper, rhs);
            solve_c[j] = solved.m;
            solve_d[j] = solved.v;
            below = above;
        }
        // Back substitution: ψ in solve_d.
        for (var j = NODES - 1u; j > 0u; j--) {
            solve_d[j - 1u] -= solve_c[j - 1u] * solve_d[j];
        }

        // The tail's moments at each row (arrival directions, as the LUT keeps them).
        for (var y = 0u; y < ROWS; y++) {
            let j = y * REFINE;
            let psi = solve_d[j];
            var phi: vec4<f32>;
            if j == 0u {
                phi = ground.m * psi + ground.v;
                ground_tail[channel] = 2.0 * PI * dot(WEIGHT * MU, psi - phi);
            } else if j == NODES - 1u {
                phi = psi;
            } else {
                let down = flux_between(x, j - 1u, channel, legendre);
                let up = flux_between(x, j, channel, legendre);
                let phi_down = down.phi_source - down.phi_gradient * (psi - solve_d[j - 1u]);
                let phi_up = up.phi_source - up.phi_gradient * (solve_d[j + 1u] - psi);
                phi = 0.5 * (phi_down + phi_up);
            }
            let mean = dot(WEIGHT, psi);
            let zz = dot(WEIGHT * MU * MU, psi);
            rows[y][0][channel] += mean;
            rows[y][1][channel] += zz;
            rows[y][2][channel] += 0.5 * (mean - zz);
            rows[y][5][channel] -= dot(WEIGHT * MU, phi);
            rows[y][1].w -= 2.6457513 * dot(WEIGHT * legendre.p[3], phi);
            rows[y][5].w += 3.0 * dot(WEIGHT * legendre.p[4], psi);
        }
    }

    store_texel(GROUND_ROW_START + x, vec4<f32>(encode_log(ground_light + max(ground_tail, vec3<f32>(0.0))), 1.0));
    for (var y = 0u; y < ROWS; y++) {
        store_moments(y * ROWS + x, rows[y]);
    }
}
