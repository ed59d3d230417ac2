//! Criterion benchmark of a body's light on the planet (`AtmosphereSky::add_body_lights`): what
//! the scene adds to every frame with a body, on the CPU.
//!
//! Run: `cargo bench -p firmament-core --bench body_light`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use firmament_core::atmosphere::body::Body;
use firmament_core::atmosphere::presets;
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

fn body_light(c: &mut Criterion) {
    let atmosphere = presets::earth();
    let center = atmosphere.planet.center;
    let mut sky = AtmosphereSky {
        atmosphere,
        suns: vec![presets::earth_sun(DVec3::new(0.0, -0.8, -0.6).normalize())],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    // A gibbous Moon with its maria, high in the night.
    sky.add_body(Body::moon(
        center + DVec3::new(0.3, 0.8, 0.6).normalize() * 384_400_000.0,
    ));
    let eye = DVec3::new(0.0, 0.0, 2.0);
    c.bench_function("moon_light", |b| {
        b.iter(|| {
            let mut lit = sky.clone();
            lit.add_body_lights(black_box(eye), |_| true);
            lit
        })
    });
}

criterion_group!(benches, body_light);
criterion_main!(benches);
