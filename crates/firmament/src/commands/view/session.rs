//! The viewer's state apart from the window: the scene document the panel edits, the scene built
//! from it, the flying camera and the clock. Every frame is built here by the scene crate's own
//! `frame_at` path, so the viewer draws exactly what `firmament render` draws for the same scene.

use std::path::Path;

use super::flight::{FlightAction, FlightController};
use super::sim_clock::SimClock;
use anyhow::{Context, Result};
use firmament_core::astro::CivilDateTime;
use firmament_core::atmosphere::Planet;
use firmament_core::sky::time_of_day::SECONDS_PER_DAY;
use firmament_core::{Frame, TimeOfDay};
use firmament_scene::{Scene, SceneDocument};
use glam::DVec3;

/// The lowest the camera may fly above the ground, metres (scenes demand altitude >= 0).
const MIN_ALTITUDE: f64 = 0.5;

/// How far away the orbit view stands, in equatorial radii from the planet's centre.
const ORBIT_RADII: f64 = 3.0;

/// The scene's own moment, which the clock's offset counts from.
#[derive(Debug, Clone, PartialEq)]
enum Moment {
    /// A local solar time of day (scenes without `time.date_time`).
    Clock(TimeOfDay),
    /// A real instant (`time.date_time`).
    Date(CivilDateTime),
}

/// Everything the viewer shows, apart from the window and the GPU.
#[derive(Debug)]
pub(crate) struct Session {
    /// The resolved scene table the panel edits and "save scene" writes.
    pub(crate) doc: SceneDocument,
    /// The scene built from `doc` by its last valid edit.
    scene: Scene,
    /// The planet under an atmosphere sky, posed in the world frame.
    planet: Option<Planet>,
    /// The scene's own moment.
    moment: Moment,
    /// Why the last edit could not be used (the scene keeps its last valid state).
    pub(crate) edit_error: Option<String>,
    /// The camera.
    pub(crate) flight: FlightController,
    /// Simulated time since the scene's own moment.
    pub(crate) clock: SimClock,
    /// The flight's pose when it was last put at the scene's camera: while it stays there, the
    /// scene's own camera values are drawn (degrees → radians → degrees is not always exact).
    aimed: Pose,
}

/// A flight pose: position (m), heading and pitch (radians).
type Pose = (DVec3, f64, f64);

/// Puts the flying camera at the scene's camera, looking where it looks (mode and speed kept);
/// the pose it took.
fn aim(flight: &mut FlightController, camera: &firmament_scene::CameraSection) -> Pose {
    flight.set_pose(
        DVec3::from_array(camera.position),
        camera.heading_deg.to_radians(),
        camera.pitch_deg.to_radians(),
    );
    pose(flight)
}

/// The flight's pose.
fn pose(flight: &FlightController) -> Pose {
    (flight.position, flight.heading, flight.pitch)
}

impl Session {
    /// A session over `doc`, with the camera and the clock at the scene's own.
    pub(crate) fn new(doc: SceneDocument) -> Result<Self> {
        let scene = doc.scene()?;
        let (planet, moment) = derived(&scene)?;
        let mut flight = FlightController::default();
        let aimed = aim(&mut flight, &scene.camera);
        Ok(Self {
            flight,
            aimed,
            doc,
            scene,
            planet,
            moment,
            edit_error: None,
            clock: SimClock::default(),
        })
    }

    /// The scene as last built (its camera and time as in the document, not as flown).
    #[cfg(test)]
    pub(crate) fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The planet under an atmosphere sky.
    pub(crate) fn planet(&self) -> Option<&Planet> {
        self.planet.as_ref()
    }

    /// Rebuilds the scene after the document changed. An edit that breaks a rule keeps the last
    /// valid scene and records the message; an edit of the camera or the time moves the flying
    /// camera or the clock there.
    pub(crate) fn document_changed(&mut self) {
        let built = self.doc.scene().map_err(anyhow::Error::from).and_then(|scene| {
            let (planet, moment) = derived(&scene)?;
            Ok((scene, planet, moment))
        });
        match built {
            Ok((scene, planet, moment)) => {
                if scene.camera != self.scene.camera {
                    self.aimed = aim(&mut self.flight, &scene.camera);
                }
                if moment != self.moment {
                    self.clock.offset_seconds = 0.0;
                }
                self.scene = scene;
                self.planet = planet;
                self.moment = moment;
                self.edit_error = None;
            }
            Err(error) => self.edit_error = Some(format!("{error:#}")),
        }
    }

    /// Back to the scene as loaded: the document, the camera and the clock.
    pub(crate) fn reset(&mut self) {
        self.doc.reset();
        self.document_changed();
        self.aimed = aim(&mut self.flight, &self.scene.camera);
        self.clock.reset();
    }

    /// Advances the clock by `real_dt` seconds and flies the camera with the `held` actions.
    pub(crate) fn advance(&mut self, held: &[FlightAction], real_dt: f64) {
        self.clock.advance(real_dt);
        let altitude = self.altitude();
        self.flight.update(held, altitude, real_dt);
        self.keep_above_ground();
    }

