//! Opaque occluders — spheres and turned boxes — whose shadows the `f64` reference integrator
//! casts exactly, to check the GPU's light shafts and shadows against
//! ([`Reference::with_occluders`](crate::atmosphere::reference::Reference::with_occluders)).
//!
//! Shapes are given in the world frame, metres; [`Occluder::to_planet_frame`] moves them into the
//! planet frame where the reference integrates (f64 keeps them to about a nanometre there, 6.4e6 m
//! from the planet's centre). Both shapes are convex, so every ray meets one in a single interval
//! and the shadow a light at infinity casts on a line is a single interval too
//! ([`Occluder::shadow_along`]).

use glam::{DQuat, DVec3};

use crate::atmosphere::Planet;
use crate::error::CoreError;
use crate::geometry::{Ray, Sphere};

/// How far past its origin, metres, a segment starts for [`Occluder::blocks`]: a point on a
/// shape's surface facing the light is not shadowed by the shape itself, rounding included.
pub const BLOCK_EPSILON: f64 = 1e-6;

/// An opaque, convex shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Occluder {
    /// A ball.
    Sphere {
        /// Centre, metres.
        center: DVec3,
        /// Radius, metres, > 0.
        radius: f64,
    },
    /// A box (cuboid) whose edges run along `orientation * X`, `* Y` and `* Z`.
    Box {
        /// Centre, metres.
        center: DVec3,
        /// Half the edge lengths along the box's own x, y and z axes, metres, each > 0.
        half_extents: DVec3,
        /// Rotation from the box's axes to the frame it is given in (normalised where used).
        orientation: DQuat,
    },
}

impl Occluder {
    /// Checks the rules: centre finite, radius or half extents finite and > 0 m, orientation a
    /// finite non-zero quaternion.
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        let center = match self {
            Self::Sphere { center, .. } | Self::Box { center, .. } => *center,
        };
        if !center.is_finite() {
            return invalid("occluder.center", format!("{:?}", center.to_array()), "must be finite");
        }
        match *self {
            Self::Sphere { radius, .. } => {
                if !(radius.is_finite() && radius > 0.0) {
                    return invalid("occluder.radius", radius.to_string(), "must be a finite radius > 0 m");
                }
            }
            Self::Box {
                half_extents,
                orientation,
                ..
            } => {
                if !(half_extents.is_finite() && half_extents.min_element() > 0.0) {
                    return invalid(
                        "occluder.half_extents",
                        format!("{:?}", half_extents.to_array()),
                        "must be finite lengths > 0 m",
                    );
                }
                if !(orientation.is_finite() && orientation.length_squared() > 0.0) {
                    return invalid(
                        "occluder.orientation",
                        format!("{:?}", orientation.to_array()),
                        "must be a finite rotation",
                    );
                }
            }
        }
        Ok(())
    }

    /// Moves this shape from the world frame into `planet`'s planet frame, where the reference
    /// integrates: the same rigid motion as [`Planet::to_planet_frame`].
    pub fn to_planet_frame(&self, planet: &Planet) -> Self {
        match *self {
            Self::Sphere { center, radius } => Self::Sphere {
                center: planet.to_planet_frame(center),
                radius,
            },
            Self::Box {
                center,
                half_extents,
                orientation,
            } => Self::Box {
                center: planet.to_planet_frame(center),
                half_extents,
                orientation: (planet.orientation.normalize().inverse() * orientation.normalize()).normalize(),
            },
        }
    }

    /// Finds the ray parameters `(near, far)`, metres, `near <= far`, between which the line
    /// through `ray` is inside the shape, or `None` when it misses. Parameters of either sign
    /// are returned (`near < 0 <= far`: the origin is inside); callers clip to what they need.
    pub fn hit(&self, ray: &Ray) -> Option<(f64, f64)> {
        match *self {
            Self::Sphere { center, radius } => Sphere { center, radius }
                .intersect(ray)
                .map(|hits| (hits.near, hits.far)),
            Self::Box {
                center,
                half_extents,
                orientation,
            } => {
                let to_box = orientation.normalize().inverse();
                slabs(to_box * (ray.origin - center), to_box * ray.direction, half_extents)
            }
        }
    }

    /// Tells whether the segment from `origin` along `direction` (normalised here), over ray
    /// parameters in (`BLOCK_EPSILON`, `max_t`) metres, meets the shape. An origin inside the
    /// shape is blocked; one on its surface looking away is not. `max_t` may be infinite (a
    /// light at infinity). A zero or non-finite direction blocks nothing.
    pub fn blocks(&self, origin: DVec3, direction: DVec3, max_t: f64) -> bool {
        let Some(ray) = Ray::new(origin, direction) else {
            return false;
        };
        self.hit(&ray)
            .is_some_and(|(near, far)| far > BLOCK_EPSILON && near < max_t)
    }

    /// Finds the part `(start, end)` of ray parameters within `[t0, t1]` (finite, metres) where
    /// the points of `ray` lie in this shape's shadow for a light at infinity in direction
    /// `towards_light` (normalised here): the points whose straight path towards the light meets
    /// the shape, the shape's inside included — what [`blocks`](Self::blocks) tells point by point,
    /// up to its `BLOCK_EPSILON`. The shadow of a convex shape is convex, so this is one
    /// interval; `None` when no point of `[t0, t1]` is shadowed. The reference splits its
    /// quadrature at these edges, where the in-scattered light jumps.
    pub fn shadow_along(&self, ray: &Ray, towards_light: DVec3, t0: f64, t1: f64) -> Option<(f64, f64)> {
        let s = towards_light.try_normalize()?;
        let (start, end) = match *self {
            Self::Sphere { center, radius } => sphere_shadow(ray, s, center, radius)?,
            Self::Box {
                center,
                half_extents,
                orientation,
            } => {
                let to_box = orientation.normalize().inverse();
                box_shadow(
                    to_box * (ray.origin - center),
                    to_box * ray.direction,
                    to_box * s,
                    half_extents,
                    (t0, t1),
                )?
            }
        };
        let (start, end) = (start.max(t0), end.min(t1));
        (start <= end).then_some((start, end))
    }
}

