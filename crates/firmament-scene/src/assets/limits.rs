//! The limits of one load ([`MAX_ASSET_BYTES`] and the model limits) and the [`Budget`] that
//! counts them down: see the [assets documentation](super).

use std::io::Read as _;
use std::path::{Path, PathBuf};

use super::confine::{AssetLimits, Confinement};

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
/// 2²⁸ = 268 435 456, 1 GiB as 8-bit RGBA (four images of [`MAX_TEXTURE_SIDE`](firmament_core::texture::MAX_TEXTURE_SIDE)²).
pub const MAX_MODEL_TEXELS: u64 = 1 << 28;

/// The message of an over-limit file: `what` ("the model gives 20000000 vertices"), then the
/// limit's value and name, and what to do instead.
pub(super) fn over_limit(what: &str, limit: impl std::fmt::Display, name: &str, advice: &str) -> String {
    format!(
        "{what}, more than the limit of {limit} (firmament_scene::assets::{name}, a hard limit of firmament's scene \
         format that no scene key raises; {advice})"
    )
}

/// The message of a file over a [`Confinement`]'s tighter limit `field` ("max_file_bytes").
pub(super) fn over_untrusted_limit(what: &str, limit: impl std::fmt::Display, field: &str) -> String {
    format!(
        "{what}, more than untrusted mode's limit of {limit} (AssetLimits::{field}; the command line raises it with \
         --{})",
        field.replace('_', "-")
    )
}

/// What one load may still read and allocate: the limits of the [assets documentation](super),
/// counted down as files are read, meshes built and images decoded.
#[derive(Debug, Clone)]
pub(super) struct Budget {
    /// Bytes left of [`AssetLimits::max_file_bytes`].
    pub(super) bytes: u64,
    /// Vertices left of [`MAX_MODEL_VERTICES`].
    pub(super) vertices: usize,
    /// Indices left of [`MAX_MODEL_INDICES`] (or three per triangle of
    /// [`AssetLimits::max_triangles`]).
    pub(super) indices: usize,
    /// Meshes left of [`MAX_MODEL_MESHES`].
    pub(super) meshes: usize,
    /// Texels left of [`MAX_MODEL_TEXELS`].
    #[cfg_attr(
        not(feature = "image-files"),
        allow(dead_code, reason = "only the image decoder counts texels")
    )]
    pub(super) texels: u64,
    /// The limits of this load: [`AssetLimits::HARD`], or a confinement's.
    pub(super) limits: AssetLimits,
    /// The folder files must resolve inside, when the scene is a stranger's.
    confinement: Option<Confinement>,
}

impl Budget {
    /// The whole budget of one load, at the hard limits, from anywhere.
    pub(super) fn new() -> Self {
        Self {
            bytes: MAX_ASSET_BYTES,
            vertices: MAX_MODEL_VERTICES,
            indices: MAX_MODEL_INDICES,
            meshes: MAX_MODEL_MESHES,
            texels: MAX_MODEL_TEXELS,
            limits: AssetLimits::HARD,
            confinement: None,
        }
    }

    /// The budget of one load under `confinement` (or [`new`](Self::new) without one): its
    /// limits, and files only from its folder.
    pub(super) fn within(confinement: Option<&Confinement>) -> Self {
        let Some(confinement) = confinement else {
            return Self::new();
        };
        let limits = confinement.limits();
        let triangle_indices = usize::try_from(limits.max_triangles.saturating_mul(3)).unwrap_or(usize::MAX);
        Self {
            bytes: limits.max_file_bytes,
            indices: triangle_indices.min(MAX_MODEL_INDICES),
            limits,
            confinement: Some(confinement.clone()),
            ..Self::new()
        }
    }

    /// Whether `field` of the limits is a confinement's, tighter than the hard one.
    fn tighter(&self, hard: u64, own: u64) -> bool {
        self.confinement.is_some() && own < hard
    }

