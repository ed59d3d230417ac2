//! Constructors of the scene's list entries, for [`SceneBuilder`](super::SceneBuilder): suns,
//! cloud layers, lights and objects, every value in the unit its name says.

use firmament_core::atmosphere::clouds::CloudKind;

use crate::color::SceneColor;
use crate::model::{
    CloudEntry, GlColor, LightEntry, LightSpaceName, MaterialEntry, MeshEntry, ObjectEntry, SpinEntry, SunEntry,
    TextureEntry, TransformEntry,
};

impl SunEntry {
    /// The body's sun at `azimuth` (from north, clockwise towards east) and `elevation` (above
    /// the horizontal plane), degrees, in the world frame; everything else the body's.
    pub fn at_deg(azimuth: f64, elevation: f64) -> Self {
        Self {
            name: None,
            azimuth_deg: Some(azimuth),
            elevation_deg: Some(elevation),
            position: None,
            angular_radius_deg: None,
            temperature: None,
            color: None,
            irradiance: None,
            limb_darkening: None,
        }
    }

    /// The same sun with a label.
    #[must_use]
    pub fn named(self, name: &str) -> Self {
        Self {
            name: Some(name.to_owned()),
            ..self
        }
    }

    /// The same sun with a disc of angular radius `radius`, degrees.
    #[must_use]
    pub fn angular_radius_deg(self, radius: f64) -> Self {
        Self {
            angular_radius_deg: Some(radius),
            ..self
        }
    }

    /// The same sun coloured as a black body at `temperature`, kelvin.
    #[must_use]
    pub fn temperature_k(self, temperature: f64) -> Self {
        Self {
            temperature: Some(temperature),
            ..self
        }
    }

    /// The body's sun towards `position` (`[east, north, up]` metres, world frame; the direction
    /// from the planet's centre to it, above the atmosphere).
    pub fn at_position_m(position: [f64; 3]) -> Self {
        Self {
            azimuth_deg: None,
            elevation_deg: None,
            position: Some(position),
            ..Self::at_deg(0.0, 0.0)
        }
    }

    /// The same sun coloured `color` (relative spectral irradiance at the model wavelengths).
    #[must_use]
    pub fn color(self, color: SceneColor) -> Self {
        Self {
            color: Some(color),
            ..self
        }
    }

    /// The same sun with linear limb darkening `coefficient`, [0, 1].
    #[must_use]
    pub fn limb_darkening(self, coefficient: f64) -> Self {
        Self {
            limb_darkening: Some(coefficient),
            ..self
        }
    }

    /// The same sun with spectral irradiance `irradiance` at 550 nm above the air, W·m⁻²·nm⁻¹.
    #[must_use]
    pub fn irradiance(self, irradiance: f64) -> Self {
        Self {
            irradiance: Some(irradiance),
            ..self
        }
    }
}

impl LightEntry {
    /// A GL light with every value GL's initial one for its index: `position` `[x, y, z, w]`
    /// (`w = 0` directional, towards the light; `w = 1` positional, metres), in eye space.
    pub fn at(position: [f64; 4]) -> Self {
        Self {
            space: LightSpaceName::Eye,
            position: Some(position),
            ambient: None,
            diffuse: None,
            specular: None,
            spot_direction: None,
            spot_exponent: None,
            spot_cutoff_deg: None,
            attenuation: None,
            flare: false,
            flare_radius: None,
        }
    }

    /// The same light fixed in the world instead of to the camera.
    #[must_use]
    pub fn in_world(self) -> Self {
        Self {
            space: LightSpaceName::World,
            ..self
        }
    }

    /// The same light with `GL_DIFFUSE` and `GL_SPECULAR` both `color`.
    #[must_use]
    pub fn color(self, color: GlColor) -> Self {
        Self {
            diffuse: Some(color),
            specular: Some(color),
            ..self
        }
    }

    /// The same light as a spot towards `direction`, its cone `cutoff` degrees wide ([0, 90]) with
    /// falloff `exponent` ([0, 128]).
    #[must_use]
    pub fn spot_deg(self, direction: [f64; 3], cutoff: f64, exponent: f64) -> Self {
        Self {
            spot_direction: Some(direction),
            spot_cutoff_deg: Some(cutoff),
            spot_exponent: Some(exponent),
            ..self
        }
    }

