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
//! the fourth event (and a path is cut after `MAX_EVENTS` = 100 000, which only a path deep in
//! an air of optical depth over a hundred comes near), so no order is cut off. The air along a
//! segment is evaluated lazily, node by node from its start, as far as the walk needs it, and the
//! transmittance towards a sun stops at optical depth `OPAQUE_DEPTH`: in Venus's or Titan's air
//! a path collides within a kilometre and most of its points see no sun at all.
//!
//! With [`ReferenceSettings::line_samples`](super::ReferenceSettings::line_samples) the light a
//! path gathers after each event is estimated along the whole next segment instead of at the next
//! collision: sunlight scattered once anywhere on the segment, at that many points jittered in
//! equal strata, and the sunlit ground at its end (Rao–Blackwellised next-event estimation; the
//! collision then adds nothing of its own). Unbiased like the default, and far less noisy where
//! only a thin shell of distant air is sunlit — at twilight a collision rarely lands there, while
//! most segments cross it.
//!
//! **Clouds.** With cloud layers a segment is split where it crosses their shells. Between
//! shells the distance is drawn as above (by inverting the air's optical depth, tabulated
//! lazily); inside a shell by delta tracking (Woodcock et al. 1965; Kutz et al. 2017) against
//! the majorant `σ̄ = the air's cell + Σ density_per_m` (the field's maximum), renewed at the
//! air's cell boundaries, so that the clouds' noise is resolved exactly however long the
//! segment. The wavelength is still picked by the path's weight; because the clouds are grey
//! their unknown transmittance cancels from the spectral-MIS weight `T_k/Σ_j p_j σ_j T_j`, which
//! needs only the air's tabulated optical depth and the clouds' density at the collision: the
//! estimator stays unbiased. A view ray's first segment, whose collision is forced, is
//! tabulated once for all its paths instead (the air's cells split at the shells and, in a
//! layer with noise, into cells of its feature step, each with the density at its middle:
//! exact for uniform layers). At a collision the next direction is drawn from a lobe picked by
//! its share of the scattering — Rayleigh, the aerosols' Henyey–Greenstein, each layer's two
//! Henyey–Greenstein lobes by their blend — and weighted by the whole medium's `σ_s·P` over the
//! mixture's density; a layer's albedo below 1 absorbs the rest. Next-event estimation towards
//! each sun multiplies the air's transmittance by an unbiased estimate of the clouds': exact
//! for uniform layers, ratio tracking through the others, with Russian roulette once it falls
//! below 0.01. In a conservative cloud Russian roulette cannot end a path, so paths through
//! clouds are cut only after `MAX_EVENTS_WITH_CLOUDS` = 100 000 events (bias below e⁻³⁶ of the
//! light for slabs up to optical depth 150). Orders are tallied as before.
//!
//! Each path has its own random stream seeded from (seed, ray, path index): results do not
//! depend on the number of threads. Without clouds none of the above draws a random number:
//! the paths and their results are bit for bit what they were.

use std::f64::consts::PI;

use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

use super::cloud_media::{self, Densities};
use super::inputs::{Reference, Segment, segment};
use crate::atmosphere::medium::{LocalCoefficients, MAX_TERMS, Medium, Phase, henyey_greenstein, rayleigh_phase};
use crate::atmosphere::spectrum::Spectrum;
use crate::geometry::Ray;

/// Orders tallied separately in [`MultipleScattering::per_order`]; higher ones go to the last.
pub const TALLIED_ORDERS: usize = 16;

/// Events after which a path is cut. Russian roulette ends paths in thin air long before; in a
/// thick, nearly conservative air (Venus: vertical optical depth 40, single-scattering albedo
/// 0.999) a path from the ground wanders for thousands of events before it reaches sunlit air
/// or leaves, as in a cloud ([`MAX_EVENTS_WITH_CLOUDS`] gives the bias of the cut).
const MAX_EVENTS: usize = 100_000;

/// Events after which a path through clouds is cut. In a conservative cloud Russian roulette
/// cannot end a path (its weight stays near 1), so the path goes on until it leaves; in a slab
/// of optical depth τ and asymmetry g the chance to be still inside after n events falls as
/// `exp(−n·π²/(3(1 − g)(τ + 1.42/(1 − g))²))` (diffusion's slowest mode), so the cut removes
/// e⁻¹⁴⁰⁰ of the light of a τ = 30, g = 0.85 slab and e⁻³⁶ of a τ = 150 one.
const MAX_EVENTS_WITH_CLOUDS: usize = 100_000;

