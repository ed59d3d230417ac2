// atmosphere/multiscattering_curvature.wgsl — a thick air's multiple-scattering moments: how
// ln Ψ bends down each column, so that a lookup between two rows follows it.
//
// Conventions: as atmosphere/luts.wgsl. One invocation per column x of MULTISCATTERING_LUT_SIZE,
// walking its rows in `multiscattering_out` (moments_out.wgsl) after an order or the sum is
// written there and before it is copied into the LUT. The alpha of each Ψ texel (0 as written,
// and so in a thin air) gets ln Ψ's second difference over the rows below and above it, the mean
// over wavelengths; the ground and top rows take their neighbour's. `sample_moments` (luts.wgsl)
// subtracts t·(1 − t)/2 of it from the linear interpolation: a quadratic through three rows.
// Read linearly, each order's march read the order before it low between rows, and the losses
// compounded over the orders (docs/ATMOSPHERE.md, "Thick airs").

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts

const COLUMNS: u32 = u32(MULTISCATTERING_LUT_SIZE.x);

fn log_psi(y: u32, x: u32) -> vec3<f32> {
    let texel = multiscattering_out[y * COLUMNS + x];
    return vec3<f32>(unpack2x16float(texel.x), unpack2x16float(texel.y).x);
}

// ln Ψ's second difference at a row from it and its neighbours (0 where any holds no light).
fn second_difference(below: vec3<f32>, here: vec3<f32>, above: vec3<f32>) -> f32 {
    let lit = all(min(min(below, here), above) > vec3<f32>(LOG_FLOOR));
    let d = below - 2.0 * here + above;
    return select(0.0, (d.x + d.y + d.z) / 3.0, lit);
}

fn store_curvature(y: u32, x: u32, log_psi_blue: f32, curvature: f32) {
    let index = y * COLUMNS + x;
    multiscattering_out[index].y = pack2x16float(vec2<f32>(log_psi_blue, curvature));
}

@compute @workgroup_size(32)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = id.x;
    if x >= COLUMNS {
        return;
    }
    var below = log_psi(0u, x);
    var here = log_psi(1u, x);
    for (var y = 1u; y + 1u < LUT_ROWS; y++) {
        let above = log_psi(y + 1u, x);
        let curvature = second_difference(below, here, above);
        if y == 1u {
            store_curvature(0u, x, below.z, curvature);
        }
        if y + 2u == LUT_ROWS {
            store_curvature(LUT_ROWS - 1u, x, above.z, curvature);
        }
        store_curvature(y, x, here.z, curvature);
        below = here;
        here = above;
    }
}
