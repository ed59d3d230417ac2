//! The contact sheet: the frames as thumbnails in a grid, in order, left to right and top to
//! bottom, on a dark background.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use image::{Rgb, RgbImage};
use rayon::prelude::*;

use super::frames::{fit_within, read_frame};
use crate::output::write_atomically;

/// Thumbnails per row (fewer when there are fewer frames).
const COLUMNS: u32 = 6;

/// A thumbnail's longest side, pixels (never larger than the frame).
const THUMBNAIL_SIDE: u32 = 240;

/// The most thumbnails on one sheet: longer time-lapses show this many frames, evenly spaced,
/// the first and last included.
pub(super) const MAX_THUMBNAILS: usize = 120;

/// Pixels between thumbnails and around the grid.
const GAP: u32 = 4;

/// The background between thumbnails (sRGB).
const BACKGROUND: Rgb<u8> = Rgb([24, 24, 24]);

/// Which frames the sheet shows: all of them, or [`MAX_THUMBNAILS`] evenly spaced.
fn chosen(count: usize) -> Vec<usize> {
    if count <= MAX_THUMBNAILS {
        return (0..count).collect();
    }
    let last = (count - 1) as f64;
    (0..MAX_THUMBNAILS)
        .map(|i| (i as f64 * last / (MAX_THUMBNAILS - 1) as f64).round() as usize)
        .collect()
}

/// Writes the contact sheet of `frames` (PNG paths, in order) to `path` as a PNG.
pub(super) fn write_contact_sheet(path: &Path, frames: &[PathBuf]) -> Result<()> {
    let picks = chosen(frames.len());
    let Some(&first) = picks.first() else {
        return Ok(());
    };
    let (width, height) = image::image_dimensions(&frames[first])
        .with_context(|| format!("cannot read the frame {}", frames[first].display()))?;
    let (tw, th) = fit_within(width, height, THUMBNAIL_SIDE);
    let count = picks.len() as u32;
    let columns = count.min(COLUMNS);
    let rows = count.div_ceil(columns);
    let mut sheet = RgbImage::from_pixel(GAP + columns * (tw + GAP), GAP + rows * (th + GAP), BACKGROUND);
    // Frames are decoded and shrunk on every core (a frame at a time per thread), then placed in
    // order: the sheet's bytes do not depend on the thread count.
    let thumbs: Vec<RgbImage> = picks
        .par_iter()
        .map(|&k| -> Result<RgbImage> {
            let frame = read_frame(&frames[k])?.to_rgb8();
            Ok(if frame.dimensions() == (tw, th) {
                frame
            } else {
                image::imageops::thumbnail(&frame, tw, th)
            })
        })
        .collect::<Result<_>>()?;
    for (i, thumb) in thumbs.iter().enumerate() {
        let (col, row) = (i as u32 % columns, i as u32 / columns);
        image::imageops::replace(
            &mut sheet,
            thumb,
            i64::from(GAP + col * (tw + GAP)),
            i64::from(GAP + row * (th + GAP)),
        );
    }
    write_atomically(path, |writer| {
        sheet
            .write_to(writer, image::ImageFormat::Png)
            .with_context(|| format!("output {}: PNG encoding failed", path.display()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_sequences_are_sampled_evenly_from_first_to_last() {
        assert_eq!(chosen(3), vec![0, 1, 2]);
        let picks = chosen(100_000);
        assert_eq!(picks.len(), MAX_THUMBNAILS);
        assert_eq!((picks[0], picks[MAX_THUMBNAILS - 1]), (0, 99_999));
        assert!(picks.windows(2).all(|w| w[0] < w[1]));
    }
}
