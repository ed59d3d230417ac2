//! The seed's own atmosphere model (`atmosphere.model = "seed"`): an `f64` port of version 3.1
//! of the GLSL "SSH GLSL Atmospheric Ray light scattering" fragment shader in seed document
//! `000_643abe256ac7a513.txt` (lines 285–476, uniforms lines 477–495, CPU side lines 498–553),
//! the reference the GPU port is tested against.
//!
//! Scene files select it as `"seed"`; in Rust it is called *empirical* (for what it is, below), so
//! that "seed" keeps meaning the founding texts, whose values [`EmpiricalAtmosphere::seed_earth`]
//! and [`EmpiricalAtmosphere::seed_mars`] hold.
//!
//! # The model
//! Not physics but an empirical colouring: the part of the view ray inside the atmosphere
//! ellipsoid and in front of the ground is integrated in [`EMPIRICAL_STEPS`] steps from its far end
//! towards the viewer; each step mixes the colour so far towards the "100 % scattered" colour B0
//! by `b = B0 · density · step / view_depth`, times a light factor (overglow plus the cosine
//! between the segment's far end and the direction to the star). A ray that sees a star's disc
//! (not hidden by the ground) starts with the star's colour and alpha 1, so that blending
//! (`ONE, ONE_MINUS_SRC_ALPHA`, seed line 252) hides the star already drawn behind it. Finally
//! negative channels are clamped to 0 and, when the largest channel exceeds 1, the colour is
//! divided by it.
//!
//! # Frame and units
//! Everything is in the **planet frame** (the seed's "ellipsoid space", lines 255–256): origin at
//! the planet centre, x and y in the equatorial plane, z along the polar axis (the CPU side sets
//! `planet_r = (re⁻², re⁻², rp⁻²)`, line 512), metres. Colours are unitless linear RGB factors
//! (the seed's display values, not radiance).
//!
//! # Corrections to the seed (issue 4)
//! 1. **Normalised view direction.** The seed interpolates the corner directions of its quad
//!    (`pixel_nor`, lines 288 and 544–547) without normalising them per fragment, so ray
//!    parameters — and the step length `dl` (line 441) — are in units of `|pixel_nor| <= 1`,
//!    not metres. Here the direction is normalised, so every length is in metres.
//! 2. **Density falloff of version 3.0.** Version 3.1's "much much faster" density (lines
//!    448–450) is `exp(altitude / planet_h) / 2.78`, which *grows* with altitude. We use version
//!    3.0's (line 187, kept commented out in 3.1 at lines 446–447): `exp(d / planet_h) / 2.78`
//!    with `d` the distance from the sample along its geocentric up `normalize(p)` to the top of
//!    the atmosphere, i.e. `exp((top − altitude) / planet_h) / 2.78`: `e / 2.78 ≈ 0.978` at the
//!    ground falling to `1 / 2.78 ≈ 0.360` at the top.
//!
//! Everything else, quirks included, follows version 3.1; see [`EmpiricalAtmosphere::color`].

use glam::DVec3;

use crate::error::CoreError;
use crate::geometry::{Ellipsoid, Ray, RayHits, Sphere};

/// Number of integration steps along the visible segment (the seed's `const int n=8`, line 390).
pub const EMPIRICAL_STEPS: usize = 8;

/// The seed's density normaliser: density is `exp(d / planet_h) / EMPIRICAL_DENSITY_DIVISOR`
/// (lines 187 and 450), unitless.
pub const EMPIRICAL_DENSITY_DIVISOR: f64 = 2.78;

/// Factor on a star's `radius⁻²` in the disc test, enlarging the disc to `radius / √0.75` to
/// "hide star texture corona" (the seed's `light_posr[i].a*0.75`, line 422), unitless.
pub const EMPIRICAL_STAR_RADIUS_INV_SQ_FACTOR: f64 = 0.75;

