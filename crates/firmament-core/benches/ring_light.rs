//! Criterion benchmark of the rings' light on the globe (`Rings::light_table` through the air's
//! `GroundTransmittance`): what the renderer makes on the CPU when the rings, the planet's air or
//! a sun's elevation over the ring plane changes.
//!
//! Run: `cargo bench -p firmament-core --bench ring_light`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use firmament_core::atmosphere::presets;
use firmament_core::atmosphere::rings::{GroundTransmittance, Rings};
use glam::DVec3;

fn ring_light(c: &mut Criterion) {
    let atmosphere = presets::saturn();
    let rings = Rings::saturn();
    let sun = DVec3::new(1.0, 0.0, 0.45).normalize();
    let mut group = c.benchmark_group("ring_light");
    group.sample_size(10);
    group.bench_function("ground_transmittance", |b| {
        b.iter(|| GroundTransmittance::new(black_box(&atmosphere)))
    });
    let air = GroundTransmittance::new(&atmosphere);
    group.bench_function("saturn_table", |b| {
        b.iter(|| rings.light_table(atmosphere.planet.radii, black_box(sun), &air))
    });
    group.finish();
}

criterion_group!(benches, ring_light);
criterion_main!(benches);
