//! The night sky as a renderer draws it: the stars as points and the Moon as a shaded disc, in
//! the frame's world frame and radiance units, already dimmed by the atmosphere's transmittance.
//!
//! # Units
//! A frame's radiance has some unit `U` (cd/m² for the physical sky: its HDR target's Y is the
//! luminance). `units_per_lux` converts an illuminance in lux into `U · sr` (1 for cd/m², since
//! 1 lx = 1 cd · sr / m²). A star is a point: its [`StarPoint::color`] is its irradiance, in
//! `U · sr` — the radiance a renderer spreads over the pixels it covers, times their solid
//! angle, must add up to it. The Moon is an extended source: [`MoonDisc::radiance`] is in `U`.
//!
//! # The Moon's surface
//! The disc is a sphere lit by the Sun with the **Lommel–Seeliger** law, the single-scattering
//! law of a dark, porous regolith whose brightness does not fall towards the limb (why the full
//! moon looks like a flat disc): the radiance of a surface element is proportional to
//! `μ₀ / (μ₀ + μ)`, μ₀ the cosine of the incidence angle, μ that of the emergence angle (Hapke,
//! *Theory of Reflectance and Emittance Spectroscopy*, 2nd ed. 2012, §9.2; Fairbairn 2005,
//! "Planetary photometry: the Lommel-Seeliger law", *JRASC* 99, 92). Here it is normalised to 1
//! at normal incidence and emergence (`2 μ₀ / (μ₀ + μ)`, [`lommel_seeliger`]), so
//! [`MoonDisc::radiance`] is the radiance of the sub-solar point seen face-on. The disc-integrated
//! light then follows Fairbairn's phase law `Φ(g) = 1 − sin(g/2) tan(g/2) ln cot(g/4)`
//! ([`lommel_seeliger_phase`]; `Φ(0) = 1`, g the phase angle), and the radiance is chosen so that
//! the light the whole disc sends — its radiance integrated over its solid angle,
//! `radiance · 2π(1 − cos α) · Φ(g)` — equals the Moon's illuminance from [`crate::astro::moon`]
//! (times `units_per_lux` and the transmittance). A unit test integrates the disc numerically.
//!
//! The phase and the orientation of the terminator need no extra input: they come from shading
//! the sphere with [`MoonDisc::sun_direction`], the direction of the Sun seen from the Moon.

use glam::{DMat3, DVec3};

use crate::astro::Instant;
use crate::astro::moon::{MoonView, moon_view};
use crate::astro::sidereal::j2000_to_horizon_matrix;
use crate::astro::stars::catalogue;
use crate::atmosphere::planet_shadow::SHADOW_ENTRIES;

/// Stars and the Moon lower than this elevation, degrees, are left out of a [`NightLayer`]
/// (the horizon with a margin for refraction, which lifts objects by ~0.6° there, and for a
/// camera above the ground, which sees a little below the horizontal).
pub const HORIZON_CUTOFF_DEG: f64 = -1.0;

/// One star, a point of light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StarPoint {
    /// Unit direction towards the star, world frame.
    pub direction: DVec3,
    /// Linear RGB irradiance from the star, frame radiance units × steradian (the star's light
    /// integrated over its tiny disc), after the atmosphere's transmittance.
    pub color: DVec3,
}

/// The Moon's disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoonDisc {
    /// Unit direction towards the Moon's centre, world frame.
    pub direction: DVec3,
    /// Angular radius of the disc seen by the observer, radians, in (0, π/2).
    pub angular_radius: f64,
    /// Unit direction towards the Sun seen from the Moon's centre, world frame.
    pub sun_direction: DVec3,
    /// Linear RGB radiance, frame radiance units, of the surface at normal incidence seen
    /// face-on (the Lommel–Seeliger law normalised to 1 there, [`lommel_seeliger`]), times the
    /// transmittance to the camera. A point of the disc shows this times
    /// `2 μ₀ / (μ₀ + μ)` ([`MoonDisc::radiance_along`]).
    pub radiance: DVec3,
    /// The planet's shadow across the Moon in a lunar eclipse: each point of the disc gets its
    /// share of the sunlight (`None` outside eclipses).
    pub shadow: Option<MoonShadow>,
}

