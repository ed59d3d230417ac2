//! The atmosphere's GPU data: the medium (rebuilt LUTs when it changes) and the per-frame view.
//!
//! Everything is planet-relative and computed in `f64` before rounding: the camera's altitude
//! and its ellipsoid terms `|o/a|² − 1` are exact, and a far camera is described by the planet
//! centre's offset on the image plane, never by its `f32` position (see `atmosphere/sky.wgsl`).

use bytemuck::{Pod, Zeroable};
use firmament_core::atmosphere::body::air::light as air_light;
use firmament_core::atmosphere::body::{self, AirLight, Body, BodySurface, MAX_BODIES};
use firmament_core::atmosphere::eclipse::MAX_ECLIPSERS;
use firmament_core::atmosphere::planet_shadow::SHADOW_ENTRIES;
use firmament_core::atmosphere::{Atmosphere, Planet, Spectrum};
use firmament_core::atmosphere::rings::{RING_TABLE_ENTRIES, Rings};
use firmament_core::atmosphere::surface::{Surface, glint};
use firmament_core::frame::{AtmosphereSky, MAX_SUNS};
use firmament_core::{Camera, DepthConvention};
use glam::{DMat3, DVec3};

pub use super::planet_view::FAR_CAMERA_RADII;
use super::medium::{
    DENSITY_TABLE_SAMPLES, LUT_ROWS, MAX_MEDIUM_TERMS, MediumGpu, MediumTermUniform, PHASE_TABLE_SAMPLES,
    is_thick_air, multiscattering_lut_height, multiscattering_lut_rows,
};
use super::planet_view::PlanetView;
use super::pack::vec3_w;

/// How far the aerial-perspective volume reaches into the air along each view ray, metres:
/// geometry farther than this gets the scattering of this distance. 100 km holds a view from a
/// mountain or an airliner to the horizon.
pub const AERIAL_PERSPECTIVE_RANGE: f64 = 100_000.0;

/// The terms of a body's air: molecules, aerosols and an absorbing gas.
pub const BODY_AIR_TERMS: usize = 3;

/// The altitude band, as fractions of the atmosphere height, over which the sky blends from the
/// sky-view LUT (below) to the per-pixel march (above, and anywhere outside the atmosphere).
pub const LUT_TO_MARCH_BAND: (f64, f64) = (0.9, 1.0);

fn spectrum_w(s: Spectrum, w: f64) -> [f32; 4] {
    [s.x as f32, s.y as f32, s.z as f32, w as f32]
}

/// Mirrors `AtmosphereParams` in `shaders/atmosphere/bindings.wgsl`: everything the LUTs depend on.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct AtmosphereParamsUniforms {
    /// Ellipsoid semi-axes (m); `w` = atmosphere height (m).
    pub radii: [f32; 4],
    /// Bottom and top radius of the LUT sphere (m); the number of terms; the height the
    /// multiple-scattering and sky-irradiance LUTs span (m, [`multiscattering_lut_height`]).
    pub lut: [f32; 4],
    /// Ground albedo.
    pub ground_albedo: [f32; 4],
    /// The medium's terms (the first `lut.z`).
    pub terms: [MediumTermUniform; MAX_MEDIUM_TERMS],
    /// x: how many terms have a density table, y: a phase table; z: 1 in a thick air
    /// ([`is_thick_air`]: the multiple-scattering LUTs' rows stand at `lut_rows` and their
    /// directions crowd at the poles), 0 in a thin one (rows evenly spread up to `lut.w`); w
    /// unused.
    pub table_counts: [u32; 4],
    /// The indices of the terms with a density table, four to a vector.
    pub density_table_terms: [[u32; 4]; MAX_MEDIUM_TERMS / 4],
    /// The indices of the terms with a phase table.
    pub phase_table_terms: [[u32; 4]; MAX_MEDIUM_TERMS / 4],
    /// The density tables, [`DENSITY_TABLE_SAMPLES`] values per term, four to a vector.
    pub density_tables: [[f32; 4]; MAX_MEDIUM_TERMS * DENSITY_TABLE_SAMPLES / 4],
    /// The phase tables, [`PHASE_TABLE_SAMPLES`] values per term, four to a vector.
    pub phase_tables: [[f32; 4]; MAX_MEDIUM_TERMS * PHASE_TABLE_SAMPLES / 4],
    /// A thick air's multiple-scattering LUT rows, altitudes (m) from the ground to `lut.w`
    /// ([`multiscattering_lut_rows`]), four to a vector; zeros in a thin air.
    pub lut_rows: [[f32; 4]; LUT_ROWS / 4],
}

