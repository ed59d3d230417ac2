//! Built-in presets: TOML files compiled into the binary, and a scene file layered over its preset.

use crate::error::{SceneError, did_you_mean};
use crate::layers::{merge, parse_table};

/// A built-in preset.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// Its name, as given to `preset = "..."` or `--preset`.
    pub name: &'static str,
    /// One line for listings.
    pub summary: &'static str,
    /// The TOML text.
    pub toml: &'static str,
}

/// Every built-in preset; `default` is the base of all scenes.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "default",
        summary: "street level at 17:45, looking west at the low sun in sunset colours",
        toml: include_str!("presets/default.toml"),
    },
    Preset {
        name: "golden-hour",
        summary: "the showcase (`render` without a scene): golden hour over objects, auto-exposure, bloom, the Sun's flare",
        toml: include_str!("presets/golden-hour.toml"),
    },
    Preset {
        name: "dawn",
        summary: "06:20, looking east as the sun clears the horizon",
        toml: include_str!("presets/dawn.toml"),
    },
    Preset {
        name: "noon",
        summary: "12:30, looking up towards the high southern sun",
        toml: include_str!("presets/noon.toml"),
    },
    Preset {
        name: "dusk",
        summary: "18:40 afterglow in the west, PBR Neutral tone curve",
        toml: include_str!("presets/dusk.toml"),
    },
    Preset {
        name: "night",
        summary: "midnight in the seed's night colours",
        toml: include_str!("presets/night.toml"),
    },
    Preset {
        name: "midsummer-night",
        summary: "gradient: 22:30 on 2024-06-21 at 60° N, the real sun low in the north-west, keyframes by its elevation",
        toml: include_str!("presets/midsummer-night.toml"),
    },
    Preset {
        name: "earth-noon",
        summary: "atmosphere: Earth at noon, 45° N, looking south at the sky and the high Sun",
        toml: include_str!("presets/earth-noon.toml"),
    },
    Preset {
        name: "earth-sunset",
        summary: "atmosphere: Earth, looking west at the Sun 2° above the horizon",
        toml: include_str!("presets/earth-sunset.toml"),
    },
    Preset {
        name: "earth-clouds",
        summary: "atmosphere: fair-weather cumulus at mid-morning, the Sun 35° up, looking away from it",
        toml: include_str!("presets/earth-clouds.toml"),
    },
    Preset {
        name: "earth-clouds-sunset",
        summary: "atmosphere: cumulus and cirrus lit red from below by the Sun 2° above the horizon",
        toml: include_str!("presets/earth-clouds-sunset.toml"),
    },
    Preset {
        name: "earth-night",
        summary: "atmosphere: a moonlit night at a real date, 45° N, the Moon and the stars looking south",
        toml: include_str!("presets/earth-night.toml"),
    },
    Preset {
        name: "eclipse-2024",
        summary: "atmosphere: the total solar eclipse of 2024-04-08 from Dallas at mid-totality, a sunset all round",
        toml: include_str!("presets/eclipse-2024.toml"),
    },
    Preset {
        name: "lunar-eclipse-2025",
        summary: "atmosphere: the total lunar eclipse of 2025-03-14 from Mexico City, the red Moon in the Earth's shadow",
        toml: include_str!("presets/lunar-eclipse-2025.toml"),
    },
    Preset {
        name: "earth-orbit",
        summary: "atmosphere: Earth from 400 km up under a global layer of clouds, looking at the limb",
        toml: include_str!("presets/earth-orbit.toml"),
    },
    Preset {
        name: "earth-moon",
        summary: "atmosphere: Earth and the Moon from cislunar space, both gibbous, the Moon in front",
        toml: include_str!("presets/earth-moon.toml"),
    },
    Preset {
        name: "mars-noon",
        summary: "atmosphere: Mars at noon on the equator, the butterscotch sky and the dust's glow",
        toml: include_str!("presets/mars-noon.toml"),
    },
    Preset {
        name: "binary-sunset",
        summary: "atmosphere: two suns, 5800 K and 3600 K, setting on an Earth-like world, clouds lit by both",
        toml: include_str!("presets/binary-sunset.toml"),
    },
    Preset {
        name: "saturn-orbit",
        summary: "atmosphere: the oblate globe of Saturn from 180 000 km, lit at a gibbous phase",
        toml: include_str!("presets/saturn-orbit.toml"),
    },
    Preset {
        name: "saturn-rings",
        summary: "atmosphere: Saturn and its main rings from 400 000 km, the globe's shadow on the rings and theirs on it",
        toml: include_str!("presets/saturn-rings.toml"),
    },
    Preset {
        name: "venus-surface",
        summary: "atmosphere: Venus on the ground at noon, the dim orange light under 92 bar of CO₂ and a cloud deck of optical depth 26",
        toml: include_str!("presets/venus-surface.toml"),
    },
    Preset {
        name: "venus-orbit",
        summary: "atmosphere: the cloud-covered globe of Venus from 30 000 km, lit at a gibbous phase",
        toml: include_str!("presets/venus-orbit.toml"),
    },
    Preset {
        name: "titan-surface",
        summary: "atmosphere: Titan at the Huygens landing site, the orange-brown sky under the haze, the Sun 50° up",
        toml: include_str!("presets/titan-surface.toml"),
    },
    Preset {
        name: "titan-orbit",
        summary: "atmosphere: Titan from 15 000 km, the globe wrapped in its orange haze, lit at a gibbous phase",
        toml: include_str!("presets/titan-orbit.toml"),
    },
    Preset {
        name: "seed-earth",
        summary: "the seed's own model: its Earth from 12 000 km, the blue-veiled globe and its glowing limb",
        toml: include_str!("presets/seed-earth.toml"),
    },
    Preset {
        name: "seed-mars",
        summary: "the seed's own model: its Mars from the ground, looking west at the low Sun",
        toml: include_str!("presets/seed-mars.toml"),
    },
    Preset {
        name: "earth-objects",
        summary: "atmosphere: spheres and blocks on a street, lit by the Sun and sky, fading with distance",
        toml: include_str!("presets/earth-objects.toml"),
    },
    Preset {
        name: "earth-shafts",
        summary: "atmosphere: light shafts through a colonnade in ground fog, the Sun low behind it",
        toml: include_str!("presets/earth-shafts.toml"),
    },
    Preset {
        name: "earth-dusk-shadow",
        summary: "atmosphere: looking east at dusk, Earth's shadow rising under the pink Belt of Venus",
        toml: include_str!("presets/earth-dusk-shadow.toml"),
    },
    Preset {
        name: "superbible-ads",
        summary: "classic: the SuperBible's blue sphere, ADS lighting per vertex (Gouraud)",
        toml: include_str!("presets/superbible-ads.toml"),
    },
    Preset {
        name: "superbible-phong",
        summary: "classic: the SuperBible's blue sphere, ADS lighting per fragment (Phong)",
        toml: include_str!("presets/superbible-phong.toml"),
    },
    Preset {
        name: "fixed-function-tour",
        summary: "classic: every light type, two-sided lighting, separate specular, textures and fog",
        toml: include_str!("presets/fixed-function-tour.toml"),
    },
    Preset {
        name: "nehe-flare",
        summary: "flare: NeHe lesson 44's light 50 units ahead, its classic lens flare, a tile turning in front of it",
        toml: include_str!("presets/nehe-flare.toml"),
    },
];

