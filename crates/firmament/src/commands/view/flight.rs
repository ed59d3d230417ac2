//! The interactive viewer's camera controller: mouse look with WASD/QE flying, or NeHe lesson 44's
//! keys ([`FlyController`]), at a speed that scales with altitude, and "go to" poses for a ground
//! and an orbit view of a planet.
//!
//! Everything is in the world frame (East-North-Up, +Z up, metres); heading is from north (+Y)
//! clockwise towards east (+X) and pitch is above the world's horizontal plane, both radians. The
//! camera never rolls. Times are seconds, speeds metres per second.
//!
//! # Speed
//! [`FlightController::speed`] is `speed_scale · (BASE_SPEED + ALTITUDE_RATE · h)` for altitude `h`
//! (clamped to `[0, MAX_ALTITUDE]`, 0 when not finite): a few m/s on the street, and far from the
//! ground the altitude grows by `ALTITUDE_RATE` = 50 % of itself per second when flying straight
//! up, so a decade of altitude takes ~4.6 s — street to orbit to 100 AU (where the speed is
//! ~7.5e12 m/s) in about a minute, or a tenth of that with [`FlightAction::Faster`] held.

use glam::{DVec2, DVec3};

use super::controller::{ControllerKey, FlyController, MAX_PITCH};
use firmament_core::atmosphere::Planet;
use firmament_core::camera::{Camera, direction_from_heading_elevation, orientation_from_heading_pitch_roll};

/// Speed at zero altitude with `speed_scale` 1, m/s.
pub(crate) const BASE_SPEED: f64 = 4.0;
/// How the speed grows with altitude, (m/s) per metre of altitude, i.e. 1/s.
pub(crate) const ALTITUDE_RATE: f64 = 0.5;
/// The altitude the speed rule saturates at, metres (~100 light years), so speeds stay finite.
pub(crate) const MAX_ALTITUDE: f64 = 1e18;
/// Speed multiplier while [`FlightAction::Faster`] is held, dimensionless.
pub(crate) const BOOST: f64 = 10.0;
/// Speed multiplier while [`FlightAction::Slower`] is held, dimensionless.
pub(crate) const CREEP: f64 = 0.1;
/// Factor one wheel notch multiplies (up) or divides (down) `speed_scale` by, dimensionless.
pub(crate) const WHEEL_STEP: f64 = 1.25;
/// Smallest `speed_scale`, dimensionless.
pub(crate) const MIN_SPEED_SCALE: f64 = 1e-3;
/// Largest `speed_scale`, dimensionless.
pub(crate) const MAX_SPEED_SCALE: f64 = 1e3;
/// Default mouse-look sensitivity, radians per pixel of mouse motion.
pub(crate) const DEFAULT_LOOK_SENSITIVITY: f64 = 0.003;
/// In NeHe mode, the controller's speed-up/slow-down acceleration as a fraction of the top speed
/// per second, 1/s: full speed in two seconds of holding the key (the viewer sets constant speeds
/// with Z/C/X instead).
pub(crate) const NEHE_ACCELERATION_RATE: f64 = 0.5;
/// Eye height of [`goto_ground`] above the surface, metres.
pub(crate) const GROUND_HEIGHT: f64 = 2.0;
/// Pitch of [`goto_ground`] above the local horizon, radians (5°).
pub(crate) const GROUND_PITCH: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// Angle of [`goto_orbit`]'s viewpoint from the zenith of the surface point under the world
/// origin, towards the south, seen from the planet's centre, radians (45°).
pub(crate) const ORBIT_ZENITH_ANGLE: f64 = std::f64::consts::FRAC_PI_4;
/// Smallest distance of [`goto_orbit`] from the planet's centre, in equatorial radii.
pub(crate) const MIN_ORBIT_RADII: f64 = 1.1;
/// Distance [`goto_orbit`] uses when given a non-finite one, in equatorial radii.
pub(crate) const DEFAULT_ORBIT_RADII: f64 = 3.0;

/// Which controls drive the camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum FlightMode {
    /// Mouse look; WASD flies forward/left/back/right, Q/E down/up, at the altitude's speed.
    #[default]
    Free,
    /// NeHe lesson 44: W/S pitch, A/D turn; its forward speed is `nehe.speed` (the viewer's Z,
    /// C and X set it to a constant forward or backward speed or stop it, as the lesson does).
    NeHe,
}

