//! Optional per-pass GPU timing of [`Renderer::record`](crate::Renderer::record) and
//! [`Renderer::record_into`](crate::Renderer::record_into), for a viewer's info panel.
//!
//! Off by default. [`Renderer::enable_pass_timing`](crate::Renderer::enable_pass_timing) turns it
//! on where the device has timestamp queries inside command encoders
//! ([`TIMESTAMP_FEATURES`], which
//! [`GpuContext::from_adapter`](crate::GpuContext::from_adapter) requests whenever the adapter
//! offers them; [`pass_timing_supported`] says whether a device has them). Elsewhere — llvmpipe's
//! GL, for one — it stays off and nothing changes.
//!
//! When on, each `record` writes a timestamp before its first command and one after each of its
//! phases ([`PHASES`]), resolves them and copies them into one of a small ring of read-back
//! buffers, which wgpu maps once the caller submits the encoder
//! ([`wgpu::CommandEncoder::map_buffer_on_submit`]): nothing to call after `queue.submit`.
//! [`Renderer::pass_times`](crate::Renderer::pass_times) polls the device without blocking and
//! returns the newest frame whose times have come back — usually one or two frames old. When every
//! buffer of the ring is still waiting for the GPU, a frame is simply not timed.
//!
//! Times are milliseconds of GPU time between the timestamps. Drivers may reorder work inside an
//! encoder and tile-based GPUs time passes loosely, so a phase's figure is approximate; their sum
//! is the GPU time of the whole `record`.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use crate::context::GpuContext;
use crate::requirements::TIMESTAMP_FEATURES;

/// The atmosphere's look-up tables (sky-view LUT, and the medium LUTs when the medium changed).
/// Only in frames whose sky is a physical atmosphere.
pub const PHASE_LUTS: &str = "LUTs";
/// The sun shadow maps of firmament's objects. Only in frames with shadows.
pub const PHASE_SHADOWS: &str = "shadows";
/// The main pass: firmament's objects, the sky behind them, the stars and the Moon (on the
/// [`record_into`](crate::Renderer::record_into) path: the sky, the stars and the Moon).
pub const PHASE_SKY_AND_OBJECTS: &str = "sky & objects";
/// Aerial perspective: the froxel volume and its application over the geometry. Only in frames
/// that build it (an atmosphere with objects, or one whose volume users asked for).
pub const PHASE_AERIAL_PERSPECTIVE: &str = "aerial perspective";
/// The cloud layers (and the aerial-perspective volume that lights the air in front of them,
/// when no object needed it). Only in frames whose physical sky has clouds.
pub const PHASE_CLOUDS: &str = "clouds";
/// The lens flares (occlusion and drawing), in every frame (near zero without flares).
pub const PHASE_FLARES: &str = "flares";
/// Auto-exposure: the luminance histogram and the adaptation. Only in frames metered
/// (`display.exposure_mode = "auto"`).
pub const PHASE_EXPOSURE: &str = "auto-exposure";
/// Bloom: the blur pyramid's way down and up. Only in frames with `display.bloom` above 0.
pub const PHASE_BLOOM: &str = "bloom";
/// Tone mapping into the caller's view: [`record`](crate::Renderer::record), and
/// [`record_into`](crate::Renderer::record_into) with an output view.
pub const PHASE_TONEMAP: &str = "tonemap";

/// Every phase a frame can have, in the order they run. A frame's [`PassTimes`] holds the ones it
/// ran, in this order.
pub const PHASES: [&str; 9] = [
    PHASE_LUTS,
    PHASE_SHADOWS,
    PHASE_SKY_AND_OBJECTS,
    PHASE_AERIAL_PERSPECTIVE,
    PHASE_CLOUDS,
    PHASE_FLARES,
    PHASE_EXPOSURE,
    PHASE_BLOOM,
    PHASE_TONEMAP,
];

/// Timestamps per frame: one before the first phase and one after each.
const QUERIES: u32 = PHASES.len() as u32 + 1;
/// Bytes of resolved timestamps per frame.
const BYTES: u64 = QUERIES as u64 * wgpu::QUERY_SIZE as u64;
/// Read-back buffers: frames whose times can be in flight at once.
const RING: usize = 3;

