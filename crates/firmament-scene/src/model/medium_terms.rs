//! `[[atmosphere.terms]]`: the medium as a list of terms, each with its spectra, its density
//! profile and its phase function (instead of the shorthand Rayleigh / Mie / ozone keys).

use serde::Deserialize;

/// One `[[atmosphere.terms]]` entry.
///
/// Spectra (`scattering`, `absorption`; m⁻¹ at density 1, default 0) are a number, `[a, b, c]`
/// at the model wavelengths, `{ rayleigh = { cross_section = m², number_density = m⁻³ } }`
/// (λ⁻⁴ from the cross-section at `reference_wavelength`, default 550 nm) or
/// `{ angstrom = { coefficient = m⁻¹, exponent = α } }` (`coefficient · (λ/λ_ref)^−α`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TermEntry {
    /// A label for people (`"haze"`); not used by the renderer.
    #[serde(default)]
    pub name: Option<String>,
    /// Scattering coefficient at density 1, m⁻¹ (default 0).
    #[serde(default)]
    pub scattering: Option<toml::Value>,
    /// Absorption coefficient at density 1, m⁻¹ (default 0).
    #[serde(default)]
    pub absorption: Option<toml::Value>,
    /// The density profile: `"exponential"` (`scale_height`), `"tent"` (`bottom`, `peak`, `top`),
    /// `"constant"`, `"layers"` (`layers`) or `"table"` (`profile_table`).
    pub profile: ProfileName,
    /// Scale height of `"exponential"`, metres, > 0.
    #[serde(default)]
    pub scale_height: Option<f64>,
    /// Where the `"tent"` starts rising from 0, metres, >= 0.
    #[serde(default)]
    pub bottom: Option<f64>,
    /// The `"tent"`'s peak (density 1), metres, > `bottom`.
    #[serde(default)]
    pub peak: Option<f64>,
    /// Where the `"tent"` is back to 0, metres, > `peak`.
    #[serde(default)]
    pub top: Option<f64>,
    /// The one or two layers of `"layers"` (Bruneton 2017's density profile layers; with two,
    /// the first holds below its `width`).
    #[serde(default)]
    pub layers: Option<Vec<LayerEntry>>,
    /// The `[altitude m, density]` pairs of `"table"`: altitudes increasing strictly, densities
    /// >= 0, linear in between and held beyond the ends.
    #[serde(default)]
    pub profile_table: Option<Vec<[f64; 2]>>,
    /// The phase function: `"rayleigh"` (default), `"cornette_shanks"` or `"henyey_greenstein"`
    /// (`g`), `"dual_henyey_greenstein"` (`g`, `g_back`, `blend`) or `"table"` (`phase_table`).
    #[serde(default)]
    pub phase: Option<PhaseName>,
    /// Asymmetry parameter (the forward lobe's for two lobes), in (−1, 1).
    #[serde(default)]
    pub g: Option<f64>,
    /// The backward lobe's asymmetry parameter, in (−1, 1).
    #[serde(default)]
    pub g_back: Option<f64>,
    /// The forward lobe's weight, in [0, 1].
    #[serde(default)]
    pub blend: Option<f64>,
    /// The `[scattering angle °, value]` pairs of `"table"`, from 0 to 180, normalised on load.
    #[serde(default)]
    pub phase_table: Option<Vec<[f64; 2]>>,
}

/// One layer of a `"layers"` profile: `exp_term·e^(exp_scale·h) + linear_term·h +
/// constant_term`, clamped to [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerEntry {
    /// Where the layer ends, metres (the first of two layers only).
    #[serde(default)]
    pub width: f64,
    /// Factor of the exponential term.
    #[serde(default)]
    pub exp_term: f64,
    /// Rate of the exponential term, m⁻¹ (−1 / scale height).
    #[serde(default)]
    pub exp_scale: f64,
    /// Slope of the linear term, m⁻¹.
    #[serde(default)]
    pub linear_term: f64,
    /// Constant term.
    #[serde(default)]
    pub constant_term: f64,
}

/// A term's density profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProfileName {
    /// `e^(−h/scale_height)`.
    Exponential,
    /// 0 at `bottom`, 1 at `peak`, 0 at `top`, linear in between.
    Tent,
    /// Density 1 everywhere.
    Constant,
    /// Bruneton's layers.
    Layers,
    /// A table of altitudes and densities.
    Table,
}

/// A term's phase function.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PhaseName {
    /// Rayleigh's `3/(16π)·(1 + ν²)`.
    Rayleigh,
    /// Cornette & Shanks (1992).
    CornetteShanks,
    /// Henyey & Greenstein (1941).
    HenyeyGreenstein,
    /// Two Henyey–Greenstein lobes.
    DualHenyeyGreenstein,
    /// A table of angles and values.
    Table,
}