/// What a held key means to the controller; the viewer maps its keys to these.
///
/// The movement actions act in [`FlightMode::Free`], the [`FlightAction::NeHe`] ones in
/// [`FlightMode::NeHe`]; each is ignored in the other mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FlightAction {
    /// Fly along the view direction.
    Forward,
    /// Fly against the view direction.
    Back,
    /// Fly to the left of the image (horizontally).
    Left,
    /// Fly to the right of the image (horizontally).
    Right,
    /// Fly up, along the world's +Z.
    Up,
    /// Fly down, along the world's −Z.
    Down,
    /// While held, fly [`BOOST`] times faster.
    Faster,
    /// While held, fly [`CREEP`] times as fast.
    Slower,
    /// A key of NeHe lesson 44's camera.
    NeHe(ControllerKey),
}

/// NeHe lesson 44's Z, C and X: "'Z' gives the camera a constant forward velocity, 'C' a
/// constant backward velocity and 'X' will stop the camera" ([`FlightController::set_nehe_velocity`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NeHeVelocity {
    /// Z: a constant forward speed.
    Forward,
    /// C: a constant backward speed.
    Backward,
    /// X: stopped.
    Stop,
}

impl NeHeVelocity {
    /// The forward speed, m/s, for a flying speed of `speed` m/s.
    pub(crate) fn speed(self, speed: f64) -> f64 {
        match self {
            Self::Forward => speed,
            Self::Backward => -speed,
            Self::Stop => 0.0,
        }
    }
}

/// The viewer's camera controller (see the module docs for frames, units and the speed rule).
///
/// `position`, `heading` and `pitch` are the state in both modes; `nehe` carries NeHe mode's
/// forward speed and rates and is kept in step with them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FlightController {
    /// Which controls are active.
    pub(crate) mode: FlightMode,
    /// Eye position, metres, world frame.
    pub(crate) position: DVec3,
    /// Heading from north (+Y), clockwise towards east (+X), radians, in [0, 2π).
    pub(crate) heading: f64,
    /// Pitch above the world's horizontal plane, radians, in [−`MAX_PITCH`, `MAX_PITCH`].
    pub(crate) pitch: f64,
    /// Multiplier of the altitude speed rule set by the mouse wheel, dimensionless, in
    /// [`MIN_SPEED_SCALE`, `MAX_SPEED_SCALE`].
    pub(crate) speed_scale: f64,
    /// Mouse-look sensitivity, radians per pixel of mouse motion.
    pub(crate) look_sensitivity: f64,
    /// NeHe mode's controller: its forward speed (m/s) persists between updates; its position,
    /// heading, pitch, top speed and acceleration are set from this controller on each update.
    pub(crate) nehe: FlyController,
}

impl FlightController {
    /// A controller in [`FlightMode::Free`] at `position` (metres) looking along `heading` and
    /// `pitch` (radians; the heading is wrapped and the pitch clamped).
    pub(crate) fn new(position: DVec3, heading: f64, pitch: f64) -> Self {
        let mut c = Self {
            mode: FlightMode::Free,
            position,
            heading: 0.0,
            pitch: 0.0,
            speed_scale: 1.0,
            look_sensitivity: DEFAULT_LOOK_SENSITIVITY,
            nehe: FlyController::new(position, 0.0, 0.0),
        };
        c.turn(heading, pitch);
        c.sync_nehe();
        c
    }

    /// A controller at `camera`'s position and looking its way: heading and pitch from its
    /// forward vector (the heading from its up vector when looking straight up or down); any roll
    /// is dropped.
    pub(crate) fn from_camera(camera: &Camera) -> Self {
        let forward = camera.forward();
        let pitch = forward.z.clamp(-1.0, 1.0).asin();
        // For a camera without roll, forward_h·cos p − up_h·sin p is the unit heading vector
        // (the horizontal parts of forward and up are cos p and −sin p times it), well defined at
        // any pitch.
        let up = camera.up();
        let (sp, cp) = pitch.sin_cos();
        let h = DVec2::new(forward.x * cp - up.x * sp, forward.y * cp - up.y * sp);
        let heading = if h.length_squared() > 0.0 { h.x.atan2(h.y) } else { 0.0 };
        Self::new(camera.position, heading, pitch)
    }

    /// `base` with this controller's position and orientation (fov, aspect and planes kept).
    pub(crate) fn camera(&self, base: &Camera) -> Camera {
        Camera {
            position: self.position,
            orientation: orientation_from_heading_pitch_roll(self.heading, self.pitch, 0.0),
            ..*base
        }
    }

