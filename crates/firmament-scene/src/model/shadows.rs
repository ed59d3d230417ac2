//! `[shadows]` and `[ground]`: the suns' shadows over objects, and the planet's surface near the
//! camera that they fall on, under `lighting.model = "sky"`.
//!
//! Both sections are optional in a file: their keys take the values below (listed in the
//! `default` preset), which for `[shadows]` are [`ShadowSettings::default`]'s.

use firmament_core::classic::shadow::ShadowSettings;
use serde::Deserialize;

/// `[shadows]`: cascaded shadow maps of the atmosphere's suns, cast by objects onto themselves
/// and the ground (Dimitrov 2007; soft edges by the suns' discs, Fernando 2005). Every numeric
/// key is checked in every scene, whether shadows are on or not.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ShadowsSection {
    /// Whether the suns cast shadows. Absent: on exactly when `lighting.model = "sky"` and
    /// `lighting.shading = "phong"`, off otherwise. `true` needs both (shadows are cast by the
    /// atmosphere's suns and looked up per fragment).
    pub enabled: Option<bool>,
    /// Texels per side of each cascade's map, 256 to 8192 (default 2048); all maps together
    /// (`map_size² × cascades × max_suns × 4` bytes) must fit in 512 MiB.
    pub map_size: u32,
    /// Cascades per casting sun, 1 to 4 (default 4): slices of the view, each with its own map.
    pub cascades: u32,
    /// How far from the camera shadows reach, metres, in (0, 100000] (default 400); beyond it
    /// everything is lit.
    #[serde(rename = "distance")]
    pub distance_m: f64,
    /// Where the cascade splits lie between uniform (0) and logarithmic (1) spacing, in [0, 1]
    /// (default 0.8).
    pub split_blend: f64,
    /// Depth bias, texels of the cascade, in [0, 16] (default 1): a receiver is moved this far
    /// towards the sun before it is compared (against shadow acne).
    #[serde(rename = "depth_bias")]
    pub depth_bias_texels: f64,
    /// Normal bias, texels of the cascade, in [0, 16] (default 1.5): a receiver is moved this far
    /// along its normal, more where the sun grazes it.
    #[serde(rename = "normal_bias")]
    pub normal_bias_texels: f64,
    /// The most suns that cast at once, 1 to 8 (default 2): those above the camera's horizon,
    /// brightest first.
    pub max_suns: u32,
}

impl Default for ShadowsSection {
    /// [`ShadowSettings::default`]'s values, `enabled` absent.
    fn default() -> Self {
        let s = ShadowSettings::default();
        Self {
            enabled: None,
            map_size: s.map_size,
            cascades: s.cascades,
            distance_m: s.distance_m,
            split_blend: s.split_blend,
            depth_bias_texels: s.depth_bias_texels,
            normal_bias_texels: s.normal_bias_texels,
            max_suns: s.max_lights,
        }
    }
}

impl ShadowsSection {
    /// The core's settings of these keys (unchecked: [`ShadowSettings::validate`] checks them).
    pub fn settings(&self) -> ShadowSettings {
        ShadowSettings {
            map_size: self.map_size,
            cascades: self.cascades,
            distance_m: self.distance_m,
            split_blend: self.split_blend,
            depth_bias_texels: self.depth_bias_texels,
            normal_bias_texels: self.normal_bias_texels,
            max_lights: self.max_suns,
        }
    }
}

/// `[ground]`: under `lighting.model = "sky"`, the planet's surface near the camera drawn as
/// geometry (a patch of the curved surface out past the horizon, at most 100 km, of the
/// atmosphere's `ground_albedo`) that objects' shadows fall on, and whose light, bounced up, lights
/// the undersides of objects. Not used by the other lighting models.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GroundSection {
    /// Whether the ground is drawn and bounces light (default `true`).
    pub enabled: bool,
}

impl Default for GroundSection {
    fn default() -> Self {
        Self { enabled: true }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absent_keys_take_the_core_s_defaults() {
        let shadows: ShadowsSection = toml::from_str("").expect("empty [shadows]");
        assert_eq!(shadows, ShadowsSection::default());
        assert_eq!(shadows.settings(), ShadowSettings::default());
        let shadows: ShadowsSection = toml::from_str("cascades = 2").expect("one key");
        assert_eq!(shadows.settings().cascades, 2);
        assert_eq!(shadows.settings().map_size, ShadowSettings::default().map_size);
        let ground: GroundSection = toml::from_str("").expect("empty [ground]");
        assert!(ground.enabled);
    }
}
