//! Sharded time-lapses: `--shard I/N` renders one of N contiguous blocks of the frames, so a
//! batch scheduler (a Slurm job array, a Kubernetes indexed Job) spreads a long time-lapse over
//! machines writing into one shared folder; `--assemble DIR` then writes the GIF and the contact
//! sheet from the frames there. Every run writes the folder's manifest (`timelapse.json`: the
//! frames' count, size, format, span and rate) or checks it, so shards of different time-lapses
//! never mix in one folder and the assembly knows what to expect.
//!
//! Contiguous blocks, not every N-th frame: auto-exposure adapts from frame to frame over the
//! scene time between them (`HeadlessRenderer::set_exposure_interval`), so in a block every frame
//! but the first follows its predecessor as in one run; the first meters afresh, as a resumed run
//! does. Frames are byte-identical to a single run's wherever the exposure is fixed or adapts
//! within one frame step (at a time-lapse's steps of seconds to minutes it does).

use std::ops::Range;
use std::path::Path;

use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};

/// The manifest's name in the output folder.
pub(super) const MANIFEST_NAME: &str = "timelapse.json";

/// The largest manifest read, bytes (one is about 200).
const MAX_MANIFEST_BYTES: u64 = 64 << 10;

/// What a time-lapse folder holds: the same for every shard of one time-lapse.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Manifest {
    /// Frames in all, numbered from 1 in the file names.
    pub(super) frames: u32,
    /// Frame size, pixels.
    pub(super) width: u32,
    /// Frame size, pixels.
    pub(super) height: u32,
    /// Whether each frame also has an EXR.
    pub(super) exr: bool,
    /// The GIF's frame rate, frames per second.
    pub(super) fps: u32,
    /// The first frame's instant, ISO 8601.
    pub(super) from: String,
    /// The last frame's instant, ISO 8601.
    pub(super) to: String,
}

/// The frames (0-based) of shard `shard` (1-based) of `shards` among `n`: the `shard`-th of
/// `shards` contiguous blocks whose sizes differ by at most one.
pub(super) fn shard_frames(shard: u32, shards: u32, n: u32) -> Range<u32> {
    let edge = |i: u32| (u64::from(i) * u64::from(n) / u64::from(shards)) as u32;
    edge(shard - 1)..edge(shard)
}

/// Fails unless `shards` is at most the `n` frames (each shard gets at least one).
pub(super) fn check_shard(shard: u32, shards: u32, n: u32) -> Result<()> {
    if shards > n {
        bail!("--shard {shard}/{shards}: more shards than the {n} frames (each shard renders at least one frame)");
    }
    Ok(())
}

/// The manifest in `dir`, if it has one.
///
/// # Errors
/// It cannot be read, is too large, or is not a manifest.
pub(super) fn read_manifest(dir: &Path) -> Result<Option<Manifest>> {
    let path = dir.join(MANIFEST_NAME);
    let meta = match std::fs::metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        other => other.with_context(|| format!("cannot read {}", path.display()))?,
    };
    if !meta.is_file() || meta.len() > MAX_MANIFEST_BYTES {
        bail!(
            "{} is not a time-lapse manifest (a regular file of at most {MAX_MANIFEST_BYTES} bytes)",
            path.display()
        );
    }
    let text = std::fs::read_to_string(&path).with_context(|| format!("cannot read {}", path.display()))?;
    let manifest =
        serde_json::from_str(&text).with_context(|| format!("{} is not a time-lapse manifest", path.display()))?;
    Ok(Some(manifest))
}

/// Fails when `dir`'s manifest describes another time-lapse than `manifest` (unless
/// `overwrite`, which replaces it).
pub(super) fn check_manifest(dir: &Path, manifest: &Manifest, overwrite: bool) -> Result<()> {
    match read_manifest(dir)? {
        Some(found) if found != *manifest && !overwrite => bail!(
            "output {}: holds another time-lapse ({} frames of {}x{} from {} to {}{}, {} frames/s); this run \
             renders {} frames of {}x{} from {} to {}{}, {} frames/s: use another folder, or --overwrite",
            dir.display(),
            found.frames,
            found.width,
            found.height,
            found.from,
            found.to,
            if found.exr { " with EXR" } else { "" },
            found.fps,
            manifest.frames,
            manifest.width,
            manifest.height,
            manifest.from,
            manifest.to,
            if manifest.exr { " with EXR" } else { "" },
            manifest.fps,
        ),
        _ => Ok(()),
    }
}

/// Writes `manifest` into `dir` (whole or not at all; shards writing it at once write the same).
pub(super) fn write_manifest(dir: &Path, manifest: &Manifest) -> Result<()> {
    let text = serde_json::to_string_pretty(manifest).context("the manifest encodes")?;
    crate::output::write_atomically(&dir.join(MANIFEST_NAME), |w| {
        use std::io::Write as _;
        writeln!(w, "{text}").context("cannot write the manifest")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_every_frame_once_in_blocks() {
        for (n, shards) in [(1, 1), (10, 3), (120, 7), (100_000, 64), (5, 5)] {
            let mut next = 0;
            for shard in 1..=shards {
                let block = shard_frames(shard, shards, n);
                assert_eq!(block.start, next, "{n} frames, shard {shard}/{shards}");
                assert!(!block.is_empty() && block.len() as u32 <= n.div_ceil(shards));
                next = block.end;
            }
            assert_eq!(next, n);
        }
        assert_eq!(shard_frames(2, 3, 10), 3..6);
        assert!(check_shard(4, 6, 5).is_err());
    }
}
