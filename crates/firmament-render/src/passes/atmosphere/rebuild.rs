//! Rebuilding the medium's LUTs (transmittance, multiple scattering, sky irradiance) when the
//! medium changes, either within one frame or — for interactive callers — one step per frame
//! while the sky keeps drawing from the last complete set.
//!
//! The build stages write a set of their own (with a uniform buffer of their own holding the new
//! medium); its last step copies the set and the medium into the textures and the buffer every
//! other stage reads. Copies are bitwise, so a build in one frame gives the pixels a direct build
//! gave.

use std::cell::Cell;
use std::ops::Range;

use firmament_core::atmosphere::Atmosphere;

use super::multiscattering::{MULTISCATTERING_ORDERS, Tail};

/// Steps of one build: the transmittance LUT, each order of the multiple-scattering LUTs (the
/// last with their sum, the sky irradiance LUT and the copy into the live set).
pub const MEDIUM_BUILD_STEPS: u32 = MULTISCATTERING_ORDERS + 1;

/// What a build step encodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum BuildStep {
    /// The transmittance LUT, then the multiple-scattering orders' start (none yet).
    Transmittance,
    /// Order `n` (1 to [`MULTISCATTERING_ORDERS`], in order) of the multiple-scattering LUTs,
    /// then, after the last, their sum and the sky irradiance LUT, and the copy of the set and
    /// the medium into the live ones.
    Order(u32),
}

impl BuildStep {
    pub(super) fn of(step: u32) -> Self {
        match step {
            0 => Self::Transmittance,
            s => Self::Order(s.min(MULTISCATTERING_ORDERS)),
        }
    }
}

/// Where the rebuild stands. `prepare` (with `&mut`) starts builds, promotes finished ones and
/// plans the frame's steps; `record_luts` (with `&`) encodes the plan and advances.
#[derive(Debug, Default)]
pub(super) struct Rebuild {
    /// Spread builds over frames (when a complete set exists to draw from meanwhile).
    pub(super) incremental: bool,
    /// The medium the live LUTs hold; `None` before the first build finished.
    live: Option<Atmosphere>,
    /// The medium being built.
    pending: Option<Atmosphere>,
    /// How the build adds the orders after the last marched one (chosen by its air).
    pub(super) tail: Tail,
    /// The next step of the build in progress.
    next: Cell<Option<u32>>,
    /// The steps the next `record_luts` encodes.
    planned: Cell<Option<(u32, u32)>>,
    /// Complete builds encoded.
    pub(super) builds: Cell<u64>,
}

impl Rebuild {
    /// Whether the newest build (finished or under way) is of `atmosphere`'s medium and shape,
    /// whatever its pose: what the medium's LUTs depend on.
    pub(super) fn is_newest(&self, atmosphere: &Atmosphere) -> bool {
        self.pending.as_ref().or(self.live.as_ref()).is_some_and(|newest| {
            newest.medium == atmosphere.medium
                && newest.planet.radii == atmosphere.planet.radii
                && newest.planet.atmosphere_height == atmosphere.planet.atmosphere_height
        })
    }

    /// Starts building `medium` with `tail` (from the first step, also when a build was under
    /// way).
    pub(super) fn start(&mut self, medium: Atmosphere, tail: Tail) {
        self.promote_finished();
        self.tail = tail;
        self.pending = Some(medium);
        self.next.set(Some(0));
    }

    /// Makes a finished build's medium the live one.
    fn promote_finished(&mut self) {
        if self.next.get().is_none()
            && let Some(done) = self.pending.take()
        {
            self.live = Some(done);
        }
    }

    /// Plans this frame's steps; the medium whose LUTs this frame's sky reads: `None` for the
    /// newest (no build under way, or this frame finishes it), else the last complete one.
    pub(super) fn plan(&mut self) -> Option<&Atmosphere> {
        self.promote_finished();
        let Some(next) = self.next.get() else {
            self.planned.set(None);
            return None;
        };
        let end = if self.incremental && self.live.is_some() {
            next + 1
        } else {
            MEDIUM_BUILD_STEPS
        };
        self.planned.set(Some((next, end)));
        if end == MEDIUM_BUILD_STEPS {
            None
        } else {
            self.live.as_ref()
        }
    }

    /// Whether a build is under way.
    pub(super) fn in_progress(&self) -> bool {
        self.next.get().is_some()
    }

    /// Takes the steps planned for this frame and marks them done (each plan is encoded once).
    pub(super) fn take_planned(&self) -> Option<Range<u32>> {
        let (start, end) = self.planned.take()?;
        self.next.set((end < MEDIUM_BUILD_STEPS).then_some(end));
        Some(start..end)
    }
}
