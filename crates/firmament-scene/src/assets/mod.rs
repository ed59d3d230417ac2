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
//! A glTF node hierarchy must be a tree (a cycle, or a node with two parents, is an error), and
//! every index must name an existing vertex.

mod gltf;
#[cfg(test)]
mod hostile_tests;
mod obj;
mod texture_file;

use std::io::Read as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use firmament_core::classic::mesh::Mesh;
pub use firmament_core::texture::MAX_TEXTURE_SIDE;
use firmament_core::texture::TextureImage;
use glam::{DMat4, DVec3};

use crate::error::SceneError;

/// The file extensions [`load_model`] reads (compared case-insensitively).
pub const MODEL_EXTENSIONS: [&str; 3] = ["obj", "gltf", "glb"];

/// The most bytes firmament reads for one mesh or texture file named by a scene: the file itself
/// and, for a model, every buffer, image and material library it names (decoded `data:` URIs
/// included), together. 1 GiB.
pub const MAX_ASSET_BYTES: u64 = 1 << 30;

/// The most vertices one model file may give, all its meshes together (a mesh drawn by several
/// glTF nodes counts once): 2²⁴ = 16 777 216.
pub const MAX_MODEL_VERTICES: usize = 1 << 24;

/// The most triangle indices (three per triangle) one model file may give, all its meshes
/// together: 3 · 2²⁴ = 50 331 648 (16 777 216 triangles).
pub const MAX_MODEL_INDICES: usize = 3 << 24;

/// The most meshes one model file may give: OBJ objects, groups and material runs, or glTF
/// triangle-list primitives once per node that draws them. 65 536.
pub const MAX_MODEL_MESHES: usize = 1 << 16;

/// The most texels the images of one model file may hold together (each distinct image once):
/// 2²⁸ = 268 435 456, 1 GiB as 8-bit RGBA (four images of [`MAX_TEXTURE_SIDE`]²).
pub const MAX_MODEL_TEXELS: u64 = 1 << 28;

/// One mesh of a model file, with what the file says about its look.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    /// The triangles, validated (`Mesh::validate` passes); shared between the meshes of a file
    /// that draw the same primitive (a glTF mesh used by several nodes).
    pub mesh: Arc<Mesh>,
    /// Mesh → model-file root transform (a glTF node's world matrix; identity for OBJ).
    pub transform: DMat4,
    /// Base (diffuse) colour factor, linear RGBA, if the file gives one.
    pub base_color: Option<[f64; 4]>,
    /// Base colour texture, if the file gives one; shared between the meshes that use it.
    pub texture: Option<Arc<TextureImage>>,
}

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
    let loader = model_loader(key, path)?;
    guarded(|| {
        let mut budget = Budget::new();
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
    guarded(|| {
        let mut budget = Budget::new();
        let bytes = budget.read_file(path, "image file")?;
        texture_file::decode(&bytes, texture_file::FormatHint::from_path(path), &mut budget)
    })
    .map_err(asset_error(key, path))
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
    let picture = load_texture(key, path)?;
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

/// The message of an over-limit file: `what` ("the model gives 20000000 vertices"), then the
/// limit's value and name, and what to do instead.
fn over_limit(what: &str, limit: impl std::fmt::Display, name: &str, advice: &str) -> String {
    format!(
        "{what}, more than the limit of {limit} (firmament_scene::assets::{name}, a hard limit of firmament's scene \
         format that no scene key raises; {advice})"
    )
}

/// What one load may still read and allocate: the limits of the [module documentation](self),
/// counted down as files are read, meshes built and images decoded.
#[derive(Debug, Clone)]
struct Budget {
    /// Bytes left of [`MAX_ASSET_BYTES`].
    bytes: u64,
    /// Vertices left of [`MAX_MODEL_VERTICES`].
    vertices: usize,
    /// Indices left of [`MAX_MODEL_INDICES`].
    indices: usize,
    /// Meshes left of [`MAX_MODEL_MESHES`].
    meshes: usize,
    /// Texels left of [`MAX_MODEL_TEXELS`].
    #[cfg_attr(
        not(feature = "image-files"),
        allow(dead_code, reason = "only the image decoder counts texels")
    )]
    texels: u64,
}

