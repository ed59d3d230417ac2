// atmosphere/multiscattering_diffusion.wgsl — the orders of light after the last one marched in a
// thick air (Venus, Titan), by the diffusion approximation, added to the multiple-scattering sums.
//
// Conventions: as atmosphere/luts.wgsl. One invocation per column x of MULTISCATTERING_LUT_SIZE
// (one mu_s), all wavelengths at once. Row y of the LUT lies at h = lut_row_to_h(y) (common.wgsl:
// a thick air's rows, crowded where its light changes fast).
//
// Where the air is optically thick, light diffuses through hundreds of orders before it reaches
// the ground, and the ratio of successive orders has not settled after the few marched
// (multiscattering_sum.wgsl's geometric tail then leaves Venus's ground black). The light of the
// orders after the last marched one, n, is instead the solution of the transport equation whose
// source is order n scattered once, and that is solved in the Eddington (P1) approximation of a
// plane-parallel column at this mu_s (Eddington 1916; Meador & Weaver, "Two-Stream
// Approximations to Radiative Transfer in Planetary Atmospheres", J. Atmos. Sci. 37, 1980):
// with J the mean radiance and H = mean(L·ω_z) over the directions ω the light arrives from (as
// the LUT's z moment; up positive),
//   dH/dz = σ_a·J − Q0,        Q0 = Σ_i (1 − f_i)·σ_s,i·Ψ_n       (the energy balance)
//   dJ/dz = 3·(σ_tr·H − Q1),   Q1 = Σ_i (a1_i − f_i)·σ_s,i·z_n    (Fick's law)
// σ_tr = σ_t − Σ a1_i·σ_s,i the transport extinction (the same with or without the delta-M peaks
// f_i), Ψ_n and z_n order n's mean and z moment. Marshak's boundary conditions: no light arrives
// from above the top, π(J + 2H) = 0; the Lambertian ground of albedo A sends up A times what
// arrives from above, the tail's own and order n's irradiance E_n: π(J − 2H) = A·(π(J + 2H) + E_n).
// Finite volumes on NODES altitudes (REFINE evenly spread between rows; the sources between rows
// interpolated as the LUT is, Ψ_n log-linearly), solved by the Thomas algorithm; the tail at
// each row adds J to Ψ, J/3 to the second moments zz and xx (isotropic), H to the z moment and
// π(J + 2H) to the sky irradiance. passes/atmosphere/multiscattering.rs runs it instead of the geometric tail in a
// thick air (gpu_types::medium::THICK_AIR_DEPTH; docs/ATMOSPHERE.md, "Thick airs").

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts

const ROWS: u32 = LUT_ROWS;
const REFINE: u32 = 8u;
const NODES: u32 = (ROWS - 1u) * REFINE + 1u;

// The smallest transport extinction the column uses, m⁻¹: where the air all but ends (the top of
// Titan's 600 km) the light streams freely; 10⁻⁹ m⁻¹ keeps Fick's law finite there.
const MIN_TRANSPORT: f32 = 1e-9;

// The column's coefficients at one altitude.
struct Column {
    absorption: vec3<f32>,
    transport: vec3<f32>,
    scattered_mean: vec3<f32>,  // Σ (1 − f_i)·σ_s,i
    scattered_first: vec3<f32>, // Σ (a1_i − f_i)·σ_s,i
}

fn column_at(h: f32) -> Column {
    let c = coefficients_at(h);
    var out: Column;
    var scattering = vec3<f32>(0.0);
    var first = vec3<f32>(0.0);
    var mean = vec3<f32>(0.0);
    for (var i = 0u; i < term_count(); i++) {
        let sigma = term_scattering(c, i);
        let f = atmosphere.terms[i].phase.w;
        let a1 = atmosphere.terms[i].legendre.x;
        scattering += sigma;
        mean += (1.0 - f) * sigma;
        first += (a1 - f) * sigma;
        out.transport -= a1 * sigma;
    }
    out.absorption = max(c.extinction - scattering, vec3<f32>(0.0));
    out.transport = max(out.transport + c.extinction, vec3<f32>(MIN_TRANSPORT));
    out.scattered_mean = mean;
    out.scattered_first = first;
    return out;
}

// Order n's mean Ψ_n and z moment at fine node j of column x: log-linear in Ψ between rows, the
// ratio z/Ψ linear (as the LUT is read).
struct Source {
    psi: vec3<f32>,
    z: vec3<f32>,
}

fn last_order_at(x: u32, j: u32) -> Source {
    let y0 = min(j / REFINE, ROWS - 2u);
    let t = f32(j - y0 * REFINE) / f32(REFINE);
    let a = multiscattering_orders[y0 * ROWS + x].last;
    let b = multiscattering_orders[(y0 + 1u) * ROWS + x].last;
    let psi0 = a[0].rgb;
    let psi1 = b[0].rgb;
    let positive = psi0 > vec3<f32>(1e-30) & psi1 > vec3<f32>(1e-30);
    let log_mix = exp(mix(log(max(psi0, vec3<f32>(1e-30))), log(max(psi1, vec3<f32>(1e-30))), t));
    var out: Source;
    out.psi = select(mix(psi0, psi1, t), log_mix, positive);
    out.z = mix(moment_ratio(a[5].rgb, psi0), moment_ratio(b[5].rgb, psi1), t) * out.psi;
    return out;
}

