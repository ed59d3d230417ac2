//! Criterion benchmark of NREL's SPA: the sun's position at 1 000 000 timestamps (one year at
//! 31.536 s steps, Golden, Colorado), on one thread and on every core with rayon.
//!
//! Run: `cargo bench -p firmament-core --bench sun_position`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use firmament_core::astro::Instant;
use firmament_core::astro::spa::{SpaInput, solar_position};
use rayon::prelude::*;

/// Timestamps in the run.
const COUNT: usize = 1_000_000;

/// One year from 2024-01-01 00:00 UT in `COUNT` steps.
fn inputs() -> Vec<SpaInput> {
    let start = 2_460_310.5;
    let step = 365.0 / COUNT as f64;
    (0..COUNT)
        .map(|i| {
            let instant = Instant {
                jd: start + step * i as f64,
                delta_t: 69.2,
            };
            SpaInput {
                elevation_m: 1830.14,
                pressure_mbar: 820.0,
                temperature_c: 11.0,
                ..SpaInput::new(instant, 39.742476, -105.1786)
            }
        })
        .collect()
}

fn sun_position(c: &mut Criterion) {
    let inputs = inputs();
    let mut group = c.benchmark_group("sun_position_1M");
    // Seconds per iteration: ten samples of one iteration each.
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.bench_function("single_thread", |b| {
        b.iter(|| {
            black_box(&inputs)
                .iter()
                .map(|input| solar_position(input).zenith_deg)
                .sum::<f64>()
        })
    });
    group.bench_function(format!("rayon_{}_threads", rayon::current_num_threads()), |b| {
        b.iter(|| {
            black_box(&inputs)
                .par_iter()
                .map(|input| solar_position(input).zenith_deg)
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, sun_position);
criterion_main!(benches);