/// Whether `device` can time passes ([`TIMESTAMP_FEATURES`]: timestamp queries written between
/// the commands of an encoder).
pub fn pass_timing_supported(device: &wgpu::Device) -> bool {
    device.features().contains(TIMESTAMP_FEATURES)
}

/// One phase's GPU time.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PassTime {
    /// The phase, one of [`PHASES`].
    pub name: &'static str,
    /// Milliseconds of GPU time between the timestamps around the phase (finite, non-negative).
    pub milliseconds: f64,
}

/// The GPU times of one frame's phases, in the order they ran.
///
/// Phases the frame skipped are absent: [`PHASE_LUTS`] without an atmosphere,
/// [`PHASE_AERIAL_PERSPECTIVE`] when no aerial perspective was built, [`PHASE_EXPOSURE`] and
/// [`PHASE_BLOOM`] when the display has no auto-exposure or bloom, [`PHASE_TONEMAP`] on the
/// [`record_into`](crate::Renderer::record_into) path without an output view.
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct PassTimes {
    /// Each phase that ran and its time.
    pub phases: Vec<PassTime>,
}

impl PassTimes {
    /// Milliseconds of GPU time of the whole frame: the sum of its phases.
    pub fn total_ms(&self) -> f64 {
        self.phases.iter().map(|p| p.milliseconds).sum()
    }

    /// Milliseconds of GPU time of the phase `name` (one of [`PHASES`]), `None` when the frame
    /// skipped it.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.phases.iter().find(|p| p.name == name).map(|p| p.milliseconds)
    }
}

/// Where a read-back buffer's mapping stands (an [`AtomicU8`] shared with the map callback).
const PENDING: u8 = 0;
const MAPPED: u8 = 1;
const FAILED: u8 = 2;
/// The encoder was dropped unsubmitted: the callback was dropped without running.
const ABANDONED: u8 = 3;

/// Lives in the map callback: marks the mapping abandoned when the callback is dropped unrun (the
/// encoder or command buffer dropped without being submitted).
struct MapSignal(Arc<AtomicU8>);

impl Drop for MapSignal {
    fn drop(&mut self) {
        // Fails (as it should) when the callback already reported.
        let _ = self
            .0
            .compare_exchange(PENDING, ABANDONED, Ordering::AcqRel, Ordering::Acquire);
    }
}

/// A read-back buffer of the ring and what it holds.
#[derive(Debug)]
struct Slot {
    buffer: wgpu::Buffer,
    /// `None`: free (unmapped, usable as a copy destination).
    in_flight: Option<InFlight>,
}

/// A frame's timestamps on their way back.
#[derive(Debug)]
struct InFlight {
    /// The phases the frame timed, in order (timestamps `1..=phases.len()` end them).
    phases: Vec<&'static str>,
    /// The frame's number, to keep the newest of several finished frames.
    frame: u64,
    /// [`PENDING`], [`MAPPED`], [`FAILED`] or [`ABANDONED`].
    status: Arc<AtomicU8>,
}

/// The ring and the newest result, behind a mutex: `record` takes `&self`.
#[derive(Debug)]
struct RingState {
    slots: Vec<Slot>,
    /// Frames handed to the ring so far.
    frames: u64,
    /// The newest finished frame's number and times.
    latest: Option<(u64, PassTimes)>,
}

/// The GPU objects of pass timing: a timestamp query set, the buffer it resolves into and the
/// ring of read-back buffers.
#[derive(Debug)]
pub struct PassTimer {
    device: wgpu::Device,
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
    state: Mutex<RingState>,
}

fn readback_buffer(device: &wgpu::Device) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("firmament Renderer pass timing readback"),
        size: BYTES,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    })
}

