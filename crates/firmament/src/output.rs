//! Image files: chosen by extension, written to a temporary file (`.firmament-*.tmp`), synced to
//! disk and renamed into place, so a failure, a kill or an OS crash never leaves a half-written
//! image. A stop at `--time-limit` or a second Ctrl-C removes the temporary files being written
//! ([`abandon_and_exit`]); only a kill (SIGKILL) or a crash can leave one behind:
//! [`remove_stale_temp_files`] clears those when a time-lapse resumes.
//!
//! Encoding is lossless and uses every core: pixels are converted in parallel, PNGs are deflated
//! fast, EXR blocks are compressed in parallel and written in order (the same bytes on any number
//! of threads). Figures: docs/PERFORMANCE.md, "Pipelined output".

use std::io::{Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use anyhow::{Context, Result, bail};
use firmament_render::headless::Image;
use rayon::prelude::*;

use crate::cli::ExrCompression;

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

/// The temporary files being written now. A stop at the time limit ([`abandon_and_exit`])
/// takes the lock, removes them and exits holding it: no file is created or renamed into place
/// after that, so nothing partial is left.
static LIVE_TEMP_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The list of live temporary files, whatever a panicking holder left it as.
fn live_temp_files() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE_TEMP_FILES.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A temporary output file, `.firmament-*.tmp`, listed while it lives; removed when dropped.
pub(crate) struct TempFile(Option<tempfile::NamedTempFile>);

impl TempFile {
    /// The open file.
    pub(crate) fn as_file(&self) -> &std::fs::File {
        self.named().as_file()
    }

    /// The open file, to write.
    pub(crate) fn as_file_mut(&mut self) -> &mut std::fs::File {
        self.0.as_mut().expect("a live temporary file").as_file_mut()
    }

    /// Renames the file to `path`; a stop at the time limit waits for the rename, or prevents it.
    pub(crate) fn persist(mut self, path: &Path) -> std::io::Result<()> {
        let named = self.0.take().expect("a live temporary file");
        let mut live = live_temp_files();
        live.retain(|p| p != named.path());
        named.persist(path).map(|_| ()).map_err(|e| e.error)
    }

    fn named(&self) -> &tempfile::NamedTempFile {
        self.0.as_ref().expect("a live temporary file")
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(named) = self.0.take() {
            let mut live = live_temp_files();
            live.retain(|p| p != named.path());
            drop(named);
        }
    }
}

/// A new temporary file in `dir`, named `.firmament-*.tmp` (removed when dropped).
pub(crate) fn temp_file_in(dir: &Path) -> std::io::Result<TempFile> {
    let mut live = live_temp_files();
    let named = tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .suffix(TEMP_SUFFIX)
        .tempfile_in(dir)?;
    live.push(named.path().to_path_buf());
    Ok(TempFile(Some(named)))
}

/// Stops the process with `code` after removing every temporary file being written, printing
/// `message` on stderr: a time limit's stop. Files already renamed into place are whole.
pub(crate) fn abandon_and_exit(message: &str, code: i32) -> ! {
    let live = live_temp_files();
    for path in live.iter() {
        let _ = std::fs::remove_file(path);
    }
    eprintln!("{message}");
    // Other threads still run while `exit` runs the atexit handlers, which tear the GPU driver
    // down (Mesa's EGL) under a render thread inside it: one that panics from now on waits,
    // silently, for the process to end, rather than print its error or exit with its own status.
    std::panic::set_hook(Box::new(|_| {
        loop {
            std::thread::park();
        }
    }));
    // Exits with the lock held: no writer creates or renames a file after this point.
    std::process::exit(code);
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

/// Pixels per parallel task when converting an image: large enough to amortise a task, small
/// enough to spread a 1280×720 frame over 16 cores.
const PIXELS_PER_TASK: usize = 1 << 15;

/// Writes an 8-bit RGBA image as an RGB PNG (8-bit sRGB, alpha dropped).
pub(crate) fn write_png(path: &Path, image: &Image<u8>) -> Result<()> {
    let rgb = rgb_of_rgba(image)?;
    write_atomically(path, |writer| {
        encode_png(writer, &rgb, image.width, image.height, image::ExtendedColorType::Rgb8)
            .with_context(|| format!("output {}: PNG encoding failed", path.display()))
    })
}

/// Writes a 16-bit RGBA image as an RGB PNG of 16 bits per channel (alpha dropped).
pub(crate) fn write_png16(path: &Path, image: &Image<u16>) -> Result<()> {
    // `image` takes 16-bit samples as native-endian bytes.
    let rgb: Vec<u8> = rgb_of_rgba(image)?.iter().flat_map(|v| v.to_ne_bytes()).collect();
    write_atomically(path, |writer| {
        encode_png(writer, &rgb, image.width, image.height, image::ExtendedColorType::Rgb16)
            .with_context(|| format!("output {}: PNG encoding failed", path.display()))
    })
}

/// `image`'s RGB channels, converted on every core.
fn rgb_of_rgba<T: Copy + Default + Send + Sync>(image: &Image<T>) -> Result<Vec<T>> {
    let pixels = image.width as usize * image.height as usize;
    if image.pixels.len() != pixels * 4 {
        bail!("image size mismatch");
    }
    let mut rgb = vec![T::default(); pixels * 3];
    rgb.par_chunks_mut(PIXELS_PER_TASK * 3)
        .zip(image.pixels.par_chunks(PIXELS_PER_TASK * 4))
        .for_each(|(rgb, rgba)| {
            for (out, pixel) in rgb.chunks_exact_mut(3).zip(rgba.chunks_exact(4)) {
                out.copy_from_slice(&pixel[..3]);
            }
        });
    Ok(rgb)
}

/// Encodes RGB rows (`color`: 8 or 16 bits a channel) as a PNG: fdeflate's fast mode after the
/// Sub filter, lossless. On sky images Sub is 4–7× faster than the adaptive filter and its files
/// smaller (docs/PERFORMANCE.md).
fn encode_png(
    writer: impl Write,
    rgb: &[u8],
    width: u32,
    height: u32,
    color: image::ExtendedColorType,
) -> image::ImageResult<()> {
    use image::ImageEncoder as _;
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    PngEncoder::new_with_quality(writer, CompressionType::Fast, FilterType::Sub).write_image(rgb, width, height, color)
}

/// A channel value an EXR file stores as a 32-bit float: `f32`, or a half float from the HDR
/// target (widened exactly).
pub(crate) trait ExrSample: Copy + Sync {
    /// The value as `f32`.
    fn to_f32(self) -> f32;
}

impl ExrSample for f32 {
    fn to_f32(self) -> f32 {
        self
    }
}

impl ExrSample for half::f16 {
    fn to_f32(self) -> f32 {
        half::f16::to_f32(self)
    }
}

/// Writes a linear RGBA image as an OpenEXR file of 32-bit float RGBA scan lines compressed
/// (losslessly) with `compression`.
pub(crate) fn write_exr<T: ExrSample>(path: &Path, image: &Image<T>, compression: ExrCompression) -> Result<()> {
    if image.pixels.len() != image.width as usize * image.height as usize * 4 {
        bail!("image size mismatch");
    }
    write_atomically(path, |writer| {
        encode_exr(writer, image, compression)
            .with_context(|| format!("output {}: EXR encoding failed", path.display()))
    })
}

/// The `exr` crate's compression for `--exr-compression`.
pub(crate) fn exr_compression(compression: ExrCompression) -> exr::compression::Compression {
    use exr::compression::Compression;
    match compression {
        ExrCompression::None => Compression::Uncompressed,
        ExrCompression::Rle => Compression::RLE,
        ExrCompression::Zip => Compression::ZIP16,
        ExrCompression::Zips => Compression::ZIP1,
        ExrCompression::Piz => Compression::PIZ,
    }
}

/// Encodes `image` (length checked) into `writer`, its blocks compressed on every core.
fn encode_exr<T: ExrSample>(
    writer: impl Write + Seek,
    image: &Image<T>,
    compression: ExrCompression,
) -> exr::error::UnitResult {
    use exr::prelude::{Blocks, Encoding, LineOrder, SpecificChannels, Vec2};
    let (width, height) = (image.width as usize, image.height as usize);
    let pixels = &image.pixels;
    let channels = SpecificChannels::rgba(|at: Vec2<usize>| {
        let i = (at.y() * width + at.x()) * 4;
        (
            pixels[i].to_f32(),
            pixels[i + 1].to_f32(),
            pixels[i + 2].to_f32(),
            pixels[i + 3].to_f32(),
        )
    });
    let encoding = Encoding {
        compression: exr_compression(compression),
        blocks: Blocks::ScanLines,
        // Blocks in file order, so the bytes do not depend on which thread finished first.
        line_order: LineOrder::Increasing,
    };
    let image = exr::image::Image::from_encoded_channels((width, height), encoding, channels);
    write_exr_blocks_in_parallel(&image, writer)
}

/// Writes an `exr` image like its own `write().to_buffered()`, with the blocks extracted and
/// compressed on rayon's threads a batch at a time (memory: a few blocks per thread) and written
/// in order. `exr`'s own parallel writer needs its `rayon` feature, which builds a thread pool per
/// file and would make `image`'s EXR encoder parallel, and unordered, too.
fn write_exr_blocks_in_parallel<'a, L: exr::image::write::layers::WritableLayers<'a>>(
    image: &'a exr::image::Image<L>,
    writer: impl Write + Seek,
) -> exr::error::UnitResult {
    use exr::block::UncompressedBlock;
    use exr::block::writer::ChunksWriter as _;
    use exr::image::write::layers::LayersWriter as _;
    let headers = image.layer_data.infer_headers(&image.attributes);
    let layers = image.layer_data.create_writer(&headers);
    exr::block::write(writer, headers, true, |meta, chunks| {
        let blocks: Vec<_> = meta.enumerate_ordered_header_block_indices().collect();
        for batch in blocks.chunks(rayon::current_num_threads() * 2) {
            let compressed: Vec<_> = batch
                .par_iter()
                .map(|&(index_in_header, index)| {
                    let data = layers.extract_uncompressed_block(&meta.headers, index);
                    let block = UncompressedBlock { index, data };
                    block
                        .compress_to_chunk(&meta.headers)
                        .map(|chunk| (index_in_header, chunk))
                })
                .collect();
            for result in compressed {
                let (index_in_header, chunk) = result?;
                chunks.write_chunk(index_in_header, chunk)?;
            }
        }
        Ok(())
    })
}