    /// The same light with constant, linear (1/m) and quadratic (1/m²) attenuation.
    #[must_use]
    pub fn attenuation(self, constant_linear_quadratic: [f64; 3]) -> Self {
        Self {
            attenuation: Some(constant_linear_quadratic),
            ..self
        }
    }

    /// The same light as a lens-flare source (when flares are on).
    #[must_use]
    pub fn with_flare(self) -> Self {
        Self { flare: true, ..self }
    }
}

impl ObjectEntry {
    /// `mesh` at the origin, GL's initial material on both sides, no texture or spin.
    pub fn new(mesh: MeshEntry) -> Self {
        Self {
            name: None,
            mesh,
            transform: Vec::new(),
            material: MaterialEntry::default(),
            back_material: None,
            texture: None,
            spin: None,
            fog_coord: 0.0,
        }
    }

    /// The same object with a label.
    #[must_use]
    pub fn named(self, name: &str) -> Self {
        Self {
            name: Some(name.to_owned()),
            ..self
        }
    }

    /// Appends `glTranslate(offset)`, metres (steps apply like GL calls: the last acts first).
    #[must_use]
    pub fn translate_m(mut self, offset: [f64; 3]) -> Self {
        self.transform.push(TransformEntry::Translate(offset));
        self
    }

    /// Appends `glRotate(angle, axis)`: `angle` degrees counter-clockwise about `axis`.
    #[must_use]
    pub fn rotate_deg(mut self, angle: f64, axis: [f64; 3]) -> Self {
        self.transform
            .push(TransformEntry::Rotate([angle, axis[0], axis[1], axis[2]]));
        self
    }

    /// Appends `glScale(factors)`.
    #[must_use]
    pub fn scale(mut self, factors: [f64; 3]) -> Self {
        self.transform.push(TransformEntry::Scale(factors));
        self
    }

    /// The same object with `material` on both sides.
    #[must_use]
    pub fn material(self, material: MaterialEntry) -> Self {
        Self { material, ..self }
    }

    /// The same object with `GL_DIFFUSE` `color` (with lighting off, its colour).
    #[must_use]
    pub fn diffuse(mut self, color: GlColor) -> Self {
        self.material.diffuse = Some(color);
        self
    }

    /// The same object with `material` on its back faces (values it leaves out come from the
    /// front material).
    #[must_use]
    pub fn back_material(self, material: MaterialEntry) -> Self {
        Self {
            back_material: Some(material),
            ..self
        }
    }

    /// The same object with `texture` modulating its lit colour.
    #[must_use]
    pub fn texture(self, texture: TextureEntry) -> Self {
        Self {
            texture: Some(texture),
            ..self
        }
    }

    /// The same object spinning about `axis` (its own frame) at `rate` degrees per second of the
    /// scene's time.
    #[must_use]
    pub fn spin_deg_per_s(self, axis: [f64; 3], rate: f64) -> Self {
        Self {
            spin: Some(SpinEntry {
                axis,
                degrees_per_second: rate,
            }),
            ..self
        }
    }
}

impl CloudEntry {
    /// A layer of `kind` from `bottom` to `top` (metres above the surface) covering `coverage`
    /// (0–1) of the sky, of extinction `density` (per metre) at full density; no wind, seed 0,
    /// albedo 1, the droplets' phase function, no coverage map.
    pub fn new_m(kind: CloudKind, bottom: f64, top: f64, coverage: f64, density_per_m: f64) -> Self {
        Self {
            bottom_m: bottom,
            top_m: top,
            coverage,
            density_per_m,
            kind,
            wind_mps: [0.0, 0.0],
            seed: 0,
            coverage_map: None,
            albedo: 1.0,
            phase: None,
        }
    }

    /// The same layer carried by a wind of `east`, `north` metres per second.
    #[must_use]
    pub fn wind_mps(self, east: f64, north: f64) -> Self {
        Self {
            wind_mps: [east, north],
            ..self
        }
    }

    /// The same layer with the noise seed `seed`.
    #[must_use]
    pub fn seed(self, seed: u32) -> Self {
        Self { seed, ..self }
    }
}