    /// The unit view direction, world frame.
    pub(crate) fn forward(&self) -> DVec3 {
        direction_from_heading_elevation(self.heading, self.pitch)
    }

    /// The unit horizontal direction to the right of the image, world frame.
    pub(crate) fn right(&self) -> DVec3 {
        let (sh, ch) = self.heading.sin_cos();
        DVec3::new(ch, -sh, 0.0)
    }

    /// Switches to `mode`, keeping position, heading and pitch; NeHe's forward speed starts at 0.
    pub(crate) fn set_mode(&mut self, mode: FlightMode) {
        if mode != self.mode {
            self.mode = mode;
            self.nehe.stop();
            self.sync_nehe();
        }
    }

    /// Switches between [`FlightMode::Free`] and [`FlightMode::NeHe`] (see [`Self::set_mode`]).
    pub(crate) fn toggle_mode(&mut self) {
        self.set_mode(match self.mode {
            FlightMode::Free => FlightMode::NeHe,
            FlightMode::NeHe => FlightMode::Free,
        });
    }

    /// Mouse look: `delta_pixels` is the mouse motion in window coordinates (+x right, +y down);
    /// moving right turns right (heading grows), moving down looks down. Works in both modes.
    pub(crate) fn look(&mut self, delta_pixels: DVec2) {
        let k = self.look_sensitivity;
        self.turn(delta_pixels.x * k, -delta_pixels.y * k);
        self.sync_nehe();
    }

    /// The mouse wheel: each notch up (positive) multiplies `speed_scale` by [`WHEEL_STEP`], each
    /// notch down divides it, within [`MIN_SPEED_SCALE`, `MAX_SPEED_SCALE`]. Fractional notches
    /// (touchpads) scale by the matching power; non-finite ones are ignored.
    pub(crate) fn wheel(&mut self, notches: f64) {
        if notches.is_finite() {
            let scale = self.clamped_speed_scale() * WHEEL_STEP.powf(notches);
            self.speed_scale = scale.clamp(MIN_SPEED_SCALE, MAX_SPEED_SCALE);
        }
    }

    /// NeHe mode's forward speed from now on: `velocity` at the flying speed at `altitude`
    /// metres ([`Self::speed`]) — kept, not a held acceleration.
    pub(crate) fn set_nehe_velocity(&mut self, velocity: NeHeVelocity, altitude: f64) {
        self.nehe.speed = velocity.speed(self.speed(altitude));
    }

    /// Flying speed at `altitude` metres, m/s: `speed_scale · (BASE_SPEED + ALTITUDE_RATE · h)`
    /// with `h` the altitude clamped to [0, `MAX_ALTITUDE`] (0 when not finite). Always finite and
    /// positive.
    pub(crate) fn speed(&self, altitude: f64) -> f64 {
        let h = if altitude.is_finite() {
            altitude.clamp(0.0, MAX_ALTITUDE)
        } else {
            0.0
        };
        self.clamped_speed_scale() * (BASE_SPEED + ALTITUDE_RATE * h)
    }

    /// Advances `dt` seconds with the `held` actions, at `altitude` metres (the viewer's altitude
    /// above its planet, or above z = 0 for a flat scene).
    ///
    /// Free mode moves along the normalised sum of the held directions (forward, the horizontal
    /// right vector, world +Z) at [`Self::speed`], times [`BOOST`] / [`CREEP`] while
    /// [`FlightAction::Faster`] / [`FlightAction::Slower`] is held. NeHe mode sets the
    /// [`FlyController`]'s top speed to [`Self::speed`] (its current speed clamped to it, so it
    /// slows on the way down) and its acceleration to [`NEHE_ACCELERATION_RATE`] times that, feeds
    /// it the held NeHe keys, then lets it fly. A non-finite or non-positive `dt` does nothing; a
    /// step that would make the position non-finite is dropped.
    pub(crate) fn update(&mut self, held: &[FlightAction], altitude: f64, dt: f64) {
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        let speed = self.speed(altitude);
        match self.mode {
            FlightMode::Free => {
                let (forward, right) = (self.forward(), self.right());
                let mut direction = DVec3::ZERO;
                let mut factor = 1.0;
                for action in held {
                    match action {
                        FlightAction::Forward => direction += forward,
                        FlightAction::Back => direction -= forward,
                        FlightAction::Right => direction += right,
                        FlightAction::Left => direction -= right,
                        FlightAction::Up => direction += DVec3::Z,
                        FlightAction::Down => direction -= DVec3::Z,
                        FlightAction::Faster => factor *= BOOST,
                        FlightAction::Slower => factor *= CREEP,
                        FlightAction::NeHe(_) => {}
                    }
                }
                if let Some(direction) = direction.try_normalize() {
                    let next = self.position + direction * (speed * factor * dt);
                    if next.is_finite() {
                        self.position = next;
                    }
                }
                self.sync_nehe();
            }
            FlightMode::NeHe => {
                self.sync_nehe();
                self.nehe.max_speed = speed;
                self.nehe.acceleration = speed * NEHE_ACCELERATION_RATE;
                self.nehe.speed = self.nehe.speed.clamp(-speed, speed);
                for action in held {
                    if let FlightAction::NeHe(key) = action {
                        self.nehe.apply_key(*key, dt);
                    }
                }
                let before = self.nehe.position;
                self.nehe.update(dt);
                if !self.nehe.position.is_finite() {
                    self.nehe.position = before;
                }
                self.position = self.nehe.position;
                self.heading = self.nehe.heading;
                self.pitch = self.nehe.pitch;
            }
        }
    }

