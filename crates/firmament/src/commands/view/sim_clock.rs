//! The interactive viewer's time controls: pause and play, faster and slower (and backwards), and
//! scrubbing the time of day and the date.
//!
//! The clock counts *simulated* seconds from the scene's own moment (its time of day, or its date
//! and time); the viewer adds [`SimClock::offset_seconds`] to that moment. Real time is wall-clock
//! seconds between frames; [`SimClock::rate`] is simulated seconds per real second.

/// Simulated seconds in an hour.
pub(crate) const SECONDS_PER_HOUR: f64 = 3600.0;
/// Simulated seconds in a day (the civil day: scrub the date by this).
pub(crate) const SECONDS_PER_DAY: f64 = 86_400.0;
/// Largest rate magnitude, simulated seconds per real second (~116 days per second).
pub(crate) const MAX_RATE: f64 = 1e7;
/// The rates [`SimClock::faster`] and [`SimClock::slower`] step through, simulated seconds per real
/// second: real time, 10 s/s, 1 min/s, 10 min/s, 1 h/s, 6 h/s, 1 day/s, 7 days/s, 30 days/s.
pub(crate) const RATE_LADDER: [f64; 9] = [
    1.0,
    10.0,
    60.0,
    600.0,
    3600.0,
    21_600.0,
    86_400.0,
    604_800.0,
    2_592_000.0,
];

/// The viewer's simulated clock.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SimClock {
    /// Simulated seconds since the scene's own moment (negative before it).
    pub(crate) offset_seconds: f64,
    /// Simulated seconds per real second; negative runs time backwards; |rate| ≤ [`MAX_RATE`].
    pub(crate) rate: f64,
    /// Whether time stands still ([`SimClock::advance`] does nothing; scrubbing still works).
    pub(crate) paused: bool,
}

impl Default for SimClock {
    /// At the scene's moment, running at real time.
    fn default() -> Self {
        Self {
            offset_seconds: 0.0,
            rate: 1.0,
            paused: false,
        }
    }
}

impl SimClock {
    /// Advances by `real_dt` real seconds: the offset grows by `rate · real_dt` simulated seconds.
    /// Does nothing while paused, or for a non-finite or negative `real_dt`.
    pub(crate) fn advance(&mut self, real_dt: f64) {
        if self.paused || !(real_dt.is_finite() && real_dt > 0.0) {
            return;
        }
        self.add(self.rate * real_dt);
    }

    /// Pauses when playing, plays when paused.
    pub(crate) fn toggle_pause(&mut self) {
        self.paused = !self.paused;
    }

    /// The next rung of [`RATE_LADDER`] above |rate|, keeping the direction (no change at the
    /// top). A stopped clock (rate 0) goes to real time, forwards.
    pub(crate) fn faster(&mut self) {
        let sign = self.direction();
        let magnitude = self.rate.abs();
        if let Some(&next) = RATE_LADDER.iter().find(|&&r| r > magnitude) {
            self.rate = sign * next;
        }
    }

    /// The next rung of [`RATE_LADDER`] below |rate|, keeping the direction (no change at real
    /// time or slower).
    pub(crate) fn slower(&mut self) {
        let sign = self.direction();
        let magnitude = self.rate.abs();
        if let Some(&next) = RATE_LADDER.iter().rev().find(|&&r| r < magnitude) {
            self.rate = sign * next;
        }
    }

    /// Runs time the other way at the same speed.
    pub(crate) fn reverse(&mut self) {
        self.rate = -self.rate;
    }

    /// Sets the rate, simulated seconds per real second, clamped to ±[`MAX_RATE`]; a non-finite
    /// rate is ignored.
    pub(crate) fn set_rate(&mut self, rate: f64) {
        if rate.is_finite() {
            self.rate = rate.clamp(-MAX_RATE, MAX_RATE);
        }
    }

    /// Moves the clock by `seconds` simulated seconds (negative goes back), paused or not: scrub
    /// the time of day by hours ([`SECONDS_PER_HOUR`]) and the date by days
    /// ([`SECONDS_PER_DAY`]). A non-finite amount is ignored.
    pub(crate) fn scrub(&mut self, seconds: f64) {
        if seconds.is_finite() {
            self.add(seconds);
        }
    }

    /// Back to the scene's moment at real time, forwards; paused or playing as before.
    pub(crate) fn reset(&mut self) {
        self.offset_seconds = 0.0;
        self.rate = 1.0;
    }

    /// The rate for an info panel: `"×60 (1 min/s)"`, `"×1 (real time)"`,
    /// `"×-3600 (1 h/s backwards)"`, `"×0 (stopped)"`. It does not say whether the clock is paused.
    pub(crate) fn describe_rate(&self) -> String {
        let rate = if self.rate.is_finite() { self.rate } else { 0.0 };
        let factor = format!("×{}", significant(rate));
        let magnitude = rate.abs();
        if magnitude == 0.0 {
            return format!("{factor} (stopped)");
        }
        if rate == 1.0 {
            return format!("{factor} (real time)");
        }
        const UNITS: [(f64, &str, &str); 5] = [
            (31_557_600.0, "year", "years"),
            (SECONDS_PER_DAY, "day", "days"),
            (SECONDS_PER_HOUR, "h", "h"),
            (60.0, "min", "min"),
            (1.0, "s", "s"),
        ];
        let (unit, one, many) = UNITS
            .iter()
            .copied()
            .find(|(unit, _, _)| magnitude >= *unit)
            .unwrap_or((1.0, "s", "s"));
        let amount = significant(magnitude / unit);
        let name = if amount == "1" { one } else { many };
        let backwards = if rate < 0.0 { " backwards" } else { "" };
        format!("{factor} ({amount} {name}/s{backwards})")
    }

