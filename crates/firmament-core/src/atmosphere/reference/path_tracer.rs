//! Monte Carlo path tracing of multiple scattering, the reference for orders ≥ 2.
//!
//! Backward paths start at the eye. Free-flight distances are sampled with *spectral MIS*: a
//! wavelength `k` is picked with probability proportional to the path's current weight at `k`,
//! the distance is drawn from `σ_t,k·T_k` (by inverting the optical depth tabulated along the
//! segment), and every wavelength is weighted by the balance heuristic over all three (Kutz et
//! al., "Spectral and Decomposition Tracking for Rendering Heterogeneous Volumes", SIGGRAPH 2017,
//! §4; Wilkie et al., "Hero Wavelength Spectral Sampling", EGSR 2014). Choosing by weight keeps
//! the sum of the weights unchanged in a non-absorbing medium, so no wavelength's weight grows
//! without bound. New directions are drawn from a mixture of Rayleigh's phase function
//! and Henyey–Greenstein (the proposal for Cornette–Shanks) and weighted by the true phase
//! function over the mixture's density. At each scattering or ground event, next-event
//! estimation adds every sun's light (a point for scattering). Russian roulette ends paths after
//! the fourth event (and a path is cut after 1000 events, which no realistic path reaches), so no
//! order is cut off.
//!
//! With [`ReferenceSettings::line_samples`](super::ReferenceSettings::line_samples) the light a
//! path gathers after each event is estimated along the whole next segment instead of at the next
//! collision: sunlight scattered once anywhere on the segment, at that many points jittered in
//! equal strata, and the sunlit ground at its end (Rao–Blackwellised next-event estimation; the
//! collision then adds nothing of its own). Unbiased like the default, and far less noisy where
//! only a thin shell of distant air is sunlit — at twilight a collision rarely lands there, while
//! most segments cross it.
//!
//! Each path has its own random stream seeded from (seed, ray, path index): results do not
//! depend on the number of threads.

use std::f64::consts::PI;

use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

use super::inputs::{Reference, Segment, segment};
use crate::atmosphere::medium::{LocalCoefficients, henyey_greenstein, rayleigh_phase};
use crate::atmosphere::spectrum::Spectrum;
use crate::geometry::Ray;

/// Orders tallied separately in [`MultipleScattering::per_order`]; higher ones go to the last.
pub const TALLIED_ORDERS: usize = 16;

/// Events after which a path is cut (a safety net: Russian roulette ends paths long before).
const MAX_EVENTS: usize = 1000;

/// Nodes of the optical-depth table along each path segment.
const TABLE_STEPS: usize = 256;

/// Multiple scattering along one ray, W·m⁻²·sr⁻¹·nm⁻¹.
#[derive(Debug, Clone, PartialEq)]
pub struct MultipleScattering {
    /// All orders ≥ 2 (for a view ray).
    pub total: Spectrum,
    /// `per_order[k]`: light scattered or reflected exactly `k` times (the last entry holds
    /// every order from `TALLIED_ORDERS − 1` up).
    pub per_order: Vec<Spectrum>,
    /// The part of `total` whose paths were reflected by the ground at least once.
    pub via_ground: Spectrum,
    /// Standard error of `total`'s mean, per wavelength.
    pub standard_error: Spectrum,
}

/// One path's contributions, by order, and the part of them that met the ground.
#[derive(Debug, Clone, Copy)]
struct Tally {
    by_order: [Spectrum; TALLIED_ORDERS],
    via_ground: Spectrum,
}

impl Tally {
    const ZERO: Self = Self {
        by_order: [Spectrum::ZERO; TALLIED_ORDERS],
        via_ground: Spectrum::ZERO,
    };

    /// Adds a contribution of `order` when it counts (order ≥ `min_order`).
    fn add(&mut self, min_order: usize, order: usize, value: Spectrum, via_ground: bool) {
        if order >= min_order && value.is_finite() {
            self.by_order[order.min(TALLIED_ORDERS - 1)] += value;
            if via_ground {
                self.via_ground += value;
            }
        }
    }

    /// Adds another tally (of contributions already counted).
    fn merge(&mut self, other: &Self) {
        for (mine, add) in self.by_order.iter_mut().zip(other.by_order) {
            *mine += add;
        }
        self.via_ground += other.via_ground;
    }