    /// Sets position, heading and pitch, wrapping the heading and clamping the pitch; NeHe's
    /// forward speed is zeroed.
    pub(crate) fn set_pose(&mut self, position: DVec3, heading: f64, pitch: f64) {
        self.position = position;
        self.heading = 0.0;
        self.pitch = 0.0;
        self.turn(heading, pitch);
        self.nehe.stop();
        self.sync_nehe();
    }

    /// Goes to [`goto_ground`]'s view of `planet`, keeping the current heading.
    pub(crate) fn go_to_ground(&mut self, planet: &Planet) {
        let (position, heading, pitch) = goto_ground(planet, self.heading);
        self.set_pose(position, heading, pitch);
    }

    /// Goes to [`goto_orbit`]'s view of `planet` from `distance_in_radii` equatorial radii.
    pub(crate) fn go_to_orbit(&mut self, planet: &Planet, distance_in_radii: f64) {
        let (position, heading, pitch) = goto_orbit(planet, distance_in_radii);
        self.set_pose(position, heading, pitch);
    }

    /// The eye's geodetic altitude above `planet` (posed in the world frame), metres.
    pub(crate) fn altitude_above(&self, planet: &Planet) -> f64 {
        altitude_above(planet, self.position)
    }

    /// Turns by the given angles (radians): the heading wraps to [0, 2π), the pitch clamps to
    /// ±`MAX_PITCH`; non-finite angles are ignored.
    fn turn(&mut self, heading_delta: f64, pitch_delta: f64) {
        if heading_delta.is_finite() {
            let heading = (self.heading + heading_delta).rem_euclid(std::f64::consts::TAU);
            // rem_euclid can round up to the modulus.
            self.heading = if heading >= std::f64::consts::TAU { 0.0 } else { heading };
        }
        if pitch_delta.is_finite() {
            self.pitch = (self.pitch + pitch_delta).clamp(-MAX_PITCH, MAX_PITCH);
        }
    }

    /// `speed_scale` within its bounds (1 when not finite).
    fn clamped_speed_scale(&self) -> f64 {
        if self.speed_scale.is_finite() {
            self.speed_scale.clamp(MIN_SPEED_SCALE, MAX_SPEED_SCALE)
        } else {
            1.0
        }
    }

    /// Copies position, heading and pitch into `nehe`.
    fn sync_nehe(&mut self) {
        self.nehe.position = self.position;
        self.nehe.heading = self.heading;
        self.nehe.pitch = self.pitch;
    }
}

impl Default for FlightController {
    /// At the origin, looking north along the horizon, in [`FlightMode::Free`].
    fn default() -> Self {
        Self::new(DVec3::ZERO, 0.0, 0.0)
    }
}

/// The geodetic altitude of world-frame `position` above `planet` (posed in the world frame),
/// metres (negative inside).
pub(crate) fn altitude_above(planet: &Planet, position: DVec3) -> f64 {
    planet.altitude(planet.to_planet_frame(position))
}

