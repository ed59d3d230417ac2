//! `firmament check SCENE`.

use anyhow::{Context, Result};

use crate::cli::CheckArgs;

/// Validates a scene file and prints a one-line summary of what it describes.
pub(crate) fn run(args: &CheckArgs) -> Result<()> {
    let scene = super::load_scene(Some(&args.scene), &args.scene_args, Vec::new())
        .with_context(|| format!("{} is not a valid scene", args.scene.display()))?;
    println!(
        "{}: ok (preset {}, {}x{}, {} at {})",
        args.scene.display(),
        scene.preset.as_deref().unwrap_or("default"),
        scene.render.width,
        scene.render.height,
        match scene.sky.model {
            firmament_scene::SkyModelName::Gradient => "gradient sky",
        },
        scene.time.time_of_day,
    );
    Ok(())
}
