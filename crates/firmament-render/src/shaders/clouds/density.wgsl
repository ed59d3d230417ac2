// clouds/density.wgsl — the cloud layers' density field: the f32 mirror of the core's
// firmament_core::atmosphere::clouds (formula in its `field` module, noise in `noise`). No bindings.
//
// Conventions (those of the core):
// - Planet frame: metres, centred on the planet, axes along its semi-axes. `p` is a point there,
//   `h` its altitude above the ellipsoid (m), as the caller computes it (the march: the
//   approximate altitude of common/ellipsoid.wgsl). Densities are extinction coefficients, m⁻¹,
//   grey; the field never exceeds the layer's `shell.w` (the majorant).
// - A layer's pattern lives in its own frame, `R·p` with R the wind's drift.
// - Noise lattices are hashed as u32 with lowbias32 (wrapping arithmetic, exact on every GPU) and
//   every feature size is a power of two metres, so a point scaled into cell units splits into
//   its integer cell and the offset in it exactly. The pattern point R·p is never rounded to
//   f32 (which at 6.4e6 m resolves 0.5 m): it is kept as a sum of terms, three of them exact
//   products (p rounded to a multiple of a power-of-two step, times R rounded to multiples of
//   2⁻¹¹: 12 bits each) and a small rest, and each term is scaled and split on its own
//   (cloud_cell). The shader's field is then the core's f64 field at the same `p` to ~1e-4 m,
//   whatever the drift; the only loss left is `p`'s own rounding, the caller's.
// - Kinds are the CLOUD_KIND_* codes of generated/constants.

#import generated/constants

// The most layers a sky has (firmament_core's MAX_CLOUD_LAYERS).
const MAX_CLOUD_LAYERS: u32 = 8u;
// Steps of a quantile table (entries 0 … 32: the quantiles at 0, 1/32, …, 1).
const CLOUD_QUANTILE_STEPS: u32 = 32u;

// Salts of the noise fields (the core's noise::salt).
const CLOUD_SALT_COLUMN_WORLEY: u32 = 0xc10d0001u;
const CLOUD_SALT_COLUMN_PERLIN_1: u32 = 0xc10d0002u;
const CLOUD_SALT_COLUMN_PERLIN_2: u32 = 0xc10d0003u;
const CLOUD_SALT_COLUMN_PERLIN_3: u32 = 0xc10d0004u;
const CLOUD_SALT_DETAIL_WORLEY: u32 = 0xc10d0011u;
const CLOUD_SALT_DETAIL_PERLIN_1: u32 = 0xc10d0012u;
const CLOUD_SALT_DETAIL_PERLIN_2: u32 = 0xc10d0013u;

// One layer (gpu_types::clouds::CloudLayerGpu). Fractions are of the layer's thickness.
struct CloudLayerGpu {
    // bottom, top (m above the surface), 1/(top − bottom) (m⁻¹), density at full strength (m⁻¹).
    shell: vec4<f32>,
    // coverage (0–1), its column-field threshold, its core threshold (both for the layer's own
    // coverage, no map), single-scattering albedo (0–1).
    coverage: vec4<f32>,
    // The phase function: g_forward, g_back, blend (the forward lobe's weight), unused.
    phase: vec4<f32>,
    // x: kind (CLOUD_KIND_*), y: seed, z: 1 when the layer has a coverage map, w: the map's slot
    // (the layer's index among those with maps).
    codes: vec4<u32>,
    // The drift rotation R by columns, rounded to multiples of 2⁻¹¹ (xyz; w unused).
    drift: array<vec4<f32>, 3>,
    // The rest of R, R minus `drift`, by columns (xyz; w unused).
    drift_rest: array<vec4<f32>, 3>,
    // The column field: 1/Worley cell (m⁻¹), Worley's weight, ridge (0 or 1), the share of
    // covered columns at full strength (core_share).
    column: vec4<f32>,
    // 1/gradient-noise cell along the pattern's x and y, along its z (m⁻¹); the step p is split
    // at (m, a power of two ≥ 1/4096 of the layer's farthest reach from the centre) and 1/step.
    column_scale: vec4<f32>,
    // The vertical profile: anchor, share below the anchor, height min, height max (fractions).
    profile: vec4<f32>,
    // dome edge (of the strength), base softness, top softness (fractions), core minimum.
    edges: vec4<f32>,
    // The detail: 1/cell (m⁻¹), Worley's share at the top, top erosion, interior erosion.
    detail: vec4<f32>,
    // The kind's column-field quantiles at 0, 1/32, …, 1: entry i at [i / 4][i % 4] (33 used).
    quantiles: array<vec4<f32>, 9>,
    // The density averaged over the columns at the layer's own coverage, over shell.w, at height
    // fractions (i / 31)²: entry i at [i / 4][i % 4] (32 used; the core's
    // mean_density_with_coverage).
    mean_profile: array<vec4<f32>, 9>,
    // From afar: the share of the coverage that counts as opaque cloud (the core's
    // CloudLayer::cover_share), unused, unused, unused.
    lod: vec4<f32>,
}

