//! The planet: an ellipsoid with a pose in the world, and an atmosphere shell above it.
//!
//! # Altitude
//! *Altitude* `h` is the geodetic height: the signed distance from a point to the closest point of
//! the ellipsoid surface, measured along that point's surface normal. [`Planet::altitude`]
//! computes it exactly (to ~1e-9 m) by solving for the foot point with Newton's method on
//! Eberly's formulation ("Distance from a Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid",
//! Geometric Tools, 2013): the foot is `x_i = p_i a_i² / (a_i² + t)` with `t` the root of
//! `F(t) = Σ (a_i p_i / (a_i² + t))² − 1`, which is convex and decreasing for `t > −min a_i²`.
//!
//! The GPU uses [`Planet::approximate_altitude`]: the first-order distance to the level set of
//! `f(p) = |p / a| − 1`, `h₁ = f / |∇f|`, plus the same estimate once more at the point `h₁` down
//! along `∇f`. For flattening up to 0.1 its error is under 2 mm below 100 km and under 2 m
//! below 1000 km (measured by this module's tests over all latitudes; the single first-order
//! step alone is off by 1 m and 96 m), far below any density scale height.
//!
//! # The atmosphere shell
//! The top of the atmosphere is the planet's ellipsoid grown by `atmosphere_height` along each
//! axis (as in seed 000). On an oblate planet its geodetic height varies by a few metres from
//! `atmosphere_height`; the density there is `e^-7` of its surface value or less for every preset.

use glam::{DQuat, DVec3};

use crate::error::CoreError;
use crate::geometry::{Ellipsoid, Ray};

/// A planet: an ellipsoid, where it is and how it is turned, and the height of its atmosphere.
///
/// The *planet frame* is centred on the planet with its axes along the ellipsoid's semi-axes
/// (`z` towards the north pole for a planet with `radii = (a, a, b)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Planet {
    /// Semi-axes along the planet frame's x, y, z, metres (`(a, a, b)` for an oblate spheroid).
    pub radii: DVec3,
    /// Centre in world coordinates, metres.
    pub center: DVec3,
    /// Rotation from the planet frame to the world frame.
    pub orientation: DQuat,
    /// Height of the atmosphere's top above the surface, metres.
    pub atmosphere_height: f64,
    /// Geometric albedo of the whole planet seen from space, clouds and air included, in [0, 1]:
    /// how much sunlight it casts on the bodies beside it (planet-shine,
    /// [`crate::atmosphere::body`]); 0 for none. The presets take their body's published value.
    pub geometric_albedo: f64,
}

impl Planet {
    /// A sphere of `radius` metres at the world origin with an atmosphere `atmosphere_height` high.
    pub fn sphere(radius: f64, atmosphere_height: f64) -> Self {
        Self::spheroid(radius, radius, atmosphere_height)
    }

    /// An oblate (or prolate) spheroid with the given equatorial and polar radii, metres.
    pub fn spheroid(equatorial_radius: f64, polar_radius: f64, atmosphere_height: f64) -> Self {
        Self {
            radii: DVec3::new(equatorial_radius, equatorial_radius, polar_radius),
            center: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
            atmosphere_height,
            geometric_albedo: 0.0,
        }
    }

    /// The same planet with geometric albedo `albedo` (see [`Self::geometric_albedo`]).
    pub fn with_geometric_albedo(self, albedo: f64) -> Self {
        Self {
            geometric_albedo: albedo,
            ..self
        }
    }

