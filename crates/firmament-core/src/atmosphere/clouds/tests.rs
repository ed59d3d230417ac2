//! Tests of the layers' density field and their rules.

use glam::{DQuat, DVec3};

use super::noise::lowbias32;
use super::*;

fn earth() -> Planet {
    Planet::sphere(6_371_000.0, 100_000.0)
}

/// A uniform number in [0, 1) for sample `i`, stream `k`.
fn uniform(i: u32, k: u32) -> f64 {
    f64::from(lowbias32(lowbias32(i.wrapping_mul(7).wrapping_add(k)) ^ 0x7e57_0001)) / 4_294_967_296.0
}

/// A uniformly random unit vector.
fn direction(i: u32) -> DVec3 {
    let z = 2.0 * uniform(i, 0) - 1.0;
    let phi = std::f64::consts::TAU * uniform(i, 1);
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// The point at altitude `h` above the surface point in direction `n` of a sphere of `radius`.
fn at(radius: f64, n: DVec3, h: f64) -> DVec3 {
    n * (radius + h)
}

fn layer(kind: CloudKind, coverage: f64, seed: u32) -> CloudLayer {
    let (bottom, top) = match kind {
        CloudKind::Cirrus => (8_000.0, 9_500.0),
        CloudKind::Altostratus => (3_000.0, 5_000.0),
        CloudKind::Stratus => (300.0, 900.0),
        _ => (1_000.0, 3_000.0),
    };
    CloudLayer {
        seed,
        ..CloudLayer::new(bottom, top, coverage, 0.04, kind)
    }
}

const NOISY: [CloudKind; 5] = [
    CloudKind::Cumulus,
    CloudKind::Stratocumulus,
    CloudKind::Stratus,
    CloudKind::Altostratus,
    CloudKind::Cirrus,
];

/// Whether the column above `n` holds cloud: the density at 40 heights through the layer (and
/// just above its bottom, where flat bases start) is positive somewhere.
fn covered(layer: &CloudLayer, radius: f64, n: DVec3) -> bool {
    let thickness = layer.top_m - layer.bottom_m;
    std::iter::once(1e-4)
        .chain((0..40).map(|k| (f64::from(k) + 0.5) / 40.0))
        .any(|x| {
            let h = layer.bottom_m + x * thickness;
            layer.density_at_altitude(at(radius, n, h), h) > 0.0
        })
}

#[test]
fn coverage_is_the_share_of_the_sky_covered() {
    let radius = 6_371_000.0;
    let columns = 6_000;
    for kind in NOISY {
        for coverage in [0.2, 0.5, 0.8] {
            let layer = layer(kind, coverage, 11);
            let hits = (0..columns).filter(|&i| covered(&layer, radius, direction(i))).count();
            let share = hits as f64 / f64::from(columns);
            assert!((share - coverage).abs() <= 0.03, "{kind:?} at {coverage}: {share}");
        }
    }
}

#[test]
fn no_coverage_is_clear_sky_and_full_coverage_covers_it() {
    let radius = 6_371_000.0;
    for kind in NOISY {
        let clear = layer(kind, 0.0, 2);
        let overcast = layer(kind, 1.0, 2);
        let mut covered_columns = 0;
        for i in 0..500 {
            let n = direction(i);
            assert!(!covered(&clear, radius, n), "{kind:?}");
            covered_columns += usize::from(covered(&overcast, radius, n));
        }
        assert!(covered_columns >= 495, "{kind:?}: {covered_columns}");
    }
}

#[test]
fn the_field_never_exceeds_density_per_m_and_reaches_near_it() {
    let radius = 6_371_000.0;
    for kind in NOISY {
        let layer = layer(kind, 0.7, 5);
        let mut max: f64 = 0.0;
        for i in 0..40_000 {
            let n = direction(i);
            let h = layer.bottom_m + uniform(i, 2) * (layer.top_m - layer.bottom_m);
            let d = layer.density_at_altitude(at(radius, n, h), h);
            assert!((0.0..=layer.density_per_m).contains(&d), "{kind:?}: {d}");
            max = max.max(d);
        }
        assert!(max > 0.4 * layer.density_per_m, "{kind:?}: max {max}");
    }
}

#[test]
fn a_uniform_layer_is_its_density_between_bottom_and_top() {
    let planet = earth();
    let layer = CloudLayer::new(1_500.0, 4_000.0, 0.1, 0.05, CloudKind::Uniform);
    for i in 0..100 {
        let n = direction(i);
        for (h, want) in [
            (1_499.0, 0.0),
            (1_500.0, 0.05),
            (2_000.0, 0.05),
            (4_000.0, 0.05),
            (4_000.5, 0.0),
        ] {
            assert_eq!(layer.density_at_altitude(at(6_371_000.0, n, h), h), want);
        }
        assert_eq!(layer.density_at(&planet, at(6_371_000.0, n, 3_000.0)), 0.05);
    }
    assert_eq!(layer.coverage_threshold(), 0.0);
}

#[test]
fn outside_the_layer_and_at_its_shells_there_is_no_cloud() {
    let radius = 6_371_000.0;
    for kind in NOISY {
        let layer = layer(kind, 1.0, 3);
        for i in 0..300 {
            let n = direction(i);
            for h in [layer.bottom_m - 1.0, layer.bottom_m, layer.top_m, layer.top_m + 1.0] {
                assert_eq!(layer.density_at_altitude(at(radius, n, h), h), 0.0, "{kind:?} at {h}");
            }
        }
    }
}

#[test]
fn the_field_is_deterministic_and_seeded() {
    let radius = 6_371_000.0;
    for kind in NOISY {
        let a = layer(kind, 0.5, 1);
        let b = layer(kind, 0.5, 2);
        let mut differ = 0;
        for i in 0..400 {
            let n = direction(i);
            let h = a.bottom_m + 0.3 * (a.top_m - a.bottom_m);
            let p = at(radius, n, h);
            assert_eq!(a.density_at_altitude(p, h), a.clone().density_at_altitude(p, h));
            differ += usize::from(a.density_at_altitude(p, h) != b.density_at_altitude(p, h));
        }
        assert!(differ > 100, "{kind:?}: seeds 1 and 2 differ at {differ} of 400 points");
    }
}

#[test]
fn the_field_is_continuous() {
    // Steps of 1 cm anywhere change the density by a small part of its maximum (the steepest
    // parts are billowed tops: a 1 cm step across them moves the density by ≲ 1e-3 of ρ).
    let radius = 6_371_000.0;
    for kind in NOISY {
        let layer = layer(kind, 0.6, 8);
        let mut worst: f64 = 0.0;
        for i in 0..20_000 {
            let n = direction(i);
            let h = layer.bottom_m + uniform(i, 3) * (layer.top_m - layer.bottom_m);
            let p = at(radius, n, h);
            let step = direction(i + 1_000_000) * 0.01;
            let d = layer.density_at_altitude(p, h);
            let moved = layer.density_at_altitude(p + step, h + step.dot(n));
            worst = worst.max((moved - d).abs() / layer.density_per_m);
        }
        assert!(worst < 2e-3, "{kind:?}: {worst}");
    }
}

#[test]
fn columns_are_radial() {
    // The column field is read at the column's foot: the same at every altitude of a radius.
    let radius = 6_371_000.0;
    let layer = layer(CloudKind::Cumulus, 0.5, 4);
    let shape = layer.kind.shape().unwrap();
    for i in 0..200 {
        let n = direction(i);
        let foot = |h: f64| {
            let p = at(radius, n, h);
            p - p * (h / p.length())
        };
        let f0 = field::column_field(shape, layer.kind, layer.seed, foot(1_000.0));
        let f1 = field::column_field(shape, layer.kind, layer.seed, foot(3_000.0));
        assert!((f0 - f1).abs() < 1e-9, "{f0} vs {f1}");
    }
}

#[test]
fn cumulus_have_flat_bases_and_tall_cores() {
    // Every covered column's cloud starts at the layer's bottom, and the strongest columns
    // reach its top.
    let radius = 6_371_000.0;
    let layer = layer(CloudKind::Cumulus, 0.4, 6);
    let mut tops = Vec::new();
    for i in 0..3_000 {
        let n = direction(i);
        if !covered(&layer, radius, n) {
            continue;
        }
        let h = layer.bottom_m + 0.002 * (layer.top_m - layer.bottom_m);
        assert!(layer.density_at_altitude(at(radius, n, h), h) > 0.0, "column {i}");
        let top = (0..100)
            .rev()
            .map(|k| f64::from(k) / 100.0)
            .find(|x| {
                let h = layer.bottom_m + x * (layer.top_m - layer.bottom_m);
                layer.density_at_altitude(at(radius, n, h), h) > 0.0
            })
            .unwrap_or(0.0);
        tops.push(top);
    }
    tops.sort_by(f64::total_cmp);
    let median = tops[tops.len() / 2];
    let high = tops[tops.len() * 95 / 100];
    assert!(
        high > 0.8 && median < 0.65 && median > 0.25,
        "median {median}, 95th {high}"
    );
}

#[test]
fn cirrus_streak_east_west() {
    // Near the equator the column field changes much more slowly eastwards than northwards.
    let shape = CloudKind::Cirrus.shape().unwrap();
    let radius = 6_371_000.0;
    let (mut east, mut north) = (0.0, 0.0);
    for i in 0..2_000 {
        let lon = uniform(i, 4) * std::f64::consts::TAU;
        let lat = (uniform(i, 5) - 0.5) * 0.6;
        let foot = |lat: f64, lon: f64| radius * super::super::planet::geodetic_normal(lat, lon);
        let step = 1_000.0 / radius;
        let f = field::column_field(shape, CloudKind::Cirrus, 3, foot(lat, lon));
        east += (field::column_field(shape, CloudKind::Cirrus, 3, foot(lat, lon + step / lat.cos())) - f).abs();
        north += (field::column_field(shape, CloudKind::Cirrus, 3, foot(lat + step, lon)) - f).abs();
    }
    assert!(north > 3.0 * east, "north {north}, east {east}");
}

#[test]
fn a_coverage_map_scales_the_coverage_where_it_is() {
    let planet = earth();
    let radius = 6_371_000.0;
    // Western hemisphere clear, eastern at full coverage.
    let map = CoverageMap::new(2, 1, vec![0.0, 1.0]).unwrap();
    let plain = layer(CloudKind::Stratocumulus, 0.6, 7);
    let mapped = CloudLayer {
        coverage_map: Some(map),
        ..plain.clone()
    };
    for i in 0..2_000 {
        let n = direction(i);
        let h = plain.bottom_m + 0.3 * (plain.top_m - plain.bottom_m);
        let p = at(radius, n, h);
        let lon = n.y.atan2(n.x);
        let weight = CoverageMap::new(2, 1, vec![0.0, 1.0]).unwrap().sample(0.0, lon);
        let coverage = plain.coverage * weight;
        let want = plain.density_with_coverage(p, h, coverage);
        assert!((mapped.density_at_altitude(p, h) - want).abs() <= 1e-12);
        // On a sphere geodetic and geocentric agree.
        assert!((mapped.density_at(&planet, p) - want).abs() <= 1e-10);
        assert!((mapped.coverage_at(&planet, p) - coverage).abs() < 1e-9);
        if (-std::f64::consts::PI..-0.5 * std::f64::consts::PI).contains(&lon) && lon < -2.0 {
            // Centre of the clear texel's side: the map there is near 0.
            assert!(mapped.coverage_at(&planet, p) < 0.5 * plain.coverage);
        }
    }
    // Without a map, the three agree exactly.
    for i in 0..200 {
        let n = direction(i);
        let h = plain.bottom_m + 0.5 * (plain.top_m - plain.bottom_m);
        let p = at(radius, n, h);
        let exact = planet.altitude(p);
        assert_eq!(plain.density_at_altitude(p, exact), plain.density_at(&planet, p));
        assert_eq!(
            plain.density_with_coverage(p, exact, plain.coverage),
            plain.density_at(&planet, p)
        );
    }
}

#[test]
fn on_an_oblate_planet_density_at_uses_the_exact_altitude() {
    let planet = Planet::spheroid(6_378_137.0, 6_356_752.3, 100_000.0);
    let layer = layer(CloudKind::Cumulus, 0.7, 12);
    for i in 0..500 {
        let n = direction(i);
        let (lat, lon) = (n.z.asin(), n.y.atan2(n.x));
        let h = layer.bottom_m + uniform(i, 6) * (layer.top_m - layer.bottom_m);
        let p = planet.surface_point(lat, lon) + super::super::planet::geodetic_normal(lat, lon) * h;
        let exact = planet.altitude(p);
        assert_eq!(layer.density_at(&planet, p), layer.density_at_altitude(p, exact));
    }
}

#[test]
fn threshold_follows_coverage() {
    for kind in NOISY {
        let mut last = f64::INFINITY;
        for coverage in [0.0, 0.2, 0.5, 0.8, 1.0] {
            let t = layer(kind, coverage, 0).coverage_threshold();
            assert!(t < last || coverage == 0.0, "{kind:?}");
            last = t;
        }
    }
}

/// `layer` with one field changed breaks the rule of `key`.
fn broken(key: &str, change: impl FnOnce(&mut CloudLayer)) {
    let mut layer = layer(CloudKind::Cumulus, 0.5, 0);
    change(&mut layer);
    match layer.validate(3) {
        Err(CoreError::InvalidItem { field, .. }) => assert_eq!(field, format!("clouds[3].{key}")),
        other => panic!("{key}: {other:?}"),
    }
}

#[test]
fn every_rule_names_its_key() {
    assert!(layer(CloudKind::Cumulus, 0.5, 0).validate(0).is_ok());
    broken("bottom", |l| l.bottom_m = -1.0);
    broken("bottom", |l| l.bottom_m = f64::NAN);
    broken("top", |l| l.top_m = l.bottom_m);
    broken("top", |l| l.top_m = f64::INFINITY);
    broken("coverage", |l| l.coverage = 1.5);
    broken("coverage", |l| l.coverage = f64::NAN);
    broken("density", |l| l.density_per_m = -0.1);
    broken("density", |l| l.density_per_m = f64::INFINITY);
    broken("wind", |l| l.wind_mps = [f64::NAN, 0.0]);
    broken("wind", |l| l.drift = DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0));
    broken("albedo", |l| l.albedo = 1.01);
    broken("phase", |l| l.phase.g_forward = 1.0);
    broken("phase", |l| l.phase.blend = -0.5);
}