impl Budget {
    /// The whole budget of one load.
    fn new() -> Self {
        Self {
            bytes: MAX_ASSET_BYTES,
            vertices: MAX_MODEL_VERTICES,
            indices: MAX_MODEL_INDICES,
            meshes: MAX_MODEL_MESHES,
            texels: MAX_MODEL_TEXELS,
        }
    }

    /// Takes `n` bytes for `what` (read or decoded).
    fn take_bytes(&mut self, n: u64, what: &str) -> Result<(), String> {
        let used = MAX_ASSET_BYTES - self.bytes;
        self.bytes = self.bytes.checked_sub(n).ok_or_else(|| {
            let before = if used > 0 {
                format!(" (after {used} bytes of the file and the files it names)")
            } else {
                String::new()
            };
            over_limit(
                &format!("{what} is {n} bytes{before}"),
                format!("{MAX_ASSET_BYTES} bytes"),
                "MAX_ASSET_BYTES",
                "split the model, or scale its textures down",
            )
        })?;
        Ok(())
    }

    /// Takes the vertices and indices of one mesh (`label`), from its declared counts.
    fn take_mesh(&mut self, vertices: usize, indices: usize, label: &str) -> Result<(), String> {
        let total = |left: usize, max: usize, n: usize| (max - left).saturating_add(n);
        self.vertices = self.vertices.checked_sub(vertices).ok_or_else(|| {
            over_limit(
                &format!(
                    "{label}: with its {vertices} vertices the file's meshes have {}",
                    total(self.vertices, MAX_MODEL_VERTICES, vertices)
                ),
                MAX_MODEL_VERTICES,
                "MAX_MODEL_VERTICES",
                "decimate the model, or split it over several files",
            )
        })?;
        self.indices = self.indices.checked_sub(indices).ok_or_else(|| {
            over_limit(
                &format!(
                    "{label}: with its {indices} triangle indices the file's meshes have {}",
                    total(self.indices, MAX_MODEL_INDICES, indices)
                ),
                MAX_MODEL_INDICES,
                "MAX_MODEL_INDICES",
                "decimate the model, or split it over several files",
            )
        })?;
        Ok(())
    }

    /// Takes `n` meshes (parts returned).
    fn take_meshes(&mut self, n: usize) -> Result<(), String> {
        self.meshes = self.meshes.checked_sub(n).ok_or_else(|| {
            over_limit(
                &format!(
                    "the file gives {} meshes or more",
                    (MAX_MODEL_MESHES - self.meshes).saturating_add(n)
                ),
                MAX_MODEL_MESHES,
                "MAX_MODEL_MESHES",
                "merge meshes, or split the model over several files",
            )
        })?;
        Ok(())
    }

    /// Takes the texels of one `width` × `height` image (`what`), before it is decoded.
    #[cfg_attr(
        not(feature = "image-files"),
        allow(dead_code, reason = "only the image decoder counts texels")
    )]
    fn take_texels(&mut self, width: u32, height: u32, what: &str) -> Result<(), String> {
        let n = u64::from(width) * u64::from(height);
        self.texels = self.texels.checked_sub(n).ok_or_else(|| {
            over_limit(
                &format!(
                    "{what} is {width} × {height}: with it the file's images have {} texels",
                    (MAX_MODEL_TEXELS - self.texels).saturating_add(n)
                ),
                MAX_MODEL_TEXELS,
                "MAX_MODEL_TEXELS",
                "scale the textures down, or share one image between materials",
            )
        })?;
        Ok(())
    }

    /// Reads a whole regular file for `what`, with the operating system's reason on failure,
    /// after checking its size against the bytes left.
    fn read_file(&mut self, path: &Path, what: &str) -> Result<Vec<u8>, String> {
        let os_error = |e: std::io::Error| match e.kind() {
            std::io::ErrorKind::NotFound => format!("{what} {} does not exist", path.display()),
            _ => format!("cannot read {what} {}: {e}", path.display()),
        };
        // `metadata` first: opening a pipe would wait for a writer.
        let metadata = std::fs::metadata(path).map_err(os_error)?;
        if !metadata.is_file() {
            return Err(format!(
                "{what} {} is not a regular file (a folder, device or pipe)",
                path.display()
            ));
        }
        let shown = format!("{what} {}", path.display());
        self.take_bytes(metadata.len(), &shown)?;
        let file = std::fs::File::open(path).map_err(os_error)?;
        let mut bytes = Vec::with_capacity(usize::try_from(metadata.len()).unwrap_or(0));
        // The file may grow between the check and the read: read at most what is left, plus one.
        file.take(metadata.len().saturating_add(self.bytes).saturating_add(1))
            .read_to_end(&mut bytes)
            .map_err(os_error)?;
        let grown = (bytes.len() as u64).saturating_sub(metadata.len());
        self.take_bytes(grown, &shown)?;
        Ok(bytes)
    }
}