/// The planet's shadow on the Moon in a lunar eclipse: the sunlight's share across it
/// ([`crate::atmosphere::planet_shadow`]), linear RGB, by the distance from the shadow's axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoonShadow {
    /// Unit world direction of the shadow's axis: from the planet away from the Sun.
    pub axis: DVec3,
    /// From the axis to the Moon's centre, across the axis, in Moon radii (world frame).
    pub offset: DVec3,
    /// Distance from the axis between entries of `light`, Moon radii.
    pub step: f64,
    /// The sunlight's share at each entry, linear RGB relative to full sunlight (entry `k` is
    /// `k · step` from the axis; 1 beyond the last).
    pub light: [DVec3; SHADOW_ENTRIES],
}

impl MoonShadow {
    /// The sunlight's share at the point of the Moon with outward unit normal `normal` (world
    /// frame).
    pub fn light_at(&self, normal: DVec3) -> DVec3 {
        let across = self.offset + normal - self.axis * normal.dot(self.axis);
        let x = across.length() / self.step;
        let i = x.floor() as usize;
        if !x.is_finite() || i + 1 >= SHADOW_ENTRIES {
            return DVec3::ONE;
        }
        self.light[i].lerp(self.light[i + 1], x - i as f64)
    }

    /// The sunlight's share averaged over the disc an observer towards `direction` (unit, from
    /// the observer to the Moon) sees ([`mean_over_face`]).
    pub fn mean_over_disc(&self, direction: DVec3) -> DVec3 {
        mean_over_face(direction, |normal| self.light_at(normal))
    }
}

/// The mean of `value` (of the outward unit normal) over the face of a sphere an observer towards
/// `direction` (unit, from the observer to its centre) sees: a 128 × 128 grid over the disc, equal
/// areas of the disc (equal solid angles) weighted alike.
pub fn mean_over_face(direction: DVec3, value: impl Fn(DVec3) -> DVec3) -> DVec3 {
    let (e1, e2) = direction.any_orthonormal_pair();
    let n = 128;
    let (mut sum, mut count) = (DVec3::ZERO, 0.0);
    for j in 0..n {
        for i in 0..n {
            let x = (f64::from(i) + 0.5) / f64::from(n) * 2.0 - 1.0;
            let y = (f64::from(j) + 0.5) / f64::from(n) * 2.0 - 1.0;
            let r2 = x * x + y * y;
            if r2 < 1.0 {
                sum += value(e1 * x + e2 * y - direction * (1.0 - r2).sqrt());
                count += 1.0;
            }
        }
    }
    sum / count
}

/// The Lommel–Seeliger law normalised to 1 at normal incidence and emergence: `2 μ₀ / (μ₀ + μ)`
/// for μ₀ > 0 (the cosine of the incidence angle; 0 on the night side) and μ ≥ 0 (the cosine of
/// the emergence angle). Dimensionless.
pub fn lommel_seeliger(mu0: f64, mu: f64) -> f64 {
    if mu0 > 0.0 && mu >= 0.0 {
        2.0 * mu0 / (mu0 + mu)
    } else {
        0.0
    }
}

pub use crate::atmosphere::body::phase::lommel_seeliger_phase;

/// The smallest [`lommel_seeliger_phase`] used to turn the Moon's illuminance into a radiance:
/// near new moon the magnitude formula and the Lommel–Seeliger law part ways (and the visible
/// crescent is thinner than a pixel), so the radiance is capped rather than diverging.
const MIN_PHASE_FACTOR: f64 = 1e-3;

