//! Criterion benchmark of the eclipse models: the eclipsed share of a limb-darkened sun (what
//! the GPU evaluates per sample, here in f64) and the Earth's shadow profile at the Moon (what a
//! lunar-eclipse frame builds once).
//!
//! Run: `cargo bench -p firmament-core --bench eclipses`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use firmament_core::atmosphere::eclipse::hidden_fraction;
use firmament_core::atmosphere::planet_shadow::{PlanetShadow, ShadowSettings};
use firmament_core::atmosphere::presets;
use glam::DVec3;

fn eclipses(c: &mut Criterion) {
    let mut group = c.benchmark_group("eclipses");
    group.bench_function("hidden_fraction_partial", |b| {
        b.iter(|| hidden_fraction(black_box(0.7), black_box(1.03), black_box(0.6)))
    });
    let earth = presets::earth();
    let sun = presets::earth_sun(DVec3::Z);
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.bench_function("earth_shadow_profile", |b| {
        b.iter(|| PlanetShadow::new(black_box(&earth), &sun, 3.9e8, &ShadowSettings::default()))
    });
    group.finish();
}

criterion_group!(benches, eclipses);
criterion_main!(benches);
