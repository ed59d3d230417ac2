//! Scenes in code: [`SceneBuilder`], typed setters over the same [`Scene`] a scene file parses
//! into. Every setter names its unit (`_deg` degrees, `_m` metres, `_per_m` per metre, `_nm`
//! nanometres, `_px` pixels, `_k` kelvin); [`SceneBuilder::build`] checks the scene with
//! [`Scene::validate`], so a bad value gives the message a scene file with it would. Entries of
//! the scene's lists (suns, cloud layers, lights, objects) have constructors of their own (`entries.rs`), and
//! [`SceneBuilder::edit`] reaches any field a setter does not cover.

use firmament_core::auto_exposure::AutoExposure;
use firmament_core::display::{Encoding, ToneCurve};

use crate::error::SceneError;
use crate::model::{
    AtmosphereModelName, Body, CloudEntry, EmpiricalSection, ExposureModeName, FlareElementEntry, FlarePresetName,
    FogCoordinateName, FogModeName, GlColor, KeyframeSection, LightEntry, LightingModelName, MiePhaseName, ObjectEntry,
    Scene, ShadingName, SkyModelName, SunEntry,
};
use crate::spectrum::SceneSpectrum;

mod entries;

/// Builds a [`Scene`] in code, starting from the built-in `default` preset (the base every scene
/// file is layered on), so that a builder and a scene file saying the same things give equal
/// scenes:
///
/// ```
/// use firmament_scene::{Body, MeshEntry, ObjectEntry, Scene};
///
/// let scene = Scene::builder()
///     .image_size_px(640, 360)
///     .atmosphere(Body::Earth)
///     .planet_location_deg(45.0, 7.0)
///     .sun_at_deg(225.0, 20.0)
///     .camera_position_m([0.0, 0.0, 1.7])
///     .camera_direction_deg(0.0, 2.0)
///     .fov_y_deg(60.0)
///     .exposure_ev100(13.5)
///     .object(ObjectEntry::new(MeshEntry::Cube { size: 2.0 }).translate_m([0.0, 10.0, 1.0]))
///     .build()?;
/// let frame = scene.frame_at(None)?; // what firmament_render draws
/// assert_eq!(frame.objects.objects.len(), 1);
///
/// // A bad value is the scene file's own message, naming the key.
/// let error = Scene::builder().fov_y_deg(0.0).build().unwrap_err();
/// assert!(error.to_string().contains("camera.fov_y"));
/// # Ok::<(), firmament_scene::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct SceneBuilder {
    scene: Scene,
}

impl Default for SceneBuilder {
    fn default() -> Self {
        Self::new()
    }
}

impl Scene {
    /// A [`SceneBuilder`] over the `default` preset.
    pub fn builder() -> SceneBuilder {
        SceneBuilder::new()
    }
}

impl SceneBuilder {
    /// The built-in `default` preset's scene, as a scene file without a `preset` key starts.
    pub fn new() -> Self {
        let scene = Scene::preset("default").unwrap_or_else(|e| unreachable!("the built-in default preset: {e}"));
        Self::from_scene(scene)
    }

    /// The built-in preset `name` (an unknown name is an error with a "did you mean").
    pub fn from_preset(name: &str) -> Result<Self, SceneError> {
        Scene::preset(name).map(Self::from_scene)
    }

    /// Any scene, e.g. one loaded from a file, to change further. The preset it records stays.
    pub fn from_scene(mut scene: Scene) -> Self {
        scene.preset.get_or_insert_with(|| "default".to_owned());
        Self { scene }
    }

    /// Checks every rule of the scene format ([`Scene::validate`]) and gives the scene.
    pub fn build(self) -> Result<Scene, SceneError> {
        self.scene.validate()?;
        Ok(self.scene)
    }

    /// The scene as it stands, unchecked (to change a field no setter covers, then
    /// [`from_scene`](Self::from_scene) or [`Scene::validate`]).
    pub fn into_scene(self) -> Scene {
        self.scene
    }

    /// `render.width`, `render.height`: the image, pixels, 1 to 16384 each.
    pub fn image_size_px(mut self, width: u32, height: u32) -> Self {
        self.scene.render.width = width;
        self.scene.render.height = height;
        self
    }

    /// `camera.position`: `[east, north, up]`, metres, in the world's East-North-Up frame.
    pub fn camera_position_m(mut self, east_north_up: [f64; 3]) -> Self {
        self.scene.camera.position = east_north_up;
        self
    }

    /// `camera.heading` (from north, clockwise towards east) and `camera.pitch` (above the
    /// horizon, [-90, 90]), degrees.
    pub fn camera_direction_deg(mut self, heading: f64, pitch: f64) -> Self {
        self.scene.camera.heading_deg = heading;
        self.scene.camera.pitch_deg = pitch;
        self
    }