/// Optical depth beyond which a transmittance is taken as zero (e⁻¹⁰⁰ ≈ 4·10⁻⁴⁴): a point deep
/// in a thick air stops summing its path to the sun there instead of crossing the whole air.
const OPAQUE_DEPTH: f64 = 100.0;

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
    // Through clouds, the first segment's medium is tabulated once for every path.
    let view = if reference.clouds.is_empty() || min_order < 2 {
        None
    } else {
        segment(&reference.atmosphere.planet, ray)
            .and_then(|s| s.before(limit).0)
            .map(|s| ViewTable::new(reference, ray, s.start, s.end))
    };
    estimate(paths, |index| {
        let mut rng = Pcg64Mcg::seed_from_u64(ray_seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let start = PathStart {
            events: 0,
            min_order,
            split_first: min_order >= 2,
            limit,
            grounded: false,
            view: view.as_ref(),
        };
        trace(reference, *ray, Spectrum::ONE, start, &mut rng)
    })
}

/// Where a path starts: events so far, the first order tallied, whether the first segment is
/// split (see [`trace`]), where an opaque surface ends the first segment, whether the path
/// was already reflected by the ground, and (through clouds) the first segment's medium.
#[derive(Debug, Clone, Copy)]
struct PathStart<'a> {
    events: usize,
    min_order: usize,
    split_first: bool,
    limit: f64,
    grounded: bool,
    view: Option<&'a ViewTable>,
}

