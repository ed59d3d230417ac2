//! The animated GIF: every frame read back from its PNG, scaled down so the longer side is at
//! most [`GIF_LONGEST_SIDE`], quantised to its own 256-colour palette, looping forever.
//!
//! Reading, quantising and LZW-compressing a frame is all the work, and frames are independent:
//! batches of them are prepared on every core (rayon), then written in order.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow};

use rayon::prelude::*;

use super::frames::{fit_within, read_frame};
use crate::output::write_atomically_or_abandon;

/// The GIF's longest side, pixels.
pub(super) const GIF_LONGEST_SIDE: u32 = 640;

/// NeuQuant's sampling speed, 1 (best, slowest) to 30: 10 is gif's own default, several times
/// faster than 1 with no visible loss on smooth skies.
const QUANTISER_SPEED: i32 = 10;

/// At most this many frames are prepared at once (and held in memory).
const MAX_WORKERS: usize = 16;

/// Memory the frames being prepared at once may take, bytes: each is decoded whole (RGB, then
/// RGBA: about 8 bytes a pixel) before it is scaled down, so large frames are prepared fewer at a
/// time.
const PREPARE_MEMORY: u64 = 1 << 30;

/// One frame, read, scaled to `width × height`, quantised and LZW-compressed.
fn prepare(path: &Path, width: u16, height: u16, delay_cs: u16) -> Result<gif::Frame<'static>> {
    let mut rgba = read_frame(path)?.to_rgba8();
    let (w, h) = (u32::from(width), u32::from(height));
    if rgba.dimensions() != (w, h) {
        rgba = image::imageops::thumbnail(&rgba, w, h);
    }
    let mut pixels = rgba.into_raw();
    let mut frame = gif::Frame::from_rgba_speed(width, height, &mut pixels, QUANTISER_SPEED);
    frame.delay = delay_cs;
    frame.make_lzw_pre_encoded();
    Ok(frame)
}

/// Writes `frames` (PNG paths, in order) to `path` as a looping GIF at `fps` frames per second
/// (GIF delays are whole hundredths of a second, so 24 fps plays at 25). `interrupted` is asked
/// before each batch of frames; when it says yes the GIF is abandoned and `false` returned.
pub(super) fn write_gif(path: &Path, frames: &[PathBuf], fps: u32, interrupted: &dyn Fn() -> bool) -> Result<bool> {
    let Some(first) = frames.first() else {
        return Ok(false);
    };
    let (width, height) =
        image::image_dimensions(first).with_context(|| format!("cannot read the frame {}", first.display()))?;
    let (gif_width, gif_height) = fit_within(width, height, GIF_LONGEST_SIDE);
    // Both at most GIF_LONGEST_SIDE, so they fit a GIF's 16-bit sizes.
    let (gif_width, gif_height) = (gif_width.min(65_535) as u16, gif_height.min(65_535) as u16);
    let delay_cs = (100.0 / f64::from(fps.max(1))).round().clamp(1.0, 65_535.0) as u16;
    let per_frame = (u64::from(width) * u64::from(height) * 8).max(1);
    let workers = rayon::current_num_threads()
        .clamp(1, MAX_WORKERS)
        .min((PREPARE_MEMORY / per_frame).max(1) as usize);
    let failed = |e: gif::EncodingError| anyhow!("output {}: GIF encoding failed: {e}", path.display());
    write_atomically_or_abandon(path, |writer| {
        let mut encoder = gif::Encoder::new(writer, gif_width, gif_height, &[]).map_err(failed)?;
        encoder.set_repeat(gif::Repeat::Infinite).map_err(failed)?;
        for batch in frames.chunks(workers) {
            if interrupted() {
                return Ok(false);
            }
            let prepared: Vec<Result<gif::Frame<'static>>> = batch
                .par_iter()
                .map(|frame| prepare(frame, gif_width, gif_height, delay_cs))
                .collect();
            for frame in prepared {
                encoder.write_lzw_pre_encoded_frame(&frame?).map_err(failed)?;
            }
        }
        // Writes the GIF's trailer.
        encoder.into_inner().map_err(failed)?;
        Ok(true)
    })
}
