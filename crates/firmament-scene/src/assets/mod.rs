//! Mesh and texture files named by a scene: Wavefront OBJ, glTF 2.0 and images.
//!
//! [`load_model`] reads `.obj` (with its `.mtl` materials), `.gltf` (external or base64 `data:`
//! buffers and images) and `.glb` files into [`LoadedMesh`]es; [`load_texture`] reads an image
//! file into a [`TextureImage`]. Every failure is a [`SceneError::Asset`] naming the scene key,
//! the path and the reason; malformed files never panic.
//!
//! # Conventions
//! - **Units**: positions are taken as metres, as stored (glTF's unit is the metre; OBJ has none).
//!   Nothing is rescaled, recentred or re-oriented (glTF's +Y up stays +Y).
//! - **Winding**: counter-clockwise front faces in both formats, as in [`Mesh`]; triangles are
//!   kept as the file orders them.
//! - **Texture coordinates** have `(0, 0)` at the lower left, as in OpenGL and [`Mesh`]. OBJ
//!   already uses that convention; glTF puts `(0, 0)` at the top left, so its `v` becomes
//!   `t = 1 − v`. Images are flipped the matching way: a [`TextureImage`]'s row 0 is the bottom
//!   row of the picture. Missing texture coordinates are `(0, 0)` for every vertex.
//! - **Texels** are converted to 8-bit RGBA and used as stored (no sRGB decoding); 16-bit and
//!   floating-point images are scaled to 0–255 (floats clamped to `[0, 1]` first).
//! - **Colours**: an OBJ material's `Kd` (alpha from `d`, else 1) or a glTF material's
//!   `baseColorFactor` become [`LoadedMesh::base_color`], as the file gives them.
//! - **Fog coordinates** (`GL_FOG_COORD`): a glTF primitive's application-specific `_FOG_COORD`
//!   attribute (scalar floats, one per vertex) becomes [`Mesh::fog_coords`]; OBJ has none.
//! - **Transforms**: a glTF mesh's [`LoadedMesh::transform`] is its node's world matrix in the
//!   file (mesh → file root), the node transforms (matrix or translation·rotation·scale)
//!   composed from the scene root down; OBJ meshes have the identity.
//!
//! # What is repaired, and logged (`tracing`)
//! - **No normals**: smooth vertex normals are computed, area-weighted (each vertex gets the sum
//!   of the unnormalised cross products of the triangles that use it, normalised); `info`.
//! - **Zero-length or non-finite normals** in the file: replaced by the computed normal for those
//!   vertices; `warn`. Other file normals that are not unit length are normalised; `debug`.
//! - A vertex whose computed normal is still zero — no triangle of non-zero area uses it, or the
//!   cross products of its triangles cancel (two faces back to back) — gets `(0, 0, 1)`; `info`.
//! - **Degenerate triangles** (a repeated index, or exactly zero area in `f64`) are dropped;
//!   `info` with how many. A mesh left without triangles is an error.
//! - glTF primitives that are not triangle lists (points, lines, strips, fans) are skipped;
//!   `warn`. A file left without triangles is an error.
//! - A missing or malformed `.mtl` file, or a diffuse map (`map_Kd`) that cannot be loaded, is
//!   not an error: the OBJ loads without that material or texture; `warn`. (A glTF file is one
//!   asset: a missing buffer or image file is an error.)
//!
//! Non-finite positions or texture coordinates, indices out of range and accessors that do not
//! fit their buffers are errors. Every returned mesh passes [`Mesh::validate`].
//!
//! # Limits
//! Every size a file can ask for is checked before anything of that size is allocated, and an
//! over-limit file is an error naming the limit, never an out-of-memory kill. These are hard
//! limits of the scene format (no scene key raises them): a model past them must be decimated,
//! split over several objects, or its textures scaled down.
//! - [`MAX_ASSET_BYTES`]: the bytes read for one mesh or texture file, every buffer, image and
//!   material library a model names (and its decoded `data:` URIs) included; each file's size is
//!   checked before it is read, and only regular files are read (not devices, pipes or folders).
//! - [`MAX_MODEL_VERTICES`], [`MAX_MODEL_INDICES`]: a model file's vertices and triangle
//!   indices, all its meshes together, checked from the declared counts (glTF accessors, OBJ
//!   `v` lines and face corners) before the data is read.
//! - [`MAX_MODEL_MESHES`]: the meshes one model file gives (a glTF mesh drawn by several nodes
//!   counts once per node).
//! - [`MAX_TEXTURE_SIDE`] for each image, checked from its header, and [`MAX_MODEL_TEXELS`] for
//!   all the images of one model file together.
//!
//! A scene from a stranger is loaded under a [`Confinement`]: every file, those a model names
//! included, must resolve inside one folder, and the [`AssetLimits`] above are lowered
//! (docs/RELIABILITY.md).
//!
//! A glTF node hierarchy must be a tree (a cycle, or a node with two parents, is an error), and
//! every index must name an existing vertex.
//!
//! [`Mesh`]: firmament_core::classic::mesh::Mesh
//! [`Mesh::fog_coords`]: firmament_core::classic::mesh::Mesh::fog_coords
//! [`Mesh::validate`]: firmament_core::classic::mesh::Mesh::validate

