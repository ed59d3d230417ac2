//! The heading/pitch/forward-speed fly camera of NeHe lesson 44 (`glCamera`).
//!
//! Keys: W/S pitch, A/D turn, speed up and slow down while held, stop (the viewer's Z/C/X set a
//! constant forward or backward speed or stop, as the lesson's text says). Rates are per second
//! (the lesson used per-frame steps) so motion does not depend on the frame rate.

use glam::DVec3;

use firmament_core::camera::{Camera, direction_from_heading_elevation, orientation_from_heading_pitch_roll};

/// Largest pitch magnitude, radians (89.9°): looking straight up or down would flip the view.
pub(crate) const MAX_PITCH: f64 = 89.9 * std::f64::consts::PI / 180.0;

/// A camera that flies along its view direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FlyController {
    /// Position, metres, world frame.
    pub(crate) position: DVec3,
    /// Heading from north, clockwise, radians, in [0, 2π).
    pub(crate) heading: f64,
    /// Pitch above the horizon, radians, in [-`MAX_PITCH`, `MAX_PITCH`].
    pub(crate) pitch: f64,
    /// Forward speed, m/s (negative flies backwards).
    pub(crate) speed: f64,
    /// Largest turn rate, rad/s.
    pub(crate) max_heading_rate: f64,
    /// Largest pitch rate, rad/s.
    pub(crate) max_pitch_rate: f64,
    /// Largest speed magnitude, m/s.
    pub(crate) max_speed: f64,
    /// Speed change per second while a speed key is held, m/s².
    pub(crate) acceleration: f64,
}

/// The keys of NeHe lesson 44's camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ControllerKey {
    /// A: turn left.
    TurnLeft,
    /// D: turn right.
    TurnRight,
    /// W: pitch up.
    PitchUp,
    /// S: pitch down.
    PitchDown,
    /// Z: speed up.
    SpeedUp,
    /// C: slow down.
    SlowDown,
    /// X: stop.
    Stop,
}

impl FlyController {
    /// A stopped controller at `position` looking along `heading` and `pitch` (radians).
    pub(crate) fn new(position: DVec3, heading: f64, pitch: f64) -> Self {
        let mut c = Self {
            position,
            heading: 0.0,
            pitch: 0.0,
            speed: 0.0,
            max_heading_rate: 90f64.to_radians(),
            max_pitch_rate: 60f64.to_radians(),
            max_speed: 100.0,
            acceleration: 20.0,
        };
        c.turn(heading, pitch);
        c
    }

    /// The unit view direction.
    pub(crate) fn forward(&self) -> DVec3 {
        direction_from_heading_elevation(self.heading, self.pitch)
    }

    /// Turns by the given angles (radians), wrapping the heading and clamping the pitch.
    pub(crate) fn turn(&mut self, heading_delta: f64, pitch_delta: f64) {
        if heading_delta.is_finite() {
            self.heading = (self.heading + heading_delta).rem_euclid(std::f64::consts::TAU);
            if self.heading >= std::f64::consts::TAU {
                self.heading = 0.0; // rem_euclid can round up to the modulus
            }
        }
        if pitch_delta.is_finite() {
            self.pitch = (self.pitch + pitch_delta).clamp(-MAX_PITCH, MAX_PITCH);
        }
    }

    /// Changes the speed by `delta` m/s, clamped to ±`max_speed`.
    pub(crate) fn change_velocity(&mut self, delta: f64) {
        if delta.is_finite() {
            self.speed = (self.speed + delta).clamp(-self.max_speed, self.max_speed);
        }
    }

    /// Stops.
    pub(crate) fn stop(&mut self) {
        self.speed = 0.0;
    }

    /// Reacts to a key held for `dt` seconds.
    pub(crate) fn apply_key(&mut self, key: ControllerKey, dt: f64) {
        let dt = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        match key {
            ControllerKey::TurnLeft => self.turn(-self.max_heading_rate * dt, 0.0),
            ControllerKey::TurnRight => self.turn(self.max_heading_rate * dt, 0.0),
            ControllerKey::PitchUp => self.turn(0.0, self.max_pitch_rate * dt),
            ControllerKey::PitchDown => self.turn(0.0, -self.max_pitch_rate * dt),
            ControllerKey::SpeedUp => self.change_velocity(self.acceleration * dt),
            ControllerKey::SlowDown => self.change_velocity(-self.acceleration * dt),
            ControllerKey::Stop => self.stop(),
        }
    }

    /// Moves along the view direction for `dt` seconds at the current speed.
    pub(crate) fn update(&mut self, dt: f64) {
        if dt.is_finite() && dt > 0.0 {
            self.position += self.forward() * (self.speed * dt);
        }
    }

    /// `base` with this controller's position and orientation (fov, aspect, planes kept).
    pub(crate) fn camera(&self, base: &Camera) -> Camera {
        Camera {
            position: self.position,
            orientation: orientation_from_heading_pitch_roll(self.heading, self.pitch, 0.0),
            ..*base
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flies_speed_times_time_along_forward() {
        let mut c = FlyController::new(DVec3::new(1.0, 2.0, 3.0), 0.7, 0.3);
        c.change_velocity(12.0);
        c.update(2.5);
        let expected = DVec3::new(1.0, 2.0, 3.0) + direction_from_heading_elevation(0.7, 0.3) * 30.0;
        assert!((c.position - expected).length() < 1e-12);
        let cam = c.camera(&Camera::default());
        assert!((cam.forward() - c.forward()).length() < 1e-12);
        assert_eq!(cam.fov_y, Camera::default().fov_y);
    }

    #[test]
    fn heading_wraps_pitch_clamps_speed_limits() {
        let mut c = FlyController::new(DVec3::ZERO, 0.0, 0.0);
        c.turn(-0.5, 0.0);
        assert!((c.heading - (std::f64::consts::TAU - 0.5)).abs() < 1e-12);
        c.turn(7.0 * std::f64::consts::TAU + 0.5, 0.0);
        assert!(c.heading.abs() < 1e-9 || (c.heading - std::f64::consts::TAU).abs() < 1e-9);
        c.turn(0.0, 10.0);
        assert_eq!(c.pitch, MAX_PITCH);
        c.turn(0.0, -20.0);
        assert_eq!(c.pitch, -MAX_PITCH);
        c.change_velocity(1e9);
        assert_eq!(c.speed, c.max_speed);
        c.turn(f64::NAN, f64::INFINITY);
        assert_eq!(c.pitch, -MAX_PITCH);
    }

    #[test]
    fn keys_follow_the_lesson() {
        let mut c = FlyController::new(DVec3::ZERO, 1.0, 0.0);
        c.apply_key(ControllerKey::TurnRight, 1.0);
        assert!((c.heading - (1.0 + c.max_heading_rate)).abs() < 1e-12);
        c.apply_key(ControllerKey::TurnLeft, 1.0);
        assert!((c.heading - 1.0).abs() < 1e-12);
        c.apply_key(ControllerKey::PitchUp, 0.5);
        assert!((c.pitch - c.max_pitch_rate * 0.5).abs() < 1e-12);
        c.apply_key(ControllerKey::PitchDown, 0.5);
        assert!(c.pitch.abs() < 1e-12);
        c.apply_key(ControllerKey::SpeedUp, 1.0);
        assert_eq!(c.speed, c.acceleration);
        c.apply_key(ControllerKey::SlowDown, 0.25);
        assert_eq!(c.speed, c.acceleration * 0.75);
        c.apply_key(ControllerKey::Stop, 0.0);
        assert_eq!(c.speed, 0.0);
    }
}