    fn total(&self) -> Spectrum {
        self.by_order.iter().copied().sum()
    }
}

/// Multiple scattering (contributions of order ≥ `min_order`) along a planet-frame ray that
/// ends on an opaque black surface at `limit` along it (infinite: no surface).
pub(super) fn multiple_scattering(
    reference: &Reference,
    ray: &Ray,
    min_order: usize,
    paths: usize,
    limit: f64,
) -> MultipleScattering {
    let ray_seed = hash(reference.settings.seed, ray.origin, ray.direction);
    estimate(paths, |index| {
        let mut rng = Pcg64Mcg::seed_from_u64(ray_seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let start = PathStart {
            events: 0,
            min_order,
            split_first: min_order >= 2,
            limit,
            grounded: false,
        };
        trace(reference, *ray, Spectrum::ONE, start, &mut rng)
    })
}

/// Where a path starts: events so far, the first order tallied, whether the first segment is
/// split (see [`trace`]), where an opaque surface ends the first segment and whether the path
/// was already reflected by the ground.
#[derive(Debug, Clone, Copy)]
struct PathStart {
    events: usize,
    min_order: usize,
    split_first: bool,
    limit: f64,
    grounded: bool,
}

impl PathStart {
    /// A path from a scattering or reflection event, with no surface in its way.
    fn after(events: usize, min_order: usize) -> Self {
        Self {
            events,
            min_order,
            split_first: false,
            limit: f64::INFINITY,
            grounded: false,
        }
    }
}

/// Sky irradiance on a surface with normal `up` at planet-frame point `p`: π × the mean radiance
/// (orders ≥ 1) over cosine-distributed directions.
///
/// Every point draws the same random numbers (the seed does not depend on `p` or `up`), so the
/// estimate is a smooth function of where it is taken: objects lit by it do not flicker as the
/// camera moves, and two nearby points differ by the physics, not by independent noise.
pub(super) fn sky_irradiance(reference: &Reference, p: DVec3, up: DVec3, paths: usize) -> Spectrum {
    let seed = reference.settings.seed ^ 0x1AB5;
    let estimate = estimate(paths, |index| {
        let mut rng = Pcg64Mcg::seed_from_u64(seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let direction = cosine_sample(up, &mut rng);
        trace(
            reference,
            Ray { origin: p, direction },
            Spectrum::ONE,
            PathStart::after(0, 1),
            &mut rng,
        )
    });
    estimate.total * PI
}

/// Paths summed together in order before blocks are combined (also in order), so that the
/// floating-point sums do not depend on how rayon splits the work.
const BLOCK: usize = 64;

fn estimate(paths: usize, path: impl Fn(usize) -> Tally + Sync) -> MultipleScattering {
    /// The sums of the paths' totals, of their squares and of their tallies.
    type Sums = (Spectrum, Spectrum, Tally);
    let paths = paths.max(1);
    let add = |mut a: Sums, b: Sums| {
        a.2.merge(&b.2);
        (a.0 + b.0, a.1 + b.1, a.2)
    };
    let zero = || (Spectrum::ZERO, Spectrum::ZERO, Tally::ZERO);
    let blocks: Vec<Sums> = (0..paths.div_ceil(BLOCK))
        .into_par_iter()
        .map(|block| {
            (block * BLOCK..((block + 1) * BLOCK).min(paths))
                .map(|index| {
                    let tally = path(index);
                    let total = tally.total();
                    (total, total * total, tally)
                })
                .fold(zero(), add)
        })
        .collect();
    let (sum, sum_squares, tally) = blocks.into_iter().fold(zero(), add);
    let n = paths as f64;
    let mean = sum / n;
    let variance = (sum_squares / n - mean * mean).max(Spectrum::ZERO);
    MultipleScattering {
        total: mean,
        per_order: tally.by_order.iter().map(|o| *o / n).collect(),
        via_ground: tally.via_ground / n,
        standard_error: (variance / n).sqrt(),
    }
}

/// One path from `ray` after `events` scattering/reflection events; returns its contributions
/// by order (only orders ≥ `min_order` are counted).
///
/// With `split_first` the first segment is handled by splitting instead of sampling: a forced
/// collision in the air, plus (when the segment ends on the ground) a branch reflected by the
/// ground with weight `T(end)`. For a view ray whose first event is not counted this removes the
/// paths that would leave with nothing, the bulk of them under a clear sky.
///
/// An opaque black surface at `start.limit` along the first segment ends it: nothing behind it
/// (ground, background) is seen.
fn trace(reference: &Reference, mut ray: Ray, mut weight: Spectrum, start: PathStart, rng: &mut Pcg64Mcg) -> Tally {
    let atmosphere = &reference.atmosphere;
    let planet = &atmosphere.planet;
    let medium = &atmosphere.medium;
    let PathStart {
        mut events,
        min_order,
        mut split_first,
        mut limit,
        mut grounded,
    } = start;
    let mut tally = Tally::ZERO;
    loop {
        let (found, walled) = match segment(planet, &ray) {
            Some(s) => s.before(limit),
            None => (None, limit.is_finite()),
        };
        limit = f64::INFINITY;
        let Some(segment) = found else {
            if !walled {
                tally.add(min_order, events, weight * reference.settings.background, grounded);
            }
            return tally;
        };
        let along_segment = reference.settings.line_samples > 0;
        if along_segment {
            let (air, ground) = line_light(reference, &ray, segment, rng);
            tally.add(min_order, events + 1, weight * air, grounded);
            tally.add(min_order, events + 1, weight * ground, true);
        }
        let flight = sample_distance(reference, &ray, segment.start, segment.end, weight, split_first, rng);
        if split_first {
            split_first = false;
            if segment.ends_on_ground {
                let depth = segment_depth(reference, &ray, segment.start, segment.end);
                let ground_weight = weight * (-depth).exp();
                let ground = Ray {
                    origin: ray.at(segment.end),
                    direction: ray.direction,
                };
                tally.merge(&reflect_and_trace(
                    reference,
                    ground,
                    ground_weight,
                    events,
                    min_order,
                    rng,
                ));
            }
            if matches!(flight, Flight::Nothing) {
                return tally;
            }
        }
        match flight {
            Flight::Nothing => return tally,
            Flight::Collision {
                t,
                weight: w,
                coefficients,
            } => {
                weight *= w;
                events += 1;
                let p = ray.at(t);
                let suns = if along_segment { &[][..] } else { &reference.suns[..] };
                for sun in suns {
                    let nu = ray.direction.dot(sun.direction);
                    let light = sun.irradiance * transmittance_to_sun(reference, p, sun.direction);
                    let value = weight * medium.scattering_phase(&coefficients, nu) * light;
                    tally.add(min_order, events, value, grounded);
                }
                // Pick the next direction from a Rayleigh / Henyey–Greenstein mixture, and
                // along segments also towards the sunlit air of suns below the horizon.
                let rayleigh = coefficients.rayleigh_scattering.y;
                let mie = coefficients.mie_scattering.y;
                let mie_share = if rayleigh + mie > 0.0 {
                    mie / (rayleigh + mie)
                } else {
                    0.5
                };
                let g = medium.mie.phase.g();
                let guides = if along_segment {
                    twilight_guides(reference, p)
                } else {
                    Vec::new()
                };
                let guide_share = if guides.is_empty() { 0.0 } else { GUIDE_SHARE };
                // No draw without guides: the default paths keep their random sequence.
                let direction = if guide_share > 0.0 && rng.random::<f64>() < guide_share {
                    let guide = guides[rng.random_range(0..guides.len())];
                    let cos = sample_henyey_greenstein(GUIDE_G, rng.random());
                    rotate_to(guide, cos, 2.0 * PI * rng.random::<f64>())
                } else {
                    let cos = if rng.random::<f64>() < mie_share {
                        sample_henyey_greenstein(g, rng.random())
                    } else {
                        sample_rayleigh(rng.random())
                    };
                    rotate_to(ray.direction, cos, 2.0 * PI * rng.random::<f64>())
                };
                let cos = ray.direction.dot(direction).clamp(-1.0, 1.0);
                let phase_pdf = (1.0 - mie_share) * rayleigh_phase(cos) + mie_share * henyey_greenstein(g, cos);
                let guide_pdf = guides
                    .iter()
                    .map(|guide| henyey_greenstein(GUIDE_G, guide.dot(direction)))
                    .sum::<f64>()
                    / guides.len().max(1) as f64;
                let pdf = (1.0 - guide_share) * phase_pdf + guide_share * guide_pdf;
                weight *= medium.scattering_phase(&coefficients, cos) / pdf;
                ray = Ray { origin: p, direction };
            }
            Flight::Boundary { weight: w } => {
                weight *= w;
                if !segment.ends_on_ground {
                    if !walled {
                        tally.add(min_order, events, weight * reference.settings.background, grounded);
                    }
                    return tally;
                }
                events += 1;
                grounded = true;
                let (start, direct) = ground_event(reference, ray.at(segment.end));
                if !along_segment {
                    tally.add(min_order, events, weight * direct, grounded);
                }
                weight *= medium.ground_albedo;
                ray = Ray {
                    origin: start,
                    direction: cosine_sample(planet.up(start), rng),
                };
            }
        }
        if events >= MAX_EVENTS {
            return tally;
        }
        if events >= 4 {
            let survive = weight.max_element().min(1.0);
            if survive <= 0.0 || rng.random::<f64>() >= survive {
                return tally;
            }
            weight /= survive;
        }
    }
}

/// The ground at planet-frame point `p`: the point just above it to continue from, and the
/// sunlight it reflects towards any direction (albedo/π × direct irradiance).
fn ground_event(reference: &Reference, p: DVec3) -> (DVec3, Spectrum) {
    let up = reference.atmosphere.planet.up(p);
    let start = p + up * 1e-3;
    let mut direct = Spectrum::ZERO;
    for sun in &reference.suns {
        let cos = up.dot(sun.direction);
        if cos > 0.0 {
            direct += sun.irradiance * transmittance_to_sun(reference, start, sun.direction) * cos;
        }
    }
    (start, direct * reference.atmosphere.medium.ground_albedo / PI)
}

/// The ground branch of a split: reflect at `ground.origin` (a ground point) and trace on.
fn reflect_and_trace(
    reference: &Reference,
    ground: Ray,
    weight: Spectrum,
    events: usize,
    min_order: usize,
    rng: &mut Pcg64Mcg,
) -> Tally {
    let mut tally = Tally::ZERO;
    let (start, direct) = ground_event(reference, ground.origin);
    let order = events + 1;
    // Along segments, the segment that ended here already counted the ground's sunlight.
    if reference.settings.line_samples == 0 {
        tally.add(min_order, order, weight * direct, true);
    }
    let direction = cosine_sample(reference.atmosphere.planet.up(start), rng);
    let rest = trace(
        reference,
        Ray {
            origin: start,
            direction,
        },
        weight * reference.atmosphere.medium.ground_albedo,
        PathStart {
            grounded: true,
            ..PathStart::after(order, min_order)
        },
        rng,
    );
    tally.merge(&rest);
    tally
}

/// Optical depth of the piecewise-constant medium [`sample_distance`] uses along a segment.
fn segment_depth(reference: &Reference, ray: &Ray, start: f64, end: f64) -> Spectrum {
    let planet = &reference.atmosphere.planet;
    let dt = (end - start) / TABLE_STEPS as f64;
    (0..=TABLE_STEPS)
        .map(|i| {
            let w = if i == 0 || i == TABLE_STEPS { 0.5 } else { 1.0 };
            reference
                .atmosphere
                .medium
                .at(planet.approximate_altitude(ray.at(start + dt * i as f64)))
                .extinction
                * w
        })
        .sum::<Spectrum>()
        * dt
}

/// The share of new directions drawn towards the twilight guides (when there are any).
const GUIDE_SHARE: f64 = 0.5;

/// Henyey–Greenstein asymmetry of the lobe about each twilight guide.
const GUIDE_G: f64 = 0.9;

/// Where the sunlit air lies from planet-frame point `p` for each sun below its horizon: level,
/// towards the sun's azimuth (the air over the terminator, far away and low in the sky). Paths
/// gathering along segments draw some of their directions about these (one-sample multiple
/// importance sampling with the phase function), so that more segments cross that air.
fn twilight_guides(reference: &Reference, p: DVec3) -> Vec<DVec3> {
    let up = reference.atmosphere.planet.up(p);
    reference
        .suns
        .iter()
        .filter(|sun| sun.direction.dot(up) < 0.0)
        .filter_map(|sun| (sun.direction - up * sun.direction.dot(up)).try_normalize())
        .collect()
}

/// The light reaching the start of `segment` (of `ray`) after one scattering or reflection: the
/// sunlight scattered once in its air, at `line_samples` points jittered in equal strata, and
/// the directly sunlit ground at its end, each attenuated on the way back.
fn line_light(reference: &Reference, ray: &Ray, segment: Segment, rng: &mut Pcg64Mcg) -> (Spectrum, Spectrum) {
    let planet = &reference.atmosphere.planet;
    let medium = &reference.atmosphere.medium;
    let (start, end) = (segment.start, segment.end);
    // Optical depth from the segment's start at the table's nodes, by trapezoids as
    // `segment_depth`, interpolated linearly between them.
    let dt = (end - start) / TABLE_STEPS as f64;
    let extinction = |i: usize| {
        medium
            .at(planet.approximate_altitude(ray.at(start + dt * i as f64)))
            .extinction
    };
    let mut depth = Vec::with_capacity(TABLE_STEPS + 1);
    depth.push(Spectrum::ZERO);
    let mut previous = extinction(0);
    for i in 1..=TABLE_STEPS {
        let next = extinction(i);
        depth.push(depth[i - 1] + (previous + next) * (0.5 * dt));
        previous = next;
    }
    let depth_at = |t: f64| {
        let x = ((t - start) / dt).clamp(0.0, TABLE_STEPS as f64);
        let i = (x as usize).min(TABLE_STEPS - 1);
        depth[i].lerp(depth[i + 1], x - i as f64)
    };
    let samples = reference.settings.line_samples;
    let stratum = (end - start) / samples as f64;
    let mut air = Spectrum::ZERO;
    for j in 0..samples {
        let t = start + stratum * (j as f64 + rng.random::<f64>());
        let p = ray.at(t);
        let coefficients = medium.at(planet.approximate_altitude(p));
        for sun in &reference.suns {
            let nu = ray.direction.dot(sun.direction);
            let light = sun.irradiance * transmittance_to_sun(reference, p, sun.direction);
            air += medium.scattering_phase(&coefficients, nu) * light * (-depth_at(t)).exp();
        }
    }
    let ground = if segment.ends_on_ground {
        ground_event(reference, ray.at(end)).1 * (-depth[TABLE_STEPS]).exp()
    } else {
        Spectrum::ZERO
    };
    (air * stratum, ground)
}

enum Flight {
    /// A scattering event at `t`; `weight` = T(t)/p(t) per wavelength (the caller multiplies by
    /// σ_s and the phase function). `coefficients` are the medium's there — the cell's mean, the
    /// same piecewise-constant medium the distance was drawn from, so that a non-absorbing
    /// medium's weights stay exactly 1.
    Collision {
        t: f64,
        weight: Spectrum,
        coefficients: LocalCoefficients,
    },
    /// The path reaches the segment's end; `weight` = T(end)/P(end).
    Boundary { weight: Spectrum },
    /// A forced collision in a segment with nothing to collide with.
    Nothing,
}

/// Draws where the path's next event is, choosing the wavelength to sample by `path_weight`.
/// With `forced`, the event is drawn among collisions only (conditioned on one happening before
/// the segment's end) and weighted accordingly; the caller accounts for the boundary separately.
fn sample_distance(
    reference: &Reference,
    ray: &Ray,
    start: f64,
    end: f64,
    path_weight: Spectrum,
    forced: bool,
    rng: &mut Pcg64Mcg,
) -> Flight {
    let planet = &reference.atmosphere.planet;
    let medium = &reference.atmosphere.medium;
    let dt = (end - start) / TABLE_STEPS as f64;
    let nodes: Vec<LocalCoefficients> = (0..=TABLE_STEPS)
        .map(|i| medium.at(planet.approximate_altitude(ray.at(start + dt * i as f64))))
        .collect();
    // Piecewise-linear optical depth: constant coefficients (the cell mean) inside each cell.
    let cell_extinction = |i: usize| (nodes[i].extinction + nodes[i + 1].extinction) * 0.5;
    let total_depth: Spectrum = (0..TABLE_STEPS).map(cell_extinction).sum::<Spectrum>() * dt;
    let collision_probability = if forced {
        Spectrum::ONE - (-total_depth).exp()
    } else {
        Spectrum::ONE
    };

    let total_weight = path_weight.element_sum();
    let choice = if total_weight > 0.0 {
        path_weight / total_weight
    } else {
        Spectrum::splat(1.0 / 3.0)
    };
    let u = rng.random::<f64>();
    let channel = if u < choice.x {
        0
    } else if u < choice.x + choice.y {
        1
    } else {
        2
    };
    if forced && collision_probability[channel] <= 0.0 {
        return Flight::Nothing;
    }
    let target = -(1.0 - rng.random::<f64>() * collision_probability[channel]).ln();
    let mut depth = Spectrum::ZERO;
    for i in 0..TABLE_STEPS {
        let sigma = cell_extinction(i);
        let next = depth + sigma * dt;
        if next[channel] >= target {
            let t_in_cell = ((target - depth[channel]) / sigma[channel]).clamp(0.0, dt);
            let transmittance = (-(depth + sigma * t_in_cell)).exp();
            let pdf = (choice * sigma * transmittance / collision_probability).element_sum();
            return Flight::Collision {
                t: start + dt * i as f64 + t_in_cell,
                weight: transmittance / pdf,
                coefficients: LocalCoefficients {
                    rayleigh_scattering: (nodes[i].rayleigh_scattering + nodes[i + 1].rayleigh_scattering) * 0.5,
                    mie_scattering: (nodes[i].mie_scattering + nodes[i + 1].mie_scattering) * 0.5,
                    extinction: sigma,
                },
            };
        }
        depth = next;
    }
    if forced {
        // Rounding put the target past the end: treat as the last cell's far edge.
        return Flight::Nothing;
    }
    let transmittance = (-depth).exp();
    Flight::Boundary {
        weight: transmittance / (choice * transmittance).element_sum(),
    }
}

/// Transmittance from `p` towards a sun (zero behind the ground), by trapezoids over
/// `TABLE_STEPS` cells.
fn transmittance_to_sun(reference: &Reference, p: DVec3, direction: DVec3) -> Spectrum {
    let planet = &reference.atmosphere.planet;
    let ray = Ray { origin: p, direction };
    let Some(segment) = segment(planet, &ray) else {
        return Spectrum::ONE;
    };
    if segment.ends_on_ground {
        return Spectrum::ZERO;
    }
    let depth = segment_depth(reference, &ray, segment.start, segment.end);
    (-depth).exp()
}

/// Cosine of the scattering angle drawn from Rayleigh's phase function (inverting its CDF
/// `(μ³ + 3μ + 4)/8`, a depressed cubic solved by Cardano's formula).
fn sample_rayleigh(u: f64) -> f64 {
    let q = 4.0 * u - 2.0;
    let root = (q * q + 1.0).sqrt();
    ((q + root).cbrt() + (q - root).cbrt()).clamp(-1.0, 1.0)
}

/// Cosine drawn from Henyey–Greenstein with asymmetry `g`.
fn sample_henyey_greenstein(g: f64, u: f64) -> f64 {
    if g.abs() < 1e-4 {
        return 2.0 * u - 1.0;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}

/// A unit vector at angle `acos(cos)` from `axis`, turned `phi` around it.
fn rotate_to(axis: DVec3, cos: f64, phi: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (u, v) = axis.any_orthonormal_pair();
    (axis * cos + (u * phi.cos() + v * phi.sin()) * sin).normalize()
}

/// A direction around `normal` with density cos θ / π.
fn cosine_sample(normal: DVec3, rng: &mut Pcg64Mcg) -> DVec3 {
    let u: f64 = rng.random();
    rotate_to(normal, u.sqrt(), 2.0 * PI * rng.random::<f64>())
}

/// A 64-bit mix of the seed and a ray, so every ray has its own random stream.
fn hash(seed: u64, a: DVec3, b: DVec3) -> u64 {
    let mut h = seed ^ 0xCBF2_9CE4_8422_2325;
    for v in [a.x, a.y, a.z, b.x, b.y, b.z] {
        h ^= v.to_bits();
        h = h.wrapping_mul(0x0100_0000_01B3).rotate_left(29);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samplers_follow_their_phase_functions() {
        // Mean cosine: Rayleigh 0, HG g.
        let n = 200_000;
        let mean_rayleigh: f64 = (0..n)
            .map(|i| sample_rayleigh((i as f64 + 0.5) / n as f64))
            .sum::<f64>()
            / n as f64;
        assert!(mean_rayleigh.abs() < 1e-6);
        let mean_hg: f64 = (0..n)
            .map(|i| sample_henyey_greenstein(0.8, (i as f64 + 0.5) / n as f64))
            .sum::<f64>()
            / n as f64;
        assert!((mean_hg - 0.8).abs() < 1e-4, "{mean_hg}");
        // Rayleigh second moment: ∫ μ² p(μ) = (3/8)∫ μ²(1+μ²) dμ = 2/5.
        let second: f64 = (0..n)
            .map(|i| sample_rayleigh((i as f64 + 0.5) / n as f64).powi(2))
            .sum::<f64>()
            / n as f64;
        assert!((second - 0.4).abs() < 1e-5, "{second}");
    }

    /// Gathering along segments estimates what collisions do, by day and at twilight, with
    /// less noise where little air is sunlit.
    #[test]
    fn gathering_along_segments_agrees_with_collisions() {
        use crate::atmosphere::{Sun, presets};
        let radius = presets::earth().planet.radii.z;
        let ray = Ray {
            origin: DVec3::new(0.0, 0.0, radius + 2.0),
            direction: DVec3::new(-(0.8f64.sqrt()), 0.0, 0.2f64.sqrt()),
        };
        for (elevation, paths) in [(30f64, 4096), (-6.0, 16384)] {
            let (s, c) = elevation.to_radians().sin_cos();
            let sun = Sun {
                direction: DVec3::new(c, 0.0, s),
                ..presets::earth_sun(DVec3::Z)
            };
            let run = |line_samples: usize| {
                let settings = super::super::ReferenceSettings {
                    paths,
                    line_samples,
                    ..Default::default()
                };
                let reference = Reference::new(presets::earth(), &[sun], settings);
                multiple_scattering(&reference, &ray, 2, paths, f64::INFINITY)
            };
            let (collisions, along) = (run(0), run(8));
            let noise = (collisions.standard_error * collisions.standard_error
                + along.standard_error * along.standard_error)
                .sqrt();
            let off = (along.total - collisions.total).abs() / noise;
            println!(
                "sun {elevation}°: collisions {} ± {}, along segments {} ± {}",
                collisions.total, collisions.standard_error, along.total, along.standard_error
            );
            assert!(off.max_element() < 4.0, "sun {elevation}°: {off}");
            if elevation < 0.0 {
                let relative = |m: &MultipleScattering| (m.standard_error / m.total).max_element();
                assert!(relative(&along) < relative(&collisions) / 2.0);
            }
        }
    }

    /// The share that met the ground is what a black ground removes, within the noise of the
    /// two estimates; a black ground leaves none.
    #[test]
    fn the_ground_share_is_what_a_black_ground_removes() {
        use crate::atmosphere::{Sun, presets};
        let sun = Sun {
            direction: DVec3::new(0.5, 0.0, 0.75f64.sqrt()),
            ..presets::earth_sun(DVec3::Z)
        };
        let radius = presets::earth().planet.radii.z;
        let ray = Ray {
            origin: DVec3::new(0.0, 0.0, radius + 1.0),
            direction: DVec3::new(-0.5, 0.0, 0.75f64.sqrt()),
        };
        let settings = super::super::ReferenceSettings {
            paths: 8192,
            ..Default::default()
        };
        let run = |albedo: f64| {
            let mut atmosphere = presets::earth();
            atmosphere.medium.ground_albedo = Spectrum::splat(albedo);
            let reference = Reference::new(atmosphere, &[sun], settings);
            multiple_scattering(&reference, &ray, 2, settings.paths, f64::INFINITY)
        };
        let (bright, black) = (run(0.3), run(0.0));
        assert_eq!(black.via_ground, Spectrum::ZERO);
        assert!(bright.via_ground.min_element() > 0.0);
        let removed = bright.total - black.total;
        let noise =
            (bright.standard_error * bright.standard_error + black.standard_error * black.standard_error).sqrt();
        let off = (bright.via_ground - removed).abs() / noise;
        assert!(off.max_element() < 4.0, "{} vs {removed} (±{noise})", bright.via_ground);
    }
}
