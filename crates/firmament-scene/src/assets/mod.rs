//! Mesh and texture files named by a scene: Wavefront OBJ, glTF 2.0 and images.
//!
//! (Stub: filled in by the loaders work.)

use std::path::Path;

use firmament_core::mesh::Mesh;
use firmament_core::texture::TextureImage;
use glam::DMat4;

use crate::error::SceneError;

/// One mesh of a model file, with what the file says about its look.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    /// The triangles, validated (`Mesh::validate` passes).
    pub mesh: Mesh,
    /// Mesh → model-file root transform (a glTF node's world matrix; identity for OBJ).
    pub transform: DMat4,
    /// Base (diffuse) colour factor, linear RGBA, if the file gives one.
    pub base_color: Option<[f64; 4]>,
    /// Base colour texture, if the file gives one.
    pub texture: Option<TextureImage>,
}

/// Loads every mesh of an OBJ (`.obj`) or glTF (`.gltf`, `.glb`) file; `key` names the scene
/// key for messages.
///
/// # Errors
/// [`SceneError::Asset`] naming `key`, the path and the reason.
pub fn load_model(key: &str, path: &Path) -> Result<Vec<LoadedMesh>, SceneError> {
    Err(SceneError::Asset {
        key: key.to_owned(),
        path: path.display().to_string(),
        reason: "model loading is not implemented yet".to_owned(),
    })
}

/// Loads an image file (PNG, …) as a texture, bottom row first.
///
/// # Errors
/// [`SceneError::Asset`] naming `key`, the path and the reason.
pub fn load_texture(key: &str, path: &Path) -> Result<TextureImage, SceneError> {
    Err(SceneError::Asset {
        key: key.to_owned(),
        path: path.display().to_string(),
        reason: "texture loading is not implemented yet".to_owned(),
    })
}
