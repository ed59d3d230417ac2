//! Criterion benchmark of a body's air's tables (`AirLight`): what the renderer makes once when
//! a body's air, size or albedo changes.
//!
//! Run: `cargo bench -p firmament-core --bench body_air`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use firmament_core::atmosphere::body::{AirLight, BodyAir};
use firmament_core::atmosphere::{Spectrum, presets};

fn body_air(c: &mut Criterion) {
    let mut group = c.benchmark_group("body_air");
    let air = BodyAir::from_atmosphere(&presets::earth()).expect("Earth's air is made of constituents");
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.bench_function("earth_air_light", |b| {
        b.iter(|| AirLight::new(black_box(&air), 6_371_000.0, Spectrum::splat(0.3)))
    });
    group.finish();
}

criterion_group!(benches, body_air);
criterion_main!(benches);
