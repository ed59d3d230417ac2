//! Lens flares: the elements a flare is made of, where they lie on screen, and how much of each
//! source can be seen.
//!
//! The construction is NeHe lesson 44's (seed 003): the flare's axis runs from the source to the
//! point on the camera axis at the source's distance (the screen centre), and an element at
//! `position` p sits at `source + (that point − source)·p` — 0 on the source, 1 on the screen
//! centre, beyond 1 past it. Occlusion follows the lesson's own to-do and Unity's SRP lens flare:
//! many depth samples over the source's disc instead of one pixel, so a flare fades instead of
//! vanishing; [`sample_pattern`] is the pattern the GPU pass uses and [`visible_fraction`] its
//! CPU statement.
//!
//! # Conventions
//! Screen positions are normalised device coordinates (NDC): x right and y up in [−1, 1].
//! Element sizes are radii in units of half the screen **height** (NDC y), drawn round on any
//! aspect ratio. Colours are linear RGB in display units: 1 is white after the frame's exposure.

use std::sync::Arc;

use glam::{DMat4, DVec2, DVec3, DVec4};

use crate::camera::Camera;
use crate::camera::frustum::{ClipDepth, Frustum};
use crate::camera::viewport::{Viewport, project_zero_to_one};
use crate::error::CoreError;
use crate::texture::TextureImage;

/// Most occlusion samples per source.
pub const MAX_FLARE_SAMPLES: u32 = 256;
/// Most elements in one flare.
pub const MAX_FLARE_ELEMENTS: usize = 64;
/// Most flare sources in a frame (suns and lights marked `flare`).
pub const MAX_FLARE_SOURCES: usize = 64;
/// Most images one flare may use ([`LensFlare::images`]).
pub const MAX_FLARE_IMAGES: usize = 16;
/// The side of every flare image, texels: image files are resampled to this square when loaded,
/// so that all of a flare's images fit one texture array.
pub const FLARE_IMAGE_SIDE: u32 = 256;

/// The shape of one flare element: drawn procedurally, or an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlareShape {
    /// A soft glow falling smoothly to zero at the element's radius.
    Glow,
    /// Rays from the centre: `points` of them (2 = one line through the centre), turned by
    /// `rotation` degrees counter-clockwise from the +x axis, narrower as `sharpness` grows.
    Streaks {
        /// Number of rays, 2 to 32.
        points: u32,
        /// Degrees, counter-clockwise from +x.
        rotation: f64,
        /// Exponent of the angular falloff, >= 1.
        sharpness: f64,
    },
    /// A ring at the element's radius, `thickness` of the radius wide.
    Halo {
        /// Ring width as a fraction of the radius, in (0, 1].
        thickness: f64,
    },
    /// A flat ghost of the aperture: a disc (`sides = 0`) or a regular polygon, its edge blurred
    /// over `softness` of the radius.
    Ghost {
        /// 0 (a disc) or 3 to 16.
        sides: u32,
        /// Degrees, counter-clockwise.
        rotation: f64,
        /// Edge blur as a fraction of the radius, in (0, 1].
        softness: f64,
    },
    /// An image ([`LensFlare::images`]`[image]`) over the element's quad, as NeHe lesson 44 drew
    /// its sprites: each texel's RGB × alpha (bytes / 255, as stored, like `GL_MODULATE`) times
    /// the element's colour is the light added. The picture's left edge is at the quad's left
    /// edge, its top row at the top, before `rotation`.
    Image {
        /// Index into [`LensFlare::images`].
        image: u32,
        /// Degrees, counter-clockwise.
        rotation: f64,
    },
}

/// The lens's aperture, the iris its blades make: the shape of the glare's diffraction starburst
/// (and of the presets' ghosts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aperture {
    /// Blades: 0 for a round iris (no spikes), else 3 to 16 (a regular polygon).
    pub blades: u32,
    /// Degrees, counter-clockwise from +x: the direction of one of the polygon's corners (as a
    /// [`FlareShape::Ghost`]'s `rotation`).
    pub rotation: f64,
}

impl Aperture {
    /// A round iris.
    pub const ROUND: Self = Self {
        blades: 0,
        rotation: 0.0,
    };

    /// The diffraction starburst's spikes: each straight edge of the iris spreads light along its
    /// normal, both ways, so an even number of blades gives as many spikes (opposite edges
    /// share a line) and an odd number twice as many; a round iris none.
    pub fn spikes(self) -> u32 {
        match self.blades {
            0 => 0,
            n if n % 2 == 0 => n,
            n => 2 * n,
        }
    }