/// The radius of the sphere the transmittance and multiple-scattering LUTs are built for: the
/// planet's mean radius `(a·b·c)^⅓` (the radius itself for a sphere).
pub fn lut_bottom_radius(atmosphere: &Atmosphere) -> f64 {
    let r = atmosphere.planet.radii;
    (r.x * r.y * r.z).cbrt()
}

impl AtmosphereParamsUniforms {
    /// The medium and shape of `atmosphere`.
    pub fn new(atmosphere: &Atmosphere) -> Self {
        let thick = is_thick_air(&atmosphere.medium, atmosphere.planet.atmosphere_height);
        Self::with_thickness(atmosphere, thick)
    }

    /// [`new`](Self::new) for a caller that knows whether the air is thick ([`is_thick_air`]).
    pub(crate) fn with_thickness(atmosphere: &Atmosphere, thick: bool) -> Self {
        let planet = &atmosphere.planet;
        let medium = MediumGpu::new(&atmosphere.medium, planet.atmosphere_height, thick);
        let bottom = lut_bottom_radius(atmosphere);
        let height = multiscattering_lut_height(&atmosphere.medium, planet.atmosphere_height, thick);
        let mut table_counts = medium.table_counts;
        let mut lut_rows = [[0.0; 4]; LUT_ROWS / 4];
        if thick {
            table_counts[2] = 1;
            let rows = multiscattering_lut_rows(&atmosphere.medium, planet.atmosphere_height, height);
            for (y, h) in rows.iter().enumerate() {
                lut_rows[y / 4][y % 4] = *h as f32;
            }
        }
        Self {
            radii: vec3_w(planet.radii, planet.atmosphere_height),
            lut: [
                bottom as f32,
                (bottom + planet.atmosphere_height) as f32,
                medium.count as f32,
                height as f32,
            ],
            ground_albedo: spectrum_w(atmosphere.medium.ground_albedo, 0.0),
            terms: medium.terms,
            table_counts,
            density_table_terms: medium.density_table_terms,
            phase_table_terms: medium.phase_table_terms,
            density_tables: medium.density_tables,
            phase_tables: medium.phase_tables,
            lut_rows,
        }
    }
}

/// Mirrors `AtmosphereSun` in `shaders/atmosphere/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct AtmosphereSunUniform {
    /// Unit direction to the sun, planet frame; `w` = angular radius, radians.
    pub direction: [f32; 4],
    /// Spectral irradiance at the top of the atmosphere, W·m⁻²·nm⁻¹; `w` = limb darkening.
    pub irradiance: [f32; 4],
    /// `x` = 1 + the body whose light this is (0: a star's), which neither hides it nor is lit
    /// by it (`Sun::from_body`); `yzw` unused.
    pub source: [u32; 4],
}

/// Mirrors `OrderSums` in `shaders/atmosphere/bindings.wgsl`: one texel's multiple-scattering
/// orders while the LUTs are built, written and read by the GPU alone (Rust sizes their buffer).
/// Each `[f32; 4]` is one of the seven sums over directions (`atmosphere/moments_out.wgsl`),
/// radiance per unit sun irradiance, sr⁻¹.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct OrderSumsGpu {
    /// Over the orders marched so far.
    pub(crate) sum: [[f32; 4]; 7],
    /// The last order alone.
    pub(crate) last: [[f32; 4]; 7],
    /// The order before it: Ψ per wavelength, and summed over them in `w`.
    pub(crate) previous_psi: [f32; 4],
    /// The sky irradiance on a horizontal surface per unit sun (rgb), the orders so far.
    pub(crate) irradiance: [f32; 4],
    /// The same, the last order alone.
    pub(crate) last_irradiance: [f32; 4],
}