    /// `camera.roll`: the image turned clockwise about the view direction, degrees.
    pub fn camera_roll_deg(mut self, roll: f64) -> Self {
        self.scene.camera.roll_deg = roll;
        self
    }

    /// `camera.fov_y`: the vertical field of view, degrees, in (0, 180).
    pub fn fov_y_deg(mut self, fov_y: f64) -> Self {
        self.scene.camera.fov_y_deg = fov_y;
        self
    }

    /// `camera.near`, `camera.far`: the clip planes, metres (`far` `None`: infinite).
    pub fn clip_planes_m(mut self, near: f64, far: Option<f64>) -> Self {
        self.scene.camera.near = near;
        self.scene.camera.far = far;
        self
    }

    /// `time.time_of_day`: local solar time, `"HH:MM"` or `"HH:MM:SS"` (without a date).
    pub fn time_of_day(mut self, time: &str) -> Self {
        time.clone_into(&mut self.scene.time.time_of_day);
        self
    }

    /// `time.date_time`: a real instant, ISO 8601 (`"2024-06-21T22:00:00+02:00"`); the sun, moon
    /// and stars stand where they were then, seen from the planet's latitude and longitude.
    pub fn date_time(mut self, iso_8601: &str) -> Self {
        self.scene.time.date_time = Some(iso_8601.to_owned());
        self
    }

    /// `time.stars`, `time.moon`: whether the night sky draws them (with a date).
    pub fn night_sky(mut self, stars: bool, moon: bool) -> Self {
        self.scene.time.stars = stars;
        self.scene.time.moon = moon;
        self
    }

    /// `display.ev100`: exposure value at ISO 100 (the exposure becomes `1 / (1.2 · 2^ev100)`).
    pub fn exposure_ev100(mut self, ev100: f64) -> Self {
        self.scene.display.ev100 = Some(ev100);
        self
    }

    /// `display.exposure`: a plain multiplier, > 0 (and no `ev100`).
    pub fn exposure_multiplier(mut self, multiplier: f64) -> Self {
        self.scene.display.exposure = multiplier;
        self.scene.display.ev100 = None;
        self
    }

    /// `display.exposure_mode = "auto"` with the `auto_*` keys from `auto`: each frame metered.
    pub fn auto_exposure(mut self, auto: AutoExposure) -> Self {
        let display = &mut self.scene.display;
        display.exposure_mode = ExposureModeName::Auto;
        display.auto_ev_min = auto.ev100_min;
        display.auto_ev_max = auto.ev100_max;
        display.auto_compensation = auto.compensation_ev;
        display.auto_speed_up = auto.speed_up_ev_per_s;
        display.auto_speed_down = auto.speed_down_ev_per_s;
        self
    }

    /// `display.bloom`: bloom's strength in [0, 1] (0 = off).
    pub fn bloom(mut self, strength: f64) -> Self {
        self.scene.display.bloom = strength;
        self
    }

    /// `display.night_vision`: the eye's scotopic vision below a few cd/m².
    pub fn night_vision(mut self, on: bool) -> Self {
        self.scene.display.night_vision = on;
        self
    }

    /// `display.tone_curve`.
    pub fn tone_curve(mut self, curve: ToneCurve) -> Self {
        self.scene.display.tone_curve = curve;
        self
    }

    /// `display.encoding`: how 8-bit outputs store the result.
    pub fn encoding(mut self, encoding: Encoding) -> Self {
        self.scene.display.encoding = encoding;
        self
    }

    /// `sky.model = "gradient"`: the keyframed gradient sky (the default).
    pub fn gradient_sky(mut self) -> Self {
        self.scene.sky.model = SkyModelName::Gradient;
        self
    }

    /// `sky.model = "clear"` with `sky.clear_color` (linear, as `glClearColor`).
    pub fn clear_sky(mut self, color: GlColor) -> Self {
        self.scene.sky.model = SkyModelName::Clear;
        self.scene.sky.clear_color = color;
        self
    }

    /// `sky.model = "atmosphere"` over `planet.body = body` (its shape, medium and sun; the
    /// physical model unless [`empirical_atmosphere`](Self::empirical_atmosphere)).
    pub fn atmosphere(mut self, body: Body) -> Self {
        self.scene.sky.model = SkyModelName::Atmosphere;
        self.scene.planet.body = body;
        self
    }

    /// `atmosphere.model = "seed"`: the seed's empirical model ([`EmpiricalAtmosphere`]) instead
    /// of the physical one; set its values with [`empirical_values`](Self::empirical_values).
    ///
    /// [`EmpiricalAtmosphere`]: firmament_core::atmosphere::empirical::EmpiricalAtmosphere
    pub fn empirical_atmosphere(mut self) -> Self {
        self.scene.atmosphere.model = AtmosphereModelName::Empirical;
        self
    }