/// The empirical model's parameters: the uniforms of the version 3.1 fragment shader other than the
/// stars (seed lines 292–302, filled on the CPU at lines 511–517).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmpiricalAtmosphere {
    /// Equatorial radius of the planet's surface, metres: the x and y semi-axes (the seed's `re`,
    /// uploaded as `planet_r.x = planet_r.y = re⁻²`, lines 479 and 511–512).
    pub equatorial_radius: f64,
    /// Polar radius of the planet's surface, metres: the z semi-axis (the seed's `rp`, uploaded
    /// as `planet_r.z = rp⁻²`, lines 480 and 511–512).
    pub polar_radius: f64,
    /// Height of the atmosphere above the surface, metres: the top is the surface ellipsoid with
    /// every semi-axis grown by it (the seed's `planet_h` / `ha`, and `planet_R = (re + ha)⁻², …`,
    /// lines 481 and 513–515). It is also the density's length scale.
    pub height: f64,
    /// Path length through the atmosphere at which its colour saturates, metres: the step weight
    /// is `step length / view_depth` (the seed's `view_depth`, lines 295, 441 and 482).
    pub view_depth: f64,
    /// The "100 % scattered atmosphere colour", linear RGB in `x, y, z`, unitless, each >= 0 (the
    /// seed's `B0.rgb`, lines 302 and 483–485).
    pub b0: DVec3,
    /// Overglow, unitless: added to the star's cosine so the sky brightens before the star rises
    /// (the seed's `B0.a`, lines 442 and 486).
    pub overglow: f64,
}

/// A star as the seed's shader sees it (one entry of `light_posr`, `light_dir`, `light_col`,
/// seed lines 299–301, filled at lines 519–531).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmpiricalStar {
    /// Centre of the star in the planet frame, metres (the seed's `light_posr[i].xyz`).
    pub position: DVec3,
    /// Radius of the star, metres, > 0 for its disc to be seen (the seed uploads
    /// `light_posr[i].a = radius⁻²`, line 524).
    pub radius: f64,
    /// Direction towards the star in the planet frame, normalised when used (the seed's
    /// `light_dir[i]`, line 527). [`EmpiricalStar::at`] sets it to `normalize(position)`.
    pub direction: DVec3,
    /// The star's colour times its visual intensity, linear RGB in `x, y, z`, unitless (the
    /// seed's `light_col[i]`; its CPU side uploads the star's colour × 10, line 528).
    pub color: DVec3,
}

impl EmpiricalStar {
    /// A star at `position` (planet frame, metres) of `radius` metres and `color` (linear RGB ×
    /// intensity), lit from the direction `normalize(position)` (a zero position gives a zero
    /// direction, which lights nothing).
    pub fn at(position: DVec3, radius: f64, color: DVec3) -> Self {
        Self {
            position,
            radius,
            direction: position.normalize_or_zero(),
            color,
        }
    }
}

/// The seed's `_view_depth` result (lines 310–348) for a ray and an ellipsoid: `None` when the
/// ellipsoid is missed or wholly behind (the seed returns `false`); otherwise the first hit ahead
/// `l0` (the exit when the origin is inside) and the second, `l1`, only when both are ahead.
fn view_depth(ray: &Ray, ellipsoid: &Ellipsoid) -> Option<(f64, Option<f64>)> {
    let RayHits { near, far } = ellipsoid.intersect(ray)?;
    if far < 0.0 {
        None
    } else if near < 0.0 {
        Some((far, None))
    } else {
        Some((near, Some(far)))
    }
}

impl EmpiricalAtmosphere {
    /// The seed's Earth uniforms (seed `000_643abe256ac7a513.txt`, lines 478–486): `re` =
    /// 6 378 141.2 m, `rp` = 6 356 754.795 061 39 m, `planet_h` = 60 km, `view_depth` = 250 km,
    /// `B0` = (0.1981, 0.4656, 0.8625), overglow 0.75.
    pub fn seed_earth() -> Self {
        Self {
            equatorial_radius: 6_378_141.2,
            polar_radius: 6_356_754.795_061_39,
            height: 60_000.0,
            view_depth: 250_000.0,
            b0: DVec3::new(0.1981, 0.4656, 0.8625),
            overglow: 0.75,
        }
    }

    /// The seed's Mars uniforms (seed `000_643abe256ac7a513.txt`, lines 487–495): `re` =
    /// 3 397 000 m, `rp` = 3 374 919.5 m, `ha` = 30 km, `view_depth` = 300 km,
    /// `B0` = (0.4314, 0.3216, 0.196), overglow 0.5.
    pub fn seed_mars() -> Self {
        Self {
            equatorial_radius: 3_397_000.0,
            polar_radius: 3_374_919.5,
            height: 30_000.0,
            view_depth: 300_000.0,
            b0: DVec3::new(0.4314, 0.3216, 0.196),
            overglow: 0.5,
        }
    }

