//! Bounds on what a command may ask for, checked before anything is allocated: an over-limit
//! request is an error that names the limit and how to raise it, never an out-of-memory kill.
//!
//! Each side of an image is bounded by the scene format (`render.width`, `render.height`: 1 to
//! 16384) and by the GPU (`max_texture_dimension_2d`, and `max_buffer_size` for the read-back);
//! the total is bounded here, by memory: a render holds the HDR target (8 bytes a pixel), depth
//! (4), the 8-bit output (4), the read-back buffer and its copy in memory, and for EXR the
//! widened `f32` pixels (16) and the encoder's copy (16). Measured on llvmpipe, whose textures
//! live in the process's memory: about 24 bytes a pixel for PNG and 48 for EXR.

use anyhow::{Result, bail};

/// The environment variable that raises (or lowers) [`DEFAULT_MAX_PIXELS`].
pub(crate) const MAX_PIXELS_VAR: &str = "FIRMAMENT_MAX_PIXELS";

/// The most pixels one image (a render, a time-lapse frame, a benchmark's targets, the viewer's
/// window) may have unless [`MAX_PIXELS_VAR`] says otherwise: 8192 × 8192, about 1.5 GiB for a
/// PNG render and 3 GiB for an EXR one.
pub(crate) const DEFAULT_MAX_PIXELS: u64 = 8192 * 8192;

/// Bytes of memory a render needs per pixel at most (EXR, measured on llvmpipe), for messages.
const BYTES_PER_PIXEL: u64 = 48;

/// The pixel limit in force: [`MAX_PIXELS_VAR`] when set, else [`DEFAULT_MAX_PIXELS`].
pub(crate) fn max_pixels() -> Result<u64> {
    match std::env::var(MAX_PIXELS_VAR) {
        Err(std::env::VarError::NotPresent) => Ok(DEFAULT_MAX_PIXELS),
        Ok(text) => match text.trim().parse::<u64>() {
            Ok(n) if n >= 1 => Ok(n),
            _ => bail!("{MAX_PIXELS_VAR} = {text:?}: must be a whole number of pixels >= 1"),
        },
        Err(std::env::VarError::NotUnicode(text)) => {
            bail!("{MAX_PIXELS_VAR} = {text:?}: must be a whole number of pixels >= 1")
        }
    }
}

/// Fails unless a `width` × `height` image (`what`: "the image", "the window") is within
/// [`max_pixels`].
pub(crate) fn check_pixels(what: &str, width: u32, height: u32) -> Result<()> {
    let pixels = u64::from(width) * u64::from(height);
    let max = max_pixels()?;
    if pixels > max {
        let gib = |n: u64| (n * BYTES_PER_PIXEL) as f64 / f64::from(1 << 30);
        bail!(
            "{what} is {width}x{height} = {pixels} pixels, over the limit of {max} pixels{}: it would need up \
             to about {:.1} GiB of memory (the limit keeps a render under about {:.1} GiB); render a smaller \
             image, or raise the limit with {MAX_PIXELS_VAR}={pixels}",
            if max == DEFAULT_MAX_PIXELS { " (8192x8192)" } else { "" },
            gib(pixels),
            gib(max),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_limit_admits_8192_squared_and_names_the_variable_beyond() {
        // The variable is not set in the unit tests' environment.
        if std::env::var_os(MAX_PIXELS_VAR).is_some() {
            return;
        }
        assert!(check_pixels("the image", 8192, 8192).is_ok());
        assert!(check_pixels("the image", 16_384, 4096).is_ok());
        let error = check_pixels("the image", 16_384, 16_384)
            .expect_err("over the limit")
            .to_string();
        assert!(
            error.contains("the image is 16384x16384 = 268435456 pixels, over the limit of 67108864 pixels")
                && error.contains("FIRMAMENT_MAX_PIXELS=268435456")
                && error.contains("12.0 GiB"),
            "{error}"
        );
    }
}