impl PathStart<'static> {
    /// A path from a scattering or reflection event, with no surface in its way.
    fn after(events: usize, min_order: usize) -> Self {
        Self {
            events,
            min_order,
            split_first: false,
            limit: f64::INFINITY,
            grounded: false,
            view: None,
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
    sky_radiance_mean(reference, p, up, paths).total * PI
}

/// The mean radiance over the hemisphere about `up` at `p`, cosine-weighted, every order from
/// the first, with its standard error: [`sky_irradiance`] over π.
pub(super) fn sky_radiance_mean(reference: &Reference, p: DVec3, up: DVec3, paths: usize) -> MultipleScattering {
    let seed = reference.settings.seed ^ 0x1AB5;
    estimate(paths, |index| {
        let mut rng = Pcg64Mcg::seed_from_u64(seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let direction = cosine_sample(up, &mut rng);
        trace(
            reference,
            Ray { origin: p, direction },
            Spectrum::ONE,
            PathStart::after(0, 1),
            &mut rng,
        )
    })
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
        view,
    } = start;
    let clouds = !reference.clouds.is_empty();
    let max_events = if clouds { MAX_EVENTS_WITH_CLOUDS } else { MAX_EVENTS };
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
        // Gathering along segments does not see clouds: with clouds it is left out.
        let along_segment = reference.settings.line_samples > 0 && !clouds;
        if along_segment {
            let (air, ground) = line_light(reference, &ray, segment, rng);
            tally.add(min_order, events + 1, weight * air, grounded);
            tally.add(min_order, events + 1, weight * ground, true);
        }
        // The optical depth of the first segment's tabulated medium, through clouds.
        let mut forced_depth = None;
        let flight = if !clouds {
            sample_distance(reference, &ray, segment.start, segment.end, weight, split_first, rng)
        } else if split_first {
            let built;
            let table = match view.filter(|v| v.start == segment.start && v.end == segment.end) {
                Some(table) => table,
                None => {
                    built = ViewTable::new(reference, &ray, segment.start, segment.end);
                    &built
                }
            };
            forced_depth = Some(table.total_depth());
            table.sample_forced(weight, rng)
        } else {
            sample_distance_clouds(reference, &ray, segment.start, segment.end, weight, rng)
        };
        if split_first {
            split_first = false;
            if segment.ends_on_ground {
                let depth = forced_depth.unwrap_or_else(|| segment_depth(reference, &ray, segment.start, segment.end));
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
                clouds: densities,
            } => {
                weight *= w;
                events += 1;
                let p = ray.at(t);
                let cloud_scattering = if clouds {
                    cloud_media::scattering(&reference.clouds, &densities)
                } else {
                    0.0
                };
                let suns = if along_segment { &[][..] } else { &reference.suns[..] };
                for sun in suns {
                    let nu = ray.direction.dot(sun.direction);
                    let light = sun.irradiance
                        * transmittance_to_sun(reference, p, sun.direction, rng)
                        * reference.sun_visible(p, sun);
                    let mut scattering = medium.scattering_phase(&coefficients, nu);
                    if cloud_scattering > 0.0 {
                        scattering += Spectrum::splat(cloud_media::scattering_phase(&reference.clouds, &densities, nu));
                    }
                    let value = weight * scattering * light;
                    tally.add(min_order, events, value, grounded);
                }
                if cloud_scattering > 0.0 {
                    let (direction, factor) =
                        scatter_with_clouds(reference, &ray, &coefficients, &densities, cloud_scattering, rng);
                    weight *= factor;
                    ray = Ray { origin: p, direction };
                } else {
                    // Pick the next direction from the mixture of the terms' phase functions, and
                    // along segments also towards the sunlit air of suns below the horizon.
                    let weights = term_weights(&coefficients);
                    let total: f64 = weights.iter().sum();
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
                        let term = pick_term(&weights, rng.random::<f64>() * total).unwrap_or(0);
                        let cos = sample_phase(&medium.terms[term].phase, rng.random());
                        rotate_to(ray.direction, cos, 2.0 * PI * rng.random::<f64>())
                    };
                    let cos = ray.direction.dot(direction).clamp(-1.0, 1.0);
                    let phase_pdf = mixture_pdf(medium, &weights, cos) / total;
                    let guide_pdf = guides
                        .iter()
                        .map(|guide| henyey_greenstein(GUIDE_G, guide.dot(direction)))
                        .sum::<f64>()
                        / guides.len().max(1) as f64;
                    let pdf = (1.0 - guide_share) * phase_pdf + guide_share * guide_pdf;
                    weight *= medium.scattering_phase(&coefficients, cos) / pdf;
                    ray = Ray { origin: p, direction };
                }
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
                let (start, direct, albedo) = ground_event(reference, &ray, segment.end, rng);
                if !along_segment {
                    tally.add(min_order, events, weight * direct, grounded);
                }
                weight *= albedo;
                ray = Ray {
                    origin: start,
                    direction: cosine_sample(planet.up(start), rng),
                };
            }
        }
        if events >= max_events {
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

/// The ground where `ray` meets it at `t`: the point just above it to continue from, the
/// sunlight it reflects back along the ray (the albedo's share, albedo/π × direct irradiance,
/// and the water's glint) and its albedo (a bounce's weight).
fn ground_event(reference: &Reference, ray: &Ray, t: f64, rng: &mut Pcg64Mcg) -> (DVec3, Spectrum, Spectrum) {
    let p = ray.at(t);
    let up = reference.atmosphere.planet.up(p);
    let start = p + up * 1e-3;
    let direct = reference.ground_reflected(start, up, -ray.direction, false, |sun| {
        transmittance_to_sun(reference, start, sun.direction, rng)
    });
    (start, direct, reference.ground_at(up).albedo)
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
    let (start, direct, albedo) = ground_event(reference, &ground, 0.0, rng);
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
        weight * albedo,
        PathStart {
            grounded: true,
            ..PathStart::after(order, min_order)
        },
        rng,
    );
    tally.merge(&rest);
    tally
}

/// Optical depth of the piecewise-constant medium [`sample_distance`] uses along a segment, or a
/// depth past [`OPAQUE_DEPTH`] in every channel once the sum from the start exceeds it there.
fn segment_depth(reference: &Reference, ray: &Ray, start: f64, end: f64) -> Spectrum {
    let planet = &reference.atmosphere.planet;
    let dt = (end - start) / TABLE_STEPS as f64;
    let mut sum = Spectrum::ZERO;
    for i in 0..=TABLE_STEPS {
        let w = if i == 0 || i == TABLE_STEPS { 0.5 } else { 1.0 };
        sum += reference
            .atmosphere
            .medium
            .at(planet.approximate_altitude(ray.at(start + dt * i as f64)))
            .extinction
            * w;
        if (sum * dt).min_element() > OPAQUE_DEPTH {
            break;
        }
    }
    sum * dt
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
            let light =
                sun.irradiance * transmittance_to_sun(reference, p, sun.direction, rng) * reference.sun_visible(p, sun);
            air += medium.scattering_phase(&coefficients, nu) * light * (-depth_at(t)).exp();
        }
    }
    let ground = if segment.ends_on_ground {
        ground_event(reference, ray, end, rng).1 * (-depth[TABLE_STEPS]).exp()
    } else {
        Spectrum::ZERO
    };
    (air * stratum, ground)
}