    /// Checks the rules: radii, height and view depth finite and > 0 (metres); every B0 channel
    /// finite and >= 0; overglow finite. Errors name the field as `atmosphere.seed.<field>`.
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        for (field, v, rule) in [
            (
                "atmosphere.seed.equatorial_radius",
                self.equatorial_radius,
                "must be a finite radius > 0 m",
            ),
            (
                "atmosphere.seed.polar_radius",
                self.polar_radius,
                "must be a finite radius > 0 m",
            ),
            ("atmosphere.seed.height", self.height, "must be a finite height > 0 m"),
            (
                "atmosphere.seed.view_depth",
                self.view_depth,
                "must be a finite length > 0 m",
            ),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return invalid(field, v.to_string(), rule);
            }
        }
        if !(self.b0.is_finite() && self.b0.min_element() >= 0.0) {
            return invalid(
                "atmosphere.seed.b0",
                format!("{:?}", self.b0.to_array()),
                "every channel must be finite and >= 0",
            );
        }
        if !self.overglow.is_finite() {
            return invalid("atmosphere.seed.overglow", self.overglow.to_string(), "must be finite");
        }
        Ok(())
    }

    /// The planet's surface: semi-axes `(re, re, rp)`, metres, centred at the origin.
    pub fn surface(&self) -> Ellipsoid {
        Ellipsoid {
            center: DVec3::ZERO,
            radii: DVec3::new(self.equatorial_radius, self.equatorial_radius, self.polar_radius),
        }
    }

    /// The top of the atmosphere: every semi-axis of [`surface`](Self::surface) grown by
    /// `height` (seed line 513), metres.
    pub fn top(&self) -> Ellipsoid {
        let surface = self.surface();
        Ellipsoid {
            radii: surface.radii + DVec3::splat(self.height),
            ..surface
        }
    }

    /// The density factor at `point` (planet frame, metres), unitless: version 3.0's
    /// `exp(d / planet_h) / 2.78` (seed line 187, correction 2 in the module docs), `d` being the
    /// distance in metres from `point` along `normalize(point)` to the top of the atmosphere (the
    /// seed's `_view_depth(p, normalize(p), planet_R)`; `d = −1` when the top is not ahead, as
    /// the seed leaves `view_depth_l0 = −1`). The centre itself, which has no up, and a
    /// non-finite point are treated as `d = −1` too.
    pub fn density(&self, point: DVec3) -> f64 {
        let d = Ray::new(point, point)
            .and_then(|up| view_depth(&up, &self.top()))
            .map_or(-1.0, |(l0, _)| l0);
        (d / self.height).exp() / EMPIRICAL_DENSITY_DIVISOR
    }

    /// The colour the seed's pass adds for one view ray: `(rgb, alpha)`, linear RGB in
    /// `[0, 1]`, unitless, and `alpha` 0 (the background shows through, blended
    /// `ONE, ONE_MINUS_SRC_ALPHA`) or 1 (a star disc was on the ray and its colour started the
    /// integration). `ray_origin` (metres) and `ray_direction` (any length, normalised here —
    /// correction 1) are in the planet frame; `stars` are the seed's `light_*` uniforms (the seed
    /// takes at most 3; here any number).
    ///
    /// Port of `atmosphere()`, seed lines 388–472:
    /// - lines 399–406: no colour when the ray misses the atmosphere (or it is behind), or when
    ///   the origin is under the ground;
    /// - lines 408–437: the visible segment: from the origin or the atmosphere's entry to the
    ///   atmosphere's exit (sky) or to the ground;
    /// - lines 420–426: for a sky ray, each star whose disc (radius enlarged by `1/√0.75`) lies
    ///   ahead of the segment's start on the line adds its colour and sets alpha to 1;
    /// - lines 439–443: step `dl = length / 8 / view_depth` and the light factor
    ///   `ll = overglow + Σ_stars dot(normalize(p1), light_dir[0])` — the seed uses star 0's
    ///   direction once per star (kept as written), `p1` the segment's far end; `ll` is not
    ///   clamped, so the night side goes negative and ends at 0;
    /// - lines 444–456: 8 samples from `p1` towards the start (`p1 − k·Δ`, `k = 0..7`; the start
    ///   itself is not sampled): `b = B0 · density · dl`, `c = c·(1 − b) + b·ll`, with the
    ///   version 3.0 density ([`density`](Self::density), correction 2);
    /// - lines 457–470: negative channels to 0; when the largest channel exceeds 1, divide by it.
    ///
    /// Never panics: a non-finite origin, a zero or non-finite direction, or parameters that fail
    /// [`validate`](Self::validate) give the "nothing" result `(0, 0, 0), 0`. Stars whose radius is
    /// not finite and > 0, or whose position or colour is not finite, show no disc; a zero or
    /// non-finite star direction lights nothing (it counts as 0 in `ll`).
    pub fn color(&self, ray_origin: DVec3, ray_direction: DVec3, stars: &[EmpiricalStar]) -> (DVec3, f64) {
        let nothing = (DVec3::ZERO, 0.0);
        if self.validate().is_err() {
            return nothing;
        }
        let Some(ray) = Ray::new(ray_origin, ray_direction) else {
            return nothing;
        };
        let Some(segment) = self.segment(&ray) else {
            return nothing;
        };
        let mut color = DVec3::ZERO;
        let mut alpha = 0.0;
        if !segment.ends_on_ground {
            for star in stars {
                if star_on_ray(segment.start, ray.direction, star) {
                    color += star.color;
                    alpha = 1.0;
                }
            }
        }
        let (start, length) = (segment.start, segment.length);
        // Lines 439–443.
        let end = start + ray.direction * length;
        let step = (end - start) / EMPIRICAL_STEPS as f64;
        let dl = length / EMPIRICAL_STEPS as f64 / self.view_depth;
        let up_at_end = end.normalize_or_zero();
        let first_light = stars.first().map_or(DVec3::ZERO, |s| s.direction.normalize_or_zero());
        let ll = self.overglow + stars.len() as f64 * up_at_end.dot(first_light);
        // Lines 444–456.
        for k in 0..EMPIRICAL_STEPS {
            let p = end - step * k as f64;
            let b = self.b0 * self.density(p) * dl;
            color = color * (DVec3::ONE - b) + b * ll;
        }
        // Lines 457–470 (`max(0)` also turns a NaN channel into 0; the upper clamp, not in the
        // seed, keeps an infinite channel from turning the division into NaN).
        color = DVec3::new(color.x.max(0.0), color.y.max(0.0), color.z.max(0.0)).min(DVec3::splat(f64::MAX));
        let largest = color.max_element();
        if largest > 1.0 {
            color /= largest;
        }
        (color, alpha)
    }
}