    /// The camera's altitude above the ground, metres: geodetic over an atmosphere's planet,
    /// the height above the plane `up = 0` under the gradient sky.
    pub(crate) fn altitude(&self) -> f64 {
        altitude_at(self.planet.as_ref(), self.flight.position)
    }

    /// Pushes a camera that flew into the ground back up to [`MIN_ALTITUDE`].
    fn keep_above_ground(&mut self) {
        let p = self.flight.position;
        let altitude = self.altitude();
        if altitude >= MIN_ALTITUDE || !altitude.is_finite() {
            return;
        }
        let up = match &self.planet {
            Some(planet) => world_up(planet, p),
            None => DVec3::Z,
        };
        self.flight.position = p + up * (MIN_ALTITUDE - altitude);
    }

    /// Goes to a ground view (2 m up, looking at the horizon), or to 2 m above the plane under
    /// the gradient sky.
    pub(crate) fn go_to_ground(&mut self) {
        match &self.planet {
            Some(planet) => self.flight.go_to_ground(planet),
            None => self.flight.position.z = 2.0,
        }
    }

    /// Goes to an orbit view of the planet; `false` when the sky has no planet.
    pub(crate) fn go_to_orbit(&mut self) -> bool {
        match &self.planet {
            Some(planet) => {
                self.flight.go_to_orbit(planet, ORBIT_RADII);
                true
            }
            None => false,
        }
    }

    /// The scene with the flown camera (its roll and lens kept), drawn at `size`.
    fn flown_scene(&self, (width, height): (u32, u32)) -> Scene {
        let mut scene = self.scene.clone();
        scene.render.width = width;
        scene.render.height = height;
        if pose(&self.flight) != self.aimed {
            scene.camera.position = self.flight.position.to_array();
            scene.camera.heading_deg = self.flight.heading.to_degrees();
            scene.camera.pitch_deg = self.flight.pitch.to_degrees();
        }
        scene
    }

    /// The frame to draw now at `size` (pixels): the flown camera at the clock's moment.
    pub(crate) fn frame(&self, size: (u32, u32)) -> Result<Frame> {
        let scene = self.flown_scene(size);
        let frame = match self.current_moment() {
            Moment::Clock(time) => scene.frame_at(Some(time)),
            Moment::Date(date) => scene.frame_at_date_time(&date),
        };
        Ok(frame?)
    }

    /// The clock's moment: the scene's own plus the clock's offset.
    fn current_moment(&self) -> Moment {
        let offset = self.clock.offset_seconds;
        match &self.moment {
            Moment::Clock(time) => Moment::Clock(
                TimeOfDay::from_seconds((time.seconds() + offset).rem_euclid(SECONDS_PER_DAY)).unwrap_or(*time),
            ),
            Moment::Date(date) => Moment::Date(firmament_scene::add_seconds(date, offset)),
        }
    }

    /// The moment shown now, as the scene file writes it (`HH:MM:SS` or ISO 8601).
    pub(crate) fn describe_moment(&self) -> String {
        match self.current_moment() {
            Moment::Clock(time) => time.to_string(),
            Moment::Date(date) => date.to_string(),
        }
    }

    /// The local solar time of day shown now, hours in [0, 24) (scenes without a date).
    pub(crate) fn hours(&self) -> Option<f64> {
        match self.current_moment() {
            Moment::Clock(time) => Some(time.hours()),
            Moment::Date(_) => None,
        }
    }

    /// Moves the clock so that the time shown is `hours` on the scene's day.
    pub(crate) fn set_hours(&mut self, hours: f64) {
        if let (Moment::Clock(own), true) = (&self.moment, hours.is_finite()) {
            self.clock.offset_seconds = hours.clamp(0.0, 24.0) * 3600.0 - own.seconds();
        }
    }

    /// Writes the flown camera, the clock's moment (rounded to the second, as scene files write
    /// times; the clock follows) and the size drawn at into the document, so that it holds the
    /// view on screen.
    pub(crate) fn store_view(&mut self, (width, height): (u32, u32)) -> Result<()> {
        let rounded = self.clock.offset_seconds.round();
        self.clock.offset_seconds = rounded;
        let mut values = vec![
            ("render.width", toml::Value::Integer(i64::from(width))),
            ("render.height", toml::Value::Integer(i64::from(height))),
        ];
        // The camera and the time only when they moved, so the scene's own values stay as written.
        if pose(&self.flight) != self.aimed {
            let position = self.flight.position.to_array().map(toml::Value::Float);
            values.extend([
                ("camera.position", toml::Value::Array(position.into())),
                ("camera.heading", toml::Value::Float(self.flight.heading.to_degrees())),
                ("camera.pitch", toml::Value::Float(self.flight.pitch.to_degrees())),
            ]);
        }
        if rounded != 0.0 {
            values.push(match self.current_moment() {
                Moment::Clock(time) => ("time.time_of_day", toml::Value::String(time.to_string())),
                Moment::Date(date) => ("time.date_time", toml::Value::String(date.to_string())),
            });
        }
        for (key, value) in values {
            self.doc.set(key, value)?;
        }
        // The document now holds the moment shown: the clock starts from it.
        let (flight, clock_rate, paused) = (self.flight, self.clock.rate, self.clock.paused);
        self.document_changed();
        self.flight = flight;
        // The document's camera is the flight's pose now (in degrees).
        self.aimed = pose(&self.flight);
        self.clock = SimClock {
            rate: clock_rate,
            paused,
            ..SimClock::default()
        };
        Ok(())
    }

