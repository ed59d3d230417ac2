//! GPU tests of the multiple-scattering LUTs' geometric tail: the orders after the last one
//! marched, summed as a series from the last two (`atmosphere/multiscattering_sum.wgsl`), against
//! marching every order up to one where nothing is left. The sky against the f64 reference is
//! tested in `atmosphere.rs`; this checks the tail alone, texel by texel, where the reference's
//! noise would hide it.

use crate::support::gpu;

use firmament_core::Camera;
use firmament_core::atmosphere::{Atmosphere, Planet, Spectrum, presets};
use firmament_core::frame::AtmosphereSky;
use firmament_render::passes::AtmospherePass;
use firmament_render::passes::atmosphere::luts::LOG_FLOOR;
use firmament_render::readback::{decode_f16, read_texture};
use firmament_render::{GpuContext, wgpu};

/// Orders marched for the comparison: on Earth order 24 is under 10⁻¹⁰ of the first.
const MANY_ORDERS: u32 = 24;

/// Ψ of every texel (rgb, decoded from its logarithm) after `build` encoded the medium's LUTs.
fn psi(ctx: &GpuContext, pass: &AtmospherePass, build: impl FnOnce(&mut wgpu::CommandEncoder)) -> Vec<f64> {
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
    build(&mut encoder);
    ctx.queue.submit([encoder.finish()]);
    let texels = decode_f16(&read_texture(ctx, &pass.luts().multiscattering.texture).expect("readback"));
    texels
        .chunks_exact(4)
        .flat_map(|t| t[..3].to_vec())
        .map(|log| {
            if f64::from(log) <= LOG_FLOOR {
                0.0
            } else {
                f64::from(log).exp()
            }
        })
        .collect()
}

/// Ψ's relative difference, the tail against many orders, over texels and wavelengths where Ψ
/// is above `floor` times its largest value: (median, worst) for floors 10⁻⁴ (the sky down to
/// the sun ~6° below the horizon) and 10⁻⁷ (deep twilight).
fn tail_errors(atmosphere: Atmosphere) -> [(f64, f64); 2] {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let sky = AtmosphereSky {
        atmosphere,
        suns: vec![],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    let mut pass = AtmospherePass::new(&ctx.device);
    pass.prepare(&ctx.queue, &sky, &Camera::default());
    let tail = psi(ctx, &pass, |e| pass.record_medium_luts(e));
    let many = psi(ctx, &pass, |e| pass.record_medium_luts_to_order(e, MANY_ORDERS));
    let largest = many.iter().copied().fold(0.0, f64::max);
    [1e-4, 1e-7].map(|floor| {
        let mut errors: Vec<f64> = tail
            .iter()
            .zip(&many)
            .filter(|&(_, &m)| m > floor * largest)
            .map(|(&t, &m)| (t - m).abs() / m)
            .collect();
        errors.sort_by(f64::total_cmp);
        (errors[errors.len() / 2], errors[errors.len() - 1])
    })
}

/// Checks the bright texels' median and worst and the dim ones' worst against `limits`.
fn check(name: &str, atmosphere: Atmosphere, limits: [f64; 3]) {
    let [bright, dim] = tail_errors(atmosphere);
    println!(
        "{name}: Ψ with the tail against {MANY_ORDERS} orders marched: median {:.3} %, worst {:.3} % \
         (Ψ ≥ 1e-4 of its largest); worst {:.2} % (≥ 1e-7)",
        bright.0 * 100.0,
        bright.1 * 100.0,
        dim.1 * 100.0
    );
    assert!(
        bright.0 < limits[0] && bright.1 < limits[1] && dim.1 < limits[2],
        "{name}: {bright:?}, {dim:?}"
    );
}

#[test]
fn the_tail_matches_marching_every_order_on_earth() {
    check("earth", presets::earth(), [0.002, 0.01, 0.05]);
}

#[test]
fn the_tail_matches_marching_every_order_in_thick_haze_and_dust() {
    let mut haze = presets::earth();
    haze.planet = Planet::sphere(6_360_000.0, 60_000.0);
    haze.medium.terms[1].scattering *= 10.0;
    haze.medium.terms[1].absorption *= 10.0;
    haze.medium.ground_albedo = Spectrum::splat(0.3);
    check("earth, haze ×10, albedo 0.3", haze, [0.005, 0.03, 0.1]);
    check("mars", presets::mars(), [0.006, 0.06, 0.4]);
}