impl MoonDisc {
    /// The disc of `view` (East-North-Up directions turned into the world frame by
    /// `world_from_enu`), its radiance set from the Moon's illuminance times `units_per_lux`
    /// (frame units · sr per lux) and `transmittance` (per channel, dimensionless).
    pub fn from_view(view: &MoonView, world_from_enu: DMat3, units_per_lux: f64, transmittance: DVec3) -> Self {
        let direction = (world_from_enu * view.direction).normalize();
        let sun_direction = (world_from_enu * view.sun_direction).normalize();
        let mut disc = Self {
            direction,
            angular_radius: view.angular_radius,
            sun_direction,
            radiance: DVec3::ZERO,
            shadow: None,
        };
        let per_radiance = disc.solid_angle() * lommel_seeliger_phase(disc.phase_angle()).max(MIN_PHASE_FACTOR);
        disc.radiance = transmittance * (view.illuminance_lux * units_per_lux / per_radiance);
        disc
    }

    /// The phase angle g, radians in [0, π]: between the Sun and the observer seen from the
    /// Moon's centre (0 at full moon).
    pub fn phase_angle(&self) -> f64 {
        self.sun_direction.angle_between(-self.direction)
    }

    /// The illuminated fraction of the disc, `(1 + cos g) / 2`, in [0, 1].
    pub fn illuminated_fraction(&self) -> f64 {
        0.5 * (1.0 + self.phase_angle().cos())
    }

    /// The disc's solid angle, steradians: `2π (1 − cos α)`.
    pub fn solid_angle(&self) -> f64 {
        // 1 − cos α = 2 sin²(α/2), without cancellation.
        4.0 * std::f64::consts::PI * (0.5 * self.angular_radius).sin().powi(2)
    }

    /// The light the whole disc sends to the observer, `radiance · Ω · Φ(g)` (times the shadow's
    /// mean share in a lunar eclipse): linear RGB, frame units × steradian (the Moon's
    /// illuminance × `units_per_lux` × the transmittance for a disc made by
    /// [`MoonDisc::from_view`], unless capped near new moon).
    pub fn illuminance(&self) -> DVec3 {
        let shade = self.shadow.map_or(DVec3::ONE, |s| s.mean_over_disc(self.direction));
        self.radiance * shade * self.solid_angle() * lommel_seeliger_phase(self.phase_angle())
    }

    /// The radiance seen along the unit world-frame view direction `view`: `None` when the ray
    /// misses the disc (or the disc is malformed), zero on the night side, else
    /// `radiance · 2 μ₀ / (μ₀ + μ)` at the point the ray meets the sphere — intersected exactly,
    /// in a form that stays accurate for a disc of a fraction of a degree.
    pub fn radiance_along(&self, view: DVec3) -> Option<DVec3> {
        let d = self.direction.try_normalize()?;
        let v = view.try_normalize()?;
        let (sin_a, _) = self.angular_radius.sin_cos();
        if !(self.angular_radius > 0.0 && self.angular_radius < std::f64::consts::FRAC_PI_2) {
            return None;
        }
        let cos_t = v.dot(d);
        if cos_t <= 0.0 {
            return None;
        }
        // The ray's offset from the centre direction: sin θ and its unit direction on the sky.
        let w = v - d * cos_t;
        let sin_t = w.length();
        // Closest approach of the ray to the centre, in Moon radii (the centre is 1/sin α away).
        let b = sin_t / sin_a;
        if b > 1.0 {
            return None;
        }
        let mu = (1.0 - b * b).max(0.0).sqrt();
        let w_hat = if sin_t > 0.0 { w / sin_t } else { DVec3::ZERO };
        // The outward normal where the ray enters the sphere: μ = −n·v = √(1 − b²) exactly.
        let normal = -d * (mu * cos_t + b * sin_t) + w_hat * (b * cos_t - mu * sin_t);
        let mu0 = normal.dot(self.sun_direction.try_normalize()?);
        let shade = self.shadow.map_or(DVec3::ONE, |shadow| shadow.light_at(normal));
        Some(self.radiance * shade * lommel_seeliger(mu0, mu))
    }

    /// Whether every field is usable: finite non-zero directions, an angular radius in (0, π/2)
    /// and a finite, non-negative radiance.
    pub fn is_valid(&self) -> bool {
        self.direction.is_finite()
            && self.direction.length_squared() > 0.0
            && self.sun_direction.is_finite()
            && self.sun_direction.length_squared() > 0.0
            && self.angular_radius > 0.0
            && self.angular_radius < std::f64::consts::FRAC_PI_2
            && self.radiance.is_finite()
            && self.radiance.min_element() >= 0.0
    }
}

