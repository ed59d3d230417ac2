//! `f32` uniforms of the cloud layers: [`CloudsGpu`], mirroring `CloudsGpu` in
//! `shaders/clouds/density.wgsl`, whose `cloud_density` evaluates the core's density field
//! (`firmament_core::atmosphere::clouds`).
//!
//! Everything is computed in `f64` and rounded once here: the coverage thresholds (from the kind's
//! quantile table), the drift `R` as its 12-bit part and the rest (so that the shader forms `R·p`
//! from exact products, see the shader's header), and the kind's shape as inverse feature sizes
//! (powers of two: exact).

use bytemuck::{Pod, Zeroable};
use firmament_core::atmosphere::Planet;
use firmament_core::atmosphere::clouds::{CloudLayer, MAX_CLOUD_LAYERS, QUANTILES};
use glam::DMat3;

use super::pack::vec3_w;

/// Rows of four in [`CloudLayerGpu::quantiles`].
const QUANTILE_ROWS: usize = QUANTILES.div_ceil(4);

/// Mirrors `CloudLayerGpu` in `shaders/clouds/density.wgsl`: one layer. Fractions are of the
/// layer's thickness.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct CloudLayerGpu {
    /// Bottom, top (m above the surface), 1/(top − bottom) (m⁻¹), density at full strength (m⁻¹).
    pub shell: [f32; 4],
    /// Coverage (0–1), its column-field threshold, its core threshold (for the layer's own
    /// coverage, no map), single-scattering albedo (0–1).
    pub coverage: [f32; 4],
    /// The phase function: g_forward, g_back, blend (the forward lobe's weight), unused.
    pub phase: [f32; 4],
    /// Kind (a `CLOUD_KIND_*` of [`super::codes`]), seed, 1 with a coverage map, the map's slot
    /// (the layer's index among those with maps).
    pub codes: [u32; 4],
    /// The drift rotation `R` by columns, rounded to multiples of 2⁻¹¹ (xyz; w unused).
    pub drift: [[f32; 4]; 3],
    /// The rest of `R`, `R − drift`, by columns (xyz; w unused).
    pub drift_rest: [[f32; 4]; 3],
    /// The column field: 1/Worley cell (m⁻¹), Worley's weight, ridge (0 or 1), the share of the
    /// covered columns at full strength.
    pub column: [f32; 4],
    /// 1/gradient-noise cell along the pattern's x and y, along its z (m⁻¹); the step the shader
    /// splits `p` at (m, [`split_step`]) and its inverse.
    pub column_scale: [f32; 4],
    /// The vertical profile: anchor, share below the anchor, height min, height max.
    pub profile: [f32; 4],
    /// Dome edge (of the strength), base softness, top softness, core minimum.
    pub edges: [f32; 4],
    /// The detail: 1/cell (m⁻¹), Worley's share at the top, top erosion, interior erosion.
    pub detail: [f32; 4],
    /// The kind's column-field quantiles at 0, 1/32, …, 1: entry `i` at `[i / 4][i % 4]`.
    pub quantiles: [[f32; 4]; QUANTILE_ROWS],
    /// The layer's density averaged over its columns at its own coverage, over `density_per_m`
    /// (0–1), at height fractions `(i / 31)²` (crowded at the bottom, where flat bases make it
    /// rise steeply): entry `i` at `[i / 4][i % 4]`
    /// ([`CloudLayer::mean_density_with_coverage`]; the level of detail from afar).
    pub mean_profile: [[f32; 4]; MEAN_PROFILE_ROWS],
    /// From afar: the share of the coverage that counts as opaque cloud
    /// ([`CloudLayer::cover_share`]), unused, unused, unused.
    pub lod: [f32; 4],
}

/// Entries of [`CloudLayerGpu::mean_profile`].
pub const MEAN_PROFILE_ENTRIES: usize = 32;
/// Rows of four of [`CloudLayerGpu::mean_profile`]: as many as the quantiles' (the last unused),
/// so that one WGSL selector (`cloud_table_entry`) reads both tables.
pub const MEAN_PROFILE_ROWS: usize = QUANTILE_ROWS;
const _: () = assert!(MEAN_PROFILE_ENTRIES <= 4 * MEAN_PROFILE_ROWS);