mod confine;
mod file_cache;
mod gltf;
#[cfg(test)]
mod hostile_tests;
mod limits;
mod mesh;
mod obj;
mod paths;
mod texture_file;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::Arc;

pub use firmament_core::texture::MAX_TEXTURE_SIDE;
use firmament_core::texture::TextureImage;

pub use self::confine::{AssetLimits, Confinement};
pub(crate) use self::file_cache::FileCache;
use self::limits::Budget;
pub use self::limits::{MAX_ASSET_BYTES, MAX_MODEL_INDICES, MAX_MODEL_MESHES, MAX_MODEL_TEXELS, MAX_MODEL_VERTICES};
pub use self::mesh::LoadedMesh;
pub(crate) use self::paths::lexical_absolute;
use crate::error::SceneError;

/// The file extensions [`load_model`] reads (compared case-insensitively).
pub const MODEL_EXTENSIONS: [&str; 3] = ["obj", "gltf", "glb"];

/// Loads every mesh of an OBJ (`.obj`) or glTF (`.gltf`, `.glb`) file; `key` names the scene
/// key for messages.
///
/// OBJ gives one mesh per object or group (and per material change within one); glTF one mesh
/// per triangle-list primitive of every mesh node in the default scene (else the first scene,
/// else every root node). See the [module documentation](self) for the conventions, repairs and
/// limits.
///
/// # Errors
/// [`SceneError::Asset`] naming `key`, the path and the reason.
pub fn load_model(key: &str, path: &Path) -> Result<Vec<LoadedMesh>, SceneError> {
    load_model_within(key, path, None)
}

/// [`load_model`] under `confinement`'s folder and limits, when there is one.
pub(crate) fn load_model_within(
    key: &str,
    path: &Path,
    confinement: Option<&Confinement>,
) -> Result<Vec<LoadedMesh>, SceneError> {
    let loader = model_loader(key, path)?;
    guarded(|| {
        let mut budget = Budget::within(confinement);
        let bytes = budget.read_file(path, "model file")?;
        loader(path, &bytes, &mut budget)
    })
    .map_err(asset_error(key, path))
}

/// Loads every mesh of a model whose file contents are `bytes`, as [`load_model`] does: `path`
/// gives the format (by its extension), the folder that the files it names are read from, and
/// the name in messages; the file itself is not read.
///
/// # Errors
/// As [`load_model`].
pub fn load_model_bytes(key: &str, path: &Path, bytes: &[u8]) -> Result<Vec<LoadedMesh>, SceneError> {
    let loader = model_loader(key, path)?;
    guarded(|| {
        let mut budget = Budget::new();
        budget.take_bytes(bytes.len() as u64, "the model file")?;
        loader(path, bytes, &mut budget)
    })
    .map_err(asset_error(key, path))
}

/// A model loader: the path (for its folder and messages), the file's bytes and the budget.
type ModelLoader = fn(&Path, &[u8], &mut Budget) -> Result<Vec<LoadedMesh>, String>;

/// The loader for `path`'s extension.
fn model_loader(key: &str, path: &Path) -> Result<ModelLoader, SceneError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match extension.as_str() {
        "obj" => Ok(obj::load),
        "gltf" | "glb" => Ok(gltf::load),
        _ => {
            let found = if extension.is_empty() {
                "no extension".to_owned()
            } else {
                format!("extension `.{extension}`")
            };
            Err(asset_error(key, path)(format!(
                "unsupported model format ({found}); supported extensions are: {}",
                MODEL_EXTENSIONS.map(|e| format!(".{e}")).join(", ")
            )))
        }
    }
}