    /// Stores the view at `size` and writes the whole scene to `path` (atomically).
    pub(crate) fn save(&mut self, path: &Path, size: (u32, u32)) -> Result<()> {
        self.store_view(size)?;
        self.doc
            .save(path)
            .with_context(|| format!("cannot save the scene to {}", path.display()))
    }
}

/// The planet and the moment a scene implies.
fn derived(scene: &Scene) -> Result<(Option<Planet>, Moment)> {
    let planet = scene.planet()?;
    let moment = match scene.date_time()? {
        Some(date) => Moment::Date(date),
        None => Moment::Clock(scene.time_of_day()?),
    };
    Ok((planet, moment))
}

/// The outward geodetic up at world-frame `position` over `planet`, in the world frame.
fn world_up(planet: &Planet, position: DVec3) -> DVec3 {
    planet.orientation.normalize() * planet.up(planet.to_planet_frame(position))
}

/// Altitude of `position` over `planet` (geodetic), or over the plane `up = 0`, metres.
fn altitude_at(planet: Option<&Planet>, position: DVec3) -> f64 {
    match planet {
        Some(planet) => planet.altitude(planet.to_planet_frame(position)),
        None => position.z,
    }
}

#[cfg(test)]
mod tests {
    use firmament_scene::SceneSource;

    use super::*;

    /// The default scene's size.
    const SIZE: (u32, u32) = (1280, 720);

    fn session(preset: &str) -> Session {
        let doc = SceneDocument::load(SceneSource::Preset(preset), None, &[]).expect("preset loads");
        Session::new(doc).expect("session")
    }

    #[test]
    fn the_first_frame_is_the_scenes_own() {
        let s = session("default");
        let own = s.scene().frame_at(None).expect("frame");
        let viewed = s.frame(SIZE).expect("frame");
        assert_eq!(viewed.camera, own.camera);
        assert_eq!(format!("{:?}", viewed.sky), format!("{:?}", own.sky));
    }

    #[test]
    fn a_bad_edit_keeps_the_last_valid_scene_and_says_why() {
        let mut s = session("default");
        s.doc.set("camera.fov_y", toml::Value::Float(-5.0)).expect("set");
        s.document_changed();
        let message = s.edit_error.clone().expect("an error");
        assert!(message.contains("camera.fov_y"), "{message}");
        assert!(s.frame(SIZE).is_ok());
        s.doc.set("camera.fov_y", toml::Value::Float(50.0)).expect("set");
        s.document_changed();
        assert!(s.edit_error.is_none());
        assert_eq!(s.scene().camera.fov_y_deg, 50.0);
    }

    #[test]
    fn the_camera_never_goes_underground() {
        let mut s = session("earth-sunset");
        s.flight.position -= world_up(s.planet().expect("planet"), s.flight.position) * 1.0e4;
        s.advance(&[], 0.0);
        assert!(s.altitude() >= MIN_ALTITUDE - 1e-6, "{}", s.altitude());
        let mut g = session("default");
        g.flight.position.z = -10.0;
        g.advance(&[], 0.0);
        assert!((g.altitude() - MIN_ALTITUDE).abs() < 1e-9);
    }

    #[test]
    fn hours_scrub_the_clock_and_store_rounds_to_the_second() {
        let mut s = session("default");
        s.set_hours(6.5);
        assert!((s.hours().expect("undated") - 6.5).abs() < 1e-9);
        s.clock.offset_seconds += 0.4;
        s.store_view(SIZE).expect("store");
        assert_eq!(s.scene().time.time_of_day, "06:30:00");
        assert_eq!(s.clock.offset_seconds, 0.0);
        assert_eq!(s.describe_moment(), "06:30:00");
    }

    #[test]
    fn a_saved_view_renders_as_shown() {
        let mut s = session("earth-sunset");
        s.flight.heading += 0.3;
        s.flight.pitch += 0.05;
        s.flight.position.z += 1234.5;
        s.clock.offset_seconds = 3600.0;
        let shown = s.frame((320, 200)).expect("frame");
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("saved.toml");
        s.save(&path, (320, 200)).expect("save");
        let saved = firmament_scene::load_file(&path, None, &[]).expect("saved scene loads");
        let rendered = saved.frame_at(None).expect("frame");
        assert!((rendered.camera.position - shown.camera.position).length() < 1e-9);
        assert!(rendered.camera.orientation.abs_diff_eq(shown.camera.orientation, 1e-12));
        assert_eq!(format!("{:?}", rendered.sky), format!("{:?}", shown.sky));
        assert_eq!(saved.render.width, 320);
    }
}