/// The size of each body's layer of the albedo maps' texture, texels (longitude × latitude):
/// about 10 km a texel on the Moon's equator. Any map is resampled to it.
pub(crate) const BODY_MAP_SIZE: (u32, u32) = (1024, 512);

/// The angle a texel of [`BODY_MAP_SIZE`] spans along a body's equator, radians.
const BODY_MAP_TEXEL_RAD: f64 = std::f64::consts::TAU / BODY_MAP_SIZE.0 as f64;

/// The size of each of a body's two layers of its air's light (`body_air_light` in
/// `shaders/atmosphere/bindings.wgsl`): the sun's zenith cosine across, altitude down — the
/// nodes of the core's [`AirLight`] tables, one per texel centre.
pub(crate) const BODY_AIR_LIGHT_SIZE: (u32, u32) = (air_light::SUN_NODES as u32, air_light::ALTITUDE_NODES as u32);

/// `light`'s two tables as the layers of `body_air_light`, Rgba16Float texels of
/// [`BODY_AIR_LIGHT_SIZE`]: Ψ (sr⁻¹ per unit irradiance), then the sky's irradiance on the
/// ground per unit irradiance, the same on every row; as each half float's bits.
pub(crate) fn body_air_light_layers(light: &AirLight) -> [Vec<u16>; 2] {
    let multiple = half_texels(&light.multiple);
    let sky = (0..air_light::ALTITUDE_NODES).flat_map(|_| half_texels(&light.sky)).collect();
    [multiple, sky]
}

/// Spectra as Rgba16Float texels (alpha 0): four half floats' bits each.
pub(crate) fn half_texels<'a>(spectra: impl IntoIterator<Item = &'a Spectrum>) -> Vec<u16> {
    spectra
        .into_iter()
        .flat_map(|s| [s.x, s.y, s.z, 0.0].map(|v| half::f16::from_f64(v).to_bits()))
        .collect()
}

/// Mirrors `AtmosphereBody` in `shaders/atmosphere/bindings.wgsl`: an airless body beside the
/// planet ([`Body`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct AtmosphereBodyUniform {
    /// Centre in the planet frame (m); `w` = the reflectance law ([`Reflectance::gpu_code`](firmament_core::atmosphere::body::Reflectance::gpu_code)).
    pub center: [f32; 4],
    /// Semi-axes along the body's axes (m); `w` = the surface
    /// ([`BodySurface::gpu_code`](firmament_core::atmosphere::body::BodySurface::gpu_code)).
    pub radii: [f32; 4],
    /// The body's x axis in the planet frame.
    pub axis_x: [f32; 4],
    /// Its y axis.
    pub axis_y: [f32; 4],
    /// Its polar z axis.
    pub axis_z: [f32; 4],
    /// Normal albedo per model wavelength, over the map's brightness where the surface is a map
    /// (the shader multiplies by the texel: [`body::map`]);
    /// `w` = 1 + the sun whose shadow of the planet the body stands in (0: none;
    /// [`Body::planet_shadow`]).
    pub albedo: [f32; 4],
    /// The shadow's axis from the planet's centre (unit, planet frame); `w` = the distance from
    /// it between the entries of the body's table in [`AtmosphereViewUniforms::body_shadows`] (m).
    pub shadow: [f32; 4],
    /// x = the height of the body's air (m; 0: airless, [`Body::air`]), its terms in
    /// [`AtmosphereViewUniforms::body_air`]; y = the body's volumetric mean radius (m); z = the
    /// width of a texel of its albedo map at its mean radius (m; 0: no map); w unused.
    pub air: [f32; 4],
}

