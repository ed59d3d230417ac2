//! `[flare]`: lens flares of the suns and of the `[[lights]]` marked `flare = true`.
//!
//! Sizes are radii in units of half the image height; positions run along the flare axis from the
//! source (0) through the image centre (1) and beyond; colours are linear RGB (see
//! [`firmament_core::flare`]).

use serde::Deserialize;

/// `flare.preset`: the built-in flare whose elements are used when `flare.elements` is absent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlarePresetName {
    /// NeHe lesson 44's glows, streaks and halos.
    Classic,
    /// A restrained modern camera look.
    Subtle,
    /// An anamorphic lens's horizontal streak.
    Anamorphic,
}

impl FlarePresetName {
    /// The name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Classic => "classic",
            Self::Subtle => "subtle",
            Self::Anamorphic => "anamorphic",
        }
    }
}

/// `kind` of a `flare.elements` entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlareKindName {
    /// A soft glow.
    Glow,
    /// Rays from the centre (`points`, `rotation`, `sharpness`).
    Streaks,
    /// A ring (`thickness`).
    Halo,
    /// A disc or polygon ghost of the aperture (`sides`, `rotation`, `softness`).
    Ghost,
    /// An image file (`file`, `rotation`), NeHe's way: its texels times the colour.
    Image,
}

/// One `flare.elements` entry. Shape values that do not belong to `kind` are errors; absent ones
/// take the defaults noted.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlareElementEntry {
    /// `"glow"`, `"streaks"`, `"halo"`, `"ghost"` or `"image"`.
    pub kind: FlareKindName,
    /// Linear RGB tint, each finite and >= 0 (default white).
    #[serde(default = "white")]
    pub color: [f64; 3],
    /// Brightness, >= 0 (default 1).
    #[serde(default = "one")]
    pub intensity: f64,
    /// Radius in units of half the image height, > 0.
    pub size: f64,
    /// Horizontal stretch, > 0 (default 1: round).
    #[serde(default = "one")]
    pub stretch: f64,
    /// Place on the flare axis: 0 the source (default), 1 the image centre, beyond 1 past it.
    #[serde(default)]
    pub position: f64,
    /// Streaks: number of rays, 2 to 32 (default 6).
    #[serde(default)]
    pub points: Option<u32>,
    /// Streaks, ghosts and images: degrees counter-clockwise from +x (default 0).
    #[serde(default, rename = "rotation")]
    pub rotation_deg: Option<f64>,
    /// Streaks: angular falloff exponent, >= 1 (default 24).
    #[serde(default)]
    pub sharpness: Option<f64>,
    /// Halo: ring width as a fraction of the radius, (0, 1] (default 0.25).
    #[serde(default)]
    pub thickness: Option<f64>,
    /// Ghost: 0 (a disc) or 3 to 16 sides (default 6).
    #[serde(default)]
    pub sides: Option<u32>,
    /// Ghost: edge blur as a fraction of the radius, (0, 1] (default 0.15).
    #[serde(default)]
    pub softness: Option<f64>,
    /// Image: a PNG, JPEG or OpenEXR file (relative paths from the scene file's folder),
    /// resampled to 256×256; its texels (RGB × alpha, as stored) times `color` are the light.
    #[serde(default)]
    pub file: Option<String>,
}

fn white() -> [f64; 3] {
    [1.0; 3]
}

fn one() -> f64 {
    1.0
}

/// `[flare]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlareSection {
    /// Whether the suns and the flare lights draw flares.
    pub enabled: bool,
    /// `"classic"`, `"subtle"` or `"anamorphic"`.
    pub preset: FlarePresetName,
    /// The elements, replacing the preset's; absent = the preset's.
    #[serde(default)]
    pub elements: Option<Vec<FlareElementEntry>>,
    /// Occlusion samples over each source's disc, 1 to 256.
    pub samples: u32,
    /// How far past the image edge (half-screens, NDC) a source's flare fades out, >= 0.
    pub margin: f64,
    /// Overall brightness, >= 0.
    pub intensity: f64,
    /// Most rise of visibility per second for the viewer's smoothing, >= 0 (0 = at once).
    pub fade_in: f64,
    /// Most fall of visibility per second, >= 0 (0 = at once).
    pub fade_out: f64,
    /// The iris's blades, 0 (round) or 3 to 16; absent = the preset's.
    #[serde(default)]
    pub aperture_blades: Option<u32>,
    /// The iris's rotation, degrees; absent = the preset's.
    #[serde(default)]
    pub aperture_rotation: Option<f64>,
    /// The glare's brightness, >= 0 (0 = none): the iris's diffraction starburst and a veiling
    /// glow about every source.
    pub glare: f64,
}
