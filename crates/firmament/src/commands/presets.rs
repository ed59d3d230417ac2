//! `firmament presets`.

/// Prints each built-in preset with its one-line summary.
pub(crate) fn run() {
    let width = firmament_scene::PRESETS.iter().map(|p| p.name.len()).max().unwrap_or(0);
    for preset in firmament_scene::PRESETS {
        println!("{:width$}  {}", preset.name, preset.summary);
    }
}