impl AtmosphereBodyUniform {
    /// `body` (world frame) as the shaders read it, in `planet`'s frame.
    fn new(body: &Body, planet: &Planet) -> Self {
        let local = body.to_planet_frame(planet);
        let axes = DMat3::from_quat(local.orientation);
        let (map_brightness, texel_m) = match &local.surface {
            BodySurface::Map(map) => (body::map::brightness(map), local.mean_radius() * BODY_MAP_TEXEL_RAD),
            _ => (1.0, 0.0),
        };
        Self {
            center: vec3_w(local.center, f64::from(local.reflectance.gpu_code())),
            radii: vec3_w(local.radii, f64::from(local.surface.gpu_code())),
            axis_x: vec3_w(axes.x_axis, 0.0),
            axis_y: vec3_w(axes.y_axis, 0.0),
            axis_z: vec3_w(axes.z_axis, 0.0),
            albedo: spectrum_w(
                local.albedo / map_brightness,
                local.planet_shadow.as_ref().map_or(0.0, |shadow| (shadow.sun + 1) as f64),
            ),
            shadow: local
                .planet_shadow
                .as_ref()
                .map_or([0.0; 4], |shadow| vec3_w(shadow.axis, shadow.profile.step_m)),
            air: [
                local.air.as_ref().map_or(0.0, |air| air.top_altitude_m) as f32,
                local.mean_radius() as f32,
                texel_m as f32,
                0.0,
            ],
        }
    }

    /// The terms of `body`'s air, in [`Constituents::terms`](firmament_core::atmosphere::medium::Constituents::terms)'
    /// order (zero when airless).
    fn air_terms(body: &Body) -> [MediumTermUniform; BODY_AIR_TERMS] {
        let Some(air) = &body.air else {
            return [MediumTermUniform::zeroed(); BODY_AIR_TERMS];
        };
        let terms = air.constituents.terms();
        std::array::from_fn(|k| MediumTermUniform::new(&terms[k], false))
    }

    /// The table of `body`'s light inside the planet's shadow (zero without one).
    fn shadow_table(body: &Body) -> [[f32; 4]; SHADOW_ENTRIES] {
        let mut table = [[0.0; 4]; SHADOW_ENTRIES];
        if let Some(shadow) = &body.planet_shadow {
            for (slot, light) in table.iter_mut().zip(&shadow.profile.light) {
                *slot = spectrum_w(*light, 0.0);
            }
        }
        table
    }
}