#[expect(
    clippy::large_enum_variant,
    reason = "a flight lives on the stack for one step of a path: boxing its coefficients would allocate at every collision"
)]
enum Flight {
    /// A scattering event at `t`; `weight` = T(t)/p(t) per wavelength (the caller multiplies by
    /// σ_s and the phase function). `coefficients` are the medium's there — the cell's mean, the
    /// same piecewise-constant medium the distance was drawn from, so that a non-absorbing
    /// medium's weights stay exactly 1.
    Collision {
        t: f64,
        weight: Spectrum,
        coefficients: LocalCoefficients,
        /// The clouds' densities there, by layer (all zero without clouds).
        clouds: Densities,
    },
    /// The path reaches the segment's end; `weight` = T(end)/P(end).
    Boundary { weight: Spectrum },
    /// A forced collision in a segment with nothing to collide with.
    Nothing,
}

/// Draws where the path's next event is, choosing the wavelength to sample by `path_weight`.
/// With `forced`, the event is drawn among collisions only (conditioned on one happening before
/// the segment's end) and weighted accordingly; the caller accounts for the boundary separately.
/// Unforced, the nodes are evaluated only as far as the walk goes (the same numbers).
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
    let node = |i: usize| medium.at(planet.approximate_altitude(ray.at(start + dt * i as f64)));
    // Piecewise-linear optical depth: constant coefficients (the cell mean) inside each cell.
    let cell_extinction = |a: &LocalCoefficients, b: &LocalCoefficients| (a.extinction + b.extinction) * 0.5;
    let collision_probability = if forced {
        let nodes: Vec<LocalCoefficients> = (0..=TABLE_STEPS).map(node).collect();
        let total_depth: Spectrum = nodes
            .windows(2)
            .map(|pair| cell_extinction(&pair[0], &pair[1]))
            .sum::<Spectrum>()
            * dt;
        Spectrum::ONE - (-total_depth).exp()
    } else {
        Spectrum::ONE
    };

    let (choice, channel) = pick_channel(path_weight, rng);
    if forced && collision_probability[channel] <= 0.0 {
        return Flight::Nothing;
    }
    let target = -(1.0 - rng.random::<f64>() * collision_probability[channel]).ln();
    let mut depth = Spectrum::ZERO;
    let mut near = node(0);
    for i in 0..TABLE_STEPS {
        let far = node(i + 1);
        let sigma = cell_extinction(&near, &far);
        let next = depth + sigma * dt;
        if next[channel] >= target {
            let t_in_cell = ((target - depth[channel]) / sigma[channel]).clamp(0.0, dt);
            let transmittance = (-(depth + sigma * t_in_cell)).exp();
            let pdf = (choice * sigma * transmittance / collision_probability).element_sum();
            return Flight::Collision {
                t: start + dt * i as f64 + t_in_cell,
                weight: transmittance / pdf,
                coefficients: LocalCoefficients {
                    extinction: sigma,
                    ..near.mean(&far)
                },
                clouds: NO_CLOUDS,
            };
        }
        depth = next;
        near = far;
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

/// No cloud anywhere.
const NO_CLOUDS: Densities = [0.0; crate::atmosphere::clouds::MAX_CLOUD_LAYERS];

/// No air.
/// Whether the atmosphere has any air at all (clouds in a vacuum, as the plane-parallel checks
/// have them, skip evaluating the air).
fn has_air(reference: &Reference) -> bool {
    reference.atmosphere.medium.has_air()
}

/// The wavelength whose free flight is drawn, picked with probability proportional to the path's
/// weight (as [`sample_distance`] does), and the probabilities.
fn pick_channel(path_weight: Spectrum, rng: &mut Pcg64Mcg) -> (Spectrum, usize) {
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
    (choice, channel)
}

/// The air along a segment as [`sample_distance`] sees it: `TABLE_STEPS` cells of constant
/// coefficients (the means of their end nodes), and the optical depth at the nodes — evaluated
/// lazily, node by node from the start, as far as a walk needs them (a path in a cloud collides
/// within metres of a segment that may be a thousand kilometres long).
struct AirTable<'a> {
    reference: &'a Reference,
    ray: Ray,
    start: f64,
    dt: f64,
    /// The last node evaluated.
    node: LocalCoefficients,
    cells: Vec<LocalCoefficients>,
    depth: Vec<Spectrum>,
}

