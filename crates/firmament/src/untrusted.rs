//! Untrusted mode: what a command may read and ask for when its scene is a stranger's
//! (`--untrusted`), and the wall-time limit (`--time-limit`). The folder and file limits are the
//! scene crate's [`Confinement`]; the pixels, frames and paths of a command are checked here.
//! docs/RELIABILITY.md has the threat model and the figures.

use std::path::Path;

use anyhow::{Context, Result, bail};
use firmament_scene::assets::{AssetLimits, Confinement};

use crate::cli::untrusted::UntrustedArgs;

/// The wall-time limit of an untrusted command without `--time-limit`, seconds.
pub(crate) const DEFAULT_TIME_LIMIT_S: f64 = 120.0;

/// The most pixels of an untrusted image without `--max-pixels`: 2048 × 2048.
pub(crate) const DEFAULT_MAX_PIXELS: u64 = 2048 * 2048;

/// The most frames of an untrusted time-lapse without `--max-frames`.
pub(crate) const DEFAULT_MAX_FRAMES: u32 = 240;

/// The most Monte Carlo paths of an untrusted reference render or sample without `--max-paths`:
/// 2²², a few seconds to a minute of the reference on one core.
pub(crate) const DEFAULT_MAX_PATHS: u64 = 1 << 22;

/// What one command may do: everything (a trusted scene), or untrusted mode's folder and budgets.
#[derive(Debug, Clone, Default)]
pub(crate) struct Policy {
    /// The allowed folder and file limits; `None` when trusted.
    confinement: Option<Confinement>,
    /// Pixels of one image.
    max_pixels: Option<u64>,
    /// Frames of a time-lapse.
    max_frames: Option<u32>,
    /// Monte Carlo paths of the reference.
    max_paths: Option<u64>,
}

impl Policy {
    /// The policy `args` ask for, for a command whose scene file is `scene` (none: a preset or
    /// the default scene).
    ///
    /// # Errors
    /// The allowed folder is not a folder.
    pub(crate) fn new(args: &UntrustedArgs, scene: Option<&Path>) -> Result<Self> {
        if !args.untrusted {
            return Ok(Self::default());
        }
        let scene_folder = scene
            .and_then(Path::parent)
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let root = args.asset_root.as_deref().unwrap_or(scene_folder);
        let limits = AssetLimits {
            max_file_bytes: args.max_file_bytes.unwrap_or(AssetLimits::UNTRUSTED.max_file_bytes),
            max_texture_side: args.max_texture_side.unwrap_or(AssetLimits::UNTRUSTED.max_texture_side),
            max_triangles: args.max_triangles.unwrap_or(AssetLimits::UNTRUSTED.max_triangles),
        };
        let confinement = Confinement::new(root)
            .with_context(|| {
                if args.asset_root.is_some() {
                    "--asset-root: the allowed folder"
                } else {
                    "--untrusted: the scene's folder, the allowed one"
                }
            })?
            .with_limits(limits);
        Ok(Self {
            confinement: Some(confinement),
            max_pixels: Some(args.max_pixels.unwrap_or(DEFAULT_MAX_PIXELS)),
            max_frames: Some(args.max_frames.unwrap_or(DEFAULT_MAX_FRAMES)),
            max_paths: Some(args.max_paths.unwrap_or(DEFAULT_MAX_PATHS)),
        })
    }

    /// The folder and file limits scenes are held to; `None` when trusted.
    pub(crate) fn confinement(&self) -> Option<&Confinement> {
        self.confinement.as_ref()
    }

    /// Fails when a `width` × `height` image (`what`: "the image", "each frame") is over
    /// untrusted mode's pixel limit. The limits of every mode (`crate::limits`) apply as well.
    pub(crate) fn check_pixels(&self, what: &str, width: u32, height: u32) -> Result<()> {
        let pixels = u64::from(width) * u64::from(height);
        match self.max_pixels {
            Some(max) if pixels > max => bail!(
                "{what} is {width}x{height} = {pixels} pixels, over untrusted mode's limit of {max} pixels \
                 (--max-pixels raises it)"
            ),
            _ => Ok(()),
        }
    }

    /// Fails when a time-lapse of `frames` frames is over untrusted mode's frame limit.
    pub(crate) fn check_frames(&self, frames: u32) -> Result<()> {
        match self.max_frames {
            Some(max) if frames > max => {
                bail!("--frames = {frames}: over untrusted mode's limit of {max} frames (--max-frames raises it)")
            }
            _ => Ok(()),
        }
    }

    /// Fails when the reference would trace more than untrusted mode's paths: `paths` in all,
    /// `how` saying how they add up ("256 paths per pixel x 4096 pixels").
    pub(crate) fn check_paths(&self, paths: u64, how: &str) -> Result<()> {
        match self.max_paths {
            Some(max) if paths > max => bail!(
                "the reference would trace {paths} paths ({how}), over untrusted mode's limit of {max} \
                 (--max-paths raises it; fewer --paths or pixels lower the count)"
            ),
            _ => Ok(()),
        }
    }
}

/// The wall-time limit `args` ask for, seconds: `--time-limit`, else
/// [`DEFAULT_TIME_LIMIT_S`] under `--untrusted`, else none.
pub(crate) fn time_limit(args: &UntrustedArgs) -> Option<f64> {
    args.time_limit
        .or_else(|| args.untrusted.then_some(DEFAULT_TIME_LIMIT_S))
}