    /// The direction of one spike, degrees counter-clockwise from +x: the normal of an edge,
    /// half a sector from a corner.
    pub fn spike_rotation(self) -> f64 {
        match self.blades {
            0 => 0.0,
            n => self.rotation + 180.0 / f64::from(n),
        }
    }
}

/// The glare's starburst: its radius (half image heights) and how narrow its spikes are (the
/// [`FlareShape::Streaks`] sharpness).
pub const GLARE_STARBURST_SIZE: f64 = 0.6;
/// See [`GLARE_STARBURST_SIZE`].
pub const GLARE_STARBURST_SHARPNESS: f64 = 64.0;
/// The glare's veiling glow about the source (light scattered in the lens): its radius (half
/// image heights) and its brightness as a share of the starburst's.
pub const GLARE_GLOW_SIZE: f64 = 0.15;
/// See [`GLARE_GLOW_SIZE`].
pub const GLARE_GLOW_SHARE: f64 = 0.5;
/// Elements the glare adds about each source.
pub const GLARE_ELEMENTS: usize = 2;

/// One element of a flare.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlareElement {
    /// Its shape.
    pub shape: FlareShape,
    /// Linear RGB tint, each >= 0.
    pub color: DVec3,
    /// Brightness multiplier, >= 0.
    pub intensity: f64,
    /// Radius in units of half the screen height, > 0.
    pub size: f64,
    /// Horizontal stretch (1 = round; an anamorphic streak is much wider than tall), > 0.
    pub stretch: f64,
    /// Place along the flare axis: 0 = the source, 1 = the screen centre, beyond 1 past it.
    pub position: f64,
}

impl FlareElement {
    /// A round element of `shape` with colour `color` (as RGB) and intensity `intensity`.
    pub fn new(shape: FlareShape, color: [f64; 3], intensity: f64, size: f64, position: f64) -> Self {
        Self {
            shape,
            color: DVec3::from_array(color),
            intensity,
            size,
            stretch: 1.0,
            position,
        }
    }
}

/// A lens flare: its elements, how occlusion is sampled, how it fades.
#[derive(Debug, Clone, PartialEq)]
pub struct LensFlare {
    /// The elements, at most [`MAX_FLARE_ELEMENTS`].
    pub elements: Vec<FlareElement>,
    /// Depth samples over each source's disc, 1 to [`MAX_FLARE_SAMPLES`].
    pub samples: u32,
    /// How far past the screen edge (in units of half the screen, NDC) a source's disc may go
    /// while its flare fades out, >= 0 (0 = cut off as the disc leaves the screen).
    pub margin: f64,
    /// Overall brightness, >= 0.
    pub intensity: f64,
    /// Visibility may rise by at most this much per second (0 = at once): a viewer's smoothing.
    /// Stills use the instantaneous value whatever this says.
    pub fade_in: f64,
    /// Visibility may fall by at most this much per second (0 = at once).
    pub fade_out: f64,
    /// The images of [`FlareShape::Image`] elements, each [`FLARE_IMAGE_SIDE`] square, at most
    /// [`MAX_FLARE_IMAGES`].
    pub images: Vec<Arc<TextureImage>>,
    /// The lens's iris, which shapes the glare's starburst.
    pub aperture: Aperture,
    /// The glare's brightness, >= 0 (0 = none): the aperture's diffraction starburst and a veiling
    /// glow about every source, as elements of this brightness at the source
    /// ([`Self::lens_elements`]).
    pub glare: f64,
}

/// NeHe's sizes are world-space half-widths of quads drawn at the light; firmament's are
/// screen-relative. The `classic` preset converts them for a light 50 units ahead under a 45°
/// field of view (the `nehe-flare` preset's view): one unit there is `1 / (50·tan 22.5°)` of half
/// the screen height.
const NEHE_UNIT: f64 = 1.0 / (50.0 * 0.414_213_562_373_095_1);

impl LensFlare {
    fn with_elements(elements: Vec<FlareElement>) -> Self {
        Self {
            elements,
            samples: 32,
            margin: 0.2,
            intensity: 1.0,
            fade_in: 0.0,
            fade_out: 0.0,
            images: Vec::new(),
            aperture: Aperture::ROUND,
            glare: 0.0,
        }
    }

