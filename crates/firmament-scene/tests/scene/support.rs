//! Helpers shared by the scene tests.

use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_scene::{Scene, SceneError, SceneSource, load};

/// Loads a scene from TOML text (its origin named `test.toml` in messages).
pub(crate) fn from_text(text: &str) -> Result<Scene, SceneError> {
    load(
        SceneSource::Text {
            text,
            origin: "test.toml",
        },
        None,
        &[],
    )
}

/// Loads built-in preset `name` with `--set` strings `sets`.
pub(crate) fn preset(name: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(name), None, &sets)
}

/// The physical sky of `scene`'s frame at its own moment.
pub(crate) fn sky_of(scene: &Scene) -> AtmosphereSky {
    match scene.frame_at(None).expect("frame").sky {
        Sky::Atmosphere(sky) => sky,
        Sky::Gradient(_) | Sky::Empirical(_) | Sky::Clear(_) => panic!("expected an atmosphere sky"),
    }
}

/// The message of a scene that must fail to load.
pub(crate) fn message(result: Result<Scene, SceneError>) -> String {
    result.expect_err("should fail").to_string()
}