/// Mirrors `CloudsGpu` in `shaders/clouds/density.wgsl`: every layer of a sky.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct CloudsGpu {
    /// Layers in use, of them with a coverage map, unused, unused.
    pub count: [u32; 4],
    /// The layers, in the frame's order; those past `count[0]` zeroed.
    pub layers: [CloudLayerGpu; MAX_CLOUD_LAYERS],
}

/// The step (m) the shader splits a point `p` of `layer` at, `p = hi + lo` with `hi` a multiple
/// of it: the least power of two with every point of the layer within 4096 steps of the centre,
/// so that `hi` has at most 12 significant bits (2048 m on the Earth).
pub fn split_step(layer: &CloudLayer, planet: &Planet) -> f64 {
    let reach = planet.radii.max_element() + layer.top_m.max(0.0);
    (reach / 4096.0).log2().ceil().exp2().max(1.0)
}

impl CloudLayerGpu {
    /// The uniform of `layer` over `planet`, whose coverage map (if any) is slot `map_slot`.
    pub fn new(layer: &CloudLayer, planet: &Planet, map_slot: u32) -> Self {
        let mut u = Self::zeroed();
        let thickness = layer.top_m - layer.bottom_m;
        u.shell = [
            layer.bottom_m as f32,
            layer.top_m as f32,
            (1.0 / thickness) as f32,
            layer.density_per_m as f32,
        ];
        let core = layer.kind.shape().map_or(0.0, |s| s.core_threshold(layer.coverage));
        u.coverage = [
            layer.coverage as f32,
            layer.coverage_threshold() as f32,
            core as f32,
            layer.albedo as f32,
        ];
        u.phase = [
            layer.phase.g_forward as f32,
            layer.phase.g_back as f32,
            layer.phase.blend as f32,
            0.0,
        ];
        let has_map = layer.coverage_map.is_some();
        u.codes = [
            layer.kind.code(),
            layer.seed,
            u32::from(has_map),
            if has_map { map_slot } else { 0 },
        ];
        let drift = DMat3::from_quat(layer.drift.normalize());
        for (k, axis) in [drift.x_axis, drift.y_axis, drift.z_axis].into_iter().enumerate() {
            let high = (axis * 2048.0).round() / 2048.0;
            u.drift[k] = vec3_w(high, 0.0);
            u.drift_rest[k] = vec3_w(axis - high, 0.0);
        }
        if let Some(shape) = layer.kind.shape() {
            u.column = [
                (1.0 / shape.worley_cell_m) as f32,
                shape.worley_weight as f32,
                shape.ridge as f32,
                shape.core_share as f32,
            ];
            let [across, polar] = shape.perlin_cell_m;
            let step = split_step(layer, planet);
            u.column_scale = [
                (1.0 / across) as f32,
                (1.0 / polar) as f32,
                step as f32,
                (1.0 / step) as f32,
            ];
            u.profile = [
                shape.anchor as f32,
                shape.share_below as f32,
                shape.height_min as f32,
                shape.height_max as f32,
            ];
            u.edges = [
                shape.dome_edge as f32,
                shape.base_softness as f32,
                shape.top_softness as f32,
                shape.core_min as f32,
            ];
            u.detail = [
                (1.0 / shape.detail_cell_m) as f32,
                shape.detail_worley as f32,
                shape.top_erosion as f32,
                shape.interior_erosion as f32,
            ];
            for (i, q) in shape.quantiles.iter().enumerate() {
                u.quantiles[i / 4][i % 4] = *q as f32;
            }
        }
        if layer.density_per_m > 0.0 {
            let last = (MEAN_PROFILE_ENTRIES - 1) as f64;
            for i in 0..MEAN_PROFILE_ENTRIES {
                let h = layer.bottom_m + thickness * (i as f64 / last).powi(2);
                let mean = layer.mean_density_with_coverage(h, layer.coverage) / layer.density_per_m;
                u.mean_profile[i / 4][i % 4] = mean as f32;
            }
        }
        u.lod = [layer.cover_share() as f32, 0.0, 0.0, 0.0];
        u
    }
}

