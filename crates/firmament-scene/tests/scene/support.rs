//! Helpers shared by the scene tests.

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
