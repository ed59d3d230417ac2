//! The wind: a rigid rotation of a layer's pattern about the planet centre.

use std::f64::consts::TAU;

use glam::{DQuat, DVec3};

use super::super::Planet;

/// The rotation from the planet frame into a layer's pattern frame after the wind `wind_mps`
/// (`[east, north]`, m/s, at `reference_point`) has blown for `seconds`: the value of
/// [`CloudLayer::drift`](super::CloudLayer::drift).
///
/// The pattern turns rigidly about the planet centre so that at `reference_point` (planet frame,
/// metres; usually the camera's position) it moves with velocity `v = east·E + north·N`, `E` and
/// `N` the geodetic east and north there (at a pole, where east is undefined, `E` is the planet
/// frame's +y turned into the tangent plane, as in [`Planet::posed_at`]): about the axis
/// `up × v / |up × v|` by the angle `|v| · seconds / |reference_point|`, computed in `f64` and
/// reduced modulo 2π so that a time-lapse years long keeps its precision. The pattern point that
/// sits at `p` at time 0 sits at `carry · p` after `seconds`, so the planet point `p` sees the
/// pattern point `carry⁻¹ · p`: this function returns `carry⁻¹`. Far from `reference_point` the
/// wind is that rotation's (the same angular velocity), not `wind_mps` in the local east/north.
///
/// No wind, no time, or `reference_point` at the centre: the identity.
pub fn wind_drift(planet: &Planet, reference_point: DVec3, wind_mps: [f64; 2], seconds: f64) -> DQuat {
    let radius = reference_point.length();
    if radius == 0.0 || !radius.is_finite() {
        return DQuat::IDENTITY;
    }
    let up = planet.up(reference_point);
    let east = DVec3::Z.cross(up).try_normalize().unwrap_or(DVec3::Y);
    let north = up.cross(east);
    let velocity = east * wind_mps[0] + north * wind_mps[1];
    let speed = velocity.length();
    let Some(axis) = up.cross(velocity).try_normalize() else {
        return DQuat::IDENTITY;
    };
    // The distance travelled over the radius, in turns first so that the reduction is exact.
    let turns = (speed * seconds / radius / TAU).rem_euclid(1.0);
    if !turns.is_finite() {
        return DQuat::IDENTITY;
    }
    DQuat::from_axis_angle(axis, -turns * TAU)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::clouds::{CloudKind, CloudLayer};

    fn earth() -> Planet {
        Planet::sphere(6_371_000.0, 100_000.0)
    }

    #[test]
    fn no_wind_or_no_time_is_the_identity() {
        let p = earth().surface_point(0.5, 1.0);
        assert_eq!(wind_drift(&earth(), p, [0.0, 0.0], 1e6), DQuat::IDENTITY);
        let q = wind_drift(&earth(), p, [10.0, 3.0], 0.0);
        assert!(q.abs_diff_eq(DQuat::IDENTITY, 1e-15) || q.abs_diff_eq(-DQuat::IDENTITY, 1e-15));
        assert_eq!(wind_drift(&earth(), DVec3::ZERO, [10.0, 0.0], 1.0), DQuat::IDENTITY);
    }

    #[test]
    fn the_reference_point_moves_with_the_wind() {
        let planet = earth();
        let (lat, lon) = (0.7_f64, -1.2_f64);
        let p = planet.surface_point(lat, lon);
        let up = planet.up(p);
        let east = DVec3::Z.cross(up).normalize();
        let north = up.cross(east);
        let wind = [12.0, -5.0];
        let v = east * wind[0] + north * wind[1];
        // After a second the pattern seen at p + v·1 s is what p saw at 0: carry · p ≈ p + v.
        let drift = wind_drift(&planet, p, wind, 1.0);
        let carried = drift.inverse() * p;
        assert!((carried - (p + v)).length() < 1e-4, "{}", (carried - (p + v)).length());
        // After an hour, along the great circle: 46.8 km from p, as far as |v|·t.
        let t = 3600.0;
        let carried = wind_drift(&planet, p, wind, t).inverse() * p;
        let arc = p.angle_between(carried) * p.length();
        assert!((arc - v.length() * t).abs() < 1e-6, "{arc}");
        // At the start it heads along v.
        assert!((carried - p).normalize().dot(v.normalize()) > 0.999);
    }

    #[test]
    fn the_pattern_carried_by_the_wind_is_the_pattern_at_the_start() {
        let planet = earth();
        let mut cloudy = 0;
        for kind in [CloudKind::Cumulus, CloudKind::Cirrus] {
            let mut layer = CloudLayer::new(1000.0, 3000.0, 0.6, 0.05, kind);
            layer.seed = 9;
            for (lat, lon, wind, t) in [(0.3, 0.2, [10.0, 0.0], 600.0), (-1.1, 2.9, [-3.0, 25.0], 7200.0)] {
                let reference = planet.surface_point(lat, lon);
                let mut later = layer.clone();
                later.drift = wind_drift(&planet, reference, wind, t);
                let carry = later.drift.inverse();
                // The columns around the reference point (10 km across) at 20 altitudes: where
                // the wind has carried them, the later layer shows what the first showed.
                for i in 0..200 {
                    let offset = DVec3::new(f64::from(i % 7) - 3.0, f64::from(i % 11) - 5.0, f64::from(i % 13) - 6.0);
                    let column = (reference + offset * 1_000.0).normalize();
                    let h = 1000.0 + 10.0 * f64::from(i);
                    let at_start = layer.density_at_altitude(column * (planet.radii.x + h), h);
                    let after = later.density_at_altitude(carry * column * (planet.radii.x + h), h);
                    assert!(
                        (at_start - after).abs() < 1e-9 * layer.density_per_m,
                        "{at_start} vs {after}"
                    );
                    cloudy += usize::from(at_start > 0.0);
                }
            }
        }
        assert!(cloudy > 50, "{cloudy}");
    }

    #[test]
    fn a_century_of_wind_keeps_its_precision() {
        let planet = earth();
        let p = planet.surface_point(0.1, 0.2);
        let wind = [30.0, 0.0];
        let day = 86_400.0;
        // A century and a day is a century, then a day: the same axis, the angles add (modulo
        // whole turns) to within a millimetre on the ground.
        let century = 100.0 * 365.25 * day;
        let at_once = wind_drift(&planet, p, wind, century + day).inverse() * p;
        let in_steps =
            wind_drift(&planet, p, wind, day).inverse() * (wind_drift(&planet, p, wind, century).inverse() * p);
        assert!(
            (at_once - in_steps).length() < 1e-3,
            "{}",
            (at_once - in_steps).length()
        );
    }
}