impl CloudsGpu {
    /// The uniforms of `layers` (the first [`MAX_CLOUD_LAYERS`]; a frame holds no more) over
    /// `planet` (whose size sets each layer's [`split_step`]).
    pub fn new(layers: &[CloudLayer], planet: &Planet) -> Self {
        let mut u = Self::zeroed();
        let used = &layers[..layers.len().min(MAX_CLOUD_LAYERS)];
        let mut maps = 0;
        for (slot, layer) in u.layers.iter_mut().zip(used) {
            *slot = CloudLayerGpu::new(layer, planet, maps);
            maps += u32::from(layer.coverage_map.is_some());
        }
        u.count = [used.len() as u32, maps, 0, 0];
        u
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use firmament_core::atmosphere::clouds::{CloudKind, CoverageMap, wind_drift};
    use glam::DVec3;

    #[test]
    fn layers_are_packed_in_order_with_their_maps_counted() {
        let planet = Planet::sphere(6_371_000.0, 100_000.0);
        let mut mapped = CloudLayer::new(8_000.0, 9_000.0, 0.3, 1e-3, CloudKind::Cirrus);
        mapped.coverage_map = Some(CoverageMap::new(1, 1, vec![0.5]).unwrap());
        let layers = [
            CloudLayer::new(1_000.0, 3_000.0, 0.4, 0.05, CloudKind::Cumulus),
            mapped.clone(),
            CloudLayer::new(500.0, 900.0, 1.0, 0.02, CloudKind::Uniform),
            mapped,
        ];
        let u = CloudsGpu::new(&layers, &planet);
        assert_eq!(u.count, [4, 2, 0, 0]);
        assert_eq!(u.layers[1].codes, [CloudKind::Cirrus.code(), 0, 1, 0]);
        assert_eq!(u.layers[3].codes[2..], [1, 1]);
        assert_eq!(u.layers[0].codes[2..], [0, 0]);
        assert_eq!(u.layers[4], CloudLayerGpu::zeroed());
        let cumulus = &u.layers[0];
        assert_eq!(cumulus.shell, [1_000.0, 3_000.0, 1.0 / 2_000.0, 0.05]);
        assert_eq!(cumulus.coverage[1], layers[0].coverage_threshold() as f32);
        assert_eq!(cumulus.column[0], 1.0 / 2048.0);
        assert_eq!(cumulus.drift_rest, [[0.0; 4]; 3]);
        assert_eq!(cumulus.drift[1], [0.0, 1.0, 0.0, 0.0]);
        let shape = CloudKind::Cumulus.shape().unwrap();
        assert_eq!(cumulus.quantiles[8][0], shape.quantiles[32] as f32);
        assert_eq!(cumulus.quantiles[2][1], shape.quantiles[9] as f32);
        // A uniform slab carries no shape.
        assert_eq!(u.layers[2].column, [0.0; 4]);
        assert_eq!(u.layers[2].codes[0], super::super::codes::CLOUD_KIND_UNIFORM);
    }

    #[test]
    fn the_drift_is_twelve_exact_bits_and_the_rest() {
        let planet = Planet::sphere(6_371_000.0, 100_000.0);
        let mut layer = CloudLayer::new(1_000.0, 3_000.0, 0.4, 0.05, CloudKind::Cumulus);
        layer.drift = wind_drift(&planet, planet.surface_point(0.5, 0.3), [10.0, 5.0], 86_400.0);
        let u = CloudLayerGpu::new(&layer, &planet, 0);
        let column =
            |m: [[f32; 4]; 3], k: usize| DVec3::new(f64::from(m[k][0]), f64::from(m[k][1]), f64::from(m[k][2]));
        let p = DVec3::new(3e6, -4e6, 2.5e6);
        let mut moved = DVec3::ZERO;
        for (k, pk) in p.to_array().into_iter().enumerate() {
            let high = column(u.drift, k);
            assert_eq!(high * 2048.0, (high * 2048.0).round(), "12 bits");
            moved += (high + column(u.drift_rest, k)) * pk;
        }
        assert!(
            (moved - layer.drift * p).length() < 1e-3,
            "{}",
            (moved - layer.drift * p).length()
        );
        // The step: 2048 m on the Earth (6.37e6 m / 4096 = 1556 m), so a point's multiple of it
        // has ≤ 12 bits.
        assert_eq!(u.column_scale[2..], [2048.0, 1.0 / 2048.0]);
        let jupiter = Planet::sphere(69_911_000.0, 1_000_000.0);
        assert_eq!(split_step(&layer, &jupiter), 32_768.0);
    }

    #[test]
    fn more_than_eight_layers_keep_the_first_eight() {
        let planet = Planet::sphere(6_371_000.0, 100_000.0);
        let layers = vec![CloudLayer::new(1_000.0, 2_000.0, 0.5, 0.01, CloudKind::Stratus); 10];
        assert_eq!(CloudsGpu::new(&layers, &planet).count[0], 8);
    }
}