impl PassTimer {
    /// The query set and buffers, or `None` when the device cannot write timestamps in encoders.
    pub fn new(ctx: &GpuContext) -> Option<Self> {
        let device = &ctx.device;
        if !pass_timing_supported(device) {
            return None;
        }
        let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("firmament Renderer pass timing queries"),
            ty: wgpu::QueryType::Timestamp,
            count: QUERIES,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament Renderer pass timing resolve buffer"),
            size: BYTES,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let slots = (0..RING)
            .map(|_| Slot {
                buffer: readback_buffer(device),
                in_flight: None,
            })
            .collect();
        Some(Self {
            device: device.clone(),
            queries,
            resolved,
            period_ns: f64::from(ctx.queue.get_timestamp_period()),
            state: Mutex::new(RingState {
                slots,
                frames: 0,
                latest: None,
            }),
        })
    }

    fn lock(&self) -> MutexGuard<'_, RingState> {
        // The state stays consistent between statements: a panic elsewhere cannot break it.
        self.state.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// The newest finished frame's times, after a non-blocking poll of the device.
    pub fn pass_times(&self, ctx: &GpuContext) -> Option<PassTimes> {
        // An error is device loss: the results stop coming, nothing more to do here.
        let _ = ctx.device.poll(wgpu::PollType::Poll);
        let mut state = self.lock();
        self.harvest(&mut state);
        state.latest.as_ref().map(|(_, times)| times.clone())
    }

    /// Blocks until the times of `frame` (from [`FrameTiming::finish`], its encoder submitted)
    /// are back: for benchmarks, which wait for each frame anyway. `None` when its read-back
    /// failed or a newer frame's times came back first.
    pub fn wait_for_frame(&self, ctx: &GpuContext, frame: u64) -> Option<PassTimes> {
        loop {
            // An error is device loss: the mapping fails and the loop ends below.
            let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
            let mut state = self.lock();
            self.harvest(&mut state);
            if let Some((latest, times)) = &state.latest
                && *latest >= frame
            {
                return (*latest == frame).then(|| times.clone());
            }
            let pending = state
                .slots
                .iter()
                .any(|slot| slot.in_flight.as_ref().is_some_and(|in_flight| in_flight.frame == frame));
            if !pending {
                return None;
            }
        }
    }

    /// Reads every mapped buffer of the ring, keeps the newest frame's times and frees the
    /// buffers whose frames finished, failed or were never submitted.
    fn harvest(&self, state: &mut RingState) {
        let RingState { slots, latest, .. } = state;
        for slot in slots.iter_mut() {
            let Some(in_flight) = &slot.in_flight else {
                continue;
            };
            match in_flight.status.load(Ordering::Acquire) {
                PENDING => continue,
                MAPPED => {
                    let times = self.read(&slot.buffer, &in_flight.phases);
                    slot.buffer.unmap();
                    if let Some(times) = times
                        && latest.as_ref().is_none_or(|(frame, _)| *frame < in_flight.frame)
                    {
                        *latest = Some((in_flight.frame, times));
                    }
                }
                ABANDONED => {}
                _ => {
                    // A failed mapping (device loss) may leave the buffer unusable: replace it.
                    tracing::debug!("firmament pass timing: a read-back failed");
                    slot.buffer = readback_buffer(&self.device);
                }
            }
            slot.in_flight = None;
        }
    }

    /// The times in a mapped read-back buffer.
    fn read(&self, buffer: &wgpu::Buffer, phases: &[&'static str]) -> Option<PassTimes> {
        let bytes = (phases.len() as u64 + 1) * u64::from(wgpu::QUERY_SIZE);
        let mapped = buffer.slice(..bytes).get_mapped_range().ok()?;
        let ticks: Vec<u64> = mapped.chunks_exact(8).map(bytemuck::pod_read_unaligned).collect();
        drop(mapped);
        let phases = phases
            .iter()
            .zip(ticks.windows(2))
            .map(|(&name, t)| PassTime {
                name,
                // Timestamps are not promised to be monotonic: a backwards step reads as zero.
                milliseconds: t[1].saturating_sub(t[0]) as f64 * self.period_ns * 1e-6,
            })
            .collect();
        Some(PassTimes { phases })
    }
}

/// The timing of one `record`: [`begin`](Self::begin), [`mark`](Self::mark) the end of each
/// phase, [`finish`](Self::finish). Does nothing when timing is off or the ring is full.
#[derive(Debug)]
pub struct FrameTiming<'a> {
    timer: Option<&'a PassTimer>,
    phases: Vec<&'static str>,
}