/// The surface point under the world origin (its foot along the surface normal) and the outward
/// normal there, both in the world frame.
fn origin_site(planet: &Planet) -> (DVec3, DVec3) {
    let origin = planet.to_planet_frame(DVec3::ZERO);
    let up = planet.up(origin);
    let foot = origin - up * planet.altitude(origin);
    let to_world = planet.orientation.normalize();
    (planet.center + to_world * foot, to_world * up)
}

/// Heading and pitch (radians, world frame) of a direction; the pitch is clamped to ±`MAX_PITCH`
/// and the heading is 0 for a vertical direction.
fn heading_pitch_of(direction: DVec3) -> (f64, f64) {
    let d = direction.normalize_or_zero();
    let heading = if d.x == 0.0 && d.y == 0.0 {
        0.0
    } else {
        d.x.atan2(d.y).rem_euclid(std::f64::consts::TAU)
    };
    let pitch = d.z.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH);
    (heading, pitch)
}

/// The unit tangent at `up` nearest the world-frame direction `towards` (any tangent when
/// `towards` is along `up`).
fn tangent_towards(up: DVec3, towards: DVec3) -> DVec3 {
    (towards - up * towards.dot(up))
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector())
}

/// A ground view of `planet` (posed in the world frame): the eye [`GROUND_HEIGHT`] above the
/// surface point under the world origin, looking [`GROUND_PITCH`] above the local horizon
/// towards `heading` (radians, world frame). Returns `(position in metres, heading, pitch)`, world
/// frame.
///
/// For a planet posed at the world origin ([`Planet::posed_at`]) the local horizon is the world's
/// horizontal plane; otherwise the direction is turned into heading and pitch in the world frame,
/// and the camera, which keeps world +Z up, sees the horizon tilted.
pub(crate) fn goto_ground(planet: &Planet, heading: f64) -> (DVec3, f64, f64) {
    let heading = if heading.is_finite() { heading } else { 0.0 };
    let (site, up) = origin_site(planet);
    let position = site + up * GROUND_HEIGHT;
    let level = tangent_towards(up, direction_from_heading_elevation(heading, 0.0));
    let (sp, cp) = GROUND_PITCH.sin_cos();
    let (heading, pitch) = heading_pitch_of(level * cp + up * sp);
    (position, heading, pitch)
}

