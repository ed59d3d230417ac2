//! Time of day on a 24-hour clock that wraps at midnight.

use std::fmt;
use std::str::FromStr;

/// Seconds in a day.
pub const SECONDS_PER_DAY: f64 = 86_400.0;

/// A time of day, seconds since midnight in `[0, 86400)`.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct TimeOfDay {
    seconds: f64,
}

/// Why a `HH:MM[:SS]` string is not a time of day.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{text}` is not a time of day: {rule}")]
pub struct TimeOfDayError {
    /// The text that was given.
    pub text: String,
    /// The rule it broke.
    pub rule: &'static str,
}

impl TimeOfDay {
    /// Midnight.
    pub const MIDNIGHT: Self = Self { seconds: 0.0 };

    /// From seconds since midnight; any finite value wraps into one day (so -60 is 23:59).
    /// Returns `None` for NaN or infinity.
    pub fn from_seconds(seconds: f64) -> Option<Self> {
        seconds.is_finite().then(|| Self {
            // rem_euclid can round up to exactly the modulus for tiny negative inputs.
            seconds: seconds.rem_euclid(SECONDS_PER_DAY) % SECONDS_PER_DAY,
        })
    }

    /// From hours since midnight (fractional hours allowed, wrapping like [`Self::from_seconds`]).
    pub fn from_hours(hours: f64) -> Option<Self> {
        Self::from_seconds(hours * 3600.0)
    }

    /// Seconds since midnight, `[0, 86400)`.
    pub fn seconds(self) -> f64 {
        self.seconds
    }

    /// Hours since midnight, `[0, 24)`.
    pub fn hours(self) -> f64 {
        self.seconds / 3600.0
    }

    /// Seconds to go forward from `self` to reach `later`, wrapping past midnight: `[0, 86400)`.
    pub fn seconds_until(self, later: Self) -> f64 {
        (later.seconds - self.seconds).rem_euclid(SECONDS_PER_DAY)
    }
}

impl FromStr for TimeOfDay {
    type Err = TimeOfDayError;

    /// Parses `HH:MM` or `HH:MM:SS` (24-hour clock, `00:00` to `23:59:59`; `24:00` means midnight).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let error = |rule| TimeOfDayError {
            text: text.to_owned(),
            rule,
        };
        let parts: Vec<&str> = text.trim().split(':').collect();
        if !(2..=3).contains(&parts.len()) {
            return Err(error("expected HH:MM or HH:MM:SS"));
        }
        let field = |s: &str, max: u32, rule| -> Result<u32, TimeOfDayError> {
            let ok = !s.is_empty() && s.len() <= 2 && s.bytes().all(|b| b.is_ascii_digit());
            let value: u32 = if ok {
                s.parse().map_err(|_| error(rule))?
            } else {
                return Err(error(rule));
            };
            if value > max { Err(error(rule)) } else { Ok(value) }
        };
        let h = field(parts[0], 24, "hours must be 0 to 24")?;
        let m = field(parts[1], 59, "minutes must be 0 to 59")?;
        let s = match parts.get(2) {
            Some(s) => field(s, 59, "seconds must be 0 to 59")?,
            None => 0,
        };
        if h == 24 && (m, s) != (0, 0) {
            return Err(error("24:00 is the only time after 23:59:59"));
        }
        let seconds = f64::from(h * 3600 + m * 60 + s);
        Ok(Self {
            seconds: seconds % SECONDS_PER_DAY,
        })
    }
}

impl fmt::Display for TimeOfDay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Truncation is intended: a clock shows completed seconds.
        let total = self.seconds.floor() as u32;
        write!(f, "{:02}:{:02}:{:02}", total / 3600, total / 60 % 60, total % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_wraps() {
        assert_eq!("06:30".parse::<TimeOfDay>().map(|t| t.hours()), Ok(6.5));
        assert_eq!("24:00".parse::<TimeOfDay>().map(|t| t.seconds()), Ok(0.0));
        assert_eq!("23:59:59".parse::<TimeOfDay>().map(|t| t.seconds()), Ok(86_399.0));
        for bad in [
            "",
            "6",
            "25:00",
            "12:60",
            "24:01",
            "ab:cd",
            "-1:00",
            "12:00:00:00",
            "1:2:99",
        ] {
            assert!(bad.parse::<TimeOfDay>().is_err(), "{bad}");
        }
        assert_eq!(TimeOfDay::from_hours(-1.0).map(|t| t.hours()), Some(23.0));
        assert_eq!(TimeOfDay::from_seconds(f64::NAN), None);
        assert_eq!(
            TimeOfDay::from_seconds(-1e-20).map(|t| t.seconds() < SECONDS_PER_DAY),
            Some(true)
        );
    }

    #[test]
    fn seconds_until_wraps() {
        let a = TimeOfDay::from_hours(23.0).expect("finite");
        let b = TimeOfDay::from_hours(1.0).expect("finite");
        assert_eq!(a.seconds_until(b), 7200.0);
        assert_eq!(b.seconds_until(a), 79_200.0);
        assert_eq!(a.to_string(), "23:00:00");
    }
}