/// Mirrors `AtmosphereView` in `shaders/atmosphere/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct AtmosphereViewUniforms {
    /// View-space direction → planet frame rotation.
    pub view_to_planet: [[f32; 4]; 4],
    /// Camera position in the planet frame (m); `w` = its exact altitude (m).
    pub camera: [f32; 4],
    /// `|o/a|² − 1` against the surface and the top; tan of half the horizontal and vertical
    /// fields of view.
    pub camera_shape: [f32; 4],
    /// Planet centre's view-space x, y over its depth; the depth (m); 1 for far-camera rays.
    pub center: [f32; 4],
    /// Geodetic up at the camera, planet frame; `w` = LUT (0) to march (1) blend.
    pub local_up: [f32; 4],
    /// First column of the spectral → linear sRGB (cd/m²) matrix.
    pub to_srgb0: [f32; 4],
    /// Second column.
    pub to_srgb1: [f32; 4],
    /// Third column.
    pub to_srgb2: [f32; 4],
    /// Range of the aerial-perspective volume (m); the projection's `A` and `B`, so that a
    /// depth-buffer value `z` lies at view depth `B / (z + A)`; the far plane's depth (0 for
    /// reversed-Z, 1 for standard).
    pub aerial: [f32; 4],
    /// x = number of suns; y = number of eclipsing bodies; z = 1 when the sky-view LUT spans
    /// the whole circle of azimuths (there are eclipsers), 0 for half of it; w = number of
    /// bodies (the first `w` eclipsers).
    pub sun_count: [u32; 4],
    /// The suns; the first `sun_count` are used.
    pub suns: [AtmosphereSunUniform; MAX_SUNS],
    /// The eclipsing bodies: centre in the planet frame (m), radius (m) in `w`; the first
    /// `sun_count[1]` are used.
    pub eclipsers: [[f32; 4]; MAX_ECLIPSERS],
    /// The planet's rings: inner and outer radius (m), Henyey–Greenstein `g`, 1 with rings (0
    /// without).
    pub rings: [f32; 4],
    /// The rings' single-scattering albedo per model wavelength; `w` unused.
    pub ring_albedo: [f32; 4],
    /// The rings' normal optical depth at `inner + k·(outer − inner)/(N − 1)`, four to a vector
    /// ([`Rings::optical_depth_table`]).
    pub ring_depth: [[f32; 4]; RING_TABLE_ENTRIES / 4],
    /// The planet's surface: x = 1 when the ground is read from the surface map (0: the
    /// medium's `ground_albedo` everywhere, no water); y = the sea's mean square slope for the
    /// suns' glint ([`glint::slope_variance`]); z = the planet's geometric albedo (its light on
    /// the bodies, [`Planet::geometric_albedo`]); w = its volumetric mean radius (m).
    pub surface: [f32; 4],
    /// The bodies beside the planet; the first `sun_count[3]` are used.
    pub bodies: [AtmosphereBodyUniform; MAX_BODIES],
    /// Per body, the sunlight's share across the planet's shadow where it stands, per model
    /// wavelength ([`PlanetShadow::light`](firmament_core::atmosphere::planet_shadow::PlanetShadow::light)).
    pub body_shadows: [[[f32; 4]; SHADOW_ENTRIES]; MAX_BODIES],
    /// Per body, its air's molecules, aerosols and absorbing gas (zero when airless).
    pub body_air: [[MediumTermUniform; BODY_AIR_TERMS]; MAX_BODIES],
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The rings' part of [`AtmosphereViewUniforms`]: radii, `g` and the flag; albedo; the optical
/// depth table (all zero without rings).
fn ring_fields(rings: Option<&Rings>) -> ([f32; 4], [f32; 4], [[f32; 4]; RING_TABLE_ENTRIES / 4]) {
    let Some(rings) = rings else {
        return ([0.0; 4], [0.0; 4], [[0.0; 4]; RING_TABLE_ENTRIES / 4]);
    };
    let table = rings.optical_depth_table();
    (
        [
            rings.inner_m() as f32,
            rings.outer_m() as f32,
            rings.phase_g as f32,
            1.0,
        ],
        spectrum_w(rings.albedo, 0.0),
        std::array::from_fn(|k| std::array::from_fn(|j| table[4 * k + j] as f32)),
    )
}

impl AtmosphereViewUniforms {
    /// The same view for a depth buffer in `convention`: the projection's `A`, `B` and the far
    /// plane's depth in `aerial` (what [`Self::new`] gives is reversed-Z's).
    pub fn for_depth_convention(mut self, camera: &Camera, convention: DepthConvention) -> Self {
        let projection = camera.projection_matrix_for(convention);
        self.aerial[1] = projection.z_axis.z as f32;
        self.aerial[2] = projection.w_axis.z as f32;
        self.aerial[3] = convention.far_depth() as f32;
        self
    }