/// An orbit view of `planet` (posed in the world frame): the eye `distance_in_radii` equatorial
/// radii from the planet's centre (at least [`MIN_ORBIT_RADII`]; [`DEFAULT_ORBIT_RADII`] when not
/// finite), [`ORBIT_ZENITH_ANGLE`] south of the zenith of the surface point under the world origin,
/// looking at the centre. Returns `(position in metres, heading, pitch)`, world frame; the centre
/// is in the middle of the view (within the 0.1° of the pitch clamp).
pub(crate) fn goto_orbit(planet: &Planet, distance_in_radii: f64) -> (DVec3, f64, f64) {
    let radii = if distance_in_radii.is_finite() {
        distance_in_radii.max(MIN_ORBIT_RADII)
    } else {
        DEFAULT_ORBIT_RADII
    };
    let distance = radii * planet.radii.x.max(planet.radii.y);
    let (_, up) = origin_site(planet);
    let south = tangent_towards(up, DVec3::NEG_Y);
    let (sa, ca) = ORBIT_ZENITH_ANGLE.sin_cos();
    let position = planet.center + (up * ca + south * sa) * distance;
    let (heading, pitch) = heading_pitch_of(planet.center - position);
    (position, heading, pitch)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3, tolerance: f64) -> bool {
        (a - b).length() <= tolerance
    }

    fn earth_at_45() -> Planet {
        Planet::spheroid(6_378_137.0, 6_356_752.3, 60_000.0).posed_at(45f64.to_radians(), 0.3)
    }

    #[test]
    fn nehe_velocity_is_kept_at_the_altitude_speed() {
        let mut c = FlightController::new(DVec3::new(0.0, 0.0, 100.0), 0.0, 0.0);
        c.mode = FlightMode::NeHe;
        let speed = c.speed(100.0);
        c.set_nehe_velocity(NeHeVelocity::Forward, 100.0);
        assert_eq!(c.nehe.speed, speed);
        c.update(&[], 100.0, 0.5);
        assert_eq!(c.nehe.speed, speed, "no key held: the speed stays");
        c.set_nehe_velocity(NeHeVelocity::Backward, 100.0);
        assert_eq!(c.nehe.speed, -speed);
        c.set_nehe_velocity(NeHeVelocity::Stop, 100.0);
        assert_eq!(c.nehe.speed, 0.0);
    }

    #[test]
    fn from_camera_and_back() {
        for (h, p) in [
            (0.0, 0.0),
            (90.0, 10.0),
            (200.0, -30.0),
            (359.0, 80.0),
            (45.0, -89.9),
            (10.0, 89.9),
        ] {
            let (h, p) = (f64::to_radians(h), f64::to_radians(p));
            let base = Camera {
                fov_y: 0.7,
                near: 3.0,
                ..Camera::from_heading_pitch(DVec3::new(1.0, -2.0, 3e7), h, p)
            };
            let c = FlightController::from_camera(&base);
            assert!((c.heading - h).abs() < 1e-9, "{h} {}", c.heading);
            assert!((c.pitch - p).abs() < 1e-9);
            let cam = c.camera(&base);
            assert!(close(cam.forward(), base.forward(), 1e-12));
            assert!(close(cam.up(), base.up(), 1e-12));
            assert_eq!(cam.position, base.position);
            assert_eq!(
                (cam.fov_y, cam.near, cam.aspect, cam.far),
                (0.7, 3.0, base.aspect, base.far)
            );
        }
        // Straight down: the heading comes from the up vector, the pitch is clamped.
        let down = Camera::looking_at(DVec3::ZERO, DVec3::NEG_Z, DVec3::X).expect("valid");
        let c = FlightController::from_camera(&down);
        assert!((c.heading - 90f64.to_radians()).abs() < 1e-9, "{}", c.heading);
        assert_eq!(c.pitch, -MAX_PITCH);
    }

    #[test]
    fn wasd_and_qe_move_at_the_altitude_speed() {
        let start = DVec3::new(10.0, 20.0, 30.0);
        let c0 = FlightController::new(start, 0.8, 0.3);
        let (altitude, dt) = (1000.0, 0.25);
        let step = c0.speed(altitude) * dt;
        for (action, direction) in [
            (FlightAction::Forward, c0.forward()),
            (FlightAction::Back, -c0.forward()),
            (FlightAction::Right, c0.right()),
            (FlightAction::Left, -c0.right()),
            (FlightAction::Up, DVec3::Z),
            (FlightAction::Down, DVec3::NEG_Z),
        ] {
            let mut c = c0;
            c.update(&[action], altitude, dt);
            assert!(close(c.position, start + direction * step, 1e-9), "{action:?}");
            assert_eq!((c.heading, c.pitch), (c0.heading, c0.pitch));
        }
        // The right vector is horizontal and at right angles to forward.
        assert!(c0.right().z == 0.0 && c0.right().dot(c0.forward()).abs() < 1e-12);
        // Boost and creep; opposite keys cancel; diagonals are not faster.
        let mut c = c0;
        c.update(&[FlightAction::Forward, FlightAction::Faster], altitude, dt);
        assert!(close(c.position, start + c0.forward() * step * BOOST, 1e-9));
        let mut c = c0;
        c.update(&[FlightAction::Up, FlightAction::Slower], altitude, dt);
        assert!(close(c.position, start + DVec3::Z * step * CREEP, 1e-9));
        let mut c = c0;
        c.update(&[FlightAction::Forward, FlightAction::Back], altitude, dt);
        assert_eq!(c.position, start);
        let mut c = c0;
        c.update(&[FlightAction::Forward, FlightAction::Right], altitude, dt);
        assert!(((c.position - start).length() - step).abs() < 1e-9);
        // NeHe keys do nothing in free mode.
        let mut c = c0;
        c.update(&[FlightAction::NeHe(ControllerKey::TurnLeft)], altitude, dt);
        assert_eq!(c, c0);
    }

    #[test]
    fn bad_time_and_altitude_give_no_nan() {
        let c0 = FlightController::new(DVec3::new(1.0, 2.0, 3.0), 0.1, 0.2);
        for dt in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
            let mut c = c0;
            c.update(&[FlightAction::Forward], 10.0, dt);
            assert_eq!(c.position, c0.position);
        }
        for altitude in [f64::NAN, f64::NEG_INFINITY, f64::INFINITY, -5.0] {
            for mode in [FlightMode::Free, FlightMode::NeHe] {
                let mut c = c0;
                c.set_mode(mode);
                c.update(
                    &[FlightAction::Forward, FlightAction::NeHe(ControllerKey::SpeedUp)],
                    altitude,
                    0.5,
                );
                assert!(
                    c.position.is_finite() && c.position != c0.position,
                    "{altitude} {mode:?}"
                );
            }
        }
        let mut c = c0;
        c.speed_scale = f64::NAN;
        assert_eq!(c.speed(0.0), BASE_SPEED);
        c.update(&[FlightAction::Forward, FlightAction::Faster], 1e300, 1e300);
        assert!(c.position.is_finite());
    }

    #[test]
    fn speed_grows_with_altitude() {
        let c = FlightController::default();
        let street = c.speed(GROUND_HEIGHT);
        assert!((1.0..10.0).contains(&street), "{street}");
        assert!(c.speed(400e3) > 1e5);
        let au100 = c.speed(1.5e13);
        assert!(au100 > 1e12 && au100 < 1e14, "{au100}");
        let mut last = 0.0;
        for e in 0..=18 {
            let s = c.speed(10f64.powi(e));
            assert!(s > last);
            last = s;
        }
        for altitude in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1e9] {
            let s = c.speed(altitude);
            assert!(s.is_finite() && s > 0.0, "{altitude}: {s}");
        }
        assert_eq!(c.speed(-1e9), BASE_SPEED);
    }

    #[test]
    fn mouse_look_signs_and_wheel_clamps() {
        let mut c = FlightController::new(DVec3::ZERO, 1.0, 0.0);
        c.look(DVec2::new(10.0, 0.0));
        assert!((c.heading - (1.0 + 10.0 * c.look_sensitivity)).abs() < 1e-12);
        c.look(DVec2::new(0.0, 10.0));
        assert!((c.pitch + 10.0 * c.look_sensitivity).abs() < 1e-12);
        c.look(DVec2::new(0.0, -1e6));
        assert_eq!(c.pitch, MAX_PITCH);
        c.look(DVec2::new(-1e6 - 0.5, f64::NAN));
        assert!((0.0..std::f64::consts::TAU).contains(&c.heading));
        assert_eq!(c.pitch, MAX_PITCH);

        let mut c = FlightController::default();
        c.wheel(1.0);
        assert!((c.speed_scale - WHEEL_STEP).abs() < 1e-12);
        c.wheel(-2.0);
        assert!((c.speed_scale - 1.0 / WHEEL_STEP).abs() < 1e-12);
        c.wheel(1e6);
        assert_eq!(c.speed_scale, MAX_SPEED_SCALE);
        c.wheel(-1e6);
        assert_eq!(c.speed_scale, MIN_SPEED_SCALE);
        c.wheel(f64::NAN);
        assert_eq!(c.speed_scale, MIN_SPEED_SCALE);
        assert!((c.speed(0.0) - MIN_SPEED_SCALE * BASE_SPEED).abs() < 1e-15);
    }

    #[test]
    fn nehe_mode_follows_the_fly_controller() {
        let altitude = 50.0;
        let mut c = FlightController::new(DVec3::new(5.0, 6.0, 7.0), 0.4, 0.1);
        c.set_mode(FlightMode::NeHe);
        let mut reference = FlyController::new(c.position, c.heading, c.pitch);
        reference.max_speed = c.speed(altitude);
        reference.acceleration = reference.max_speed * NEHE_ACCELERATION_RATE;
        let keys = [
            vec![ControllerKey::SpeedUp, ControllerKey::TurnRight],
            vec![ControllerKey::SpeedUp, ControllerKey::PitchUp],
            vec![],
            vec![ControllerKey::SlowDown, ControllerKey::TurnLeft],
        ];
        for frame in &keys {
            let held: Vec<FlightAction> = frame.iter().map(|k| FlightAction::NeHe(*k)).collect();
            // Free-mode actions are ignored in NeHe mode.
            let mut held_all = held.clone();
            held_all.extend([FlightAction::Forward, FlightAction::Up, FlightAction::Faster]);
            c.update(&held_all, altitude, 0.5);
            for k in frame {
                reference.apply_key(*k, 0.5);
            }
            reference.update(0.5);
            assert!(close(c.position, reference.position, 1e-9));
            assert!((c.heading - reference.heading).abs() < 1e-12);
            assert!((c.pitch - reference.pitch).abs() < 1e-12);
            assert_eq!(c.nehe.speed, reference.speed);
        }
        assert!(c.position != DVec3::new(5.0, 6.0, 7.0));
        // Mouse look works in NeHe mode too, and descending clamps the speed to the lower top speed.
        c.look(DVec2::new(100.0, 0.0));
        assert_eq!(c.nehe.heading, c.heading);
        c.nehe.speed = 1e9;
        c.update(&[], 0.0, 1e-3);
        assert_eq!(c.nehe.speed, c.speed(0.0));
    }

    #[test]
    fn switching_modes_keeps_the_pose() {
        let mut c = FlightController::new(DVec3::new(1.0, 2.0, 3.0), 2.0, -0.3);
        c.update(&[FlightAction::Forward], 100.0, 1.0);
        let (position, heading, pitch) = (c.position, c.heading, c.pitch);
        c.toggle_mode();
        assert_eq!(c.mode, FlightMode::NeHe);
        assert_eq!((c.position, c.heading, c.pitch), (position, heading, pitch));
        assert_eq!(
            (c.nehe.position, c.nehe.heading, c.nehe.pitch, c.nehe.speed),
            (position, heading, pitch, 0.0)
        );
        c.update(&[FlightAction::NeHe(ControllerKey::SpeedUp)], 100.0, 1.0);
        c.update(&[FlightAction::NeHe(ControllerKey::TurnLeft)], 100.0, 0.5);
        let (position, heading, pitch) = (c.position, c.heading, c.pitch);
        c.set_mode(FlightMode::Free);
        assert_eq!((c.position, c.heading, c.pitch), (position, heading, pitch));
        c.update(&[], 100.0, 1.0);
        assert_eq!(c.position, position);
        // Back in NeHe mode the controller starts stopped.
        c.set_mode(FlightMode::NeHe);
        c.update(&[], 100.0, 1.0);
        assert_eq!(c.position, position);
    }

    #[test]
    fn go_to_ground_stands_two_metres_up_looking_at_the_horizon() {
        let planet = earth_at_45();
        let mut c = FlightController::new(DVec3::new(1e9, 0.0, 0.0), 1.2, -1.0);
        c.set_mode(FlightMode::NeHe);
        c.nehe.speed = 50.0;
        c.go_to_ground(&planet);
        assert!(
            (c.altitude_above(&planet) - GROUND_HEIGHT).abs() < 1e-6,
            "{}",
            c.altitude_above(&planet)
        );
        assert!(close(c.position, DVec3::new(0.0, 0.0, GROUND_HEIGHT), 1e-6));
        assert!((c.heading - 1.2).abs() < 1e-9);
        assert!((c.pitch - GROUND_PITCH).abs() < 1e-9);
        assert_eq!(c.nehe.speed, 0.0);

        // An unposed planet centred on the origin: the site is a pole; the view is still 5° above
        // the local horizon.
        let planet = Planet::spheroid(6_378_137.0, 6_356_752.3, 60_000.0);
        let (position, heading, pitch) = goto_ground(&planet, f64::NAN);
        assert!((altitude_above(&planet, position) - GROUND_HEIGHT).abs() < 1e-6);
        let up = planet.up(planet.to_planet_frame(position));
        let elevation = direction_from_heading_elevation(heading, pitch).dot(up).asin();
        assert!((elevation - GROUND_PITCH).abs() < 1e-9, "{elevation}");
    }

    #[test]
    fn go_to_orbit_sees_the_planet() {
        for planet in [earth_at_45(), Planet::spheroid(60_268_000.0, 54_364_000.0, 1e6)] {
            for radii in [1.5, 3.0, 1e6] {
                let mut c = FlightController::default();
                c.go_to_orbit(&planet, radii);
                let to_centre = planet.center - c.position;
                let expected = radii * planet.radii.x;
                assert!((to_centre.length() - expected).abs() < 1e-9 * expected);
                let cam = c.camera(&Camera::default());
                let angle = cam.forward().dot(to_centre.normalize()).clamp(-1.0, 1.0).acos();
                assert!(angle < 1e-6, "{radii}: {angle}");
                assert!(angle < cam.fov_y / 2.0);
                assert!(c.altitude_above(&planet) > 0.0);
            }
        }
        // Too close or not finite: pushed out / the default.
        let planet = earth_at_45();
        let (p, _, _) = goto_orbit(&planet, 0.5);
        assert!(((p - planet.center).length() / planet.radii.x - MIN_ORBIT_RADII).abs() < 1e-9);
        let (p, _, _) = goto_orbit(&planet, f64::NAN);
        assert!(((p - planet.center).length() / planet.radii.x - DEFAULT_ORBIT_RADII).abs() < 1e-9);
    }
}
