//! Bounds on what a command may ask for, checked before anything is allocated: an over-limit
//! request is an error that names the limit and how to raise it, never an out-of-memory kill.
//!
//! Each side of an image is bounded by the scene format (`render.width`, `render.height`: 1 to
//! 16384) and by the GPU (`max_texture_dimension_2d`, and `max_buffer_size` for the read-back);
//! the total is bounded here, twice: by a fixed pixel limit that a variable raises, and by the
//! memory the machine has free now. A render holds the HDR target (8 bytes a pixel), depth
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

/// Bytes of memory a GPU render needs per pixel at most (EXR, measured on llvmpipe).
const GPU_BYTES_PER_PIXEL: u64 = 48;

/// Bytes of memory `render --reference` needs per pixel at most: the `f64` radiance (24, twice
/// while rayon gathers it), then the `f32` image (16) and the encoder's copy of it (16).
const REFERENCE_BYTES_PER_PIXEL: u64 = 72;

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

/// Fails unless a `width` × `height` GPU render (`what`: "the image", "the window") is within
/// [`max_pixels`] and the memory free now.
pub(crate) fn check_pixels(what: &str, width: u32, height: u32) -> Result<()> {
    check_image(what, width, height, GPU_BYTES_PER_PIXEL, available_memory())
}

/// [`check_pixels`] for `render --reference`, which holds `f64` pixels on the CPU.
pub(crate) fn check_reference_pixels(what: &str, width: u32, height: u32) -> Result<()> {
    check_image(what, width, height, REFERENCE_BYTES_PER_PIXEL, available_memory())
}

/// GiB, for messages.
fn gib(bytes: u64) -> f64 {
    bytes as f64 / f64::from(1 << 30)
}

/// Fails unless `width` × `height` pixels are within [`max_pixels`] and, at `bytes_per_pixel`,
/// within the `available` memory (when known).
fn check_image(what: &str, width: u32, height: u32, bytes_per_pixel: u64, available: Option<Available>) -> Result<()> {
    let pixels = u64::from(width) * u64::from(height);
    let max = max_pixels()?;
    let need = pixels.saturating_mul(bytes_per_pixel);
    if pixels > max {
        bail!(
            "{what} is {width}x{height} = {pixels} pixels, over the limit of {max} pixels{}: it would need up \
             to about {:.1} GiB of memory (the limit keeps a render under about {:.1} GiB); render a smaller \
             image, or raise the limit with {MAX_PIXELS_VAR}={pixels}",
            if max == DEFAULT_MAX_PIXELS { " (8192x8192)" } else { "" },
            gib(need),
            gib(max.saturating_mul(bytes_per_pixel)),
        );
    }
    if let Some(available) = available
        && need > available.bytes
    {
        bail!(
            "{what} is {width}x{height} = {pixels} pixels: rendering it needs about {:.1} GiB of memory \
             ({bytes_per_pixel} bytes a pixel), more than the {:.1} GiB {}; render a smaller image, or {} \
             ({MAX_PIXELS_VAR} does not lift this check)",
            gib(need),
            gib(available.bytes),
            available.source,
            available.advice,
        );
    }
    Ok(())
}

/// Memory a render may still allocate, and where that figure comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Available {
    /// Bytes.
    bytes: u64,
    /// The figure's source, for messages ("available (MemAvailable in /proc/meminfo)").
    source: &'static str,
    /// How to have more, for messages.
    advice: &'static str,
}

