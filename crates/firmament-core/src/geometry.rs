//! Rays, spheres and axis-aligned ellipsoids, intersected in `f64` with care for cancellation.
//!
//! The quadratic is solved in the numerically stable form of Hearn & Baker / *Numerical Recipes*
//! (`q = -(b + sign(b)·√Δ)/2`, roots `q/a` and `c/q`) with the discriminant computed as
//! `r² − |f − (f·d)d|²` (Haines et al., "Precision Improvements for Ray/Sphere Intersection",
//! *Ray Tracing Gems*, 2019, ch. 7), which stays accurate for a ray 1 m above a planet and for one
//! fired from 100 AU away.

use glam::DVec3;

/// A ray: `origin + t · direction`, `t` in metres along the unit `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Start point, metres.
    pub origin: DVec3,
    /// Unit direction.
    pub direction: DVec3,
}

impl Ray {
    /// A ray from `origin` along `direction` (normalised here). `None` for a zero or non-finite
    /// direction or a non-finite origin.
    pub fn new(origin: DVec3, direction: DVec3) -> Option<Self> {
        let direction = direction.try_normalize()?;
        origin.is_finite().then_some(Self { origin, direction })
    }

    /// The point at parameter `t`, metres along the ray.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }
}

/// Where a ray enters and leaves a closed surface: ray parameters in metres, `near <= far`.
/// `near < 0 <= far` means the origin is inside; both negative means the surface is behind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHits {
    /// Entry parameter, metres.
    pub near: f64,
    /// Exit parameter, metres.
    pub far: f64,
}

/// A sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre, metres.
    pub center: DVec3,
    /// Radius, metres, > 0.
    pub radius: f64,
}

impl Sphere {
    /// Both intersections of the infinite line through `ray` with the sphere (including those
    /// behind the origin), or `None` when the line misses. A tangent ray gives `near == far`.
    pub fn intersect(&self, ray: &Ray) -> Option<RayHits> {
        unit_quadratic_hits(ray.origin - self.center, ray.direction, self.radius)
    }

    /// True when `point` is inside or on the sphere.
    pub fn contains(&self, point: DVec3) -> bool {
        (point - self.center).length_squared() <= self.radius * self.radius
    }
}

/// An ellipsoid with semi-axes along its frame's x, y and z (a planet: `radii = (a, a, b)` with
/// equatorial radius `a` and polar radius `b`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// Centre, metres.
    pub center: DVec3,
    /// Semi-axes along x, y, z, metres, each > 0.
    pub radii: DVec3,
}

impl Ellipsoid {
    /// Both intersections of the line through `ray` with the ellipsoid, like
    /// [`Sphere::intersect`]; parameters are metres along the (unit) world ray.
    pub fn intersect(&self, ray: &Ray) -> Option<RayHits> {
        // Scale space so the ellipsoid becomes a sphere of radius `s` (the smallest semi-axis,
        // keeping numbers near their original magnitude). The ray parameter is unchanged by a
        // linear map, so we solve for t with the scaled, *unnormalised* direction.
        let s = self.radii.min_element();
        let scale = DVec3::splat(s) / self.radii;
        let f = (ray.origin - self.center) * scale;
        let d = ray.direction * scale;
        let d_len = d.length();
        // Solve along the normalised scaled direction, then convert back: t_world = t_scaled / |d|.
        let hits = unit_quadratic_hits(f, d / d_len, s)?;
        Some(RayHits {
            near: hits.near / d_len,
            far: hits.far / d_len,
        })
    }

    /// True when `point` is inside or on the ellipsoid.
    pub fn contains(&self, point: DVec3) -> bool {
        ((point - self.center) / self.radii).length_squared() <= 1.0
    }

    /// The outward unit normal of the ellipsoid's surface at (or near) `point`.
    pub fn normal_at(&self, point: DVec3) -> DVec3 {
        ((point - self.center) / (self.radii * self.radii)).normalize_or_zero()
    }
}