// Every layer of a sky (gpu_types::clouds::CloudsGpu).
struct CloudsGpu {
    // x: layers in use, y: of them with a coverage map, zw: unused.
    count: vec4<u32>,
    layers: array<CloudLayerGpu, 8>,
}

// Chris Wellons's lowbias32 integer hash.
fn cloud_lowbias32(x_in: u32) -> u32 {
    var x = x_in;
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// The key of one noise field of a layer: its seed, kind and the field's salt.
fn cloud_key(seed: u32, kind: u32, salt: u32) -> u32 {
    return cloud_lowbias32(seed ^ cloud_lowbias32(salt ^ (kind << 24u)));
}

// The hash of lattice cell `c` under `key`.
fn cloud_hash(c: vec3<i32>, key: u32) -> u32 {
    let h = cloud_lowbias32(key ^ bitcast<u32>(c.x));
    let k = cloud_lowbias32(h ^ bitcast<u32>(c.y));
    return cloud_lowbias32(k ^ bitcast<u32>(c.z));
}

// A point in cell units: its lattice cell and the offset in it, 0 ≤ f < 1.
struct CloudCell {
    cell: vec3<i32>,
    f: vec3<f32>,
}

// A pattern-frame point (m) as the sum t0 + t1 + t2 + rest, each t exact in f32.
struct CloudPoint {
    t0: vec3<f32>,
    t1: vec3<f32>,
    t2: vec3<f32>,
    rest: vec3<f32>,
}

// The pattern-frame point R·p of `p` (planet frame, m): p = hi + lo with hi a multiple of the
// layer's step (≤ 12 significant bits), the columns of `drift` multiples of 2⁻¹¹ (≤ 12 bits), so
// that drift·hi is three exact products; the rest drift·lo + drift_rest·p is small (~km) and
// rounds to ~1e-4 m.
fn cloud_pattern_point(layer: CloudLayerGpu, p: vec3<f32>) -> CloudPoint {
    let hi = round(p * layer.column_scale.w) * layer.column_scale.z;
    let lo = p - hi;
    let r = mat3x3<f32>(layer.drift[0].xyz, layer.drift[1].xyz, layer.drift[2].xyz);
    let rest = mat3x3<f32>(layer.drift_rest[0].xyz, layer.drift_rest[1].xyz, layer.drift_rest[2].xyz);
    return CloudPoint(r[0] * hi.x, r[1] * hi.y, r[2] * hi.z, r * lo + rest * p);
}

// Term `t` scaled by the power-of-two scale `s`: its cell (exact) added to `cell`, its offset
// returned.
fn cloud_split(t: vec3<f32>, s: vec3<f32>, cell: ptr<function, vec3<i32>>) -> vec3<f32> {
    let st = t * s;
    let i = floor(st);
    *cell += vec3<i32>(i);
    return st - i;
}

// The point `q` times the power-of-two scale `s` (per axis, m⁻¹) as its cell and offset, its
// terms split one by one so that their sum is never rounded.
fn cloud_cell(q: CloudPoint, s: vec3<f32>) -> CloudCell {
    var cell = vec3<i32>(0);
    let f = cloud_split(q.t0, s, &cell) + cloud_split(q.t1, s, &cell) + cloud_split(q.t2, s, &cell)
        + cloud_split(q.rest, s, &cell);
    let k = floor(f);
    return CloudCell(cell + vec3<i32>(k), f - k);
}

// Perlin's quintic fade.
fn cloud_fade(t: vec3<f32>) -> vec3<f32> {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Perlin's improved-noise gradient (12 edges, 4 repeated) from the hash's top 4 bits, dotted
// with f.
fn cloud_gradient(hash: u32, f: vec3<f32>) -> f32 {
    let h = hash >> 28u;
    let u = select(f.y, f.x, h < 8u);
    let v = select(select(f.z, f.x, h == 12u || h == 14u), f.y, h < 4u);
    return select(-u, u, (h & 1u) == 0u) + select(-v, v, (h & 2u) == 0u);
}

// The gradient of corner `o` of cell `c`.
fn cloud_corner(c: CloudCell, o: vec3<i32>, key: u32) -> f32 {
    return cloud_gradient(cloud_hash(c.cell + o, key), c.f - vec3<f32>(o));
}

// Perlin's improved gradient noise, about −1 … 1.
fn cloud_perlin(c: CloudCell, key: u32) -> f32 {
    let w = cloud_fade(c.f);
    let x00 = mix(cloud_corner(c, vec3<i32>(0, 0, 0), key), cloud_corner(c, vec3<i32>(1, 0, 0), key), w.x);
    let x10 = mix(cloud_corner(c, vec3<i32>(0, 1, 0), key), cloud_corner(c, vec3<i32>(1, 1, 0), key), w.x);
    let x01 = mix(cloud_corner(c, vec3<i32>(0, 0, 1), key), cloud_corner(c, vec3<i32>(1, 0, 1), key), w.x);
    let x11 = mix(cloud_corner(c, vec3<i32>(0, 1, 1), key), cloud_corner(c, vec3<i32>(1, 1, 1), key), w.x);
    return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

// Worley's F1²: the squared distance (cell units) to the nearest feature point, one per cell at
// 10-bit offsets, over the 27 neighbouring cells.
fn cloud_worley_squared(c: CloudCell, key: u32) -> f32 {
    var nearest = 1e30;
    for (var dz = -1; dz <= 1; dz++) {
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                let o = vec3<i32>(dx, dy, dz);
                let h = cloud_hash(c.cell + o, key);
                let bits = vec3<u32>(h & 1023u, (h >> 10u) & 1023u, (h >> 20u) & 1023u);
                let d = vec3<f32>(o) + (vec3<f32>(bits) + 0.5) / 1024.0 - c.f;
                nearest = min(nearest, dot(d, d));
            }
        }
    }
    return nearest;
}

// The column field F at the pattern-frame column foot q (m), 0–1.
fn cloud_column_field(layer: CloudLayerGpu, q: CloudPoint) -> f32 {
    let seed = layer.codes.y;
    let kind = layer.codes.x;
    let weight = layer.column.y;
    var f = 0.0;
    if weight > 0.0 {
        let cells = cloud_worley_squared(cloud_cell(q, vec3<f32>(layer.column.x)), cloud_key(seed, kind, CLOUD_SALT_COLUMN_WORLEY));
        f += weight * clamp(1.0 - cells, 0.0, 1.0);
    }
    if weight < 1.0 {
        let s = layer.column_scale.xxy;
        let n1 = cloud_perlin(cloud_cell(q, s), cloud_key(seed, kind, CLOUD_SALT_COLUMN_PERLIN_1));
        let n2 = cloud_perlin(cloud_cell(q, s * 2.0), cloud_key(seed, kind, CLOUD_SALT_COLUMN_PERLIN_2));
        let n3 = cloud_perlin(cloud_cell(q, s * 4.0), cloud_key(seed, kind, CLOUD_SALT_COLUMN_PERLIN_3));
        let n = (n1 + 0.5 * n2 + 0.25 * n3) * (4.0 / 7.0);
        let ridge = layer.column.z;
        let g = (0.5 + 0.5 * n) * (1.0 - ridge) + (1.0 - abs(n)) * ridge;
        f += (1.0 - weight) * g;
    }
    return clamp(f, 0.0, 1.0);
}

// The detail D at the pattern-frame point q (m) and height fraction x, 0–1.
fn cloud_detail(layer: CloudLayerGpu, q: CloudPoint, x: f32) -> f32 {
    let seed = layer.codes.y;
    let kind = layer.codes.x;
    let s = vec3<f32>(layer.detail.x);
    let cell = cloud_cell(q, s);
    let n1 = cloud_perlin(cell, cloud_key(seed, kind, CLOUD_SALT_DETAIL_PERLIN_1));
    let n2 = cloud_perlin(cloud_cell(q, s * 2.0), cloud_key(seed, kind, CLOUD_SALT_DETAIL_PERLIN_2));
    let wisps = 0.5 + 0.5 * ((n1 + 0.5 * n2) * (2.0 / 3.0));
    let billows = layer.detail.y * x;
    var d = wisps * (1.0 - billows);
    if billows > 0.0 {
        d += billows * max(1.0 - cloud_worley_squared(cell, cloud_key(seed, kind, CLOUD_SALT_DETAIL_WORLEY)), 0.0);
    }
    return clamp(d, 0.0, 1.0);
}

// Entry i of a table of nine rows of four (entry i at [i / 4][i % 4]). Constant indices only into
// the array (it is a value here, which some backends cannot index at run time without a copy).
fn cloud_table_entry(rows: array<vec4<f32>, 9>, i: u32) -> f32 {
    let r = i / 4u;
    var row = rows[0];
    row = select(row, rows[1], r == 1u);
    row = select(row, rows[2], r == 2u);
    row = select(row, rows[3], r == 3u);
    row = select(row, rows[4], r == 4u);
    row = select(row, rows[5], r == 5u);
    row = select(row, rows[6], r == 6u);
    row = select(row, rows[7], r == 7u);
    row = select(row, rows[8], r == 8u);
    return row[i % 4u];
}

// Quantile i (0 … 32) of the layer's column field.
fn cloud_quantile(layer: CloudLayerGpu, i: u32) -> f32 {
    return cloud_table_entry(layer.quantiles, i);
}

// The column-field threshold that leaves `coverage` (0–1) of the columns covered: the
// 1 − coverage quantile, linear between the table's entries.
fn cloud_coverage_threshold(layer: CloudLayerGpu, coverage: f32) -> f32 {
    let u = (1.0 - clamp(coverage, 0.0, 1.0)) * f32(CLOUD_QUANTILE_STEPS);
    let i = min(u32(floor(u)), CLOUD_QUANTILE_STEPS - 1u);
    let f = u - f32(i);
    let q0 = cloud_quantile(layer, i);
    return q0 + (cloud_quantile(layer, i + 1u) - q0) * f;
}

// The cubic smoothstep of t clamped to 0–1.
fn cloud_smooth(t: f32) -> f32 {
    let c = clamp(t, 0.0, 1.0);
    return c * c * (3.0 - 2.0 * c);
}

// The field with the coverage there and its two thresholds given.
fn cloud_density_at(layer: CloudLayerGpu, p: vec3<f32>, h: f32, coverage: f32, t: f32, t_core: f32) -> f32 {
    return cloud_density_detailed(layer, p, h, coverage, t, t_core, true);
}

// The same, with the detail D evaluated (`detailed`) or taken as ½, its mean: for light marches
// and samples farther than a pixel's footprint resolves (not the core's field, a filtered one).
fn cloud_density_detailed(layer: CloudLayerGpu, p: vec3<f32>, h: f32, coverage: f32, t: f32, t_core: f32, detailed: bool) -> f32 {
    if !(h >= layer.shell.x && h <= layer.shell.y) {
        return 0.0;
    }
    if layer.codes.x == CLOUD_KIND_UNIFORM {
        return layer.shell.w;
    }
    let radius = length(p);
    if radius == 0.0 || !(coverage > 0.0) {
        return 0.0;
    }
    let x = (h - layer.shell.x) * layer.shell.z;
    let q = cloud_pattern_point(layer, p);
    // The column's foot p − h·n in the pattern frame: R·p − h·R·n.
    let n = p / radius;
    let down = h * (mat3x3<f32>(layer.drift[0].xyz, layer.drift[1].xyz, layer.drift[2].xyz) * n
        + mat3x3<f32>(layer.drift_rest[0].xyz, layer.drift_rest[1].xyz, layer.drift_rest[2].xyz) * n);
    let f = cloud_column_field(layer, CloudPoint(q.t0, q.t1, q.t2, q.rest - down));
    if f <= t {
        return 0.0;
    }
    let s = min((f - t) / (t_core - t), 1.0);
    let full = cloud_full_thickness(layer, s);
    if !cloud_within(layer, full, x) {
        return 0.0;
    }
    var d = 0.5;
    if detailed {
        d = cloud_detail(layer, q, x);
    }
    return layer.shell.w * cloud_eroded(layer, full, s, x, d);
}

// A column's cloud thickness before erosion (fraction of the layer) at strength s: a parabola in
// the strength times a quarter circle (step 5 of the core's field).
fn cloud_full_thickness(layer: CloudLayerGpu, s: f32) -> f32 {
    let u = min(s / layer.edges.x, 1.0);
    let body = s * (2.0 - s);
    return (layer.profile.z + (layer.profile.w - layer.profile.z) * body) * sqrt(u * (2.0 - u));
}

// Whether height fraction x lies inside a column's uneroded cloud of thickness `full` (erosion
// only lowers it: outside, there is none).
fn cloud_within(layer: CloudLayerGpu, full: f32, x: f32) -> bool {
    let anchor = layer.profile.x;
    let below = layer.profile.y;
    return x > anchor - below * full && x < anchor + (1.0 - below) * full;
}

// The density over the layer's, 0–1, at height fraction x of a column of strength s, uneroded
// thickness `full` and detail d (step 6; the core's field::in_column).
fn cloud_eroded(layer: CloudLayerGpu, full: f32, s: f32, x: f32, d: f32) -> f32 {
    let anchor = layer.profile.x;
    let below = layer.profile.y;
    let thickness = full * (1.0 - layer.detail.z * (1.0 - d));
    let bottom = anchor - below * thickness;
    let top = anchor + (1.0 - below) * thickness;
    let fall = cloud_smooth((x - bottom) / layer.edges.y) * cloud_smooth((top - x) / layer.edges.z);
    let core = layer.edges.w + (1.0 - layer.edges.w) * s;
    return fall * core * (1.0 - layer.detail.w * (1.0 - d));
}

// The density at altitude h averaged over the layer's columns, with the coverage there and its
// two thresholds given, m⁻¹: the field from afar (the core's field::mean_density). Each interval
// of the quantile table above the threshold counts with its share of the columns at its middle,
// the detail at its mean.
fn cloud_mean_density_at(layer: CloudLayerGpu, h: f32, coverage: f32, t: f32, t_core: f32) -> f32 {
    if !(h >= layer.shell.x && h <= layer.shell.y) {
        return 0.0;
    }
    if layer.codes.x == CLOUD_KIND_UNIFORM {
        return layer.shell.w;
    }
    if !(coverage > 0.0) {
        return 0.0;
    }
    let x = (h - layer.shell.x) * layer.shell.z;
    var sum = 0.0;
    var lo = cloud_quantile(layer, 0u);
    for (var i = 1u; i <= CLOUD_QUANTILE_STEPS; i++) {
        let hi = cloud_quantile(layer, i);
        let start = max(lo, t);
        if hi > start {
            let share = (hi - start) / (hi - lo) / f32(CLOUD_QUANTILE_STEPS);
            let s = min((0.5 * (start + hi) - t) / (t_core - t), 1.0);
            let full = cloud_full_thickness(layer, s);
            if cloud_within(layer, full, x) {
                sum += share * cloud_eroded(layer, full, s, x, 0.5);
            }
        }
        lo = hi;
    }
    return layer.shell.w * sum;
}

// The density at altitude h averaged over the columns at the layer's own coverage, m⁻¹: its mean
// profile, linear in √x between entries (cloud_mean_density_at at the layer's coverage,
// tabulated).
fn cloud_mean_density(layer: CloudLayerGpu, h: f32) -> f32 {
    if !(h >= layer.shell.x && h <= layer.shell.y) {
        return 0.0;
    }
    let u = sqrt(clamp((h - layer.shell.x) * layer.shell.z, 0.0, 1.0)) * 31.0;
    let i = min(u32(floor(u)), 30u);
    let a = cloud_table_entry(layer.mean_profile, i);
    return layer.shell.w * (a + (cloud_table_entry(layer.mean_profile, i + 1u) - a) * (u - f32(i)));
}

// The same with the coverage there given, 0–1 (the core's
// CloudLayer::mean_density_with_coverage).
fn cloud_mean_density_with_coverage(layer: CloudLayerGpu, h: f32, coverage: f32) -> f32 {
    let t = cloud_coverage_threshold(layer, coverage);
    let t_core = cloud_coverage_threshold(layer, coverage * layer.column.w);
    return cloud_mean_density_at(layer, h, coverage, t, t_core);
}

// The extinction of `layer` at `p` (planet frame, m), altitude `h` (m), m⁻¹, with the layer's own
// coverage (no coverage map): the core's CloudLayer::density_at_altitude.
fn cloud_density(layer: CloudLayerGpu, p: vec3<f32>, h: f32) -> f32 {
    return cloud_density_at(layer, p, h, layer.coverage.x, layer.coverage.y, layer.coverage.z);
}

// The same with the coverage there given, 0–1 (the layer's coverage times its map's value, read by
// the caller at equirect_uv): the core's CloudLayer::density_with_coverage.
fn cloud_density_with_coverage(layer: CloudLayerGpu, p: vec3<f32>, h: f32, coverage_here: f32) -> f32 {
    let t = cloud_coverage_threshold(layer, coverage_here);
    let t_core = cloud_coverage_threshold(layer, coverage_here * layer.column.w);
    return cloud_density_at(layer, p, h, coverage_here, t, t_core);
}

// The size of the layer's columns, m: its Worley cell, or its gradient noise's across cell for
// kinds without Worley (the core's CloudLayer::column_cell_m; a uniform slab has none).
fn cloud_column_cell(layer: CloudLayerGpu) -> f32 {
    return 1.0 / select(layer.column_scale.x, layer.column.x, layer.column.y > 0.0);
}

// The share of rays through the layer that meet cloud where a pixel spans many columns, for a
// ray crossing it over `horizontal` metres along the ground with `coverage` of the columns
// covered: 1 − (1 − c)ⁿ, c the coverage's opaque share, over n = 1 + r²/(1 + r) independent
// columns, r the crossing in CLOUD_COLUMN_SPACING_CELLS cells; 1 for a uniform slab (the core's
// CloudLayer::cover_seen).
fn cloud_cover_seen(layer: CloudLayerGpu, coverage: f32, horizontal: f32) -> f32 {
    let c = clamp(coverage * layer.lod.x, 0.0, 1.0);
    if layer.codes.x == CLOUD_KIND_UNIFORM || c >= 1.0 {
        return 1.0;
    }
    let r = max(horizontal, 0.0) / (CLOUD_COLUMN_SPACING_CELLS * cloud_column_cell(layer));
    return 1.0 - pow(1.0 - c, 1.0 + r * r / (1.0 + r));
}
