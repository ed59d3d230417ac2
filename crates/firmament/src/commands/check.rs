//! `firmament check [SCENE]`.

use anyhow::{Context, Result};
use firmament_scene::{AtmosphereModelName, Scene, SkyModelName};

use crate::cli::CheckArgs;

/// Validates a scene file (or a preset, or the default scene) and prints a one-line summary of
/// what it describes.
pub(crate) fn run(args: &CheckArgs) -> Result<()> {
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &args.scene_args);
    let policy = crate::untrusted::Policy::new(&args.untrusted, args.scene.as_deref())?;
    let scene = super::scene_input::load_scene(
        args.scene.as_deref(),
        &args.scene_args,
        Vec::new(),
        policy.confinement(),
    )
    .with_context(|| format!("{what} is not a valid scene"))?;
    policy.check_pixels("the image", scene.render.width, scene.render.height)?;
    // Builds the meshes and loads the mesh and texture files, so those are checked too.
    let frame = scene
        .frame_at(None)
        .with_context(|| format!("{what} is not a valid scene"))?;
    let objects = match frame.objects.objects.len() {
        0 => String::new(),
        1 => ", 1 object".to_owned(),
        n => format!(", {n} objects"),
    };
    println!(
        "{what}: ok (preset {}, {}x{}, {}{objects})",
        scene.preset.as_deref().unwrap_or("default"),
        scene.render.width,
        scene.render.height,
        sky_summary(&scene),
    );
    Ok(())
}

/// `gradient sky at 17:45`, or `atmosphere of earth, 1 sun, 2 cloud layers, camera at altitude
/// 1.7 m`.
fn sky_summary(scene: &Scene) -> String {
    match scene.sky.model {
        SkyModelName::Gradient => format!("gradient sky at {}", scene.time.time_of_day),
        SkyModelName::Clear => "clear colour".to_owned(),
        SkyModelName::Atmosphere => {
            let suns = match scene.suns.len() {
                1 => "1 sun".to_owned(),
                n => format!("{n} suns"),
            };
            let altitude = scene
                .camera_altitude()
                .map(|h| format!(", camera at altitude {} m", (h * 10.0).round() / 10.0))
                .unwrap_or_default();
            let model = match scene.atmosphere.model {
                AtmosphereModelName::Physical => "atmosphere",
                AtmosphereModelName::Empirical => "seed atmosphere",
            };
            // The physical atmosphere draws the cloud layers; the seed's model has none.
            let clouds = match (scene.atmosphere.model, scene.clouds.len()) {
                (AtmosphereModelName::Empirical, _) | (_, 0) => String::new(),
                (_, 1) => ", 1 cloud layer".to_owned(),
                (_, n) => format!(", {n} cloud layers"),
            };
            format!("{model} of {}, {suns}{clouds}{altitude}", scene.planet.body.name())
        }
    }
}