/// How many presets may build on each other before we call it a loop.
const MAX_DEPTH: usize = 8;

/// Finds a preset by name, with a "did you mean" when there is none.
pub(crate) fn find(name: &str) -> Result<&'static Preset, SceneError> {
    PRESETS
        .iter()
        .find(|p| p.name == name)
        .ok_or_else(|| SceneError::UnknownPreset {
            name: name.to_owned(),
            suggestion: did_you_mean(name, PRESETS.iter().map(|p| p.name))
                .map(|best| format!("; did you mean `{best}`?"))
                .unwrap_or_default(),
            known: PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", "),
        })
}

/// A scene file's table layered over its preset (`preset_override`, else its own `preset` key,
/// else `default`).
pub(crate) fn layer_file(text: &str, origin: &str, preset_override: Option<&str>) -> Result<toml::Table, SceneError> {
    let own = parse_table(text, origin)?;
    let named = match own.get("preset") {
        None => None,
        Some(toml::Value::String(name)) => Some(name.clone()),
        Some(other) => {
            return Err(SceneError::WrongType {
                key: "preset".to_owned(),
                message: format!("expected a preset name (a string), found {}", other.type_str()),
            });
        }
    };
    let name = preset_override
        .map(str::to_owned)
        .or(named)
        .unwrap_or_else(|| "default".to_owned());
    let mut base = resolved_table(&name)?;
    merge(&mut base, own);
    base.insert("preset".to_owned(), toml::Value::String(name));
    Ok(base)
}

/// The fully layered table of a preset: `default`, then each preset it builds on, then itself.
pub(crate) fn resolved_table(name: &str) -> Result<toml::Table, SceneError> {
    resolve(name, 0)
}

fn resolve(name: &str, depth: usize) -> Result<toml::Table, SceneError> {
    if depth > MAX_DEPTH {
        return Err(SceneError::PresetTooDeep {
            name: name.to_owned(),
            depth: MAX_DEPTH,
        });
    }
    let preset = find(name)?;
    let mut own = parse_table(preset.toml, &format!("preset `{name}`"))?;
    if name == "default" {
        own.insert("preset".to_owned(), toml::Value::String(name.to_owned()));
        return Ok(own);
    }
    let base_name = own
        .get("preset")
        .and_then(toml::Value::as_str)
        .unwrap_or("default")
        .to_owned();
    let mut base = resolve(&base_name, depth + 1)?;
    merge(&mut base, own);
    base.insert("preset".to_owned(), toml::Value::String(name.to_owned()));
    Ok(base)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_preset_suggests() {
        let err = find("nigth").expect_err("unknown");
        assert!(err.to_string().contains("did you mean `night`"), "{err}");
    }
}