impl<'a> AirTable<'a> {
    fn new(reference: &'a Reference, ray: &Ray, start: f64, end: f64) -> Self {
        let mut table = Self {
            reference,
            ray: *ray,
            start,
            dt: (end - start) / TABLE_STEPS as f64,
            node: LocalCoefficients::NONE,
            cells: Vec::with_capacity(TABLE_STEPS),
            depth: Vec::with_capacity(TABLE_STEPS + 1),
        };
        table.node = table.node_at(0);
        table.depth.push(Spectrum::ZERO);
        table
    }

    fn node_at(&self, i: usize) -> LocalCoefficients {
        if !has_air(self.reference) {
            return LocalCoefficients::NONE;
        }
        let planet = &self.reference.atmosphere.planet;
        let at = self.ray.at(self.start + self.dt * i as f64);
        self.reference.atmosphere.medium.at(planet.approximate_altitude(at))
    }

    /// Evaluates the cells up to `i`.
    fn reach(&mut self, i: usize) {
        while self.cells.len() <= i.min(TABLE_STEPS - 1) {
            let k = self.cells.len();
            let next = self.node_at(k + 1);
            let (a, b) = (self.node, next);
            let cell = a.mean(&b);
            self.depth.push(self.depth[k] + cell.extinction * self.dt);
            self.cells.push(cell);
            self.node = next;
        }
    }

    /// The cell holding parameter `t`.
    fn cell(&self, t: f64) -> usize {
        if self.dt.is_nan() || self.dt <= 0.0 {
            return 0;
        }
        (((t - self.start) / self.dt).max(0.0) as usize).min(TABLE_STEPS - 1)
    }

    /// The coefficients of cell `i`.
    fn coefficients(&mut self, i: usize) -> LocalCoefficients {
        self.reach(i);
        self.cells[i]
    }

    /// Optical depth from the segment's start to node `i`.
    fn depth_to_node(&mut self, i: usize) -> Spectrum {
        if i > 0 {
            self.reach(i - 1);
        }
        self.depth[i]
    }

    /// Optical depth from the segment's start to `t`.
    fn depth_at(&mut self, t: f64) -> Spectrum {
        let i = self.cell(t);
        self.reach(i);
        self.depth[i] + self.cells[i].extinction * (t - (self.start + self.dt * i as f64))
    }
}