/// Logs (`warn`) that the model file `model` names a `what` at `file` outside its own folder (an
/// absolute path, a `file:` URI, or `..` past the folder): the user asked for the model, and
/// should hear of what else it reads.
fn note_outside(model: &Path, file: &Path, what: &str) {
    let folder = model.parent().unwrap_or(Path::new(""));
    if !lexical_absolute(file).starts_with(lexical_absolute(folder)) {
        tracing::warn!(
            "{}: reading its {what} {}, which is outside the model's folder",
            model.display(),
            file.display()
        );
    }
}

/// `path` made absolute against the working directory (an empty path is the working directory),
/// with `.` dropped and each `..` taking away the component before it — on the text alone, links
/// not followed: what "inside a folder" is judged on, for scenes and for models.
pub(crate) fn lexical_absolute(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().map_or_else(|_| path.to_path_buf(), |cwd| cwd.join(path))
    };
    let mut out = PathBuf::new();
    for component in absolute.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// A mesh as a file gives it, before the repairs of [`finish_mesh`].
#[derive(Debug, Clone, Default)]
struct RawMesh {
    /// Vertex positions.
    positions: Vec<[f32; 3]>,
    /// Per-vertex normals, if the file has them (one per position).
    normals: Option<Vec<[f32; 3]>>,
    /// Per-vertex texture coordinates, OpenGL convention, if the file has them.
    tex_coords: Option<Vec<[f32; 2]>>,
    /// Triangle list.
    indices: Vec<u32>,
    /// Per-vertex fog coordinates (glTF `_FOG_COORD`), if the file has them.
    fog_coords: Option<Vec<f32>>,
}