/// The slab test: where the line `origin + t·direction` is inside the centred axis-aligned box
/// with half extents `half`.
fn slabs(origin: DVec3, direction: DVec3, half: DVec3) -> Option<(f64, f64)> {
    let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
    for axis in 0..3 {
        let (o, d, h) = (origin[axis], direction[axis], half[axis]);
        if d == 0.0 {
            // Parallel to this slab: inside it everywhere or nowhere.
            if o.abs() > h {
                return None;
            }
            continue;
        }
        let (a, b) = ((-h - o) / d, (h - o) / d);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    (near <= far).then_some((near, far))
}

/// The shadow of a ball on a line: the points `w` (relative to the centre) from which a step
/// `u ≥ 0` along `s` reaches the ball. That needs the line towards the light to meet the ball
/// (the cylinder `|w⊥| ≤ r` about the axis along `s`) and either `w·s ≤ 0` (the ball lies ahead)
/// or `w` inside the ball; the ball lies within the cylinder, so the shadow is
/// (cylinder ∩ half-space) ∪ ball, a single interval.
fn sphere_shadow(ray: &Ray, s: DVec3, center: DVec3, radius: f64) -> Option<(f64, f64)> {
    let f = ray.origin - center;
    let v = ray.direction;
    let across = |x: DVec3| x - s * x.dot(s);
    let (f_across, v_across) = (across(f), across(v));
    // The cylinder: a circle in the plane across `s`, met by the line's projection there
    // (parameter τ = t·|v⊥|), with the same stable quadratic as any sphere.
    let cylinder = match v_across.try_normalize() {
        Some(d) => {
            let speed = v_across.length();
            Sphere {
                center: DVec3::ZERO,
                radius,
            }
            .intersect(&Ray {
                origin: f_across,
                direction: d,
            })
            .map(|hits| (hits.near / speed, hits.far / speed))
        }
        // The line runs along `s`: inside the cylinder everywhere or nowhere.
        None => (f_across.length() <= radius).then_some((f64::NEG_INFINITY, f64::INFINITY)),
    };
    // The half-space w·s ≤ 0: f·s + t·(v·s) ≤ 0.
    let (fs, vs) = (f.dot(s), v.dot(s));
    let half_space = if vs > 0.0 {
        Some((f64::NEG_INFINITY, -fs / vs))
    } else if vs < 0.0 {
        Some((-fs / vs, f64::INFINITY))
    } else {
        (fs <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY))
    };
    let behind = cylinder
        .zip(half_space)
        .map(|(a, b)| (a.0.max(b.0), a.1.min(b.1)))
        .filter(|(near, far)| near <= far);
    let ball = Sphere { center, radius }
        .intersect(ray)
        .map(|hits| (hits.near, hits.far));
    match (behind, ball) {
        (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
        (a, b) => a.or(b),
    }
}

/// The shadow of a centred axis-aligned box (half extents `half`) on the line `o + t·v` for a
/// light along `s`, within `range`: the `t` for which some `u ≥ 0` puts `o + t·v + u·s` in the
/// box. Along each axis with `s_i ≠ 0` the box bounds `u` between two lines in `t` of the same
/// slope, `L_i(t) ≤ u ≤ U_i(t)` (and `u ≥ 0` adds `L = 0`); a `u` exists exactly when every
/// lower bound is below every upper bound, `L_i(t) ≤ U_j(t)` for all `i, j` — each a half-line
/// in `t`, so the answer is their intersection, with no search. Axes with `s_i = 0` bound `t`
/// directly, like a slab.
fn box_shadow(o: DVec3, v: DVec3, s: DVec3, half: DVec3, range: (f64, f64)) -> Option<(f64, f64)> {
    let (mut start, mut end) = range;
    // Keeps the t with p + q·t ≤ 0.
    let mut keep = |p: f64, q: f64| {
        if q > 0.0 {
            end = end.min(-p / q);
        } else if q < 0.0 {
            start = start.max(-p / q);
        } else if p > 0.0 {
            end = f64::NEG_INFINITY;
        }
    };
    // Lower and upper bounds on u as (intercept, slope) in t; u ≥ 0 first.
    let mut lower = vec![(0.0, 0.0)];
    let mut upper = Vec::with_capacity(3);
    for axis in 0..3 {
        let (oi, vi, si, hi) = (o[axis], v[axis], s[axis], half[axis]);
        // A light this close to parallel moves the point along the axis by under 1e-15 of `u`
        // (nanometres for any shadow inside an atmosphere): treat it as parallel.
        if si.abs() < 1e-15 {
            keep(-hi - oi, -vi);
            keep(oi - hi, vi);
            continue;
        }
        let (a, b) = ((-hi - oi) / si, (hi - oi) / si);
        let slope = -vi / si;
        lower.push((a.min(b), slope));
        upper.push((a.max(b), slope));
    }
    for &(lower_at, lower_slope) in &lower {
        for &(upper_at, upper_slope) in &upper {
            keep(lower_at - upper_at, lower_slope - upper_slope);
        }
    }
    (start <= end).then_some((start, end))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, SQRT_2};

    use proptest::prelude::*;

    use super::*;

    fn ray(origin: [f64; 3], direction: [f64; 3]) -> Ray {
        Ray::new(DVec3::from_array(origin), DVec3::from_array(direction)).unwrap()
    }

    fn close(got: Option<(f64, f64)>, want: (f64, f64)) {
        let got = got.unwrap_or_else(|| panic!("missed, want {want:?}"));
        assert!(
            (got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12,
            "{got:?} vs {want:?}"
        );
    }

    #[test]
    fn a_sphere_is_hit_where_the_hand_says() {
        let ball = Occluder::Sphere {
            center: DVec3::new(1.0, 2.0, 3.0),
            radius: 2.0,
        };
        close(ball.hit(&ray([1.0, 2.0, -5.0], [0.0, 0.0, 1.0])), (6.0, 10.0));
        // Off-centre by 1.2: half chord √(4 − 1.44) = 1.6.
        close(ball.hit(&ray([-4.0, 3.2, 3.0], [1.0, 0.0, 0.0])), (3.4, 6.6));
        // From inside: one root behind.
        close(ball.hit(&ray([1.0, 2.0, 3.0], [1.0, 0.0, 0.0])), (-2.0, 2.0));
        assert_eq!(ball.hit(&ray([10.0, 0.0, 0.0], [0.0, 1.0, 0.0])), None);
    }

    #[test]
    fn a_box_is_hit_where_the_hand_says() {
        let upright = Occluder::Box {
            center: DVec3::ZERO,
            half_extents: DVec3::new(1.0, 2.0, 3.0),
            orientation: DQuat::IDENTITY,
        };
        close(upright.hit(&ray([-5.0, 0.5, 0.5], [1.0, 0.0, 0.0])), (4.0, 6.0));
        close(upright.hit(&ray([0.0, -10.0, 0.0], [0.0, 1.0, 0.0])), (8.0, 12.0));
        close(upright.hit(&ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])), (-3.0, 3.0));
        // Through the corner region diagonally: x enters at 4, y at 3 → inside from 4 to 6.
        close(
            upright.hit(&ray([-5.0, -5.0, 0.0], [1.0, 1.0, 0.0])),
            (4.0 * SQRT_2, 6.0 * SQRT_2),
        );
        // Parallel to a face, outside it.
        assert_eq!(upright.hit(&ray([-5.0, 2.5, 0.0], [1.0, 0.0, 0.0])), None);
        assert_eq!(upright.hit(&ray([-5.0, -5.0, 0.0], [1.0, 0.1, 0.0])), None);
    }

    #[test]
    fn a_turned_box_is_hit_where_the_hand_says() {
        // A unit cube turned 45° about z: a diamond |x'| + |y'| ≤ √2 in plan.
        let diamond = Occluder::Box {
            center: DVec3::new(10.0, 0.0, 0.0),
            half_extents: DVec3::ONE,
            orientation: DQuat::from_rotation_z(FRAC_PI_4),
        };
        close(
            diamond.hit(&ray([0.0, 0.0, 0.5], [1.0, 0.0, 0.0])),
            (10.0 - SQRT_2, 10.0 + SQRT_2),
        );
        close(
            diamond.hit(&ray([0.0, 0.5, 0.0], [1.0, 0.0, 0.0])),
            (10.0 - SQRT_2 + 0.5, 10.0 + SQRT_2 - 0.5),
        );
        assert_eq!(diamond.hit(&ray([0.0, 1.5, 0.0], [1.0, 0.0, 0.0])), None);
        // Turned 90° about y: the box's z (half extent 3) now runs along world x.
        let lying = Occluder::Box {
            center: DVec3::ZERO,
            half_extents: DVec3::new(1.0, 2.0, 3.0),
            orientation: DQuat::from_rotation_y(FRAC_PI_2),
        };
        close(lying.hit(&ray([-10.0, 0.0, 0.0], [1.0, 0.0, 0.0])), (7.0, 13.0));
        close(lying.hit(&ray([0.0, 0.0, -10.0], [0.0, 0.0, 1.0])), (9.0, 11.0));
    }

    #[test]
    fn segments_are_blocked_only_by_what_lies_on_them() {
        for shape in [
            Occluder::Sphere {
                center: DVec3::ZERO,
                radius: 1.0,
            },
            Occluder::Box {
                center: DVec3::ZERO,
                half_extents: DVec3::ONE,
                orientation: DQuat::from_rotation_x(0.3),
            },
        ] {
            let from = DVec3::new(-5.0, 0.0, 0.0);
            assert!(shape.blocks(from, DVec3::X, f64::INFINITY));
            assert!(shape.blocks(from, DVec3::X * 7.0, 4.5), "the direction is normalised");
            assert!(!shape.blocks(from, DVec3::X, 3.5), "the segment ends in front");
            assert!(!shape.blocks(from, -DVec3::X, f64::INFINITY), "the shape is behind");
            assert!(
                shape.blocks(DVec3::new(0.1, 0.2, 0.0), DVec3::Y, f64::INFINITY),
                "inside"
            );
            assert!(
                !shape.blocks(DVec3::new(1.0, 0.0, 0.0), DVec3::X, f64::INFINITY),
                "on the surface"
            );
            assert!(!shape.blocks(from, DVec3::ZERO, f64::INFINITY));
        }
    }

    #[test]
    fn shadows_fall_where_the_hand_says() {
        let ball = Occluder::Sphere {
            center: DVec3::new(0.0, 0.0, 3.0),
            radius: 1.0,
        };
        let along_x = ray([-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        close(ball.shadow_along(&along_x, DVec3::Z, 0.0, 100.0), (4.0, 6.0));
        close(ball.shadow_along(&along_x, DVec3::Z, 5.0, 100.0), (5.0, 6.0));
        assert_eq!(ball.shadow_along(&along_x, -DVec3::Z, 0.0, 100.0), None);
        // A line through the ball towards the light: shadowed up to the ball's far side.
        let up = ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        close(ball.shadow_along(&up, DVec3::Z, -10.0, 10.0), (-10.0, 4.0));
        let slab = Occluder::Box {
            center: DVec3::new(15.0, 0.0, 50.0),
            half_extents: DVec3::new(5.0, 500.0, 0.5),
            orientation: DQuat::IDENTITY,
        };
        let low = ray([0.0, 0.0, 1.7], [1.0, 0.0, 0.0]);
        close(slab.shadow_along(&low, DVec3::Z, 0.0, 1e6), (10.0, 20.0));
        // Light from 45° up towards +x: the slab's underside (48.3 ± 0.5 m above the line) casts
        // the shadow 47.8 to 48.8 m back towards −x, 1 m longer for the slab's thickness.
        let slanted = DVec3::new(1.0, 0.0, 1.0);
        close(
            slab.shadow_along(&low, slanted, -100.0, 1e6),
            (10.0 - 48.8, 20.0 - 47.8),
        );
        assert_eq!(slab.shadow_along(&low, slanted, 0.0, 1e6), None);
    }

    fn occluders() -> impl Strategy<Value = Occluder> {
        let vec = || (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z));
        prop_oneof![
            (vec(), 0.2..2.0f64).prop_map(|(center, radius)| Occluder::Sphere { center, radius }),
            (vec(), (0.1..2.0f64, 0.1..2.0f64, 0.1..2.0f64), vec()).prop_map(|(center, (x, y, z), axis)| {
                Occluder::Box {
                    center,
                    half_extents: DVec3::new(x, y, z),
                    orientation: DQuat::from_scaled_axis(axis),
                }
            }),
        ]
    }

    proptest! {
        /// The shadow interval agrees with blocking point by point, away from its edges.
        #[test]
        fn shadow_intervals_agree_with_blocking(
            shape in occluders(),
            origin in (-6.0..6.0f64, -6.0..6.0f64, -6.0..6.0f64),
            direction in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            light in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        ) {
            let ray = Ray::new(DVec3::from(origin), DVec3::from(direction));
            let light = DVec3::from(light);
            prop_assume!(ray.is_some() && light.length() > 0.1);
            let ray = ray.expect("checked");
            let shadow = shape.shadow_along(&ray, light, -20.0, 20.0);
            for i in 0..=4000 {
                let t = -20.0 + 40.0 * f64::from(i) / 4000.0;
                let inside = shadow.is_some_and(|(a, b)| a <= t && t <= b);
                let near_edge = shadow.is_some_and(|(a, b)| (t - a).abs() < 1e-5 || (t - b).abs() < 1e-5);
                if !near_edge {
                    prop_assert_eq!(inside, shape.blocks(ray.at(t), light, f64::INFINITY), "t = {} in {:?}", t, shadow);
                }
            }
        }
    }

    #[test]
    fn moving_into_the_planet_frame_keeps_hits_to_the_nanometre() {
        let planet = crate::atmosphere::presets::earth()
            .planet
            .posed_at(45f64.to_radians(), 10f64.to_radians());
        let view = ray([0.0, 0.0, 1.7], [1.0, 0.2, 0.1]);
        let in_planet = planet.ray_to_planet_frame(&view);
        for shape in [
            Occluder::Sphere {
                center: DVec3::new(30.0, 6.0, 4.0),
                radius: 1.0,
            },
            Occluder::Box {
                center: DVec3::new(30.0, 6.0, 4.0),
                half_extents: DVec3::new(2.0, 1.0, 3.0),
                orientation: DQuat::from_rotation_z(0.4),
            },
        ] {
            let world = shape.hit(&view).unwrap();
            let planet_frame = shape.to_planet_frame(&planet).hit(&in_planet).unwrap();
            assert!((world.0 - planet_frame.0).abs() < 1e-8 && (world.1 - planet_frame.1).abs() < 1e-8);
        }
    }

    #[test]
    fn validation_names_the_field() {
        let field = |shape: Occluder| match shape.validate() {
            Err(CoreError::Invalid { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let ball = |center, radius| Occluder::Sphere { center, radius };
        let cube = |half_extents, orientation| Occluder::Box {
            center: DVec3::ZERO,
            half_extents,
            orientation,
        };
        assert_eq!(ball(DVec3::ZERO, 1.0).validate(), Ok(()));
        assert_eq!(cube(DVec3::ONE, DQuat::from_rotation_z(1.0)).validate(), Ok(()));
        assert_eq!(field(ball(DVec3::NAN, 1.0)), "occluder.center");
        assert_eq!(field(ball(DVec3::ZERO, 0.0)), "occluder.radius");
        assert_eq!(field(ball(DVec3::ZERO, f64::INFINITY)), "occluder.radius");
        assert_eq!(
            field(cube(DVec3::new(1.0, -1.0, 1.0), DQuat::IDENTITY)),
            "occluder.half_extents"
        );
        assert_eq!(
            field(cube(DVec3::ONE, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0))),
            "occluder.orientation"
        );
    }
}
