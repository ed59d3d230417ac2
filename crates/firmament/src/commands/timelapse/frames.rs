//! The written frames as the GIF and the contact sheet read them back.

use std::path::Path;

use anyhow::{Context, Result};

/// Reads a frame back from its PNG.
pub(super) fn read_frame(path: &Path) -> Result<image::DynamicImage> {
    image::open(path).with_context(|| format!("cannot read the frame {}", path.display()))
}

/// `(width, height)` scaled down (never up) so that the longer side is at most `longest`,
/// keeping the aspect ratio; each side at least 1.
pub(super) fn fit_within(width: u32, height: u32, longest: u32) -> (u32, u32) {
    let side = width.max(height);
    if side <= longest {
        return (width, height);
    }
    let scale = f64::from(longest) / f64::from(side);
    let fit = |v: u32| ((f64::from(v) * scale).round() as u32).clamp(1, longest);
    (fit(width), fit(height))
}