    /// +1 forwards (or stopped), −1 backwards.
    fn direction(&self) -> f64 {
        if self.rate < 0.0 { -1.0 } else { 1.0 }
    }

    /// Adds simulated seconds, keeping the offset finite.
    fn add(&mut self, seconds: f64) {
        let next = self.offset_seconds + seconds;
        if next.is_finite() {
            self.offset_seconds = next;
        }
    }
}

/// `x` with at most 3 significant digits after the point (integers in full), trailing zeros dropped.
fn significant(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        return format!("{x:.0}");
    }
    let digits = x.abs().log10().floor();
    let decimals = (2.0 - digits).clamp(0.0, 15.0) as usize;
    let text = format!("{x:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advances_at_the_rate_unless_paused() {
        let mut clock = SimClock::default();
        assert_eq!((clock.offset_seconds, clock.rate, clock.paused), (0.0, 1.0, false));
        clock.advance(0.5);
        assert_eq!(clock.offset_seconds, 0.5);
        clock.set_rate(60.0);
        clock.advance(2.0);
        assert_eq!(clock.offset_seconds, 120.5);
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, 0.0] {
            clock.advance(bad);
        }
        assert_eq!(clock.offset_seconds, 120.5);
        clock.toggle_pause();
        clock.advance(10.0);
        assert_eq!(clock.offset_seconds, 120.5);
        clock.toggle_pause();
        clock.reverse();
        clock.advance(1.0);
        assert_eq!(clock.offset_seconds, 60.5);
    }

    #[test]
    fn faster_and_slower_walk_the_ladder() {
        let mut clock = SimClock::default();
        for &rung in &RATE_LADDER[1..] {
            clock.faster();
            assert_eq!(clock.rate, rung);
        }
        clock.faster();
        assert_eq!(clock.rate, RATE_LADDER[RATE_LADDER.len() - 1]);
        for &rung in RATE_LADDER[..RATE_LADDER.len() - 1].iter().rev() {
            clock.slower();
            assert_eq!(clock.rate, rung);
        }
        clock.slower();
        assert_eq!(clock.rate, 1.0);
        // Off the ladder: to the neighbouring rungs; backwards keeps its direction.
        clock.set_rate(-100.0);
        clock.faster();
        assert_eq!(clock.rate, -600.0);
        clock.set_rate(-100.0);
        clock.slower();
        assert_eq!(clock.rate, -60.0);
        clock.set_rate(0.0);
        clock.faster();
        assert_eq!(clock.rate, 1.0);
        clock.set_rate(0.25);
        clock.slower();
        assert_eq!(clock.rate, 0.25);
        assert!(RATE_LADDER.iter().all(|&r| r <= MAX_RATE));
    }

    #[test]
    fn rate_is_clamped_and_scrub_and_reset_work() {
        let mut clock = SimClock::default();
        clock.set_rate(1e12);
        assert_eq!(clock.rate, MAX_RATE);
        clock.set_rate(-1e12);
        assert_eq!(clock.rate, -MAX_RATE);
        clock.set_rate(f64::NAN);
        assert_eq!(clock.rate, -MAX_RATE);
        clock.paused = true;
        clock.scrub(SECONDS_PER_DAY);
        clock.scrub(-2.0 * SECONDS_PER_HOUR);
        clock.scrub(f64::INFINITY);
        assert_eq!(clock.offset_seconds, SECONDS_PER_DAY - 2.0 * SECONDS_PER_HOUR);
        clock.scrub(f64::MAX);
        clock.scrub(f64::MAX);
        assert!(clock.offset_seconds.is_finite());
        clock.reset();
        assert_eq!(
            clock,
            SimClock {
                paused: true,
                ..SimClock::default()
            }
        );
    }

    #[test]
    fn describes_the_rate() {
        let mut clock = SimClock::default();
        let mut describe = |rate| {
            clock.rate = rate;
            clock.describe_rate()
        };
        assert_eq!(describe(1.0), "×1 (real time)");
        assert_eq!(describe(10.0), "×10 (10 s/s)");
        assert_eq!(describe(60.0), "×60 (1 min/s)");
        assert_eq!(describe(600.0), "×600 (10 min/s)");
        assert_eq!(describe(-3600.0), "×-3600 (1 h/s backwards)");
        assert_eq!(describe(21_600.0), "×21600 (6 h/s)");
        assert_eq!(describe(86_400.0), "×86400 (1 day/s)");
        assert_eq!(describe(604_800.0), "×604800 (7 days/s)");
        assert_eq!(describe(2_592_000.0), "×2592000 (30 days/s)");
        assert_eq!(describe(MAX_RATE), "×10000000 (116 days/s)");
        assert_eq!(describe(-1e8), "×-100000000 (3.17 years/s backwards)");
        assert_eq!(describe(0.5), "×0.5 (0.5 s/s)");
        assert_eq!(describe(0.0), "×0 (stopped)");
        assert_eq!(describe(f64::NAN), "×0 (stopped)");
        assert_eq!(describe(90.0), "×90 (1.5 min/s)");
    }
}