/// What of the night sky a frame draws: stars and the Moon, world frame, frame units.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NightLayer {
    /// The stars (empty: none drawn).
    pub stars: Vec<StarPoint>,
    /// The Moon, when it is up.
    pub moon: Option<MoonDisc>,
}

impl NightLayer {
    /// The sky at `instant` for an observer at geodetic `latitude_deg`, `longitude_deg` (east
    /// positive) and `height_m` above the ellipsoid: every catalogue star brighter than
    /// `limiting_magnitude` (V) and the Moon, those above [`HORIZON_CUTOFF_DEG`].
    ///
    /// - Directions: the catalogue's J2000.0 positions precessed, nutated and turned to the local
    ///   East-North-Up frame ([`j2000_to_horizon_matrix`]), then into the world frame by
    ///   `world_from_enu` (identity when the world is the local ENU frame). No refraction.
    /// - A star's colour is `star_color(B−V) · star_illuminance_lux(V) · units_per_lux ·
    ///   transmittance(direction)`; the Moon's radiance is set likewise from its illuminance
    ///   ([`MoonDisc::from_view`]).
    /// - `units_per_lux`: frame radiance units × sr per lux (1 for a frame in cd/m²);
    ///   `transmittance(world direction)`: per-channel transmittance from space to the camera
    ///   (return 0 where the ground hides the sky).
    ///
    /// Stars the Moon's disc hides, and those whose direction or colour is not finite, are left
    /// out.
    #[expect(
        clippy::too_many_arguments,
        reason = "an instant, a place, a frame, units and a limit: each independent"
    )]
    pub fn at(
        instant: &Instant,
        latitude_deg: f64,
        longitude_deg: f64,
        height_m: f64,
        world_from_enu: DMat3,
        units_per_lux: f64,
        limiting_magnitude: f64,
        transmittance: impl Fn(DVec3) -> DVec3,
    ) -> Self {
        let to_enu = j2000_to_horizon_matrix(instant, latitude_deg.to_radians(), longitude_deg.to_radians());
        let min_z = HORIZON_CUTOFF_DEG.to_radians().sin();
        let view = moon_view(instant, latitude_deg, longitude_deg, height_m);
        let moon = (view.direction.z >= min_z)
            .then(|| {
                let direction = (world_from_enu * view.direction).normalize();
                MoonDisc::from_view(&view, world_from_enu, units_per_lux, transmittance(direction))
            })
            .filter(MoonDisc::is_valid);
        let behind_moon = |d: DVec3| moon.is_some_and(|m| d.angle_between(m.direction) <= m.angular_radius);
        let stars = catalogue()
            .iter()
            .filter(|star| star.v_mag < limiting_magnitude)
            .filter_map(|star| {
                let enu = (to_enu * star.unit_vector()).normalize();
                if enu.z < min_z {
                    return None;
                }
                let direction = (world_from_enu * enu).normalize();
                if behind_moon(direction) {
                    return None;
                }
                let c = star.color();
                let color =
                    DVec3::new(c.r, c.g, c.b) * (star.illuminance_lux() * units_per_lux) * transmittance(direction);
                (direction.is_finite() && color.is_finite()).then_some(StarPoint { direction, color })
            })
            .collect();
        Self { stars, moon }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::CivilDateTime;
    use crate::astro::moon::next_phase;
    use crate::astro::stars::{named_star, star_color, star_illuminance_lux};

    fn utc(y: i32, mo: u32, d: u32, h: u32, mi: u32) -> Instant {
        Instant::from_civil(&CivilDateTime::utc(y, mo, d, h, mi, 0.0), None).expect("valid date")
    }

    fn clear(_: DVec3) -> DVec3 {
        DVec3::ONE
    }

    #[test]
    fn night_sky_polaris_stands_at_the_latitude() {
        let polaris = named_star("Polaris").expect("Polaris");
        let pole = DVec3::new(0.0, 45f64.to_radians().cos(), 45f64.to_radians().sin());
        for hour in [0, 5, 11, 17, 23] {
            let layer = NightLayer::at(
                &utc(2025, 1, 15, hour, 7),
                45.0,
                10.0,
                0.0,
                DMat3::IDENTITY,
                1.0,
                2.1,
                clear,
            );
            let nearest = layer
                .stars
                .iter()
                .min_by(|a, b| {
                    a.direction
                        .angle_between(pole)
                        .total_cmp(&b.direction.angle_between(pole))
                })
                .expect("stars");
            let elevation = nearest.direction.z.asin().to_degrees();
            eprintln!("{hour:>2} h UTC: Polaris at elevation {elevation:.3}°");
            assert!((elevation - 45.0).abs() < 1.0, "{elevation}");
            let c = star_color(polaris.b_minus_v);
            let expected = DVec3::new(c.r, c.g, c.b) * star_illuminance_lux(polaris.v_mag);
            assert!((nearest.color - expected).length() < 1e-12 * expected.length());
        }
    }

    #[test]
    fn night_sky_shows_about_half_the_stars() {
        let all = catalogue().iter().filter(|s| s.v_mag < 6.0).count() as f64;
        for (instant, lat) in [
            (utc(2025, 1, 15, 22, 0), 45.0),
            (utc(2025, 7, 1, 3, 0), -30.0),
            (utc(2024, 3, 20, 12, 0), 0.0),
        ] {
            let layer = NightLayer::at(&instant, lat, 0.0, 0.0, DMat3::IDENTITY, 1.0, 6.0, clear);
            let share = layer.stars.len() as f64 / all;
            eprintln!("latitude {lat}: {} of {all} stars up, {share:.3}", layer.stars.len());
            assert!((0.40..0.60).contains(&share), "{share}");
            let min_z = HORIZON_CUTOFF_DEG.to_radians().sin();
            assert!(layer.stars.iter().all(|s| s.direction.z >= min_z));
        }
    }

    #[test]
    fn night_sky_applies_the_frame_units_and_transmittance() {
        let instant = utc(2025, 1, 15, 22, 0);
        let plain = NightLayer::at(&instant, 45.0, 0.0, 0.0, DMat3::IDENTITY, 1.0, 3.0, clear);
        let half = |d: DVec3| DVec3::new(0.5, 0.25, d.z.max(0.0));
        let turn = DMat3::from_rotation_z(0.3);
        let scaled = NightLayer::at(&instant, 45.0, 0.0, 0.0, turn, 1000.0, 3.0, half);
        assert_eq!(plain.stars.len(), scaled.stars.len());
        for (a, b) in plain.stars.iter().zip(&scaled.stars) {
            assert!((turn * a.direction - b.direction).length() < 1e-12);
            let expected = a.color * 1000.0 * half(b.direction);
            assert!((b.color - expected).length() <= 1e-12 * expected.length().max(1e-30));
        }
    }

    /// The disc's light by brute force: radiance along rays on a fine grid in the tangent plane,
    /// each weighted by its solid angle `du dv / (1 + u² + v²)^{3/2}`.
    fn integrate(disc: &MoonDisc, n: u32) -> DVec3 {
        let d = disc.direction.normalize();
        let e1 = d.any_orthonormal_vector();
        let e2 = d.cross(e1);
        let t = disc.angular_radius.tan() * 1.001;
        let step = 2.0 * t / f64::from(n);
        let mut sum = DVec3::ZERO;
        for i in 0..n {
            for j in 0..n {
                let u = -t + (f64::from(i) + 0.5) * step;
                let v = -t + (f64::from(j) + 0.5) * step;
                let r2 = 1.0 + u * u + v * v;
                if let Some(l) = disc.radiance_along(d + e1 * u + e2 * v) {
                    sum += l * step * step / (r2 * r2.sqrt());
                }
            }
        }
        sum
    }

    #[test]
    fn night_sky_moon_disc_sends_the_moon_s_illuminance() {
        let start = utc(2025, 3, 1, 0, 0);
        let mut instants = vec![
            next_phase(&start, 180.0),
            next_phase(&start, 90.0),
            next_phase(&start, 270.0),
        ];
        instants.push(start.plus_seconds(5.0 * 86_400.0)); // a crescent
        instants.push(next_phase(&start, 140.0)); // gibbous
        let world = DMat3::from_rotation_x(0.4);
        for instant in instants {
            let view = moon_view(&instant, 48.0, 11.0, 500.0);
            let transmittance = DVec3::new(0.8, 0.7, 0.5);
            let disc = MoonDisc::from_view(&view, world, 1.0, transmittance);
            assert!(disc.is_valid());
            let expected = transmittance * view.illuminance_lux;
            let integrated = integrate(&disc, 800);
            let error = ((integrated - expected) / expected).abs().max_element();
            let closed = ((disc.illuminance() - expected) / expected).abs().max_element();
            eprintln!(
                "phase angle {:6.2}°, k = {:.3}: ∫ L dΩ = {:.5e} lx (green), illuminance {:.5e} lx: \
                 error {:.2e} (closed form {:.1e})",
                disc.phase_angle().to_degrees(),
                disc.illuminated_fraction(),
                integrated.y,
                expected.y,
                error,
                closed
            );
            assert!(error < 0.005, "{error}");
            assert!(closed < 1e-9, "{closed}");
            assert!((disc.illuminated_fraction() - view.phase.illuminated_fraction).abs() < 1e-9);
        }
    }

    #[test]
    fn night_sky_lommel_seeliger_phase_law_matches_the_integral() {
        // Φ(g) against the disc integral of 2μ₀/(μ₀+μ) in units of the full disc, for a tiny
        // Moon (the plane-parallel limit the law is stated in).
        for g_deg in [0.0, 10.0, 45.0, 90.0, 120.0, 150.0, 170.0] {
            let g = f64::to_radians(g_deg);
            let d = DVec3::NEG_Z;
            let disc = MoonDisc {
                direction: d,
                angular_radius: 1e-3,
                sun_direction: DVec3::new(g.sin(), 0.0, g.cos()),
                radiance: DVec3::ONE,
                shadow: None,
            };
            let full = disc.solid_angle();
            let ratio = integrate(&disc, 600).x / full;
            let law = lommel_seeliger_phase(g);
            eprintln!("g = {g_deg:5.1}°: integral {ratio:.5}, Φ {law:.5}");
            assert!((ratio - law).abs() < 2e-3, "{g_deg}: {ratio} vs {law}");
        }
        assert_eq!(lommel_seeliger_phase(std::f64::consts::PI), 0.0);
        assert_eq!(lommel_seeliger_phase(f64::NAN), 0.0);
    }

    #[test]
    fn night_sky_disc_rays_and_bad_input() {
        let disc = MoonDisc {
            direction: DVec3::Y,
            angular_radius: 0.01,
            sun_direction: DVec3::NEG_Y, // full moon
            radiance: DVec3::splat(2.0),
            shadow: None,
        };
        // Flat: the same radiance from the centre to near the limb, where the observer's finite
        // distance (the ray is θ ≤ α off the Sun's direction) brightens it a little.
        for (offset, tolerance) in [(0.0, 1e-12), (0.005, 3e-3), (0.0099, 0.05)] {
            let l = disc.radiance_along(DVec3::new(offset, 1.0, 0.0)).expect("hit");
            assert!((l / 2.0 - DVec3::ONE).abs().max_element() < tolerance, "{offset}: {l}");
        }
        assert_eq!(disc.radiance_along(DVec3::new(0.0101, 1.0, 0.0)), None);
        assert_eq!(disc.radiance_along(DVec3::NEG_Y), None);
        assert_eq!(disc.radiance_along(DVec3::ZERO), None);
        // New moon: dark everywhere.
        let new = MoonDisc {
            sun_direction: DVec3::Y,
            ..disc
        };
        assert_eq!(new.radiance_along(DVec3::Y), Some(DVec3::ZERO));
        let bad = MoonDisc {
            direction: DVec3::NAN,
            ..disc
        };
        assert!(!bad.is_valid() && bad.radiance_along(DVec3::Y).is_none());
        assert!(NightLayer::default().stars.is_empty() && NightLayer::default().moon.is_none());
    }
}