impl EmpiricalAtmosphere {
    /// The part of `ray` that the seed integrates (lines 400–437): from where it enters the
    /// atmosphere (or its origin, inside) to where it leaves it or meets the ground. `None` when
    /// it misses the atmosphere or starts under the ground.
    fn segment(&self, ray: &Ray) -> Option<Segment> {
        // Lines 400–406.
        let (atm_first, atm_second) = view_depth(ray, &self.top())?;
        let ground = view_depth(ray, &self.surface());
        if let Some((_, None)) = ground {
            return None; // under ground
        }
        // Lines 408–437: `start` is the seed's p0 and `length` its l0.
        let (start, length) = match ground {
            None => match atm_second {
                None => (ray.origin, atm_first), // inside the atmosphere to its boundary
                Some(exit) => (ray.at(atm_first), exit - atm_first), // boundary to boundary
            },
            Some((ground_first, _)) if atm_first < ground_first => {
                (ray.at(atm_first), ground_first - atm_first) // from the boundary to the ground
            }
            Some((ground_first, _)) => (ray.origin, ground_first), // inside, to the ground
        };
        Some(Segment {
            start,
            length,
            ends_on_ground: ground.is_some(),
        })
    }

    /// How much of a star's colour survives the seed's 8 steps along a view ray towards it: the
    /// star's disc starts the ray with its colour `c`, and each step takes `c·(1 − b)` of it
    /// (line 456), so the share left is `Π (1 − b_k)` per channel, in [0, 1] — the seed's own
    /// extinction, red near its horizon. 1 when the ray misses the atmosphere; 0 when the ground
    /// hides the star, or for a bad ray or bad parameters. Used to tint a seed star's flare.
    pub fn star_transmittance(&self, ray_origin: DVec3, ray_direction: DVec3) -> DVec3 {
        if self.validate().is_err() {
            return DVec3::ZERO;
        }
        let Some(ray) = Ray::new(ray_origin, ray_direction) else {
            return DVec3::ZERO;
        };
        let Some(segment) = self.segment(&ray) else {
            // Missing the atmosphere: clear, unless the origin is under the ground.
            let under_ground = view_depth(&ray, &self.surface()).is_some_and(|(_, exit)| exit.is_none());
            return if under_ground { DVec3::ZERO } else { DVec3::ONE };
        };
        if segment.ends_on_ground {
            return DVec3::ZERO;
        }
        let end = segment.start + ray.direction * segment.length;
        let step = (end - segment.start) / EMPIRICAL_STEPS as f64;
        let dl = segment.length / EMPIRICAL_STEPS as f64 / self.view_depth;
        (0..EMPIRICAL_STEPS).fold(DVec3::ONE, |share, k| {
            let b = self.b0 * self.density(end - step * k as f64) * dl;
            share * (DVec3::ONE - b).clamp(DVec3::ZERO, DVec3::ONE)
        })
    }
}