    /// Checks the rules: radii finite and > 0, no radius more than 10× another, atmosphere height
    /// finite and > 0, centre finite, orientation a finite non-zero quaternion, geometric albedo
    /// in [0, 1].
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        for (field, r) in [
            ("planet.radii.x", self.radii.x),
            ("planet.radii.y", self.radii.y),
            ("planet.radii.z", self.radii.z),
        ] {
            if !(r.is_finite() && r > 0.0) {
                return invalid(field, r.to_string(), "must be a finite radius > 0 m");
            }
        }
        if self.radii.max_element() > 10.0 * self.radii.min_element() {
            return invalid(
                "planet.radii",
                format!("{:?}", self.radii.to_array()),
                "no radius may be more than 10 times another",
            );
        }
        if !(self.atmosphere_height.is_finite() && self.atmosphere_height > 0.0) {
            return invalid(
                "atmosphere.height",
                self.atmosphere_height.to_string(),
                "must be a finite height > 0 m",
            );
        }
        if !self.center.is_finite() {
            return invalid(
                "planet.center",
                format!("{:?}", self.center.to_array()),
                "must be finite",
            );
        }
        if !(0.0..=1.0).contains(&self.geometric_albedo) {
            return invalid(
                "planet.geometric_albedo",
                self.geometric_albedo.to_string(),
                "must be in [0, 1]",
            );
        }
        if !(self.orientation.is_finite() && self.orientation.length_squared() > 0.0) {
            return invalid(
                "planet.orientation",
                format!("{:?}", self.orientation.to_array()),
                "must be a finite rotation",
            );
        }
        Ok(())
    }

    /// Flattening `(a − c)/a` of the largest and smallest semi-axes (0 for a sphere).
    pub fn flattening(&self) -> f64 {
        1.0 - self.radii.min_element() / self.radii.max_element()
    }

    /// The surface, in the planet frame.
    pub fn surface(&self) -> Ellipsoid {
        Ellipsoid {
            center: DVec3::ZERO,
            radii: self.radii,
        }
    }

    /// The top of the atmosphere, in the planet frame.
    pub fn atmosphere_top(&self) -> Ellipsoid {
        Ellipsoid {
            center: DVec3::ZERO,
            radii: self.radii + DVec3::splat(self.atmosphere_height),
        }
    }

    /// The radius of the sphere of the ellipsoid's volume, `(a·b·c)^⅓` metres.
    pub fn mean_radius(&self) -> f64 {
        self.radii.element_product().cbrt()
    }

    /// The planet-frame point of the surface whose outward normal has geodetic `latitude` and
    /// `longitude` (radians): `x_i = a_i² n_i / |a n|`, exact for any ellipsoid.
    pub fn surface_point(&self, latitude: f64, longitude: f64) -> DVec3 {
        let n = geodetic_normal(latitude, longitude);
        let a = self.radii;
        a * a * n / (a * n).length()
    }

    /// This planet, posed so that the world frame is the local East-North-Up frame of the surface
    /// point at geodetic `latitude` and `longitude` (radians): the world origin lies on the
    /// surface, +Z along its normal, +Y towards the north pole (+X at a pole, where north is
    /// undefined, is the planet frame's +Y direction turned into the tangent plane).
    pub fn posed_at(self, latitude: f64, longitude: f64) -> Self {
        let up = geodetic_normal(latitude, longitude);
        let east = DVec3::Z.cross(up).try_normalize().unwrap_or(DVec3::Y);
        let north = up.cross(east);
        // Rows of the planet → world rotation are the ENU axes in planet coordinates.
        let to_world = glam::DMat3::from_cols(east, north, up).transpose();
        let orientation = DQuat::from_mat3(&to_world).normalize();
        Self {
            center: -(orientation * self.surface_point(latitude, longitude)),
            orientation,
            ..self
        }
    }

    /// A world-space point in the planet frame.
    pub fn to_planet_frame(&self, world: DVec3) -> DVec3 {
        self.orientation.normalize().inverse() * (world - self.center)
    }

    /// A world-space direction in the planet frame.
    pub fn direction_to_planet_frame(&self, world: DVec3) -> DVec3 {
        self.orientation.normalize().inverse() * world
    }

    /// A world-space ray in the planet frame.
    pub fn ray_to_planet_frame(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self.to_planet_frame(ray.origin),
            direction: self.direction_to_planet_frame(ray.direction),
        }
    }

    /// Exact geodetic altitude of a planet-frame point, metres (negative inside).
    pub fn altitude(&self, p: DVec3) -> f64 {
        let foot = self.surface_foot(p);
        let sign = if (p / self.radii).length_squared() < 1.0 {
            -1.0
        } else {
            1.0
        };
        sign * (p - foot).length()
    }

    /// The GPU's altitude (error bound in the module docs): a first-order distance to the
    /// surface, `f/|∇f|` for `f(p) = |p/a| − 1`, refined once by the same estimate at the point
    /// that distance down along `∇f`.
    pub fn approximate_altitude(&self, p: DVec3) -> f64 {
        let (h1, down) = self.first_order_altitude(p);
        let (h2, _) = self.first_order_altitude(p + down * h1);
        h1 + h2
    }

    /// `f/|∇f|` and the unit vector along `−∇f` at `p`.
    fn first_order_altitude(&self, p: DVec3) -> (f64, DVec3) {
        let q = p / self.radii;
        let q_len = q.length();
        let gradient = p / (self.radii * self.radii) / q_len;
        let gradient_len = gradient.length();
        if gradient_len == 0.0 || !gradient_len.is_finite() {
            return (-self.radii.min_element(), DVec3::ZERO);
        }
        ((q_len - 1.0) / gradient_len, -gradient / gradient_len)
    }

    /// The outward geodetic "up" (the surface normal at the foot point) of a planet-frame point.
    pub fn up(&self, p: DVec3) -> DVec3 {
        self.surface().normal_at(self.surface_foot(p))
    }

    /// The closest point on the surface to planet-frame point `p`.
    fn surface_foot(&self, p: DVec3) -> DVec3 {
        let a2 = self.radii * self.radii;
        let ap = self.radii * p;
        let f = |t: f64| {
            let v = ap / (a2 + DVec3::splat(t));
            (
                v.length_squared() - 1.0,
                -2.0 * (v * v / (a2 + DVec3::splat(t))).element_sum(),
            )
        };
        // F is decreasing and convex on (−min a², ∞). At t₀ = max a·|p| − min a² every
        // a_i² + t₀ ≥ a_i·|p|, so F(t₀) ≤ 0: Newton from there walks left to the root without
        // overshooting, and t₀ is the root itself for a sphere. The clamp only guards rounding.
        let t_min = -a2.min_element();
        let mut t = p.length() * self.radii.max_element() + t_min;
        for _ in 0..100 {
            let (value, slope) = f(t);
            if slope == 0.0 || !value.is_finite() {
                break;
            }
            let next = (t - value / slope).max(0.5 * (t + t_min));
            if (next - t).abs() <= 1e-15 * (t.abs() + a2.min_element()) {
                t = next;
                break;
            }
            t = next;
        }
        let foot = a2 * p / (a2 + DVec3::splat(t));
        if foot.is_finite() {
            foot
        } else {
            // p at the centre of a sphere: every surface point is closest; pick the pole.
            DVec3::new(0.0, 0.0, self.radii.z)
        }
    }
}

