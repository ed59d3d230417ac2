//! Frames in flight: the main thread submits frame N + 1 to the GPU before it collects frame N,
//! and each collected frame is encoded (its EXR, then its PNG) as one task on rayon's threads, so
//! rendering, read-back and encoding overlap and encoding uses every core. At most
//! [`queue_depth`] frames wait for or are in encoding, which bounds memory; a frame counts as done
//! once its files are renamed into place.

use std::path::PathBuf;
use std::sync::mpsc;

use anyhow::{Context, Result};
use firmament_render::headless::FramePixels;

use crate::cli::ExrCompression;
use crate::output::{write_exr, write_png};

/// Bytes of frames the encoding queue may hold: decoded pixels (4 bytes a pixel for the PNG, 8
/// more for the EXR's half floats), not counting the encoders' own buffers.
const QUEUE_BUDGET_BYTES: u64 = 1 << 30;

/// How many frames may wait for or be in encoding: one per rayon thread plus one ready for the
/// first thread that frees up, fewer when frames are so large that they would pass
/// [`QUEUE_BUDGET_BYTES`] (at least one).
pub(super) fn queue_depth(width: u32, height: u32, exr: bool) -> usize {
    let bytes_per_pixel = if exr { 12 } else { 4 };
    let frame_bytes = u64::from(width) * u64::from(height) * bytes_per_pixel;
    let fit = (QUEUE_BUDGET_BYTES / frame_bytes.max(1)).max(1);
    (rayon::current_num_threads() + 1).min(usize::try_from(fit).unwrap_or(usize::MAX))
}

/// One frame's pixels and where they go.
pub(super) struct EncodeJob {
    /// The frame, 0-based.
    pub(super) index: u32,
    /// Its read-back images: the display image, and the HDR one when `exr` is set.
    pub(super) pixels: FramePixels,
    /// The PNG's path.
    pub(super) png: PathBuf,
    /// The EXR's path and compression, with `--exr`.
    pub(super) exr: Option<(PathBuf, ExrCompression)>,
}

impl EncodeJob {
    /// Writes the EXR (if any), then the PNG: a PNG on disk means the frame is whole.
    fn run(self) -> Result<()> {
        if let Some((path, compression)) = &self.exr {
            let hdr = self.pixels.hdr.as_ref().context("no HDR image was read back")?;
            write_exr(path, hdr, *compression)?;
        }
        let ldr = self.pixels.ldr.as_ref().context("no display image was read back")?;
        write_png(&self.png, ldr)
    }
}

/// Frames being encoded on rayon's threads, at most `depth` at once. Dropping it waits for the
/// frames still encoding, so that no task outlives the run (a temporary file it left would only
/// be cleared by the next run).
pub(super) struct EncodeQueue {
    depth: usize,
    outstanding: usize,
    sender: mpsc::Sender<(u32, Result<()>)>,
    receiver: mpsc::Receiver<(u32, Result<()>)>,
}

impl EncodeQueue {
    /// An empty queue of at most `depth` frames (at least 1).
    pub(super) fn new(depth: usize) -> Self {
        let (sender, receiver) = mpsc::channel();
        Self {
            depth: depth.max(1),
            outstanding: 0,
            sender,
            receiver,
        }
    }

    /// Starts encoding `job`, first waiting for a free place in the queue; calls `done` with
    /// each frame finished meanwhile. Fails with the first frame that failed.
    pub(super) fn push(&mut self, job: EncodeJob, done: &mut impl FnMut(u32)) -> Result<()> {
        while self.outstanding >= self.depth {
            self.wait_one(done)?;
        }
        let sender = self.sender.clone();
        self.outstanding += 1;
        rayon::spawn(move || {
            let index = job.index;
            let result = job.run();
            // The receiver lives until every task has answered (see Drop).
            let _ = sender.send((index, result));
        });
        Ok(())
    }

    /// Calls `done` with each frame finished since the last call, without waiting.
    pub(super) fn poll(&mut self, done: &mut impl FnMut(u32)) -> Result<()> {
        while let Ok((index, result)) = self.receiver.try_recv() {
            self.outstanding -= 1;
            result?;
            done(index);
        }
        Ok(())
    }

    /// Waits for every queued frame, calling `done` with each.
    pub(super) fn finish(&mut self, done: &mut impl FnMut(u32)) -> Result<()> {
        while self.outstanding > 0 {
            self.wait_one(done)?;
        }
        Ok(())
    }

    fn wait_one(&mut self, done: &mut impl FnMut(u32)) -> Result<()> {
        let (index, result) = self
            .receiver
            .recv()
            .context("an encoding task ended without answering")?;
        self.outstanding -= 1;
        result?;
        done(index);
        Ok(())
    }
}

impl Drop for EncodeQueue {
    fn drop(&mut self) {
        while self.outstanding > 0 && self.receiver.recv().is_ok() {
            self.outstanding -= 1;
        }
    }
}