impl<'a> FrameTiming<'a> {
    /// Writes the first timestamp when `timer` is on and a read-back buffer is free.
    pub fn begin(timer: Option<&'a PassTimer>, encoder: &mut wgpu::CommandEncoder) -> Self {
        let timer = timer.filter(|timer| {
            let mut state = timer.lock();
            timer.harvest(&mut state);
            state.slots.iter().any(|slot| slot.in_flight.is_none())
        });
        if let Some(timer) = timer {
            encoder.write_timestamp(&timer.queries, 0);
        }
        Self {
            timer,
            phases: Vec::with_capacity(PHASES.len()),
        }
    }

    /// Ends the phase `name` with a timestamp.
    pub fn mark(&mut self, encoder: &mut wgpu::CommandEncoder, name: &'static str) {
        if let Some(timer) = self.timer
            && self.phases.len() < PHASES.len()
        {
            self.phases.push(name);
            encoder.write_timestamp(&timer.queries, self.phases.len() as u32);
        }
    }

    /// Resolves the frame's timestamps into a free read-back buffer, to be mapped when the
    /// encoder is submitted; the frame's number for [`PassTimer::wait_for_frame`], `None` when
    /// the frame is not timed.
    pub fn finish(self, encoder: &mut wgpu::CommandEncoder) -> Option<u64> {
        let timer = self.timer?;
        let mut state = timer.lock();
        state.frames += 1;
        let frame = state.frames;
        // Free at `begin`; taken since only by another thread recording at the same time.
        let slot = state.slots.iter_mut().find(|slot| slot.in_flight.is_none())?;
        let queries = self.phases.len() as u32 + 1;
        let bytes = u64::from(queries) * u64::from(wgpu::QUERY_SIZE);
        encoder.resolve_query_set(&timer.queries, 0..queries, &timer.resolved, 0);
        encoder.copy_buffer_to_buffer(&timer.resolved, 0, &slot.buffer, 0, bytes);
        let status = Arc::new(AtomicU8::new(PENDING));
        let signal = MapSignal(Arc::clone(&status));
        encoder.map_buffer_on_submit(&slot.buffer, wgpu::MapMode::Read, ..bytes, move |result| {
            // The whole signal moves in (not just its `Arc`), to be dropped after reporting.
            let signal = signal;
            signal
                .0
                .store(if result.is_ok() { MAPPED } else { FAILED }, Ordering::Release);
        });
        slot.in_flight = Some(InFlight {
            phases: self.phases,
            frame,
            status,
        });
        Some(frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_and_lookup() {
        let times = PassTimes {
            phases: vec![
                PassTime {
                    name: PHASE_SKY_AND_OBJECTS,
                    milliseconds: 1.5,
                },
                PassTime {
                    name: PHASE_TONEMAP,
                    milliseconds: 0.25,
                },
            ],
        };
        assert_eq!(times.total_ms(), 1.75);
        assert_eq!(times.get(PHASE_TONEMAP), Some(0.25));
        assert_eq!(times.get(PHASE_LUTS), None);
        assert_eq!(PassTimes::default().total_ms(), 0.0);
    }

    #[test]
    fn an_unrun_callback_marks_its_mapping_abandoned() {
        let status = Arc::new(AtomicU8::new(PENDING));
        drop(MapSignal(Arc::clone(&status)));
        assert_eq!(status.load(Ordering::Acquire), ABANDONED);

        let status = Arc::new(AtomicU8::new(PENDING));
        let signal = MapSignal(Arc::clone(&status));
        signal.0.store(MAPPED, Ordering::Release);
        drop(signal);
        assert_eq!(status.load(Ordering::Acquire), MAPPED);
    }
}