    /// Every element the lens draws about each source: the flare's own, then — with glare — the
    /// aperture's starburst (spikes along its edges' normals, [`Aperture::spikes`]; none for a
    /// round iris) and a veiling glow, both at the source.
    pub fn lens_elements(&self) -> Vec<FlareElement> {
        let mut elements = self.elements.clone();
        if self.glare > 0.0 {
            let white = [1.0, 1.0, 1.0];
            let spikes = self.aperture.spikes();
            if spikes > 0 {
                let starburst = FlareShape::Streaks {
                    points: spikes,
                    rotation: self.aperture.spike_rotation(),
                    sharpness: GLARE_STARBURST_SHARPNESS,
                };
                elements.push(FlareElement::new(
                    starburst,
                    white,
                    self.glare,
                    GLARE_STARBURST_SIZE,
                    0.0,
                ));
            }
            let glow = self.glare * GLARE_GLOW_SHARE;
            elements.push(FlareElement::new(FlareShape::Glow, white, glow, GLARE_GLOW_SIZE, 0.0));
        }
        elements
    }

    /// NeHe lesson 44's flare (seed 003, `glCamera::RenderLensFlare`): a big glow and 16 streaks
    /// at the light, a small glow, then glows and halos along the axis at the lesson's positions,
    /// colours and scales. The lesson draws each with alpha 0.5 (1 for the big glow and streaks)
    /// and `GL_SRC_ALPHA, GL_ONE` blending: that alpha is the intensity here.
    pub fn classic() -> Self {
        use FlareShape::{Glow, Halo};
        let halo = Halo { thickness: 0.25 };
        let streaks = FlareShape::Streaks {
            points: 16,
            rotation: 0.0,
            sharpness: 24.0,
        };
        let nehe = |shape, color: [f64; 3], alpha: f64, scale: f64, position: f64| {
            FlareElement::new(shape, color, alpha, scale * NEHE_UNIT, position)
        };
        Self::with_elements(vec![
            nehe(Glow, [0.60, 0.60, 0.8], 1.0, 16.0, 0.0),
            nehe(streaks, [0.60, 0.60, 0.8], 1.0, 16.0, 0.0),
            nehe(Glow, [0.8, 0.8, 1.0], 0.5, 3.5, 0.0),
            nehe(Glow, [0.9, 0.6, 0.4], 0.5, 0.6, 0.1),
            nehe(halo, [0.8, 0.5, 0.6], 0.5, 1.7, 0.15),
            nehe(halo, [0.9, 0.2, 0.1], 0.5, 0.83, 0.175),
            nehe(halo, [0.7, 0.7, 0.4], 0.5, 1.6, 0.285),
            nehe(Glow, [0.9, 0.9, 0.2], 0.5, 0.8, 0.2755),
            nehe(Glow, [0.93, 0.82, 0.73], 0.5, 1.0, 0.4775),
            nehe(halo, [0.7, 0.6, 0.5], 0.5, 1.4, 0.49),
            nehe(Glow, [0.7, 0.8, 0.3], 0.5, 1.8, 0.65),
            nehe(Glow, [0.4, 0.3, 0.2], 0.5, 1.4, 0.63),
            nehe(halo, [0.7, 0.5, 0.5], 0.5, 1.4, 0.8),
            nehe(Glow, [0.8, 0.5, 0.1], 0.5, 0.6, 0.7825),
            nehe(halo, [0.5, 0.5, 0.7], 0.5, 1.7, 1.0),
            nehe(Glow, [0.4, 0.1, 0.9], 0.5, 2.0, 0.975),
        ])
    }

    /// A restrained modern camera look: a soft glow, faint six-sided aperture ghosts mirrored
    /// through the centre, and a wide faint halo; a six-bladed iris.
    pub fn subtle() -> Self {
        let aperture = Aperture {
            blades: 6,
            rotation: 15.0,
        };
        let ghost = |sides| FlareShape::Ghost {
            sides,
            rotation: aperture.rotation,
            softness: 0.15,
        };
        let elements = vec![
            FlareElement::new(FlareShape::Glow, [1.0, 0.95, 0.85], 0.35, 0.25, 0.0),
            FlareElement::new(ghost(6), [0.5, 0.7, 1.0], 0.05, 0.06, 1.3),
            FlareElement::new(ghost(6), [0.6, 1.0, 0.7], 0.04, 0.1, 1.6),
            FlareElement::new(ghost(0), [1.0, 0.7, 0.5], 0.03, 0.16, 1.9),
            FlareElement::new(ghost(6), [0.7, 0.6, 1.0], 0.04, 0.05, 0.6),
            FlareElement::new(FlareShape::Halo { thickness: 0.08 }, [0.8, 0.9, 1.0], 0.03, 0.9, 1.0),
        ];
        Self {
            aperture,
            ..Self::with_elements(elements)
        }
    }