/// The unit outward normal at geodetic `latitude` and `longitude` (radians), planet frame.
pub fn geodetic_normal(latitude: f64, longitude: f64) -> DVec3 {
    DVec3::new(
        latitude.cos() * longitude.cos(),
        latitude.cos() * longitude.sin(),
        latitude.sin(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn saturn_like() -> Planet {
        Planet::spheroid(60_268_000.0, 60_268_000.0 * 0.9, 1_000_000.0)
    }

    fn on_normal(planet: &Planet, latitude: f64, longitude: f64, h: f64) -> DVec3 {
        planet.surface_point(latitude, longitude) + geodetic_normal(latitude, longitude) * h
    }

    #[test]
    fn posed_planet_puts_the_world_origin_on_the_surface_with_enu_axes() {
        for (lat, lon) in [(45.0_f64, 10.0_f64), (0.0, -120.0), (-89.0, 33.0), (90.0, 0.0)] {
            let planet = saturn_like().posed_at(lat.to_radians(), lon.to_radians());
            let origin = planet.to_planet_frame(DVec3::ZERO);
            assert!(planet.altitude(origin).abs() < 1e-6, "{lat} {lon}");
            let up = planet.direction_to_planet_frame(DVec3::Z);
            assert!((up - planet.up(origin)).length() < 1e-9, "{lat} {lon}: {up}");
            let above = planet.to_planet_frame(DVec3::new(0.0, 0.0, 1234.5));
            assert!((planet.altitude(above) - 1234.5).abs() < 1e-6);
            if lat.abs() < 90.0 {
                // North (+Y) points towards the pole: its planet-frame z component is positive.
                assert!(planet.direction_to_planet_frame(DVec3::Y).z > 0.0);
            }
        }
    }

    #[test]
    fn exact_altitude_recovers_constructed_heights() {
        let planet = saturn_like();
        for lat in [-89.9_f64, -60.0, -10.0, 0.0, 0.001, 33.0, 45.0, 80.0, 90.0] {
            for h in [-1000.0, 0.0, 1.0, 8_000.0, 1_000_000.0, 1.5e11] {
                let p = on_normal(&planet, lat.to_radians(), 0.7, h);
                let got = planet.altitude(p);
                let tolerance = 1e-6 * (1.0 + h.abs() / 1e6);
                assert!((got - h).abs() < tolerance, "lat {lat} h {h}: {got}");
            }
        }
    }

    #[test]
    fn approximate_altitude_error_is_as_documented() {
        let planet = saturn_like();
        assert!((planet.flattening() - 0.1).abs() < 1e-12);
        let mut worst_100km: f64 = 0.0;
        let mut worst_1000km: f64 = 0.0;
        for i in 0..=180 {
            let lat = (i as f64 * 0.5).to_radians();
            for h in [0.0, 1_000.0, 10_000.0, 50_000.0, 100_000.0, 500_000.0, 1_000_000.0] {
                let p = on_normal(&planet, lat, 0.0, h);
                let error = (planet.approximate_altitude(p) - h).abs();
                if h <= 100_000.0 {
                    worst_100km = worst_100km.max(error);
                }
                worst_1000km = worst_1000km.max(error);
            }
        }
        assert!(worst_100km < 2e-3, "{worst_100km}");
        assert!(worst_1000km < 2.0, "{worst_1000km}");
    }

    #[test]
    fn frames_round_trip_and_rays_hit_the_posed_planet() {
        let mut planet = Planet::spheroid(6_378_137.0, 6_356_752.314_245, 60_000.0);
        planet.center = DVec3::new(1.5e11, -2.0e9, 3.0);
        planet.orientation = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.4);
        let world_north_pole = planet.center + planet.orientation * DVec3::new(0.0, 0.0, planet.radii.z + 10.0);
        let p = planet.to_planet_frame(world_north_pole);
        assert!((planet.altitude(p) - 10.0).abs() < 1e-3);
        assert!((planet.up(p) - DVec3::Z).length() < 1e-9);
    }

    #[test]
    fn bad_planets_name_their_field() {
        let mut planet = Planet::sphere(-1.0, 100.0);
        assert!(matches!(
            planet.validate(),
            Err(CoreError::Invalid {
                field: "planet.radii.x",
                ..
            })
        ));
        planet = Planet::spheroid(1.0, 11.0, 1.0);
        assert!(matches!(
            planet.validate(),
            Err(CoreError::Invalid {
                field: "planet.radii",
                ..
            })
        ));
        planet = Planet::sphere(1.0, 0.0);
        assert!(matches!(
            planet.validate(),
            Err(CoreError::Invalid {
                field: "atmosphere.height",
                ..
            })
        ));
        planet = Planet::sphere(f64::NAN, 1.0);
        assert!(planet.validate().is_err());
    }
}