/// Hits of a line `f + t·d` (origin relative to the centre, unit `d`) with a centred sphere of
/// radius `r`.
fn unit_quadratic_hits(f: DVec3, d: DVec3, r: f64) -> Option<RayHits> {
    // a = 1 for a unit direction; b' = f·d is half the usual b.
    let b = f.dot(d);
    // Δ/4 = r² − |f − (f·d)d|²: the squared half-chord, free of the cancellation in b² − c.
    let closest = f - d * b;
    let disc = (r - closest.length()) * (r + closest.length());
    if disc < 0.0 || !disc.is_finite() {
        return None;
    }
    let c = f.length_squared() - r * r;
    let q = -(b + b.signum() * disc.sqrt());
    if q == 0.0 {
        // b = 0 and Δ = 0: the ray is tangent at its own origin.
        return Some(RayHits { near: 0.0, far: 0.0 });
    }
    let (t0, t1) = (q, c / q);
    Some(RayHits {
        near: t0.min(t1),
        far: t0.max(t1),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const EARTH_A: f64 = 6_378_137.0;
    const EARTH_B: f64 = 6_356_752.314_245;
    const AU: f64 = 1.495_978_707e11;

    fn earth() -> Ellipsoid {
        Ellipsoid {
            center: DVec3::ZERO,
            radii: DVec3::new(EARTH_A, EARTH_A, EARTH_B),
        }
    }

    /// Brute force: march the implicit function `g(t)` from `t0` to `t1` and bisect sign changes.
    fn march(g: impl Fn(f64) -> f64, t0: f64, t1: f64, steps: usize) -> Vec<f64> {
        let mut roots = Vec::new();
        let dt = (t1 - t0) / steps as f64;
        let mut a = t0;
        let mut ga = g(a);
        for i in 1..=steps {
            let b = t0 + dt * i as f64;
            let gb = g(b);
            if ga == 0.0 {
                roots.push(a);
            } else if ga.signum() != gb.signum() && gb != 0.0 {
                let (mut lo, mut hi, mut glo) = (a, b, ga);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    let gm = g(mid);
                    if gm.signum() == glo.signum() {
                        lo = mid;
                        glo = gm;
                    } else {
                        hi = mid;
                    }
                }
                roots.push(0.5 * (lo + hi));
            }
            a = b;
            ga = gb;
        }
        roots
    }

    fn vec3() -> impl Strategy<Value = DVec3> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        #[test]
        fn sphere_hits_match_marching(o in vec3(), d in vec3(), r in 0.1..2.0f64, scale in prop::sample::select(vec![1e-3, 1.0, 1e6])) {
            let ray = Ray::new(o * 3.0 * scale, d);
            prop_assume!(ray.is_some());
            let ray = ray.expect("checked");
            let sphere = Sphere { center: DVec3::ZERO, radius: r * scale };
            let g = |t: f64| (ray.at(t).length() - sphere.radius) / scale;
            let roots = march(g, -10.0 * scale, 10.0 * scale, 4000);
            match sphere.intersect(&ray) {
                Some(hits) => {
                    // Grazing rays may touch without a sign change: only check clear crossings.
                    if roots.len() == 2 {
                        prop_assert!((hits.near - roots[0]).abs() < 1e-9 * scale, "{hits:?} {roots:?}");
                        prop_assert!((hits.far - roots[1]).abs() < 1e-9 * scale, "{hits:?} {roots:?}");
                    }
                    prop_assert!((ray.at(hits.near).length() - sphere.radius).abs() < 1e-9 * scale);
                }
                None => prop_assert!(roots.is_empty(), "missed but marching found {roots:?}"),
            }
            prop_assert_eq!(sphere.contains(ray.origin), g(0.0) <= 0.0);
        }

        #[test]
        fn ellipsoid_hits_match_marching(o in vec3(), d in vec3(), radii in (0.2..2.0f64, 0.2..2.0f64, 0.2..2.0f64)) {
            let ray = Ray::new(o * 3.0, d);
            prop_assume!(ray.is_some());
            let ray = ray.expect("checked");
            let e = Ellipsoid { center: DVec3::new(0.1, -0.2, 0.3), radii: DVec3::new(radii.0, radii.1, radii.2) };
            let g = |t: f64| ((ray.at(t) - e.center) / e.radii).length() - 1.0;
            let roots = march(g, -12.0, 12.0, 6000);
            match e.intersect(&ray) {
                Some(hits) => {
                    if roots.len() == 2 {
                        prop_assert!((hits.near - roots[0]).abs() < 1e-9, "{hits:?} {roots:?}");
                        prop_assert!((hits.far - roots[1]).abs() < 1e-9, "{hits:?} {roots:?}");
                    }
                    prop_assert!(g(hits.near).abs() < 1e-9 && g(hits.far).abs() < 1e-9);
                }
                None => prop_assert!(roots.is_empty(), "missed but marching found {roots:?}"),
            }
            prop_assert_eq!(e.contains(ray.origin), g(0.0) <= 0.0);
        }
    }

    #[test]
    fn one_metre_above_the_ellipsoid_looking_down() {
        for lat in [0.0f64, 30.0, 60.0, 89.9] {
            let (s, c) = lat.to_radians().sin_cos();
            // A surface point and its normal (geodetic latitude), then 1 m up along the normal.
            let n = DVec3::new(c, 0.0, s);
            let e2 = 1.0 - (EARTH_B * EARTH_B) / (EARTH_A * EARTH_A);
            let nu = EARTH_A / (1.0 - e2 * s * s).sqrt();
            let surface = DVec3::new(nu * c, 0.0, nu * (1.0 - e2) * s);
            let ray = Ray::new(surface + n, -n).expect("valid");
            let hits = earth().intersect(&ray).expect("hits the ground");
            assert!((hits.near - 1.0).abs() < 1e-6, "lat {lat}: {}", hits.near);
        }
    }

    #[test]
    fn from_100_au_towards_the_centre() {
        let origin = DVec3::new(100.0 * AU, 0.0, 0.0);
        let ray = Ray::new(origin, -origin).expect("valid");
        let hits = earth().intersect(&ray).expect("hits");
        let expected = 100.0 * AU - EARTH_A;
        assert!(((hits.near - expected) / expected).abs() < 1e-12, "{}", hits.near);
        // Towards the pole from above: the polar radius.
        let origin = DVec3::new(0.0, 0.0, 100.0 * AU);
        let hits = earth()
            .intersect(&Ray::new(origin, -origin).expect("valid"))
            .expect("hits");
        assert!(((hits.near - (100.0 * AU - EARTH_B)) / (100.0 * AU)).abs() < 1e-12);
        // And a ray aimed just past the limb misses.
        let ray = Ray::new(
            DVec3::new(100.0 * AU, 0.0, 0.0),
            DVec3::new(-100.0 * AU, EARTH_A * 1.0001, 0.0),
        )
        .expect("valid");
        assert!(earth().intersect(&ray).is_none());
    }

    #[test]
    fn inside_tangent_and_behind() {
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        let inside = s
            .intersect(&Ray::new(DVec3::ZERO, DVec3::X).expect("valid"))
            .expect("hits");
        assert_eq!((inside.near, inside.far), (-1.0, 1.0));
        let tangent = s
            .intersect(&Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X).expect("valid"))
            .expect("touches");
        assert!((tangent.near - 5.0).abs() < 1e-12 && (tangent.far - 5.0).abs() < 1e-12);
        let behind = s
            .intersect(&Ray::new(DVec3::new(5.0, 0.0, 0.0), DVec3::X).expect("valid"))
            .expect("line hits");
        assert!(behind.near < 0.0 && behind.far < 0.0);
        assert!(Ray::new(DVec3::ZERO, DVec3::ZERO).is_none());
        assert!(Ray::new(DVec3::NAN, DVec3::X).is_none());
    }
}