/// A [`SceneError::Asset`] for `key` and `path` with a reason.
fn asset_error<'a>(key: &'a str, path: &'a Path) -> impl Fn(String) -> SceneError + 'a {
    move |reason| SceneError::Asset {
        key: key.to_owned(),
        path: path.display().to_string(),
        reason,
    }
}

/// Loads an image file (PNG, …) as a texture, bottom row first.
///
/// Reads PNG, JPEG and OpenEXR (the formats the `image` crate is built with here), converts to
/// 8-bit RGBA and flips the rows so that row 0 is the bottom of the picture (`t = 0`).
///
/// # Errors
/// [`SceneError::Asset`] naming `key`, the path and the reason: the file cannot be read or
/// decoded, it is larger than [`MAX_ASSET_BYTES`], or a side is 0 or more than
/// [`MAX_TEXTURE_SIDE`].
pub fn load_texture(key: &str, path: &Path) -> Result<TextureImage, SceneError> {
    load_texture_within(key, path, None)
}

/// [`load_texture`] under `confinement`'s folder and limits, when there is one.
pub(crate) fn load_texture_within(
    key: &str,
    path: &Path,
    confinement: Option<&Confinement>,
) -> Result<TextureImage, SceneError> {
    guarded(|| {
        let mut budget = Budget::within(confinement);
        let bytes = budget.read_file(path, "image file")?;
        texture_file::decode(&bytes, texture_file::FormatHint::from_path(path), &mut budget)
    })
    .map_err(asset_error(key, path))
}

/// Images decoded from files, while the files stay as they were.
static TEXTURES: FileCache<TextureImage> = FileCache::new();

/// [`load_texture_within`], decoded once while the file keeps its length and modification time
/// and shared (never from the cache under a confinement: see [`FileCache`]).
pub(crate) fn load_texture_shared(
    key: &str,
    path: &Path,
    confinement: Option<&Confinement>,
) -> Result<Arc<TextureImage>, SceneError> {
    TEXTURES.get_or_make(
        &[path],
        confinement.is_none(),
        |image| std::mem::size_of_val(image.texels.as_slice()),
        || load_texture_within(key, path, confinement),
    )
}

/// Decodes an image whose file contents are `bytes`, as [`load_texture`] does; `path` is the
/// name in messages, and its extension the format to assume when the contents do not tell.
///
/// # Errors
/// As [`load_texture`].
pub fn load_texture_bytes(key: &str, path: &Path, bytes: &[u8]) -> Result<TextureImage, SceneError> {
    guarded(|| {
        let mut budget = Budget::new();
        budget.take_bytes(bytes.len() as u64, "the image file")?;
        texture_file::decode(bytes, texture_file::FormatHint::from_path(path), &mut budget)
    })
    .map_err(asset_error(key, path))
}

/// Loads an image file as a flare element's picture: [`load_texture`], then resampled to
/// [`FLARE_IMAGE_SIDE`](firmament_core::flare::FLARE_IMAGE_SIDE) square (Catmull-Rom), so every
/// image of a flare fits one texture array.
///
/// # Errors
/// As [`load_texture`].
pub fn load_flare_image(key: &str, path: &Path) -> Result<TextureImage, SceneError> {
    load_flare_image_within(key, path, None)
}

/// [`load_flare_image`] under `confinement`'s folder and limits, when there is one.
pub(crate) fn load_flare_image_within(
    key: &str,
    path: &Path,
    confinement: Option<&Confinement>,
) -> Result<TextureImage, SceneError> {
    let picture = load_texture_within(key, path, confinement)?;
    Ok(texture_file::resampled(
        &picture,
        firmament_core::flare::FLARE_IMAGE_SIDE,
    ))
}

/// Runs a loader, turning a panic inside a parser dependency into an error: the parsers are
/// third-party code fed with user files, and a malformed file must not bring the program down.
fn guarded<T>(load: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(load)).unwrap_or_else(|_| {
        Err("the file is malformed: its parser failed on it (panicked; see the message above)".to_owned())
    })
}