/// The stretch of a view ray the seed integrates.
struct Segment {
    /// Where integration starts (the seed's p0), planet frame, metres.
    start: DVec3,
    /// Its length (the seed's l0), metres.
    length: f64,
    /// Whether it ends on the ground (no star can be seen along it).
    ends_on_ground: bool,
}

/// The seed's `_star_colide` (lines 351–386) with the 0.75 enlargement of line 422: true when the
/// line from `start` along `direction` meets the star's enlarged sphere at or ahead of `start`.
fn star_on_ray(start: DVec3, direction: DVec3, star: &EmpiricalStar) -> bool {
    if !(star.radius.is_finite() && star.radius > 0.0 && star.position.is_finite() && star.color.is_finite()) {
        return false;
    }
    let sphere = Sphere {
        center: star.position,
        radius: star.radius / EMPIRICAL_STAR_RADIUS_INV_SQ_FACTOR.sqrt(),
    };
    Ray::new(start, direction)
        .and_then(|ray| sphere.intersect(&ray))
        .is_some_and(|hits| hits.far >= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SUN_DISTANCE: f64 = 1.496e11;
    const SUN_RADIUS: f64 = 6.957e8;

    fn sun_along(direction: DVec3, color: DVec3) -> EmpiricalStar {
        EmpiricalStar::at(direction.normalize() * SUN_DISTANCE, SUN_RADIUS, color)
    }

    fn sphere() -> EmpiricalAtmosphere {
        EmpiricalAtmosphere {
            polar_radius: 6_378_141.2,
            ..EmpiricalAtmosphere::seed_earth()
        }
    }

    #[test]
    fn presets_are_valid_and_hold_the_seed_values() {
        let e = EmpiricalAtmosphere::seed_earth();
        assert_eq!(e.validate(), Ok(()));
        assert_eq!(e.polar_radius, 6_356_754.795_061_39);
        assert_eq!(e.b0, DVec3::new(0.1981, 0.4656, 0.8625));
        let m = EmpiricalAtmosphere::seed_mars();
        assert_eq!(m.validate(), Ok(()));
        assert_eq!(
            (m.equatorial_radius, m.height, m.overglow),
            (3_397_000.0, 30_000.0, 0.5)
        );
    }

    #[test]
    fn a_ray_missing_the_atmosphere_gives_nothing() {
        let a = EmpiricalAtmosphere::seed_earth();
        let sun = sun_along(DVec3::X, DVec3::ONE);
        // 10 000 km up the x axis, looking further out and sideways.
        let o = DVec3::new(1.0e7, 0.0, 0.0);
        assert_eq!(a.color(o, DVec3::X, &[sun]), (DVec3::ZERO, 0.0));
        assert_eq!(a.color(o, DVec3::Y, &[sun]), (DVec3::ZERO, 0.0));
        // Even when the ray points at a star: the seed draws nothing outside the atmosphere.
        let star_dir = DVec3::new(1.0, 1.0, 0.0);
        let star = sun_along(star_dir, DVec3::ONE);
        assert_eq!(a.color(o, star_dir, &[star]), (DVec3::ZERO, 0.0));
    }

    #[test]
    fn under_ground_and_bad_rays_give_nothing() {
        let a = EmpiricalAtmosphere::seed_earth();
        let sun = sun_along(DVec3::X, DVec3::ONE);
        assert_eq!(
            a.color(DVec3::new(6.0e6, 0.0, 0.0), DVec3::X, &[sun]),
            (DVec3::ZERO, 0.0)
        );
        let o = DVec3::new(6.4e6, 0.0, 0.0);
        assert_eq!(a.color(o, DVec3::ZERO, &[sun]), (DVec3::ZERO, 0.0));
        assert_eq!(a.color(o, DVec3::NAN, &[sun]), (DVec3::ZERO, 0.0));
        assert_eq!(a.color(DVec3::INFINITY, DVec3::X, &[sun]), (DVec3::ZERO, 0.0));
        // Non-finite stars neither panic nor leak NaN.
        let o = DVec3::new(a.equatorial_radius + 10.0, 0.0, 0.0);
        for star in [
            EmpiricalStar {
                color: DVec3::INFINITY,
                ..sun
            },
            EmpiricalStar {
                color: DVec3::NAN,
                ..sun
            },
            EmpiricalStar {
                direction: DVec3::NAN,
                ..sun
            },
            EmpiricalStar {
                position: DVec3::NAN,
                radius: f64::NAN,
                ..sun
            },
        ] {
            let (c, alpha) = a.color(o, DVec3::X, &[star]);
            assert!(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0, "{c}");
            assert!(alpha == 0.0 || alpha == 1.0);
        }
        let o = DVec3::new(6.4e6, 0.0, 0.0);
        let bad = EmpiricalAtmosphere { height: 0.0, ..a };
        assert_eq!(bad.color(o, DVec3::Y, &[sun]), (DVec3::ZERO, 0.0));
    }

    #[test]
    fn the_density_is_version_3_0s() {
        let a = sphere();
        let top = a.equatorial_radius + a.height;
        for dir in [DVec3::X, DVec3::new(0.3, -0.5, 0.8).normalize()] {
            let at_ground = a.density(dir * a.equatorial_radius);
            let at_top = a.density(dir * top);
            let half = a.density(dir * (top - 0.5 * a.height));
            assert!((at_ground - 1.0_f64.exp() / 2.78).abs() < 1e-12, "{at_ground}");
            assert!((at_top - 1.0 / 2.78).abs() < 1e-6, "{at_top}");
            assert!((half - 0.5_f64.exp() / 2.78).abs() < 1e-12, "{half}");
            assert!(at_ground > half && half > at_top);
        }
        // Above the top the seed's l0 stays −1.
        assert_eq!(a.density(DVec3::X * 2.0 * top), (-1.0 / a.height).exp() / 2.78);
    }

    /// Zenith ray from the ground of a sphere, sun overhead, hand-computed: the segment runs 60 km
    /// from the ground to the top; `dl = 60 000 / 8 / 250 000 = 0.03`, `ll = 0.75 + 1`; samples at
    /// altitudes 60, 52.5, …, 7.5 km, density `exp((60 − h)/60)/2.78`.
    #[test]
    fn zenith_from_the_ground_by_hand() {
        let a = sphere();
        let sun = sun_along(DVec3::X, DVec3::ONE);
        let o = DVec3::X * (a.equatorial_radius + 1.0);
        let length = a.height - 1.0;
        let dl = length / 8.0 / 250_000.0;
        let by_hand = |start: DVec3| {
            let mut c = start;
            for k in 0..8 {
                let alt = a.height - k as f64 * length / 8.0;
                let b = a.b0 * ((a.height - alt) / a.height).exp() / 2.78 * dl;
                c = c * (DVec3::ONE - b) + b * 1.75;
            }
            // Lines 457–470: divide by the largest channel when it exceeds 1.
            if c.max_element() > 1.0 { c / c.max_element() } else { c }
        };
        // The sun is overhead, so its disc is on this ray, which starts inside the atmosphere:
        // the star's colour (1, 1, 1) starts the integration and alpha is 1; the result
        // (1.020, 1.047, 1.086 by hand) exceeds 1 and is divided by its blue channel.
        let (c, alpha) = a.color(o, DVec3::X * 3.0, &[sun]);
        let expected = by_hand(DVec3::ONE);
        assert!((c - expected).abs().max_element() < 1e-9, "{c} vs {expected}");
        assert_eq!((c.z, alpha), (1.0, 1.0));
        // Without a disc (radius 0) the integration starts at black.
        let (c_no_disc, alpha_no_disc) = a.color(o, DVec3::X, &[EmpiricalStar { radius: 0.0, ..sun }]);
        let expected = by_hand(DVec3::ZERO);
        assert_eq!(alpha_no_disc, 0.0);
        assert!(
            (c_no_disc - expected).abs().max_element() < 1e-9,
            "{c_no_disc} vs {expected}"
        );
        // The same numbers from an independent hand computation (Python, the loop above).
        let pinned = DVec3::new(0.047_705_554_454_358, 0.110_336_538_123_622, 0.199_590_594_145_508);
        assert!((c_no_disc - pinned).abs().max_element() < 1e-12, "{c_no_disc}");
        let pinned = DVec3::new(0.940_035_688_382_347, 0.964_762_441_124_426, 1.0);
        assert!((c - pinned).abs().max_element() < 1e-12, "{c}");
        // Blue sky for Earth's B0.
        assert!(c_no_disc.z > c_no_disc.y && c_no_disc.y > c_no_disc.x && c_no_disc.x > 0.0);
    }

    #[test]
    fn the_limb_from_space_is_bluish_and_normalised() {
        let a = EmpiricalAtmosphere::seed_earth();
        let sun = sun_along(DVec3::X, DVec3::ONE);
        // From 20 000 km out along −y, a ray grazing 30 km above the equator over the sub-solar
        // point (the sun along +x).
        let o = DVec3::new(a.equatorial_radius + 30_000.0, -2.0e7, 0.0);
        let (c, alpha) = a.color(o, DVec3::Y, &[sun]);
        assert_eq!(alpha, 0.0);
        assert!(c.x > 0.0 && c.z > c.y && c.y > c.x, "{c}");
        eprintln!("limb: {c}");
        assert!(c.max_element() <= 1.0);
        // A long limb path makes the pre-normalisation colour exceed 1: the largest channel is
        // then exactly 1.
        assert!((c.z - 1.0).abs() < 1e-15, "{c}");
        // The same line seen from 25 AU (the seed's stated range): the same colour.
        let far = DVec3::new(o.x, -25.0 * 1.496e11, 0.0);
        let (c_far, _) = a.color(far, DVec3::Y, &[sun]);
        assert!((c_far - c).abs().max_element() < 1e-6, "{c_far} vs {c}");
        // The ground under the same viewer, seen straight down, is darker than 1 and bluish.
        let (g, _) = a.color(DVec3::new(0.0, -2.0e7, 0.0), DVec3::Y, &[sun]);
        eprintln!("ground: {g}");
        assert!(g.z < 1.0 && g.z > g.y && g.y > g.x && g.x > 0.0, "{g}");
    }

    #[test]
    fn a_star_disc_starts_the_ray_and_is_normalised() {
        let a = EmpiricalAtmosphere::seed_earth();
        let dir = DVec3::new(0.2, 1.0, 0.1).normalize();
        let sun = sun_along(dir, DVec3::new(10.0, 9.0, 8.0));
        let o = DVec3::Z * (a.polar_radius + 100.0);
        let (c, alpha) = a.color(o, dir, &[sun]);
        assert_eq!(alpha, 1.0);
        assert_eq!(c.max_element(), 1.0);
        assert!(c.x >= c.y && c.y > 0.0, "{c}");
        // Enlarged by 1/√0.75: a ray just outside the true disc but inside the enlarged one hits.
        let side = dir.any_orthonormal_vector();
        let off = (dir * SUN_DISTANCE + side * SUN_RADIUS * 1.1 - o).normalize();
        assert_eq!(a.color(o, off, &[sun]).1, 1.0);
        let off = (dir * SUN_DISTANCE + side * SUN_RADIUS * 1.2 - o).normalize();
        assert_eq!(a.color(o, off, &[sun]).1, 0.0);
        // Hidden by the ground: no disc.
        let below = sun_along(-DVec3::Z, DVec3::ONE);
        assert_eq!(a.color(o, -DVec3::Z, &[below]).1, 0.0);
    }

    #[test]
    fn star_transmittance_is_the_seeds_own_extinction() {
        let a = EmpiricalAtmosphere::seed_earth();
        let o = DVec3::Z * (a.polar_radius + 2.0);
        let overhead = a.star_transmittance(o, DVec3::Z);
        let low = a.star_transmittance(o, DVec3::new(1.0, 0.0, 0.02).normalize());
        // By hand overhead: 8 steps of 60 km / 8 / 250 km, density between 0.36 and 0.98.
        assert!(
            overhead.min_element() > 0.5 && overhead.max_element() < 1.0,
            "{overhead}"
        );
        // The seed's B0 is blue, so what gets through is reddened, more so near the horizon.
        assert!(low.x > low.z && low.x < overhead.x, "{low}");
        assert_eq!(a.star_transmittance(o, -DVec3::Z), DVec3::ZERO);
        // From far away, a ray past the planet keeps everything.
        let far = DVec3::X * 1e9;
        assert_eq!(a.star_transmittance(far, DVec3::Z), DVec3::ONE);
        assert_eq!(a.star_transmittance(o, DVec3::ZERO), DVec3::ZERO);
    }

    #[test]
    fn night_side_is_dark_and_overglow_lights_the_terminator() {
        let a = EmpiricalAtmosphere::seed_earth();
        let sun = sun_along(-DVec3::X, DVec3::ONE);
        let o = DVec3::X * (a.equatorial_radius + 1.0);
        // Zenith at midnight: ll = 0.75 − 1 < 0, clamped to black.
        assert_eq!(a.color(o, DVec3::X, &[sun]).0, DVec3::ZERO);
        // At the terminator only the overglow lights the sky.
        let o = DVec3::Y * (a.equatorial_radius + 1.0);
        let (c, _) = a.color(o, DVec3::Y, &[sun]);
        assert!(c.z > 0.0);
        // With no star at all, ll is the overglow.
        let (c_none, _) = a.color(o, DVec3::Y, &[]);
        assert!((c - c_none).abs().max_element() < 1e-12);
    }

    #[test]
    fn a_sphere_is_symmetric_about_the_sun_axis() {
        let a = sphere();
        let axis = DVec3::new(0.3, 0.4, 0.866).normalize();
        let sun = sun_along(axis, DVec3::ONE);
        let o = DVec3::new(a.equatorial_radius + 2_000.0, 1_000.0, -3_000.0);
        let d = DVec3::new(-0.2, 0.9, 0.3);
        let (c0, a0) = a.color(o, d, &[sun]);
        assert!(c0.max_element() > 0.0);
        for k in 1..6 {
            let q = glam::DQuat::from_axis_angle(axis, k as f64 * 1.1);
            let (c, alpha) = a.color(q * o, q * d, &[sun]);
            assert!((c - c0).abs().max_element() < 1e-9, "{c} vs {c0}");
            assert_eq!(alpha, a0);
        }
        // From space, through the limb.
        let o = DVec3::new(2.0e7, 0.0, 0.0);
        let d = DVec3::new(-2.0e7, a.equatorial_radius + 20_000.0, 0.0);
        let (c0, _) = a.color(o, d, &[sun]);
        assert!(c0.max_element() > 0.0);
        for k in 1..6 {
            let q = glam::DQuat::from_axis_angle(axis, k as f64 * 0.9);
            let (c, _) = a.color(q * o, q * d, &[sun]);
            assert!((c - c0).abs().max_element() < 1e-9, "{c} vs {c0}");
        }
    }

    #[test]
    fn the_direction_length_does_not_matter() {
        let a = EmpiricalAtmosphere::seed_mars();
        let sun = sun_along(DVec3::new(1.0, 0.5, 0.2), DVec3::ONE);
        let o = DVec3::new(a.equatorial_radius + 500.0, 0.0, 0.0);
        let d = DVec3::new(0.3, 1.0, 0.1);
        let (c1, _) = a.color(o, d, &[sun]);
        let (c2, _) = a.color(o, d * 1e-3, &[sun]);
        assert!((c1 - c2).abs().max_element() < 1e-12);
        // Mars' B0 makes a reddish sky.
        assert!(c1.x > c1.y && c1.y > c1.z && c1.z > 0.0, "{c1}");
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let field = |a: EmpiricalAtmosphere| match a.validate() {
            Err(CoreError::Invalid { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let e = EmpiricalAtmosphere::seed_earth();
        assert_eq!(
            field(EmpiricalAtmosphere {
                equatorial_radius: -1.0,
                ..e
            }),
            "atmosphere.seed.equatorial_radius"
        );
        assert_eq!(
            field(EmpiricalAtmosphere {
                polar_radius: -6.0e6,
                ..e
            }),
            "atmosphere.seed.polar_radius"
        );
        assert_eq!(
            field(EmpiricalAtmosphere { height: 0.0, ..e }),
            "atmosphere.seed.height"
        );
        assert_eq!(
            field(EmpiricalAtmosphere {
                view_depth: f64::INFINITY,
                ..e
            }),
            "atmosphere.seed.view_depth"
        );
        assert_eq!(
            field(EmpiricalAtmosphere {
                b0: DVec3::new(0.1, f64::NAN, 0.3),
                ..e
            }),
            "atmosphere.seed.b0"
        );
        assert_eq!(
            field(EmpiricalAtmosphere {
                b0: DVec3::new(-0.1, 0.2, 0.3),
                ..e
            }),
            "atmosphere.seed.b0"
        );
        assert_eq!(
            field(EmpiricalAtmosphere {
                overglow: f64::NAN,
                ..e
            }),
            "atmosphere.seed.overglow"
        );
    }
}