/// [`sample_distance`] through clouds, unforced: the air as the same piecewise-constant table,
/// the segment split where it crosses the layers' shells. Between shells the distance is drawn
/// by inverting the air's optical depth; inside a shell by delta tracking (Woodcock) against
/// the majorant `σ̄ = the air's cell + Σ density_per_m` of the layers there, renewed cell by
/// cell, so that the noise inside is resolved exactly. Both draw from `σ_c·T_c` of the chosen wavelength `c`, air and clouds
/// together. The clouds' transmittance, unknown, is grey: it cancels from the spectral-MIS
/// weight `T_k/Σ_j p_j σ_j T_j`, which needs only the air's optical depth and the clouds'
/// density at the collision.
fn sample_distance_clouds(
    reference: &Reference,
    ray: &Ray,
    start: f64,
    end: f64,
    path_weight: Spectrum,
    rng: &mut Pcg64Mcg,
) -> Flight {
    let planet = &reference.atmosphere.planet;
    let layers = &reference.clouds;
    let mut air = AirTable::new(reference, ray, start, end);
    let (choice, channel) = pick_channel(path_weight, rng);
    // A collision at `t` in air cell `i`.
    let collision = |air: &mut AirTable, t: f64, i: usize, densities: Densities| {
        let coefficients = air.coefficients(i);
        let transmittance =
            (-(air.depth_to_node(i) + coefficients.extinction * (t - (air.start + air.dt * i as f64)))).exp();
        let sigma = coefficients.extinction + Spectrum::splat(densities.iter().sum::<f64>());
        let pdf = (choice * sigma * transmittance).element_sum();
        Flight::Collision {
            t,
            weight: transmittance / pdf,
            coefficients,
            clouds: densities,
        }
    };
    for piece in cloud_media::pieces(planet, layers, ray, start, end) {
        if piece.inside == 0 {
            // Clear air: invert its optical depth from the piece's start.
            let goal = air.depth_at(piece.a)[channel] - (1.0 - rng.random::<f64>()).ln();
            let last = air.cell(piece.b);
            let mut i = air.cell(piece.a);
            while i < last && air.depth_to_node(i + 1)[channel] < goal {
                i += 1;
            }
            if i == last && air.depth_at(piece.b)[channel] < goal {
                continue;
            }
            let sigma = air.coefficients(i).extinction[channel];
            let cell_start = air.start + air.dt * i as f64;
            let t = if sigma > 0.0 {
                cell_start + (goal - air.depth_to_node(i)[channel]) / sigma
            } else {
                cell_start
            };
            return collision(&mut air, t.clamp(piece.a, piece.b), i, NO_CLOUDS);
        }
        let cloud_majorant: f64 = piece.layers().map(|l| layers[l].density_per_m).sum();
        let mut t = piece.a;
        // The air is constant in each cell: the majorant is that cell's air and the layers'
        // `density_per_m`, renewed at each cell boundary (the flight is memoryless), so that
        // cells are evaluated only as far as the walk goes.
        let mut checked = air.cell(piece.a);
        let mut air_majorant = air.coefficients(checked).extinction[channel];
        loop {
            let majorant = air_majorant + cloud_majorant;
            if majorant.is_nan() || majorant <= 0.0 {
                break;
            }
            let step = -(1.0 - rng.random::<f64>()).ln() / majorant;
            // A majorant holds for the cells it was taken over: stop at the next cell's start.
            let cell_end = air.start + air.dt * (checked + 1) as f64;
            let limit = if checked + 1 < TABLE_STEPS {
                cell_end.min(piece.b)
            } else {
                piece.b
            };
            if t + step >= limit {
                if limit >= piece.b {
                    break;
                }
                // Memoryless: restart from the cell boundary with the next cell's majorant.
                t = limit;
                checked += 1;
                air_majorant = air.coefficients(checked).extinction[channel];
                continue;
            }
            t += step;
            let p = ray.at(t);
            let h = planet.approximate_altitude(p);
            let mut densities = NO_CLOUDS;
            for l in piece.layers() {
                densities[l] = cloud_media::density_inside(planet, &layers[l], p, h);
            }
            let sigma = air_majorant + densities.iter().sum::<f64>();
            if rng.random::<f64>() * majorant < sigma {
                return collision(&mut air, t, checked, densities);
            }
        }
    }
    let transmittance = (-air.depth_to_node(TABLE_STEPS)).exp();
    Flight::Boundary {
        weight: transmittance / (choice * transmittance).element_sum(),
    }
}

/// The first segment of a view ray through clouds as a piecewise-constant medium, built once for
/// all its paths so that its collisions can be forced (drawn conditioned on one happening): the
/// air's `TABLE_STEPS` cells as [`sample_distance`] has them, split at the layers' shells and,
/// inside a layer with noise, into cells no longer than its feature step, each with the clouds'
/// density at its middle (exact for uniform layers).
#[derive(Debug)]
struct ViewTable {
    start: f64,
    end: f64,
    /// Cell boundaries, metres along the ray (one more than the cells).
    edges: Vec<f64>,
    /// Each cell's air, clouds and total extinction.
    cells: Vec<(LocalCoefficients, Densities, Spectrum)>,
    /// Optical depth from the start to each boundary, air and clouds.
    depth: Vec<Spectrum>,
}

impl ViewTable {
    pub(super) fn new(reference: &Reference, ray: &Ray, start: f64, end: f64) -> Self {
        let planet = &reference.atmosphere.planet;
        let layers = &reference.clouds;
        let mut air = AirTable::new(reference, ray, start, end);
        air.reach(TABLE_STEPS);
        let pieces = cloud_media::pieces(planet, layers, ray, start, end);
        let mut edges: Vec<f64> = (0..TABLE_STEPS).map(|i| start + air.dt * i as f64).collect();
        edges.push(end);
        for piece in &pieces {
            edges.extend([piece.a, piece.b]);
            let step = piece
                .layers()
                .filter_map(|l| cloud_media::feature_step(&layers[l]))
                .fold(f64::INFINITY, f64::min);
            if step.is_finite() {
                let n = ((piece.b - piece.a) / step).ceil() as usize;
                edges.extend((1..n).map(|k| piece.a + (piece.b - piece.a) * k as f64 / n as f64));
            }
        }
        edges.retain(|t| *t >= start && *t <= end);
        edges.sort_by(f64::total_cmp);
        edges.dedup();
        let mut cells = Vec::with_capacity(edges.len());
        let mut depth = Vec::with_capacity(edges.len());
        depth.push(Spectrum::ZERO);
        for w in edges.windows(2) {
            let middle = 0.5 * (w[0] + w[1]);
            let p = ray.at(middle);
            let h = planet.approximate_altitude(p);
            let mut densities = NO_CLOUDS;
            let piece = pieces
                .partition_point(|piece| piece.b <= middle)
                .min(pieces.len().saturating_sub(1));
            if let Some(piece) = pieces.get(piece) {
                for l in piece.layers() {
                    densities[l] = cloud_media::density_inside(planet, &layers[l], p, h);
                }
            }
            let coefficients = air.coefficients(air.cell(middle));
            let sigma = coefficients.extinction + Spectrum::splat(densities.iter().sum::<f64>());
            depth.push(depth[depth.len() - 1] + sigma * (w[1] - w[0]));
            cells.push((coefficients, densities, sigma));
        }
        Self {
            start,
            end,
            edges,
            cells,
            depth,
        }
    }