    /// An anamorphic lens: a long thin horizontal blue streak through the source and a few
    /// horizontally stretched ghosts.
    pub fn anamorphic() -> Self {
        let line = FlareShape::Streaks {
            points: 2,
            rotation: 0.0,
            sharpness: 200.0,
        };
        let oval = FlareShape::Ghost {
            sides: 0,
            rotation: 0.0,
            softness: 0.4,
        };
        Self::with_elements(vec![
            FlareElement {
                stretch: 8.0,
                ..FlareElement::new(line, [0.4, 0.6, 1.0], 0.6, 0.5, 0.0)
            },
            FlareElement::new(FlareShape::Glow, [0.7, 0.8, 1.0], 0.4, 0.15, 0.0),
            FlareElement {
                stretch: 2.5,
                ..FlareElement::new(oval, [0.3, 0.5, 1.0], 0.05, 0.08, 1.4)
            },
            FlareElement {
                stretch: 2.5,
                ..FlareElement::new(oval, [0.5, 0.4, 1.0], 0.04, 0.12, 1.8)
            },
        ])
    }

    /// The named preset: `classic`, `subtle` or `anamorphic`.
    pub fn preset(name: &str) -> Option<Self> {
        match name {
            "classic" => Some(Self::classic()),
            "subtle" => Some(Self::subtle()),
            "anamorphic" => Some(Self::anamorphic()),
            _ => None,
        }
    }

    /// Checks every rule stated on the fields; the error names the field (`flare.…`).
    pub fn validate(&self) -> Result<(), CoreError> {
        let fail =
            |field: String, value: String, rule: &'static str| Err(CoreError::InvalidItem { field, value, rule });
        if !(1..=MAX_FLARE_SAMPLES).contains(&self.samples) {
            return fail("flare.samples".into(), self.samples.to_string(), "must be 1 to 256");
        }
        for (field, value) in [
            ("flare.margin", self.margin),
            ("flare.intensity", self.intensity),
            ("flare.fade_in", self.fade_in),
            ("flare.fade_out", self.fade_out),
            ("flare.glare", self.glare),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return fail(field.into(), value.to_string(), "must be a finite number >= 0");
            }
        }
        if self.images.len() > MAX_FLARE_IMAGES {
            return fail(
                "flare.elements".into(),
                format!("{} images", self.images.len()),
                "at most 16 different image files",
            );
        }
        for image in &self.images {
            if image.width != FLARE_IMAGE_SIDE || image.height != FLARE_IMAGE_SIDE {
                return fail(
                    "flare.images".into(),
                    format!("{}x{}", image.width, image.height),
                    "flare images must be resampled to 256x256 texels",
                );
            }
        }
        let blades = self.aperture.blades;
        if blades != 0 && !(3..=16).contains(&blades) {
            return fail(
                "flare.aperture_blades".into(),
                blades.to_string(),
                "must be 0 (a round iris) or 3 to 16",
            );
        }
        if !self.aperture.rotation.is_finite() {
            return fail(
                "flare.aperture_rotation".into(),
                self.aperture.rotation.to_string(),
                "must be finite (degrees)",
            );
        }
        if self.elements.len() > MAX_FLARE_ELEMENTS {
            return fail(
                "flare.elements".into(),
                format!("{} elements", self.elements.len()),
                "at most 64 elements",
            );
        }
        if self.glare > 0.0 && self.elements.len() + GLARE_ELEMENTS > MAX_FLARE_ELEMENTS {
            return fail(
                "flare.elements".into(),
                format!("{} elements", self.elements.len()),
                "at most 62 elements with glare (its starburst and glow take two of the 64)",
            );
        }
        for (i, e) in self.elements.iter().enumerate() {
            let key = |f: &str| format!("flare.elements[{i}].{f}");
            if !e.color.is_finite() || e.color.min_element() < 0.0 {
                return fail(
                    key("color"),
                    format!("{}", e.color),
                    "every component must be finite and >= 0",
                );
            }
            if !(e.intensity.is_finite() && e.intensity >= 0.0) {
                return fail(
                    key("intensity"),
                    e.intensity.to_string(),
                    "must be a finite number >= 0",
                );
            }
            for (name, value) in [("size", e.size), ("stretch", e.stretch)] {
                if !(value.is_finite() && value > 0.0) {
                    return fail(key(name), value.to_string(), "must be a finite number > 0");
                }
            }
            if !e.position.is_finite() {
                return fail(key("position"), e.position.to_string(), "must be a finite number");
            }
            match e.shape {
                FlareShape::Glow => {}
                FlareShape::Streaks {
                    points,
                    rotation,
                    sharpness,
                } => {
                    if !(2..=32).contains(&points) {
                        return fail(key("points"), points.to_string(), "must be 2 to 32");
                    }
                    if !rotation.is_finite() {
                        return fail(key("rotation"), rotation.to_string(), "must be finite degrees");
                    }
                    if !(sharpness.is_finite() && sharpness >= 1.0) {
                        return fail(key("sharpness"), sharpness.to_string(), "must be a finite number >= 1");
                    }
                }
                FlareShape::Halo { thickness } => {
                    if !(thickness > 0.0 && thickness <= 1.0) {
                        return fail(key("thickness"), thickness.to_string(), "must be in (0, 1]");
                    }
                }
                FlareShape::Ghost {
                    sides,
                    rotation,
                    softness,
                } => {
                    if sides != 0 && !(3..=16).contains(&sides) {
                        return fail(key("sides"), sides.to_string(), "must be 0 (a disc) or 3 to 16");
                    }
                    if !rotation.is_finite() {
                        return fail(key("rotation"), rotation.to_string(), "must be finite degrees");
                    }
                    if !(softness > 0.0 && softness <= 1.0) {
                        return fail(key("softness"), softness.to_string(), "must be in (0, 1]");
                    }
                }
                FlareShape::Image { image, rotation } => {
                    if image as usize >= self.images.len() {
                        return fail(key("image"), image.to_string(), "must index the flare's images");
                    }
                    if !rotation.is_finite() {
                        return fail(key("rotation"), rotation.to_string(), "must be finite degrees");
                    }
                }
            }
        }
        Ok(())
    }
}

