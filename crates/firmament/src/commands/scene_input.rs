//! What every command does with its scene arguments: load the scene (a file, a preset or the
//! default) with the command's own overrides before the user's `--set`s, and describe it.

use anyhow::Result;
use firmament_scene::assets::Confinement;
use firmament_scene::{Scene, SceneDocument, SceneSource};

use crate::cli::SceneArgs;

/// The largest scene file read, bytes. Scene files are a few kilobytes; anything near this is
/// not one, and is refused before it is read into memory.
pub(crate) const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// Loads a scene from a file or a preset (the default scene when neither is given), with
/// `extra` overrides applied before the user's `--set`s, held to `confinement` when it is a
/// stranger's (its files checked before any is read).
pub(crate) fn load_scene(
    file: Option<&std::path::Path>,
    args: &SceneArgs,
    extra: Vec<String>,
    confinement: Option<&Confinement>,
) -> Result<Scene> {
    let mut overrides = extra;
    overrides.extend(args.overrides.iter().cloned());
    let mut document = load_document(file, args.preset.as_deref(), &overrides)?;
    if let Some(confinement) = confinement {
        document.confine(confinement.clone());
    }
    Ok(document.scene()?)
}

/// The scene document of a file or a preset (the default scene when neither is given), with
/// `overrides` applied. A scene file is read only up to [`MAX_SCENE_FILE_BYTES`].
pub(crate) fn load_document(
    file: Option<&std::path::Path>,
    preset: Option<&str>,
    overrides: &[String],
) -> Result<SceneDocument> {
    let Some(path) = file else {
        return Ok(SceneDocument::load(
            SceneSource::Preset(preset.unwrap_or("default")),
            None,
            overrides,
        )?);
    };
    let too_big = |size: String| {
        anyhow::anyhow!(
            "cannot read scene file {}: {size}, over the limit of {} MiB for a scene file (scene files are a \
             few kilobytes: is it the right file?)",
            path.display(),
            MAX_SCENE_FILE_BYTES >> 20
        )
    };
    match std::fs::metadata(path) {
        Ok(meta) if meta.is_file() && meta.len() > MAX_SCENE_FILE_BYTES => {
            return Err(too_big(format!("{} bytes", meta.len())));
        }
        // A pipe or a device (`/dev/stdin`) has no size: read it, but no further than the limit.
        Ok(meta) if !meta.is_file() && !meta.is_dir() => {
            use std::io::Read as _;
            let unreadable = |e: std::io::Error| anyhow::anyhow!("cannot read scene file {}: {e}", path.display());
            let mut bytes = Vec::new();
            std::fs::File::open(path)
                .and_then(|f| f.take(MAX_SCENE_FILE_BYTES + 1).read_to_end(&mut bytes))
                .map_err(unreadable)?;
            if bytes.len() as u64 > MAX_SCENE_FILE_BYTES {
                return Err(too_big(format!("more than {MAX_SCENE_FILE_BYTES} bytes")));
            }
            let text = String::from_utf8(bytes).map_err(|_| {
                unreadable(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    "stream did not contain valid UTF-8",
                ))
            })?;
            let origin = path.display().to_string();
            return Ok(SceneDocument::load(
                SceneSource::Text {
                    text: &text,
                    origin: &origin,
                },
                preset,
                overrides,
            )?);
        }
        _ => {}
    }
    Ok(SceneDocument::load_file(path, preset, overrides)?)
}

/// `render.width` / `render.height` overrides for `--width` / `--height` (before the user's
/// `--set`s, like every shorthand).
pub(crate) fn size_overrides(width: Option<u32>, height: Option<u32>) -> Vec<String> {
    let mut extra = Vec::new();
    if let Some(w) = width {
        extra.push(format!("render.width={w}"));
    }
    if let Some(h) = height {
        extra.push(format!("render.height={h}"));
    }
    extra
}

/// The `time.time_of_day` override for `--time HH:MM`, quoted so that the scene's own validation
/// names the rule for a bad time.
pub(crate) fn time_override(time: Option<&str>) -> Option<String> {
    time.map(|t| format!("time.time_of_day=\"{}\"", t.replace('"', "")))
}

/// How messages name the scene: its file, its preset, or the default scene.
pub(crate) fn describe_scene(file: Option<&std::path::Path>, args: &SceneArgs) -> String {
    match (file, &args.preset) {
        (Some(path), _) => path.display().to_string(),
        (None, Some(preset)) => format!("preset `{preset}`"),
        (None, None) => "the default scene".to_owned(),
    }
}

/// The preset `render` and `view` draw when given neither a scene file nor a preset: the
/// showcase (physical atmosphere at golden hour, objects, auto-exposure, bloom, the Sun's flare).
pub(crate) const SHOWCASE_PRESET: &str = "golden-hour";

/// `args`, with `preset` as the preset when neither a scene file nor a preset was given (for the
/// commands that need an atmosphere scene by default).
pub(crate) fn with_default_preset(args: &SceneArgs, scene: Option<&std::path::Path>, preset: &str) -> SceneArgs {
    SceneArgs {
        preset: args
            .preset
            .clone()
            .or_else(|| scene.is_none().then(|| preset.to_owned())),
        overrides: args.overrides.clone(),
    }
}