    /// Takes `n` bytes for `what` (read or decoded).
    pub(super) fn take_bytes(&mut self, n: u64, what: &str) -> Result<(), String> {
        let max = self.limits.max_file_bytes;
        let used = max - self.bytes;
        self.bytes = self.bytes.checked_sub(n).ok_or_else(|| {
            let before = if used > 0 {
                format!(" (after {used} bytes of the file and the files it names)")
            } else {
                String::new()
            };
            let what = format!("{what} is {n} bytes{before}");
            if self.tighter(MAX_ASSET_BYTES, max) {
                over_untrusted_limit(&what, format!("{max} bytes"), "max_file_bytes")
            } else {
                over_limit(
                    &what,
                    format!("{MAX_ASSET_BYTES} bytes"),
                    "MAX_ASSET_BYTES",
                    "split the model, or scale its textures down",
                )
            }
        })?;
        Ok(())
    }

    /// Fails, with the limit's name, when an image's side `name` ("width") is 0 or longer than
    /// the budget's longest side.
    #[cfg_attr(
        not(feature = "image-files"),
        allow(dead_code, reason = "only the image decoder checks sides")
    )]
    pub(super) fn check_texture_side(&self, name: &str, side: u32) -> Result<(), String> {
        let max = self.limits.max_texture_side;
        if side == 0 {
            return Err(format!("the image {name} is 0 pixels"));
        }
        if side <= max {
            return Ok(());
        }
        let what = format!("the image {name} is {side} pixels");
        Err(
            if self.tighter(u64::from(firmament_core::texture::MAX_TEXTURE_SIDE), u64::from(max)) {
                over_untrusted_limit(&what, format!("{max} pixels on a side"), "max_texture_side")
            } else {
                over_limit(
                    &what,
                    format!("{max} pixels on a side"),
                    "MAX_TEXTURE_SIDE",
                    "scale the image down",
                )
            },
        )
    }

    /// Under a confinement, `path` (the file of `what`) resolved inside its folder, or why it is
    /// refused; `None` without one. Nothing is read.
    pub(super) fn confined(&self, path: &Path, what: &str) -> Result<Option<PathBuf>, String> {
        self.confinement
            .as_ref()
            .map(|c| c.resolve_path(path))
            .transpose()
            // The path is not quoted: it may name a place outside the folder.
            .map_err(|why| format!("{what}: {}", why.rule()))
    }

    /// Takes the vertices and indices of one mesh (`label`), from its declared counts.
    pub(super) fn take_mesh(&mut self, vertices: usize, indices: usize, label: &str) -> Result<(), String> {
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
        let max_indices = usize::try_from(self.limits.max_triangles.saturating_mul(3))
            .unwrap_or(usize::MAX)
            .min(MAX_MODEL_INDICES);
        self.indices = self.indices.checked_sub(indices).ok_or_else(|| {
            let what = format!(
                "{label}: with its {indices} triangle indices the file's meshes have {}",
                total(self.indices, max_indices, indices)
            );
            if self.tighter(MAX_MODEL_INDICES as u64, max_indices as u64) {
                over_untrusted_limit(
                    &what,
                    format!("{max_indices} indices ({} triangles)", max_indices / 3),
                    "max_triangles",
                )
            } else {
                over_limit(
                    &what,
                    MAX_MODEL_INDICES,
                    "MAX_MODEL_INDICES",
                    "decimate the model, or split it over several files",
                )
            }
        })?;
        Ok(())
    }

    /// Takes `n` meshes (parts returned).
    pub(super) fn take_meshes(&mut self, n: usize) -> Result<(), String> {
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
    pub(super) fn take_texels(&mut self, width: u32, height: u32, what: &str) -> Result<(), String> {
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
    /// Under a confinement, the file is read from its resolved path, and only when that lies
    /// inside the allowed folder.
    pub(super) fn read_file(&mut self, path: &Path, what: &str) -> Result<Vec<u8>, String> {
        let resolved = self.confined(path, what)?;
        let path = resolved.as_deref().unwrap_or(path);
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