/// Something that flares: a sun (at infinity) or a light at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlareSource {
    /// World frame: `w = 0`, the direction towards a source at infinity (any length > 0);
    /// `w = 1`, the source's position, metres.
    pub position: DVec4,
    /// The source's angular radius (radians, `w = 0`) or radius (metres, `w = 1`): the disc the
    /// occlusion samples cover.
    pub radius: f64,
    /// How bright its flare is (linear RGB, 1 = the elements' own colours): for a sun, its
    /// transmittance to the camera relative to space; for a light, its diffuse colour.
    pub color: DVec3,
}

impl FlareSource {
    /// The unit direction from `eye` towards the source and the tangent of its angular radius.
    fn seen_from(&self, eye: DVec3) -> Option<(DVec3, f64)> {
        if self.position.w == 0.0 {
            let d = self.position.truncate().try_normalize()?;
            Some((d, self.radius.tan()))
        } else {
            let to = self.position.truncate() / self.position.w - eye;
            let distance = to.length();
            let d = to.try_normalize()?;
            Some((d, (self.radius / distance).min(1e6)))
        }
    }
}

/// Where a source is on screen and how much its position lets it flare.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SourceOnScreen {
    /// Centre of its disc, NDC.
    pub center: DVec2,
    /// Radius of its disc in NDC x and y (an ellipse on a non-square screen), each >= 1e-4.
    pub disc: DVec2,
    /// 1 while the disc touches the screen, falling to 0 as it moves `margin` past the edge.
    pub edge_fade: f64,
}