    /// `planet.latitude` (geodetic, north, [-90, 90]) and `planet.longitude` (east) of the world
    /// origin, degrees.
    pub fn planet_location_deg(mut self, latitude: f64, longitude: f64) -> Self {
        self.scene.planet.latitude_deg = latitude;
        self.scene.planet.longitude_deg = longitude;
        self
    }

    /// `planet.equatorial_radius`, `planet.polar_radius`, metres (an ellipsoid).
    pub fn planet_radii_m(mut self, equatorial: f64, polar: f64) -> Self {
        self.scene.planet.equatorial_radius = Some(equatorial);
        self.scene.planet.polar_radius = Some(polar);
        self
    }

    /// `planet.radius`, metres (a sphere).
    pub fn planet_sphere_m(mut self, radius: f64) -> Self {
        self.scene.planet.radius = Some(radius);
        self
    }

    /// `planet.atmosphere_height`: the top of the atmosphere above the surface, metres.
    pub fn atmosphere_height_m(mut self, height: f64) -> Self {
        self.scene.planet.atmosphere_height = Some(height);
        self
    }

    /// `atmosphere.rayleigh_scattering` (m⁻¹ at the three model wavelengths, at the surface) and
    /// `atmosphere.rayleigh_scale_height` (metres).
    pub fn rayleigh_per_m(mut self, scattering: [f64; 3], scale_height_m: f64) -> Self {
        let air = &mut self.scene.atmosphere;
        air.rayleigh_scattering = Some(SceneSpectrum(scattering));
        air.rayleigh_scale_height = Some(scale_height_m);
        self
    }

    /// The aerosols: `atmosphere.mie_scattering` and `mie_extinction` (m⁻¹ per model wavelength,
    /// at the surface), `mie_scale_height` (metres) and the asymmetry `mie_g` in (−1, 1).
    pub fn mie_per_m(mut self, scattering: [f64; 3], extinction: [f64; 3], scale_height_m: f64, g: f64) -> Self {
        let air = &mut self.scene.atmosphere;
        air.mie_scattering = Some(SceneSpectrum(scattering));
        air.mie_extinction = Some(SceneSpectrum(extinction));
        air.mie_scale_height = Some(scale_height_m);
        air.mie_g = Some(g);
        self
    }

    /// `atmosphere.mie_phase`.
    pub fn mie_phase(mut self, phase: MiePhaseName) -> Self {
        self.scene.atmosphere.mie_phase = Some(phase);
        self
    }

    /// Ozone: `atmosphere.ozone_absorption` (m⁻¹ per model wavelength, at the peak) and its tent's
    /// `ozone_bottom`, `ozone_peak` and `ozone_top` altitudes, metres.
    pub fn ozone_per_m(mut self, absorption: [f64; 3], bottom_m: f64, peak_m: f64, top_m: f64) -> Self {
        let air = &mut self.scene.atmosphere;
        air.ozone_absorption = Some(SceneSpectrum(absorption));
        air.ozone_bottom = Some(bottom_m);
        air.ozone_peak = Some(peak_m);
        air.ozone_top = Some(top_m);
        self
    }

    /// `atmosphere.ground_albedo` per model wavelength, [0, 1].
    pub fn ground_albedo(mut self, albedo: [f64; 3]) -> Self {
        self.scene.atmosphere.ground_albedo = Some(SceneSpectrum(albedo));
        self
    }

    /// `atmosphere.wavelengths`: the three model wavelengths, nanometres.
    pub fn wavelengths_nm(mut self, wavelengths: [f64; 3]) -> Self {
        self.scene.atmosphere.wavelengths = Some(wavelengths);
        self
    }

    /// Adds a `[[suns]]` entry.
    pub fn sun(mut self, sun: SunEntry) -> Self {
        self.scene.suns.push(sun);
        self
    }

    /// Adds the body's sun at `azimuth` (from north, clockwise) and `elevation`, degrees.
    pub fn sun_at_deg(self, azimuth: f64, elevation: f64) -> Self {
        self.sun(SunEntry::at_deg(azimuth, elevation))
    }

    /// Removes every sun (a preset's included).
    pub fn no_suns(mut self) -> Self {
        self.scene.suns.clear();
        self
    }

    /// Adds a `[[clouds]]` layer (drawn by the physical atmosphere).
    pub fn cloud(mut self, layer: CloudEntry) -> Self {
        self.scene.clouds.push(layer);
        self
    }

    /// Removes every cloud layer (a preset's included).
    pub fn no_clouds(mut self) -> Self {
        self.scene.clouds.clear();
        self
    }

