//! One module per subcommand.

mod bench;
mod check;
mod presets;
mod render;
mod sky_sample;
pub(crate) mod sun;
pub(crate) mod timelapse;
mod view;

use anyhow::Result;
use firmament_scene::{Scene, SceneSource};

use crate::cli::{Command, SceneArgs};

/// Runs a parsed command.
pub(crate) fn run(command: Command) -> Result<()> {
    match command {
        Command::Render(args) => render::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::SkySample(args) => sky_sample::run(&args),
        Command::Sun(args) => sun::run(&args),
        Command::Timelapse(args) => timelapse::run(&args),
        Command::View(args) => view::run(&args),
        Command::Presets => {
            presets::run();
            Ok(())
        }
    }
}

/// Loads a scene from a file or a preset (the default scene when neither is given), with
/// `extra` overrides applied before the user's `--set`s.
pub(crate) fn load_scene(file: Option<&std::path::Path>, args: &SceneArgs, extra: Vec<String>) -> Result<Scene> {
    let mut overrides = extra;
    overrides.extend(args.overrides.iter().cloned());
    let scene = match file {
        Some(path) => firmament_scene::load_file(path, args.preset.as_deref(), &overrides),
        None => firmament_scene::load(
            SceneSource::Preset(args.preset.as_deref().unwrap_or("default")),
            None,
            &overrides,
        ),
    };
    Ok(scene?)
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

/// How messages name the scene: its file, its preset, or the default scene.
pub(crate) fn describe_scene(file: Option<&std::path::Path>, args: &SceneArgs) -> String {
    match (file, &args.preset) {
        (Some(path), _) => path.display().to_string(),
        (None, Some(preset)) => format!("preset `{preset}`"),
        (None, None) => "the default scene".to_owned(),
    }
}

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