/// Checks a [`RawMesh`] and repairs what the [module documentation](self) lists, logging it;
/// `file` and `label` (which mesh of the file) name it in messages.
fn finish_mesh(raw: RawMesh, file: &Path, label: &str) -> Result<Mesh, String> {
    let file = file.display();
    let n = raw.positions.len();
    if n == 0 {
        return Err(format!("{label} has no vertices"));
    }
    if let Some((i, p)) = raw
        .positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
    {
        return Err(format!("{label}: vertex {i} has a non-finite position {p:?}"));
    }
    let tex_coords = match raw.tex_coords {
        None => vec![[0.0; 2]; n],
        Some(t) if t.len() != n => {
            return Err(format!("{label}: {} texture coordinates for {n} vertices", t.len()));
        }
        Some(t) => {
            if let Some((i, t)) = t.iter().enumerate().find(|(_, t)| !t.iter().all(|c| c.is_finite())) {
                return Err(format!("{label}: vertex {i} has non-finite texture coordinates {t:?}"));
            }
            t
        }
    };
    if let Some(normals) = &raw.normals {
        if normals.len() != n {
            return Err(format!("{label}: {} normals for {n} vertices", normals.len()));
        }
    }
    if !raw.indices.len().is_multiple_of(3) {
        return Err(format!(
            "{label}: {} indices, not a whole number of triangles",
            raw.indices.len()
        ));
    }
    if let Some(i) = raw.indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!(
            "{label}: index {i} is out of range (the mesh has {n} vertices)"
        ));
    }

    // Drop degenerate triangles; sum the others' unnormalised normals (twice their area) per vertex.
    let position = |i: u32| DVec3::from(raw.positions[i as usize].map(f64::from));
    let mut indices = Vec::with_capacity(raw.indices.len());
    let mut sums = vec![DVec3::ZERO; n];
    let mut dropped = 0_usize;
    for triangle in raw.indices.chunks_exact(3) {
        let (a, b, c) = (triangle[0], triangle[1], triangle[2]);
        let cross = (position(b) - position(a)).cross(position(c) - position(a));
        if a == b || b == c || a == c || cross == DVec3::ZERO {
            dropped += 1;
            continue;
        }
        indices.extend_from_slice(triangle);
        for v in triangle {
            sums[*v as usize] += cross;
        }
    }
    let total = raw.indices.len() / 3;
    if indices.is_empty() {
        return Err(if total == 0 {
            format!("{label} has no triangles")
        } else {
            format!("{label} has no triangles left: all {total} are degenerate (zero area or a repeated vertex)")
        });
    }
    if dropped > 0 {
        tracing::info!(
            "{file}: {label}: dropped {dropped} of {total} triangles as degenerate (zero area or a repeated vertex)"
        );
    }

    let mut fallbacks = 0_usize;
    let mut computed = |v: usize| -> [f32; 3] {
        let sum = sums[v];
        if sum == DVec3::ZERO {
            fallbacks += 1;
            [0.0, 0.0, 1.0]
        } else {
            // `sum` is finite (products of f32 coordinates cannot overflow an f64) and non-zero.
            sum.normalize().as_vec3().to_array()
        }
    };
    let normals = match raw.normals {
        None => {
            tracing::info!("{file}: {label} has no normals; computing smooth area-weighted vertex normals");
            (0..n).map(&mut computed).collect()
        }
        Some(given) => {
            let (mut replaced, mut renormalised) = (0_usize, 0_usize);
            let normals = given
                .iter()
                .enumerate()
                .map(|(v, normal)| {
                    let d = DVec3::from(normal.map(f64::from));
                    let length = d.length();
                    if !length.is_finite() || length == 0.0 {
                        replaced += 1;
                        computed(v)
                    } else if (length - 1.0).abs() > 1e-6 {
                        renormalised += 1;
                        (d / length).as_vec3().to_array()
                    } else {
                        *normal
                    }
                })
                .collect();
            if replaced > 0 {
                tracing::warn!(
                    "{file}: {label}: {replaced} vertex normals are zero or not finite; replaced by computed smooth normals"
                );
            }
            if renormalised > 0 {
                tracing::debug!("{file}: {label}: normalised {renormalised} vertex normals that were not unit length");
            }
            normals
        }
    };
    if fallbacks > 0 {
        tracing::info!(
            "{file}: {label}: {fallbacks} vertices have no triangle of non-zero area to take a normal from (or their \
             triangles' normals cancel); they get the normal (0, 0, 1)"
        );
    }

    let mesh = Mesh {
        positions: raw.positions,
        normals,
        tex_coords,
        indices,
        fog_coords: raw.fog_coords.unwrap_or_default(),
    };
    mesh.validate().map_err(|e| format!("{label}: {e}"))?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn is_unit(normal: [f32; 3]) -> bool {
        (f64::from(Vec3::from(normal).length()) - 1.0).abs() < 1e-6
    }

    fn raw(positions: &[[f32; 3]], indices: &[u32]) -> RawMesh {
        RawMesh {
            positions: positions.to_vec(),
            indices: indices.to_vec(),
            ..RawMesh::default()
        }
    }

    const FILE: &str = "test.obj";

    #[test]
    fn computed_normals_are_area_weighted() {
        // Vertex 0 is shared by a triangle of area 2 facing +z and one of area 0.5 facing +y.
        let positions = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
        ];
        let mesh = finish_mesh(raw(&positions, &[0, 1, 2, 0, 3, 4]), Path::new(FILE), "mesh").expect("valid");
        let expected = DVec3::new(0.0, 0.5, 2.0).normalize();
        assert!((DVec3::from(mesh.normals[0].map(f64::from)) - expected).length() < 1e-7);
        assert_eq!(mesh.normals[1], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[3], [0.0, 1.0, 0.0]);
        assert_eq!(mesh.tex_coords, vec![[0.0; 2]; 5]);
        assert!(mesh.normals.iter().all(|n| is_unit(*n)));
    }

    #[test]
    fn degenerate_triangles_are_dropped_and_lonely_vertices_get_plus_z() {
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [5.0, 5.0, 5.0],
        ];
        // (0, 1, 3) is collinear, (1, 1, 2) repeats a vertex; vertex 3 is only in a degenerate one, 4 in none.
        let mesh = finish_mesh(raw(&positions, &[0, 1, 2, 0, 1, 3, 1, 1, 2]), Path::new(FILE), "mesh").expect("valid");
        assert_eq!(mesh.indices, [0, 1, 2]);
        assert_eq!(mesh.normals[3], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[4], [0.0, 0.0, 1.0]);
        // Seen from -z the triangle is counter-clockwise: its normal is still +z by the cross product.
        let flipped = finish_mesh(raw(&positions, &[0, 2, 1]), Path::new(FILE), "mesh").expect("valid");
        assert_eq!(flipped.normals[0], [0.0, 0.0, -1.0]);
    }

    #[test]
    fn file_normals_are_repaired() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut m = raw(&positions, &[0, 1, 2]);
        m.normals = Some(vec![[0.0, 0.0, 0.0], [0.0, 3.0, 4.0], [f32::NAN, 0.0, 1.0]]);
        let mesh = finish_mesh(m, Path::new(FILE), "mesh").expect("valid");
        assert_eq!(mesh.normals[0], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[1], [0.0, 0.6, 0.8]);
        assert_eq!(mesh.normals[2], [0.0, 0.0, 1.0]);
    }

    #[test]
    fn broken_meshes_are_errors() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let error = |m: RawMesh| finish_mesh(m, Path::new(FILE), "mesh `x`").expect_err("broken");
        assert!(error(raw(&positions, &[0, 1, 1])).contains("all 1 are degenerate"));
        assert!(error(raw(&positions, &[])).contains("no triangles"));
        assert!(error(raw(&positions, &[0, 1, 3])).contains("index 3 is out of range"));
        assert!(error(raw(&positions, &[0, 1])).contains("2 indices"));
        assert!(error(raw(&[], &[])).contains("no vertices"));
        let mut nan = raw(&positions, &[0, 1, 2]);
        nan.positions[1][2] = f32::INFINITY;
        assert!(error(nan).contains("vertex 1 has a non-finite position"));
        let mut tex = raw(&positions, &[0, 1, 2]);
        tex.tex_coords = Some(vec![[0.0, 0.0]; 2]);
        assert!(error(tex).contains("2 texture coordinates for 3 vertices"));
    }
}

#[cfg(test)]
mod path_tests {
    use super::*;

    #[test]
    fn lexical_absolute_climbs_out_with_dot_dot() {
        assert_eq!(lexical_absolute(Path::new("/a/b/../c/./d")), PathBuf::from("/a/c/d"));
        assert_eq!(lexical_absolute(Path::new("/a/b/../../../x")), PathBuf::from("/../x"));
        assert!(!lexical_absolute(Path::new("/s/scenes/../shared/x.obj")).starts_with("/s/scenes"));
        assert!(lexical_absolute(Path::new("/s/scenes/./sub/../x.obj")).starts_with("/s/scenes"));
        let cwd = std::env::current_dir().expect("a working directory");
        assert_eq!(lexical_absolute(Path::new("")), cwd);
        assert_eq!(lexical_absolute(Path::new("m/../t.png")), cwd.join("t.png"));
    }
}