    fn total_depth(&self) -> Spectrum {
        self.depth[self.depth.len() - 1]
    }

    /// A forced collision, as [`sample_distance`] draws one.
    fn sample_forced(&self, path_weight: Spectrum, rng: &mut Pcg64Mcg) -> Flight {
        let collision_probability = Spectrum::ONE - (-self.total_depth()).exp();
        let (choice, channel) = pick_channel(path_weight, rng);
        if collision_probability[channel] <= 0.0 || self.cells.is_empty() {
            return Flight::Nothing;
        }
        let target = -(1.0 - rng.random::<f64>() * collision_probability[channel]).ln();
        let i = self.depth[1..].partition_point(|d| d[channel] < target);
        let Some((coefficients, densities, sigma)) = self.cells.get(i) else {
            // Rounding put the target past the end.
            return Flight::Nothing;
        };
        let length = self.edges[i + 1] - self.edges[i];
        let sigma = *sigma;
        let t_in_cell = if sigma[channel] > 0.0 {
            ((target - self.depth[i][channel]) / sigma[channel]).clamp(0.0, length)
        } else {
            0.0
        };
        let transmittance = (-(self.depth[i] + sigma * t_in_cell)).exp();
        let pdf = (choice * sigma * transmittance / collision_probability).element_sum();
        Flight::Collision {
            t: self.edges[i] + t_in_cell,
            weight: transmittance / pdf,
            coefficients: *coefficients,
            clouds: *densities,
        }
    }
}

/// A new direction after a collision where clouds scatter: a lobe picked by its share of the
/// scattering (Rayleigh, the aerosols' Henyey–Greenstein proposal, each layer's forward and
/// backward Henyey–Greenstein lobes; the air's at the middle wavelength), drawn, and weighted
/// by the whole medium's `σ_s·P` over the mixture's density. Returns the direction and the
/// factor for the path's weight.
fn scatter_with_clouds(
    reference: &Reference,
    ray: &Ray,
    coefficients: &LocalCoefficients,
    densities: &Densities,
    cloud_scattering: f64,
    rng: &mut Pcg64Mcg,
) -> (DVec3, Spectrum) {
    let medium = &reference.atmosphere.medium;
    let layers = &reference.clouds;
    let weights = term_weights(coefficients);
    let air: f64 = weights.iter().sum();
    let total = air + cloud_scattering;
    let u = rng.random::<f64>() * total;
    let cos = if let Some(term) = pick_term(&weights, u) {
        sample_phase(&medium.terms[term].phase, rng.random())
    } else {
        let mut rest = u - air;
        let mut chosen = None;
        for (layer, d) in layers.iter().zip(densities) {
            let share = layer.albedo * d;
            if share > 0.0 {
                chosen = Some(layer);
                if rest < share {
                    break;
                }
                rest -= share;
            }
        }
        match chosen {
            Some(layer) => cloud_media::sample_phase(&layer.phase, rng.random(), rng.random()),
            None => 2.0 * rng.random::<f64>() - 1.0,
        }
    };
    let direction = rotate_to(ray.direction, cos, 2.0 * PI * rng.random::<f64>());
    let cos = ray.direction.dot(direction).clamp(-1.0, 1.0);
    let clouds = cloud_media::scattering_phase(layers, densities, cos);
    let pdf = (mixture_pdf(medium, &weights, cos) + clouds) / total;
    let value = medium.scattering_phase(coefficients, cos) + Spectrum::splat(clouds);
    (direction, value / pdf)
}