/// The least of the memory the system has available, the room left under the process's
/// address-space limit (`ulimit -v`) and under its cgroup's memory limit (cgroup v2), each when
/// readable: Linux only; `None` elsewhere, where only the pixel limit applies.
fn available_memory() -> Option<Available> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let meminfo = read("/proc/meminfo")
        .and_then(|t| meminfo_available(&t))
        .map(|bytes| Available {
            bytes,
            source: "available (MemAvailable in /proc/meminfo)",
            advice: "free memory (close other programs)",
        });
    let address_space = read("/proc/self/limits")
        .and_then(|t| address_space_limit(&t))
        .map(|limit| {
            let used = read("/proc/self/status").and_then(|t| vm_size(&t)).unwrap_or(0);
            Available {
                bytes: limit.saturating_sub(used),
                source: "left under this process's address-space limit (ulimit -v)",
                advice: "raise that limit (ulimit -v)",
            }
        });
    let cgroup = read("/proc/self/cgroup")
        .and_then(|t| t.lines().find_map(|l| l.strip_prefix("0::").map(str::to_owned)))
        .and_then(|group| {
            let dir = format!("/sys/fs/cgroup{}", group.trim_end_matches('/'));
            let max = read(&format!("{dir}/memory.max"))?.trim().parse::<u64>().ok()?;
            let current = read(&format!("{dir}/memory.current"))?.trim().parse::<u64>().ok()?;
            Some(Available {
                bytes: max.saturating_sub(current),
                source: "left under this process's cgroup memory limit (memory.max)",
                advice: "raise the cgroup's memory.max",
            })
        });
    [meminfo, address_space, cgroup]
        .into_iter()
        .flatten()
        .min_by_key(|a| a.bytes)
}

/// `MemAvailable` of `/proc/meminfo`, bytes.
fn meminfo_available(meminfo: &str) -> Option<u64> {
    kib_field(meminfo, "MemAvailable:")
}

/// `VmSize` of `/proc/self/status`, bytes.
fn vm_size(status: &str) -> Option<u64> {
    kib_field(status, "VmSize:")
}

/// A `Name:   1234 kB` line's value, bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find_map(|l| l.strip_prefix(name))?;
    let kib = line.trim().strip_suffix("kB")?.trim().parse::<u64>().ok()?;
    kib.checked_mul(1024)
}

/// The soft `Max address space` of `/proc/self/limits`, bytes; `None` when unlimited.
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits.lines().find_map(|l| l.strip_prefix("Max address space"))?;
    line.split_whitespace().next()?.parse::<u64>().ok()
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
        assert!(check_image("the image", 8192, 8192, GPU_BYTES_PER_PIXEL, None).is_ok());
        assert!(check_image("the image", 16_384, 4096, GPU_BYTES_PER_PIXEL, None).is_ok());
        let error = check_image("the image", 16_384, 16_384, GPU_BYTES_PER_PIXEL, None)
            .expect_err("over the limit")
            .to_string();
        assert!(
            error.contains("the image is 16384x16384 = 268435456 pixels, over the limit of 67108864 pixels")
                && error.contains("FIRMAMENT_MAX_PIXELS=268435456")
                && error.contains("12.0 GiB"),
            "{error}"
        );
    }

    #[test]
    fn memory_is_checked_against_what_is_available() {
        if std::env::var_os(MAX_PIXELS_VAR).is_some() {
            return;
        }
        let little = Some(Available {
            bytes: 1 << 30,
            source: "available (MemAvailable in /proc/meminfo)",
            advice: "free memory",
        });
        // 4096 x 4096 x 48 bytes = 768 MiB fits in 1 GiB; 8192 x 8192 x 48 = 3 GiB does not.
        assert!(check_image("the image", 4096, 4096, GPU_BYTES_PER_PIXEL, little).is_ok());
        let error = check_image("the image", 8192, 8192, GPU_BYTES_PER_PIXEL, little)
            .expect_err("over the memory")
            .to_string();
        assert!(
            error.contains(
                "needs about 3.0 GiB of memory (48 bytes a pixel), more than the 1.0 GiB available \
                 (MemAvailable in /proc/meminfo)"
            ),
            "{error}"
        );
        assert!(check_image("the image", 8192, 8192, GPU_BYTES_PER_PIXEL, None).is_ok());
    }

    #[test]
    fn proc_files_parse() {
        let meminfo = "MemTotal:       24684084 kB\nMemFree:         1000 kB\nMemAvailable:   23543120 kB\n";
        assert_eq!(meminfo_available(meminfo), Some(23_543_120 * 1024));
        assert_eq!(vm_size("Name:\tfirmament\nVmSize:\t    3892 kB\n"), Some(3892 * 1024));
        let unlimited = "Max stack size            8388608              unlimited            bytes     \n\
                         Max address space         unlimited            unlimited            bytes     \n";
        assert_eq!(address_space_limit(unlimited), None);
        let limited = "Max address space         1073741824           unlimited            bytes     \n";
        assert_eq!(address_space_limit(limited), Some(1 << 30));
        assert_eq!(meminfo_available("MemTotal: 1 kB\n"), None);
    }
}