#[test]
fn at_most_eight_layers() {
    let eight = vec![layer(CloudKind::Cirrus, 0.5, 0); MAX_CLOUD_LAYERS];
    assert!(validate_layers(&eight).is_ok());
    let nine = vec![layer(CloudKind::Cirrus, 0.5, 0); MAX_CLOUD_LAYERS + 1];
    match validate_layers(&nine) {
        Err(CoreError::Invalid { field, .. }) => assert_eq!(field, "clouds"),
        other => panic!("{other:?}"),
    }
    let mut bad = eight;
    bad[5].albedo = 2.0;
    match validate_layers(&bad) {
        Err(CoreError::InvalidItem { field, .. }) => assert_eq!(field, "clouds[5].albedo"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_default_phase_is_the_droplets_fit() {
    assert_eq!(
        layer(CloudKind::Stratus, 1.0, 0).phase,
        DualHenyeyGreenstein::CLOUD_DROPLETS
    );
    assert_eq!(CloudKind::from_name("altostratus"), Some(CloudKind::Altostratus));
    assert_eq!(CloudKind::Uniform.code(), 5);
}

/// How much moving a point by half a metre (what `f32` rounding does to a planet-frame point at
/// the Earth's radius, before the shader sees it) changes the density: the noise a GPU march with
/// `f32` positions adds to the field (the shader's own evaluation at a given point is exact to
/// ~1e-5, see the GPU test). Printed, and loosely bounded.
#[test]
fn sensitivity_to_half_a_metre() {
    let radius = 6_371_000.0;
    for kind in NOISY {
        let layer = layer(kind, 0.6, 21);
        let mut diffs: Vec<f64> = (0..20_000)
            .map(|i| {
                let n = direction(i);
                let h = layer.bottom_m + uniform(i, 7) * (layer.top_m - layer.bottom_m);
                let p = at(radius, n, h);
                let e = direction(i + 5_000_000) * 0.5;
                (layer.density_at_altitude(p + e, h) - layer.density_at_altitude(p, h)).abs() / layer.density_per_m
            })
            .collect();
        diffs.sort_by(f64::total_cmp);
        let p99 = diffs[diffs.len() * 99 / 100];
        let max = diffs[diffs.len() - 1];
        println!("{kind:?}: 99th percentile {p99:.2e}, max {max:.2e} of density_per_m");
        let inside: Vec<f64> = diffs.iter().copied().filter(|&d| d > 0.0).collect();
        println!(
            "  nonzero {} of {}: their median {:.2e}",
            inside.len(),
            diffs.len(),
            inside.get(inside.len() / 2).copied().unwrap_or(0.0)
        );
        assert!(p99 < 1e-2 && max < 0.1, "{kind:?}: {p99} {max}");
    }
}

#[test]
fn a_broken_layer_seen_from_afar_covers_more_of_a_slanted_view() {
    let cumulus = CloudLayer::new(1_500.0, 3_000.0, 0.3, 0.05, CloudKind::Cumulus);
    let cell = cumulus.column_cell_m().expect("cumulus has columns");
    assert_eq!(cell, super::shape::CUMULUS.worley_cell_m);
    // Straight down a ray crosses one column: it meets opaque cloud as often as the layer
    // covers, less its columns' thin edges.
    let share = cumulus.cover_share();
    assert!(share > 0.8 && share < 1.0, "{share}");
    let c = 0.3 * share;
    assert!((cumulus.cover_seen(0.3, 0.0) - c).abs() < 1e-15);
    // Across 3 spacings, 1 + 9/4 columns.
    let across = 3.0 * COLUMN_SPACING_CELLS * cell;
    assert!((cumulus.cover_seen(0.3, across) - (1.0 - (1.0 - c).powf(3.25))).abs() < 1e-12);
    // Grazing, nearly every ray meets some cloud; a clear sky stays clear.
    assert!(cumulus.cover_seen(0.3, 100.0 * cell) > 1.0 - 1e-12);
    assert_eq!(cumulus.cover_seen(0.0, 10.0 * cell), 0.0);
    // A uniform slab has no columns: every ray meets it.
    let slab = CloudLayer::new(1_000.0, 2_000.0, 0.3, 0.01, CloudKind::Uniform);
    assert_eq!(slab.column_cell_m(), None);
    assert_eq!(slab.cover_seen(0.3, 0.0), 1.0);
    // Kinds without Worley cells measure columns in their gradient noise's.
    for kind in CloudKind::ALL {
        let layer = CloudLayer::new(1_000.0, 2_000.0, 0.5, 0.01, kind);
        if let (Some(cell), Some(shape)) = (layer.column_cell_m(), kind.shape()) {
            assert!(
                cell == shape.worley_cell_m || cell == shape.perlin_cell_m[0],
                "{kind:?}"
            );
        }
    }
}