// Fick's law between nodes j and j + 1 as H = alpha·(J_{j+1} − J_j) + beta.
struct Flux {
    alpha: vec3<f32>,
    beta: vec3<f32>,
}

// The altitude of fine node j.
fn node_h(j: u32) -> f32 {
    return lut_row_to_h(f32(j) / f32(REFINE));
}

fn flux_between(x: u32, j: u32) -> Flux {
    let dz = node_h(j + 1u) - node_h(j);
    let column = column_at(0.5 * (node_h(j) + node_h(j + 1u)));
    let below = last_order_at(x, j);
    let above = last_order_at(x, j + 1u);
    let q1 = column.scattered_first * 0.5 * (below.z + above.z);
    var out: Flux;
    out.alpha = 1.0 / (3.0 * dz * column.transport);
    out.beta = q1 / column.transport;
    return out;
}

var<private> solve_c: array<vec3<f32>, NODES>;
var<private> solve_d: array<vec3<f32>, NODES>;

@compute @workgroup_size(32)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = id.x;
    if x >= ROWS {
        return;
    }
    let albedo = atmosphere.ground_albedo.rgb;
    let ground = decode_log(textureLoad(previous_ground_irradiance, vec2<i32>(i32(x), 0), 0).rgb);
    // The ground's H = kappa·J − epsilon (its boundary condition solved for H).
    let kappa = (1.0 - albedo) / (2.0 * (1.0 + albedo));
    let epsilon = albedo * ground / (2.0 * PI * (1.0 + albedo));

    // Node j's balance H_{j+½} − H_{j−½} = w·(σ_a·J_j − Q0_j), w the length of its cell (from
    // halfway to the node below to halfway to the one above; the ground's H is H_{−½} and the
    // top's −J/2 is H_{N−½}), written as
    // lower·J_{j−1} + diagonal·J_j + upper·J_{j+1} = rhs and swept forward (Thomas).
    var below = Flux(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var j = 0u; j < NODES; j++) {
        let h = node_h(j);
        let column = column_at(h);
        let q0 = column.scattered_mean * last_order_at(x, j).psi;
        let w = 0.5 * (node_h(min(j + 1u, NODES - 1u)) - node_h(max(j, 1u) - 1u));
        var above = Flux(vec3<f32>(0.0), vec3<f32>(0.0));
        if j + 1u < NODES {
            above = flux_between(x, j);
        }
        var lower = below.alpha;
        var diagonal = above.alpha + below.alpha + w * column.absorption;
        let upper = above.alpha;
        var rhs = w * q0 + above.beta - below.beta;
        if j == 0u {
            lower = vec3<f32>(0.0);
            diagonal = above.alpha + kappa + w * column.absorption;
            rhs = w * q0 + above.beta + epsilon;
        } else if j == NODES - 1u {
            diagonal = below.alpha + vec3<f32>(0.5) + w * column.absorption;
            rhs = w * q0 - below.beta;
        }
        // −lower·J_{j−1} + diagonal·J_j − upper·J_{j+1} = rhs, swept.
        var denominator = diagonal;
        var d = rhs;
        if j > 0u {
            denominator -= lower * solve_c[j - 1u];
            d += lower * solve_d[j - 1u];
        }
        solve_c[j] = upper / denominator;
        solve_d[j] = d / denominator;
        below = above;
    }
    // Back substitution: J in solve_d.
    for (var j = NODES - 1u; j > 0u; j--) {
        solve_d[j - 1u] += solve_c[j - 1u] * solve_d[j];
    }

    for (var y = 0u; y < ROWS; y++) {
        let j = y * REFINE;
        let mean = max(solve_d[j], vec3<f32>(0.0));
        var h: vec3<f32>;
        if j == 0u {
            h = kappa * mean - epsilon;
        } else if j == NODES - 1u {
            h = -0.5 * mean;
        } else {
            let down = flux_between(x, j - 1u);
            let up = flux_between(x, j);
            let h_down = down.alpha * (solve_d[j] - solve_d[j - 1u]) + down.beta;
            let h_up = up.alpha * (solve_d[j + 1u] - solve_d[j]) + up.beta;
            h = 0.5 * (h_down + h_up);
        }
        let index = y * ROWS + x;
        multiscattering_orders[index].sum[0] += vec4<f32>(mean, 0.0);
        multiscattering_orders[index].sum[1] += vec4<f32>(mean / 3.0, 0.0);
        multiscattering_orders[index].sum[2] += vec4<f32>(mean / 3.0, 0.0);
        multiscattering_orders[index].sum[5] += vec4<f32>(h, 0.0);
        multiscattering_orders[index].irradiance += vec4<f32>(max(PI * (mean + 2.0 * h), vec3<f32>(0.0)), 0.0);
    }
}
