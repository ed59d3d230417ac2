//! Criterion benchmark of what the scene format's checks cost per command (issue 10: validation
//! and limits must cost nothing measurable on the render path): `Scene::validate` on built-in
//! presets, and loading a preset (TOML parse, merge, validate) for scale, against a frame built
//! from the scene (`Scene::frame_at`, which a render does next).
//!
//! Run: `cargo bench -p firmament-scene --bench validation`. Figures: docs/RELIABILITY.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use firmament_scene::Scene;

/// Presets of growing size: the default gradient sky, the physical sky with objects, the tour of
/// every classic light and fog mode.
const PRESETS: [&str; 3] = ["default", "earth-objects", "fixed-function-tour"];

fn validation(c: &mut Criterion) {
    for name in PRESETS {
        let scene = Scene::preset(name).unwrap_or_else(|e| panic!("preset {name}: {e}"));
        c.bench_function(&format!("validate/{name}"), |b| {
            b.iter(|| black_box(&scene).validate());
        });
        c.bench_function(&format!("load/{name}"), |b| b.iter(|| Scene::preset(black_box(name))));
        c.bench_function(&format!("frame_at/{name}"), |b| {
            b.iter(|| black_box(&scene).frame_at(None))
        });
    }
}

criterion_group!(benches, validation);
criterion_main!(benches);