/// Transmittance from `p` towards a sun (zero behind the ground): the air's by trapezoids over
/// `TABLE_STEPS` cells, times (with clouds) an unbiased estimate of the clouds'
/// ([`cloud_media::transmittance_estimate`]: exact for uniform layers, ratio tracking through
/// the others).
fn transmittance_to_sun(reference: &Reference, p: DVec3, direction: DVec3, rng: &mut Pcg64Mcg) -> Spectrum {
    let planet = &reference.atmosphere.planet;
    let ray = Ray { origin: p, direction };
    let Some(segment) = segment(planet, &ray) else {
        return Spectrum::ONE;
    };
    if segment.ends_on_ground {
        return Spectrum::ZERO;
    }
    if reference.clouds.is_empty() {
        let depth = segment_depth(reference, &ray, segment.start, segment.end);
        return (-depth).exp();
    }
    let clouds = cloud_media::transmittance_estimate(planet, &reference.clouds, &ray, segment.start, segment.end, rng);
    if clouds == 0.0 {
        return Spectrum::ZERO;
    }
    if !has_air(reference) {
        return Spectrum::splat(clouds);
    }
    let depth = segment_depth(reference, &ray, segment.start, segment.end);
    (-depth).exp() * clouds
}

/// Each term's share in choosing the next direction: its scattering at the middle wavelength.
fn term_weights(coefficients: &LocalCoefficients) -> [f64; MAX_TERMS] {
    coefficients.scattering.map(|s| s.y.max(0.0))
}

/// The term whose cumulative share `u` falls in (`u` drawn in [0, Σ weights)), or `None` past
/// the last (the clouds' share, where they scatter too).
fn pick_term(weights: &[f64; MAX_TERMS], mut u: f64) -> Option<usize> {
    for (i, w) in weights.iter().enumerate() {
        if *w > 0.0 {
            if u < *w {
                return Some(i);
            }
            u -= w;
        }
    }
    None
}

/// Cosine of the scattering angle drawn for a term: exactly from Rayleigh, Henyey–Greenstein and
/// the dual lobes, from Henyey–Greenstein with the same `g` for Cornette–Shanks, and from a
/// density in 0.1° bins for a table ([`proposal_pdf`] is the density drawn from).
fn sample_phase(phase: &Phase, u: f64) -> f64 {
    match phase {
        Phase::Rayleigh => sample_rayleigh(u),
        Phase::CornetteShanks { g } | Phase::HenyeyGreenstein { g } => sample_henyey_greenstein(*g, u),
        Phase::DualHenyeyGreenstein(dual) => {
            if u < dual.blend {
                sample_henyey_greenstein(dual.g_forward, u / dual.blend)
            } else {
                sample_henyey_greenstein(dual.g_back, (u - dual.blend) / (1.0 - dual.blend))
            }
        }
        Phase::Table(table) => table.sample(u),
    }
}

/// The density, sr⁻¹, [`sample_phase`] draws directions from.
fn proposal_pdf(phase: &Phase, cos: f64) -> f64 {
    match phase {
        Phase::Rayleigh => rayleigh_phase(cos),
        Phase::CornetteShanks { g } | Phase::HenyeyGreenstein { g } => henyey_greenstein(*g, cos),
        Phase::DualHenyeyGreenstein(dual) => dual.eval(cos),
        Phase::Table(table) => table.sampling_pdf(cos),
    }
}

/// `Σ weight_i · proposal_i(cos)`: the mixture's density times the weights' sum.
fn mixture_pdf(medium: &Medium, weights: &[f64; MAX_TERMS], cos: f64) -> f64 {
    medium
        .terms
        .iter()
        .zip(weights)
        .filter(|(_, w)| **w > 0.0)
        .map(|(term, w)| w * proposal_pdf(&term.phase, cos))
        .sum()
}

/// Cosine of the scattering angle drawn from Rayleigh's phase function (inverting its CDF
/// `(μ³ + 3μ + 4)/8`, a depressed cubic solved by Cardano's formula).
fn sample_rayleigh(u: f64) -> f64 {
    let q = 4.0 * u - 2.0;
    let root = (q * q + 1.0).sqrt();
    ((q + root).cbrt() + (q - root).cbrt()).clamp(-1.0, 1.0)
}

/// Cosine drawn from Henyey–Greenstein with asymmetry `g`.
pub(super) fn sample_henyey_greenstein(g: f64, u: f64) -> f64 {
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