    /// `lighting.model` and `lighting.shading`.
    pub fn lighting(mut self, model: LightingModelName, shading: ShadingName) -> Self {
        self.scene.lighting.model = model;
        self.scene.lighting.shading = shading;
        self
    }

    /// Adds a `[[lights]]` entry (classic lighting).
    pub fn light(mut self, light: LightEntry) -> Self {
        self.scene.lights.push(light);
        self
    }

    /// Adds an `[[objects]]` entry.
    pub fn object(mut self, object: ObjectEntry) -> Self {
        self.scene.objects.push(object);
        self
    }

    /// `fog.mode = "none"`.
    pub fn no_fog(mut self) -> Self {
        self.scene.fog.mode = FogModeName::None;
        self
    }

    /// `fog.mode = "linear"` from `start` to `end` metres, in `color` (GL RGBA).
    pub fn linear_fog_m(mut self, start: f64, end: f64, color: GlColor) -> Self {
        let fog = &mut self.scene.fog;
        (fog.mode, fog.start, fog.end, fog.color) = (FogModeName::Linear, start, end, color);
        self
    }

    /// `fog.mode = "exp"` of `density` per metre, in `color`.
    pub fn exp_fog_per_m(mut self, density: f64, color: GlColor) -> Self {
        let fog = &mut self.scene.fog;
        (fog.mode, fog.density, fog.color) = (FogModeName::Exp, density, color);
        self
    }

    /// `fog.mode = "height"`: extinction `density` (1/m) at `base_height_m`, falling by
    /// `falloff` (1/m) with height, in `color`.
    pub fn height_fog_per_m(mut self, density: f64, falloff: f64, base_height_m: f64, color: GlColor) -> Self {
        let fog = &mut self.scene.fog;
        (fog.mode, fog.density, fog.falloff, fog.base_height, fog.color) =
            (FogModeName::Height, density, falloff, base_height_m, color);
        self
    }

    /// `flare.enabled = true` with the built-in `preset`'s elements.
    pub fn flare(mut self, preset: FlarePresetName) -> Self {
        self.scene.flare.enabled = true;
        self.scene.flare.preset = preset;
        self
    }

    /// Changes the scene directly — any field, each documented with its unit and rule — for
    /// what no setter covers; [`build`](Self::build) checks it all the same.
    pub fn edit(mut self, change: impl FnOnce(&mut Scene)) -> Self {
        change(&mut self.scene);
        self
    }

    /// `time.pressure` (millibars) and `time.temperature` (°C): the air at the observer, for the
    /// sun's refraction.
    pub fn refraction_air(mut self, pressure_mbar: f64, temperature_c: f64) -> Self {
        self.scene.time.pressure = pressure_mbar;
        self.scene.time.temperature = temperature_c;
        self
    }

    /// `time.delta_t`: TT − UT, seconds (`None`: estimated for the date).
    pub fn delta_t_s(mut self, delta_t: Option<f64>) -> Self {
        self.scene.time.delta_t = delta_t;
        self
    }

    /// `time.star_limit`: the faintest star drawn, visual magnitude, <= 6.5.
    pub fn star_limit_mag(mut self, magnitude: f64) -> Self {
        self.scene.time.star_limit = magnitude;
        self
    }

    /// `sun.latitude` and `sun.declination`: the gradient sky's sun path, degrees.
    pub fn gradient_sun_path_deg(mut self, latitude: f64, declination: f64) -> Self {
        self.scene.sun.latitude_deg = latitude;
        self.scene.sun.declination_deg = declination;
        self
    }

    /// The gradient sky's `[[sky.gradient.keyframes]]`, replacing the preset's.
    pub fn gradient_keyframes(mut self, keyframes: Vec<KeyframeSection>) -> Self {
        self.scene.sky.gradient.keyframes = keyframes;
        self
    }

    /// `[atmosphere.seed]`: the empirical model's values (used when
    /// [`empirical_atmosphere`](Self::empirical_atmosphere) picks it).
    pub fn empirical_values(mut self, values: EmpiricalSection) -> Self {
        self.scene.atmosphere.empirical = values;
        self
    }

    /// `fog.coordinate`: what distance the classic fog uses.
    pub fn fog_coordinate(mut self, coordinate: FogCoordinateName) -> Self {
        self.scene.fog.coordinate = coordinate;
        self
    }

    /// `flare.intensity` (>= 0) and `flare.samples` (occlusion samples per source, 1 to 256).
    pub fn flare_look(mut self, intensity: f64, samples: u32) -> Self {
        self.scene.flare.intensity = intensity;
        self.scene.flare.samples = samples;
        self
    }

    /// `flare.elements`: the flare's own elements instead of the preset's.
    pub fn flare_elements(mut self, elements: Vec<FlareElementEntry>) -> Self {
        self.scene.flare.elements = Some(elements);
        self
    }
}
