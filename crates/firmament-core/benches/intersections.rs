//! Criterion benchmarks of the core intersection and culling functions.
//!
//! Run: `cargo bench -p firmament-core --bench intersections`. Figures: docs/PERFORMANCE.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use firmament_core::Camera;
use firmament_core::camera::frustum::{ClipDepth, Frustum};
use firmament_core::geometry::{Ellipsoid, Ray, Sphere};
use glam::DVec3;

const EARTH: Ellipsoid = Ellipsoid {
    center: DVec3::ZERO,
    radii: DVec3::new(6_378_137.0, 6_378_137.0, 6_356_752.3),
};

fn rays() -> [(&'static str, Ray); 3] {
    let ray = |o: DVec3, d: DVec3| {
        Ray::new(o, d).unwrap_or(Ray {
            origin: o,
            direction: DVec3::X,
        })
    };
    [
        ("hit", ray(DVec3::new(2e7, 1e5, 3e5), DVec3::NEG_X)),
        ("miss", ray(DVec3::new(2e7, 1e7, 0.0), DVec3::NEG_X)),
        ("inside", ray(DVec3::new(1e3, 0.0, 6.0e6), DVec3::new(0.3, 0.1, 1.0))),
    ]
}

fn intersections(c: &mut Criterion) {
    let sphere = Sphere {
        center: DVec3::ZERO,
        radius: 6_371_000.0,
    };
    for (name, ray) in rays() {
        c.bench_function(&format!("sphere_intersect/{name}"), |b| {
            b.iter(|| black_box(sphere).intersect(black_box(&ray)))
        });
        c.bench_function(&format!("ellipsoid_intersect/{name}"), |b| {
            b.iter(|| black_box(EARTH).intersect(black_box(&ray)))
        });
    }
    let cam = Camera::from_heading_pitch(DVec3::new(0.0, 0.0, 2.0), 0.3, 0.1);
    let frustum = Frustum::from_view_projection(&(cam.projection_matrix() * cam.view_matrix()), ClipDepth::ZeroToOne);
    c.bench_function("frustum_sphere", |b| {
        b.iter(|| black_box(&frustum).intersects_sphere(black_box(DVec3::new(3.0, 40.0, 5.0)), 2.0))
    });
}

criterion_group!(benches, intersections);
criterion_main!(benches);
