//! Image files: chosen by extension, written to a temporary file (`.firmament-*.tmp`), synced to
//! disk and renamed into place, so a failure, a kill or an OS crash never leaves a half-written
//! image. Only a kill (SIGKILL, a second Ctrl-C) can leave the temporary file itself behind:
//! [`remove_stale_temp_files`] clears those when a time-lapse resumes.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result, bail};
use firmament_render::headless::Image;

/// The image formats `render` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OutputFormat {
    /// 8-bit sRGB, display-referred.
    Png,
    /// 32-bit float linear RGBA, scene-referred.
    Exr,
}

impl OutputFormat {
    /// The format for a path's extension (case-insensitive).
    pub(crate) fn from_path(path: &Path) -> Result<Self> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Self::Png),
            Some("exr") => Ok(Self::Exr),
            _ => bail!(
                "output {}: the file name must end in .png (8-bit sRGB) or .exr (linear float)",
                path.display()
            ),
        }
    }
}

/// Fails unless the output can be written: its folder exists, is a folder and takes a new file
/// (proved with a temporary file, removed at once), and the output is not itself a folder. Run
/// before the slow parts, so that a typo fails at once rather than after a render.
pub(crate) fn check_parent_dir(path: &Path) -> Result<()> {
    let dir = parent(path);
    if !dir.is_dir() {
        bail!("output {}: the folder {} does not exist", path.display(), dir.display());
    }
    if path.is_dir() {
        bail!("output {}: is a folder; name a file in it", path.display());
    }
    temp_file_in(dir)
        .with_context(|| format!("output {}: cannot create a file in {}", path.display(), dir.display()))?;
    Ok(())
}

/// The start and end of the temporary files' names.
const TEMP_PREFIX: &str = ".firmament-";
const TEMP_SUFFIX: &str = ".tmp";

/// A new temporary file in `dir`, named `.firmament-*.tmp` (removed when dropped).
pub(crate) fn temp_file_in(dir: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .suffix(TEMP_SUFFIX)
        .tempfile_in(dir)
}

/// Removes the temporary files (`.firmament-*.tmp`) a killed run left in `dir`; returns how many.
/// Only files of exactly that form are touched; a missing folder has none.
pub(crate) fn remove_stale_temp_files(dir: &Path) -> Result<usize> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(0);
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let stale = name.len() > TEMP_PREFIX.len() + TEMP_SUFFIX.len()
            && name.starts_with(TEMP_PREFIX)
            && name.ends_with(TEMP_SUFFIX)
            && entry.file_type().is_ok_and(|t| t.is_file());
        if stale {
            std::fs::remove_file(entry.path())
                .with_context(|| format!("cannot remove the stale temporary file {}", entry.path().display()))?;
            removed += 1;
        }
    }
    Ok(removed)
}

fn parent(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Writes `path` through a temporary file in the same folder, renamed into place, so the file is
/// either complete or absent.
pub(crate) fn write_atomically(path: &Path, write: impl FnOnce(&mut Writer<'_>) -> Result<()>) -> Result<()> {
    write_atomically_or_abandon(path, |writer| write(writer).map(|()| true)).map(|_| ())
}

/// The buffered temporary file that [`write_atomically`] hands its writer.
pub(crate) type Writer<'a> = std::io::BufWriter<&'a mut std::fs::File>;

/// [`write_atomically`] whose `write` may return `false` to abandon the file (a time-lapse
/// interrupted while it writes its GIF): the temporary file is removed and `false` returned.
pub(crate) fn write_atomically_or_abandon(
    path: &Path,
    write: impl FnOnce(&mut Writer<'_>) -> Result<bool>,
) -> Result<bool> {
    let mut tmp = temp_file_in(parent(path)).with_context(|| {
        format!(
            "output {}: cannot create a file in {}",
            path.display(),
            parent(path).display()
        )
    })?;
    {
        let mut writer = std::io::BufWriter::new(tmp.as_file_mut());
        if !write(&mut writer)? {
            return Ok(false);
        }
        writer
            .flush()
            .with_context(|| format!("output {}: cannot write the file", path.display()))?;
    }
    // On disk before the rename: otherwise an OS crash soon after could leave the new name on an
    // empty or partial file (the rename reaching the disk before the data).
    tmp.as_file()
        .sync_all()
        .with_context(|| format!("output {}: cannot write the file to disk", path.display()))?;
    // Temporary files are created private (0600); an image is an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .with_context(|| format!("output {}: cannot set permissions", path.display()))?;
    }
    tmp.persist(path)
        .with_context(|| format!("output {}: cannot write the file", path.display()))?;
    Ok(true)
}

/// Writes an 8-bit RGBA image as an RGB PNG.
pub(crate) fn write_png(path: &Path, image: &Image<u8>) -> Result<()> {
    let rgb: Vec<u8> = image.pixels.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    let buffer = image::RgbImage::from_raw(image.width, image.height, rgb).context("image size mismatch")?;
    write_atomically(path, |writer| {
        buffer
            .write_to(writer, image::ImageFormat::Png)
            .with_context(|| format!("output {}: PNG encoding failed", path.display()))
    })
}

/// Writes a linear float RGBA image as an OpenEXR file.
pub(crate) fn write_exr(path: &Path, image: &Image<f32>) -> Result<()> {
    let buffer = image::Rgba32FImage::from_raw(image.width, image.height, image.pixels.clone())
        .context("image size mismatch")?;
    write_atomically(path, |writer| {
        buffer
            .write_to(writer, image::ImageFormat::OpenExr)
            .with_context(|| format!("output {}: EXR encoding failed", path.display()))
    })
}