/// Where `source` appears to `camera` (whose aspect is the target's), or `None` when it cannot
/// flare: behind the camera (or level with it), outside the side planes of the frustum widened
/// by `margin`. The frustum test is the core's [`Frustum`] on the source's bounding sphere (for
/// a sun, a sphere of its angular radius at unit distance); the position is the core's
/// [`project_zero_to_one`].
pub fn on_screen(camera: &Camera, source: &FlareSource, margin: f64) -> Option<SourceOnScreen> {
    let (direction, tan_radius) = source.seen_from(camera.position)?;
    let forward = camera.forward();
    let cos_angle = direction.dot(forward);
    if cos_angle <= 1e-6 {
        return None;
    }
    // Camera-relative at unit distance: suns and far lights alike keep their precision.
    let view = camera.view_rotation();
    let projection = camera.projection_matrix();
    let viewport = Viewport::new(2.0, 2.0);
    let win = project_zero_to_one(direction, &view, &projection, &viewport)?;
    let center = DVec2::new(win.x - 1.0, win.y - 1.0);
    // The disc's radius on screen: tan(radius) at unit distance, over the eye depth there.
    let focal = DVec2::new(projection.x_axis.x, projection.y_axis.y);
    let disc = (focal * tan_radius / cos_angle).max(DVec2::splat(1e-4));
    let frustum = Frustum::from_view_projection(&(projection * view), ClipDepth::ZeroToOne);
    let sphere_radius = tan_radius / (1.0 + tan_radius * tan_radius).sqrt();
    let inside = frustum.planes[..4]
        .iter()
        .all(|plane| plane.distance(direction) >= -sphere_radius);
    let edge_fade = if inside {
        1.0
    } else {
        let outside = (center.abs() - DVec2::ONE - disc).max_element();
        if margin > 0.0 {
            (1.0 - outside / margin).clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    (edge_fade > 0.0).then_some(SourceOnScreen {
        center,
        disc,
        edge_fade,
    })
}

/// The screen positions (NDC) of elements at `positions` along the flare axis of `source`,
/// by NeHe's construction in 3D: the point on the camera axis at the source's distance, the
/// vector from the source to it, each element at `source + vector·position`, projected. `None`
/// for an element that falls behind the camera (a far negative position) or a source that
/// cannot be placed.
pub fn element_centers(camera: &Camera, source: &FlareSource, positions: &[f64]) -> Vec<Option<DVec2>> {
    let Some((direction, _)) = source.seen_from(camera.position) else {
        return vec![None; positions.len()];
    };
    // Camera-relative, at unit distance: scaling the whole construction by the source's
    // distance does not move its projection.
    let light = direction;
    let on_axis = camera.forward();
    let view: DMat4 = camera.view_rotation();
    let projection = camera.projection_matrix();
    let viewport = Viewport::new(2.0, 2.0);
    positions
        .iter()
        .map(|&p| {
            let point = light + (on_axis - light) * p;
            if point.dot(on_axis) <= 1e-9 {
                return None;
            }
            let win = project_zero_to_one(point, &view, &projection, &viewport)?;
            Some(DVec2::new(win.x - 1.0, win.y - 1.0))
        })
        .collect()
}

/// The golden angle, radians: `π·(3 − √5)`.
const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653_3;

/// `n` sample points in the unit disc: Vogel's golden-angle spiral, `r = √((i + ½)/n)`,
/// `θ = i·golden angle` — each covers an equal share of the disc's area.
pub fn sample_pattern(n: u32) -> Vec<DVec2> {
    (0..n)
        .map(|i| {
            let r = ((f64::from(i) + 0.5) / f64::from(n)).sqrt();
            let theta = f64::from(i) * GOLDEN_ANGLE;
            DVec2::new(r * theta.cos(), r * theta.sin())
        })
        .collect()
}

/// The share of `n` samples over the disc at `center` with radii `disc` (NDC) that `occluded`
/// says are not hidden: the CPU statement of the occlusion pass.
pub fn visible_fraction(center: DVec2, disc: DVec2, n: u32, occluded: impl Fn(DVec2) -> bool) -> f64 {
    let pattern = sample_pattern(n);
    let visible = pattern.iter().filter(|&&s| !occluded(center + s * disc)).count();
    visible as f64 / f64::from(n.max(1))
}

/// The next smoothed visibility: `previous` moves towards `target` by at most `fade_in·dt`
/// upwards or `fade_out·dt` downwards (a rate of 0 jumps at once).
pub fn smoothed_visibility(previous: f64, target: f64, dt: f64, fade_in: f64, fade_out: f64) -> f64 {
    let step = target - previous;
    let limit = if step >= 0.0 { fade_in } else { fade_out };
    if limit <= 0.0 {
        target
    } else {
        previous + step.clamp(-limit * dt, limit * dt)
    }
}

/// The flares of a frame: the flare and its sources (empty: none).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FlareLayer {
    /// The flare every source draws; `None`: no flares.
    pub flare: Option<LensFlare>,
    /// The sources, at most [`MAX_FLARE_SOURCES`].
    pub sources: Vec<FlareSource>,
}

#[cfg(test)]
mod tests {
    use glam::DQuat;

    use super::*;

    fn camera() -> Camera {
        Camera {
            position: DVec3::new(3.0, -2.0, 1.0),
            orientation: DQuat::IDENTITY,
            fov_y: 45f64.to_radians(),
            aspect: 16.0 / 9.0,
            near: 0.1,
            far: Some(1000.0),
        }
    }

    fn sun(direction: DVec3) -> FlareSource {
        FlareSource {
            position: direction.extend(0.0),
            radius: 0.004675,
            color: DVec3::ONE,
        }
    }

    #[test]
    fn presets_are_valid_and_classic_is_the_lesson_s() {
        for name in ["classic", "subtle", "anamorphic"] {
            LensFlare::preset(name).expect(name).validate().expect(name);
        }
        let classic = LensFlare::classic();
        assert_eq!(classic.elements.len(), 16);
        let last = classic.elements[15];
        assert_eq!((last.position, last.color), (0.975, DVec3::new(0.4, 0.1, 0.9)));
        assert!((classic.elements[0].size - 16.0 * NEHE_UNIT).abs() < 1e-15);
    }

    #[test]
    fn element_positions_follow_nehe_s_construction() {
        let camera = camera();
        let d = (camera.forward() * 5.0 + camera.right() * 1.5 + camera.up() * 0.8).normalize();
        let source = sun(d);
        let centers = element_centers(&camera, &source, &[0.0, 0.5, 1.0, 1.5]);
        let at = on_screen(&camera, &source, 0.0).expect("visible");
        // 0: the source itself; 1: the screen centre.
        assert!((centers[0].expect("placed") - at.center).length() < 1e-12);
        assert!(centers[2].expect("placed").length() < 1e-12);
        // The NeHe points in world space at the source's true distance, projected with the
        // full view matrix, land on the same spots.
        let distance = 250.0;
        let light = camera.position + d * distance;
        let axis_point = camera.position + camera.forward() * distance;
        let vp = camera.projection_matrix() * camera.view_matrix();
        for (p, c) in [0.5, 1.5].iter().zip([centers[1], centers[3]]) {
            let world = light + (axis_point - light) * *p;
            let clip = vp * world.extend(1.0);
            let ndc = clip.truncate().truncate() / clip.w;
            assert!((ndc - c.expect("placed")).length() < 1e-9, "{p}: {ndc} vs {c:?}");
        }
        // Mirrored through the centre: 0.5 lies half-way in 3D, not in 2D (perspective), but on
        // the line from the source through the centre.
        let (a, b) = (at.center, centers[1].expect("placed"));
        assert!(a.perp_dot(b).abs() < 1e-12);
    }

    #[test]
    fn sources_behind_or_far_off_screen_do_not_flare() {
        let camera = camera();
        assert!(on_screen(&camera, &sun(-camera.forward()), 1.0).is_none());
        assert!(on_screen(&camera, &sun(camera.right()), 1.0).is_none());
        // Just past the right edge: fades over the margin.
        let tan_half_x = (camera.fov_y / 2.0).tan() * camera.aspect;
        let edge = |ndc_x: f64| sun((camera.forward() + camera.right() * tan_half_x * ndc_x).normalize());
        let disc = on_screen(&camera, &edge(0.5), 0.2).expect("on screen").disc.x;
        assert_eq!(on_screen(&camera, &edge(0.99), 0.2).expect("on").edge_fade, 1.0);
        // (The disc grows a little off axis, so "half-way" is approximate.)
        let half = on_screen(&camera, &edge(1.1 + disc), 0.2).expect("fading").edge_fade;
        assert!((half - 0.5).abs() < 0.02, "{half}");
        assert!(on_screen(&camera, &edge(1.21 + disc), 0.2).is_none());
        assert!(on_screen(&camera, &edge(1.01 + disc), 0.0).is_none());
        // A point light behind the camera, and one ahead.
        let ahead = FlareSource {
            position: (camera.position + camera.forward() * 10.0).extend(1.0),
            radius: 0.1,
            color: DVec3::ONE,
        };
        let at = on_screen(&camera, &ahead, 0.0).expect("ahead");
        assert!(at.center.length() < 1e-12);
        let focal = camera.projection_matrix().y_axis.y;
        assert!((at.disc.y - focal * 0.01).abs() < 1e-12, "{}", at.disc);
        let behind = FlareSource {
            position: (camera.position - camera.forward() * 10.0).extend(1.0),
            ..ahead
        };
        assert!(on_screen(&camera, &behind, 1.0).is_none());
    }

    #[test]
    fn samples_cover_the_disc_evenly() {
        let n = 256;
        let pattern = sample_pattern(n);
        assert!(pattern.iter().all(|s| s.length() < 1.0));
        // Half-plane and quarter-disc shares within 1/n + 2 %.
        let right = visible_fraction(DVec2::ZERO, DVec2::ONE, n, |p| p.x < 0.0);
        assert!((right - 0.5).abs() < 1.0 / f64::from(n) + 0.02, "{right}");
        let inner = visible_fraction(DVec2::ZERO, DVec2::ONE, n, |p| p.length() > 0.5);
        assert!((inner - 0.25).abs() < 1.0 / f64::from(n) + 0.02, "{inner}");
        assert_eq!(visible_fraction(DVec2::ZERO, DVec2::ONE, 32, |_| true), 0.0);
    }

    #[test]
    fn visibility_fades_at_its_rates() {
        assert_eq!(smoothed_visibility(0.0, 1.0, 0.1, 0.0, 0.0), 1.0);
        assert!((smoothed_visibility(0.0, 1.0, 0.1, 2.0, 5.0) - 0.2).abs() < 1e-15);
        assert!((smoothed_visibility(1.0, 0.0, 0.1, 2.0, 5.0) - 0.5).abs() < 1e-15);
        assert_eq!(smoothed_visibility(0.9, 1.0, 0.1, 2.0, 5.0), 1.0);
    }

    #[test]
    fn bad_flares_name_the_field() {
        let mut flare = LensFlare::classic();
        flare.samples = 0;
        assert!(flare.validate().unwrap_err().to_string().contains("flare.samples"));
        let mut flare = LensFlare::classic();
        flare.elements[3].size = -1.0;
        let message = flare.validate().unwrap_err().to_string();
        assert!(message.contains("flare.elements[3].size"), "{message}");
        let mut flare = LensFlare::classic();
        flare.elements[0].color.x = f64::NAN;
        assert!(flare.validate().unwrap_err().to_string().contains("elements[0].color"));
    }

    #[test]
    fn image_elements_need_their_image() {
        let image = FlareShape::Image {
            image: 0,
            rotation: 0.0,
        };
        let mut flare = LensFlare::classic();
        flare.elements[2].shape = image;
        let message = flare.validate().unwrap_err().to_string();
        assert!(message.contains("flare.elements[2].image"), "{message}");
        let texel = [255, 255, 255, 255];
        let side = FLARE_IMAGE_SIDE;
        let picture = TextureImage::checkerboard(side, 2, texel, [0; 4]).expect("a valid checkerboard");
        flare.images.push(Arc::new(picture));
        assert_eq!(flare.validate(), Ok(()));
        let small = TextureImage::checkerboard(16, 2, texel, [0; 4]).expect("a valid checkerboard");
        flare.images[0] = Arc::new(small);
        assert!(flare.validate().unwrap_err().to_string().contains("256x256"));
    }

    #[test]
    fn the_starburst_has_a_spike_pair_per_edge_direction() {
        let aperture = |blades| Aperture { blades, rotation: 10.0 };
        assert_eq!(
            [0, 5, 6, 7, 8].map(|n| aperture(n).spikes()),
            [0, 10, 6, 14, 8],
            "round, odd and even irises"
        );
        // A hexagon with a corner at 10°: its edges' normals at 40°, 100°, …
        assert!((aperture(6).spike_rotation() - 40.0).abs() < 1e-12);
        let mut flare = LensFlare::subtle();
        assert_eq!(flare.lens_elements(), flare.elements, "no glare, no extra elements");
        flare.glare = 0.8;
        let lens = flare.lens_elements();
        assert_eq!(lens.len(), flare.elements.len() + GLARE_ELEMENTS);
        let FlareShape::Streaks { points, rotation, .. } = lens[lens.len() - 2].shape else {
            panic!("a starburst: {:?}", lens[lens.len() - 2]);
        };
        assert_eq!(
            (points, rotation),
            (6, 45.0),
            "the subtle preset's six-bladed iris at 15°"
        );
        assert!(lens[lens.len() - 2..].iter().all(|e| e.position == 0.0));
        flare.aperture = Aperture::ROUND;
        assert_eq!(
            flare.lens_elements().len(),
            flare.elements.len() + 1,
            "a round iris: the glow only"
        );
        flare.aperture.blades = 2;
        assert!(
            flare
                .validate()
                .unwrap_err()
                .to_string()
                .contains("flare.aperture_blades")
        );
    }
}