    /// The view of `sky` by `camera` (whose aspect ratio is the target's).
    pub fn new(sky: &AtmosphereSky, camera: &Camera) -> Self {
        let atmosphere = &sky.atmosphere;
        let planet = &atmosphere.planet;
        let top_radii = planet.radii + DVec3::splat(planet.atmosphere_height);
        let o = planet.to_planet_frame(camera.position);
        let altitude = planet.altitude(o);
        let up = planet.up(o);
        let shape = PlanetView::new(camera, planet.center, planet.orientation, o, planet.radii, top_radii);
        let (band_low, band_high) = LUT_TO_MARCH_BAND;
        let height = planet.atmosphere_height;
        let blend = if shape.far {
            1.0
        } else {
            smoothstep(band_low * height, band_high * height, altitude)
        };

        let projection = camera.projection_matrix();
        let to_srgb = atmosphere.spectral_conversion().to_linear_srgb_matrix();
        let mut suns = [AtmosphereSunUniform::zeroed(); MAX_SUNS];
        for (slot, sun) in suns.iter_mut().zip(&sky.suns) {
            let direction = planet.direction_to_planet_frame(sun.direction).normalize_or_zero();
            *slot = AtmosphereSunUniform {
                // A negative radius: a light whose disc is not drawn (the shaders use its size).
                direction: vec3_w(
                    direction,
                    if sun.disc {
                        sun.angular_radius
                    } else {
                        -sun.angular_radius
                    },
                ),
                irradiance: spectrum_w(sun.irradiance, sun.limb_darkening),
                source: [sun.from_body.map_or(0, |b| b as u32 + 1), 0, 0, 0],
            };
        }
        let mut eclipsers = [[0.0; 4]; MAX_ECLIPSERS];
        for (slot, body) in eclipsers.iter_mut().zip(&sky.eclipsers) {
            *slot = vec3_w(planet.to_planet_frame(body.center), body.radius_m);
        }
        let eclipser_count = sky.eclipsers.len().min(MAX_ECLIPSERS);
        let (rings, ring_albedo, ring_depth) = ring_fields(sky.rings.as_ref());
        let mut bodies = [AtmosphereBodyUniform::zeroed(); MAX_BODIES];
        let mut body_shadows = [[[0.0; 4]; SHADOW_ENTRIES]; MAX_BODIES];
        let mut body_air = [[MediumTermUniform::zeroed(); BODY_AIR_TERMS]; MAX_BODIES];
        for (i, body) in sky.bodies.iter().take(MAX_BODIES).enumerate() {
            bodies[i] = AtmosphereBodyUniform::new(body, planet);
            body_shadows[i] = AtmosphereBodyUniform::shadow_table(body);
            body_air[i] = AtmosphereBodyUniform::air_terms(body);
        }
        Self {
            view_to_planet: shape.view_to_planet,
            camera: vec3_w(o, altitude),
            camera_shape: shape.camera_shape,
            center: shape.center,
            local_up: vec3_w(up, blend),
            to_srgb0: vec3_w(to_srgb.x_axis, 0.0),
            to_srgb1: vec3_w(to_srgb.y_axis, 0.0),
            to_srgb2: vec3_w(to_srgb.z_axis, 0.0),
            aerial: [
                AERIAL_PERSPECTIVE_RANGE as f32,
                projection.z_axis.z as f32,
                projection.w_axis.z as f32,
                0.0,
            ],
            sun_count: [
                sky.suns.len().min(MAX_SUNS) as u32,
                eclipser_count as u32,
                u32::from(eclipser_count > 0),
                sky.bodies.len().min(MAX_BODIES) as u32,
            ],
            suns,
            eclipsers,
            rings,
            ring_albedo,
            ring_depth,
            surface: surface_fields(sky.surface.as_ref(), planet),
            bodies,
            body_shadows,
            body_air,
        }
    }
}

/// The surface's part of [`AtmosphereViewUniforms`]: the flag, the glint's slope variance, the
/// planet's geometric albedo and volumetric mean radius.
fn surface_fields(surface: Option<&Surface>, planet: &Planet) -> [f32; 4] {
    let (flag, slopes) = surface.map_or((0.0, 0.0), |s| (1.0, glint::slope_variance(s.wind_speed_mps) as f32));
    [
        flag,
        slopes,
        planet.geometric_albedo as f32,
        planet.radii.element_product().cbrt() as f32,
    ]
}
