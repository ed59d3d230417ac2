//! Calendar dates to Julian Dates, and ΔT = TT − UT.
//!
//! Julian Day from the Gregorian or Julian calendar: Meeus, *Astronomical Algorithms* (2nd ed.,
//! 1998), eq. 7.1, which SPA (Reda & Andreas 2004, eq. 4) uses too. ΔT when the caller gives
//! none: the polynomials of Espenak & Meeus (*Five Millennium Canon of Solar Eclipses*, NASA
//! TP-2006-214141, 2006), a few seconds from the measured value over 1950–2050.

use crate::error::CoreError;

/// Seconds in a day.
const SECONDS_PER_DAY: f64 = 86_400.0;

/// Julian Date of J2000.0 (2000-01-01 12:00 TT).
pub const J2000: f64 = 2_451_545.0;

/// A calendar date and a time of day, in UTC (or any other clock, with `offset_hours`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CivilDateTime {
    /// Year, astronomical numbering (1 BC = 0).
    pub year: i32,
    /// Month, 1 to 12.
    pub month: u32,
    /// Day of the month, 1 to 31.
    pub day: u32,
    /// Hour, 0 to 23.
    pub hour: u32,
    /// Minute, 0 to 59.
    pub minute: u32,
    /// Second, [0, 61) (a leap second may be 60.x).
    pub second: f64,
    /// The clock's offset from UTC, hours (−7 for MST); UTC = local − offset.
    pub offset_hours: f64,
}

impl CivilDateTime {
    /// A UTC date and time.
    pub fn utc(year: i32, month: u32, day: u32, hour: u32, minute: u32, second: f64) -> Self {
        Self {
            year,
            month,
            day,
            hour,
            minute,
            second,
            offset_hours: 0.0,
        }
    }

    /// The same date and time on a clock `offset_hours` from UTC.
    pub fn with_offset(self, offset_hours: f64) -> Self {
        Self { offset_hours, ..self }
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        if !(-4000..=8000).contains(&self.year) {
            return invalid("year", self.year.to_string(), "must be in [-4000, 8000]");
        }
        if !(1..=12).contains(&self.month) {
            return invalid("month", self.month.to_string(), "must be in [1, 12]");
        }
        if self.day < 1 || self.day > days_in_month(self.year, self.month) {
            return invalid("day", self.day.to_string(), "must be a day of that month");
        }
        if self.hour > 23 {
            return invalid("hour", self.hour.to_string(), "must be in [0, 23]");
        }
        if self.minute > 59 {
            return invalid("minute", self.minute.to_string(), "must be in [0, 59]");
        }
        if !(self.second.is_finite() && (0.0..61.0).contains(&self.second)) {
            return invalid("second", self.second.to_string(), "must be in [0, 61)");
        }
        if !(self.offset_hours.is_finite() && self.offset_hours.abs() <= 18.0) {
            return invalid("offset_hours", self.offset_hours.to_string(), "must be in [-18, 18]");
        }
        Ok(())
    }

    /// Julian Date of this instant on the UTC time line (Meeus eq. 7.1; Gregorian calendar from
    /// 1582-10-15, Julian before).
    pub fn julian_date(&self) -> f64 {
        let (mut year, mut month) = (f64::from(self.year), f64::from(self.month));
        if self.month <= 2 {
            year -= 1.0;
            month += 12.0;
        }
        let gregorian = (self.year, self.month, self.day) >= (1582, 10, 15);
        let b = if gregorian {
            let a = (year / 100.0).floor();
            2.0 - a + (a / 4.0).floor()
        } else {
            0.0
        };
        let day_fraction =
            (f64::from(self.hour) + f64::from(self.minute) / 60.0 + self.second / 3600.0 - self.offset_hours) / 24.0;
        (365.25 * (year + 4716.0)).floor() + (30.6001 * (month + 1.0)).floor() + f64::from(self.day) + day_fraction + b
            - 1524.5
    }
}

/// `±HH:MM` for a clock offset in hours, `Z` for UTC (ISO 8601).
pub fn format_offset(hours: f64) -> String {
    if hours == 0.0 {
        return "Z".to_owned();
    }
    let minutes = (hours.abs() * 60.0).round() as u32;
    let sign = if hours < 0.0 { '-' } else { '+' };
    format!("{sign}{:02}:{:02}", minutes / 60, minutes % 60)
}

/// ISO 8601 on the date-time's own clock: `2003-10-17T12:30:30-07:00`; a fraction of a second is
/// written to the millisecond, trailing zeros kept (`16:00:00.250`).
impl std::fmt::Display for CivilDateTime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:04}-{:02}-{:02}T{:02}:{:02}:",
            self.year, self.month, self.day, self.hour, self.minute
        )?;
        if self.second.fract() == 0.0 {
            write!(f, "{:02}", self.second as u32)?;
        } else {
            write!(f, "{:06.3}", self.second)?;
        }
        f.write_str(&format_offset(self.offset_hours))
    }
}

/// Days in a month of the proleptic Gregorian calendar (Julian leap rule before 1583).
pub fn days_in_month(year: i32, month: u32) -> u32 {
    let leap = if year < 1583 {
        year.rem_euclid(4) == 0
    } else {
        (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
    };
    match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => 0,
    }
}

/// One instant: a Julian Date in Universal Time and ΔT = TT − UT.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instant {
    /// Julian Date, Universal Time (days).
    pub jd: f64,
    /// ΔT = TT − UT, seconds.
    pub delta_t: f64,
}

impl Instant {
    /// From a civil date and time, with ΔT given (seconds) or estimated by [`delta_t_estimate`].
    pub fn from_civil(civil: &CivilDateTime, delta_t: Option<f64>) -> Result<Self, CoreError> {
        civil.validate()?;
        let jd = civil.julian_date();
        let delta_t = match delta_t {
            Some(dt) if dt.is_finite() && dt.abs() <= 10_000.0 => dt,
            Some(dt) => {
                return Err(CoreError::Invalid {
                    field: "delta_t",
                    value: dt.to_string(),
                    rule: "must be finite, within ±10000 s",
                });
            }
            None => delta_t_estimate(decimal_year(civil)),
        };
        Ok(Self { jd, delta_t })
    }

    /// From a Julian Date (UT), with ΔT estimated for that date.
    pub fn from_jd(jd: f64) -> Self {
        Self {
            jd,
            delta_t: delta_t_estimate(2000.0 + (jd - J2000) / 365.25),
        }
    }

    /// Julian Ephemeris Date (Terrestrial Time): `jd + ΔT / 86400`.
    pub fn jde(&self) -> f64 {
        self.jd + self.delta_t / SECONDS_PER_DAY
    }

    /// Julian centuries of UT since J2000.0.
    pub fn centuries_ut(&self) -> f64 {
        (self.jd - J2000) / 36_525.0
    }

    /// Julian centuries of TT since J2000.0.
    pub fn centuries_tt(&self) -> f64 {
        (self.jde() - J2000) / 36_525.0
    }

    /// The same instant moved by `seconds`, keeping ΔT.
    pub fn plus_seconds(&self, seconds: f64) -> Self {
        Self {
            jd: self.jd + seconds / SECONDS_PER_DAY,
            delta_t: self.delta_t,
        }
    }
}

/// The year with its fraction, as Espenak & Meeus's ΔT polynomials take it (`y = year + (month −
/// 0.5) / 12`).
fn decimal_year(civil: &CivilDateTime) -> f64 {
    f64::from(civil.year) + (f64::from(civil.month) - 0.5) / 12.0
}

/// ΔT = TT − UT in seconds for a decimal year, by Espenak & Meeus (2006) for −500 to 2150, and
/// their long-term parabola outside that.
pub fn delta_t_estimate(year: f64) -> f64 {
    let y = year;
    let parabola = |y: f64| {
        let u = (y - 1820.0) / 100.0;
        -20.0 + 32.0 * u * u
    };
    if !(-500.0..2150.0).contains(&y) {
        return parabola(y);
    }
    if y < 500.0 {
        let u = y / 100.0;
        return 10583.6 - 1014.41 * u + 33.78311 * u.powi(2) - 5.952053 * u.powi(3) - 0.1798452 * u.powi(4)
            + 0.022174192 * u.powi(5)
            + 0.0090316521 * u.powi(6);
    }
    if y < 1600.0 {
        let u = (y - 1000.0) / 100.0;
        return 1574.2 - 556.01 * u + 71.23472 * u.powi(2) + 0.319781 * u.powi(3)
            - 0.8503463 * u.powi(4)
            - 0.005050998 * u.powi(5)
            + 0.0083572073 * u.powi(6);
    }
    if y < 1700.0 {
        let t = y - 1600.0;
        return 120.0 - 0.9808 * t - 0.01532 * t.powi(2) + t.powi(3) / 7129.0;
    }
    if y < 1800.0 {
        let t = y - 1700.0;
        return 8.83 + 0.1603 * t - 0.0059285 * t.powi(2) + 0.00013336 * t.powi(3) - t.powi(4) / 1_174_000.0;
    }
    if y < 1860.0 {
        let t = y - 1800.0;
        return 13.72 - 0.332447 * t + 0.0068612 * t.powi(2) + 0.0041116 * t.powi(3) - 0.00037436 * t.powi(4)
            + 0.0000121272 * t.powi(5)
            - 0.0000001699 * t.powi(6)
            + 0.000000000875 * t.powi(7);
    }
    if y < 1900.0 {
        let t = y - 1860.0;
        return 7.62 + 0.5737 * t - 0.251754 * t.powi(2) + 0.01680668 * t.powi(3) - 0.0004473624 * t.powi(4)
            + t.powi(5) / 233_174.0;
    }
    if y < 1920.0 {
        let t = y - 1900.0;
        return -2.79 + 1.494119 * t - 0.0598939 * t.powi(2) + 0.0061966 * t.powi(3) - 0.000197 * t.powi(4);
    }
    if y < 1941.0 {
        let t = y - 1920.0;
        return 21.20 + 0.84493 * t - 0.076100 * t.powi(2) + 0.0020936 * t.powi(3);
    }
    if y < 1961.0 {
        let t = y - 1950.0;
        return 29.07 + 0.407 * t - t.powi(2) / 233.0 + t.powi(3) / 2547.0;
    }
    if y < 1986.0 {
        let t = y - 1975.0;
        return 45.45 + 1.067 * t - t.powi(2) / 260.0 - t.powi(3) / 718.0;
    }
    if y < 2005.0 {
        let t = y - 2000.0;
        return 63.86 + 0.3345 * t - 0.060374 * t.powi(2)
            + 0.0017275 * t.powi(3)
            + 0.000651814 * t.powi(4)
            + 0.00002373599 * t.powi(5);
    }
    if y < 2050.0 {
        let t = y - 2000.0;
        return 62.92 + 0.32217 * t + 0.005589 * t.powi(2);
    }
    -20.0 + 32.0 * ((y - 1820.0) / 100.0).powi(2) - 0.5628 * (2150.0 - y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn julian_dates_match_meeus_examples() {
        // Meeus, example 7.a: 1957 October 4.81 → JD 2436116.31.
        let sputnik = CivilDateTime::utc(1957, 10, 4, 19, 26, 24.0);
        assert!((sputnik.julian_date() - 2_436_116.31).abs() < 1e-9);
        // Table 7.a: 2000 Jan 1.5 → 2451545.0; 1600 Dec 31.0 → 2305812.5; 837 Apr 10.3 (Julian).
        assert_eq!(CivilDateTime::utc(2000, 1, 1, 12, 0, 0.0).julian_date(), J2000);
        assert_eq!(CivilDateTime::utc(1600, 12, 31, 0, 0, 0.0).julian_date(), 2_305_812.5);
        let julian = CivilDateTime::utc(837, 4, 10, 7, 12, 0.0).julian_date();
        assert!((julian - 2_026_871.8).abs() < 1e-9);
    }

    #[test]
    fn date_times_print_as_iso_8601_on_their_own_clock() {
        let golden = CivilDateTime::utc(2003, 10, 17, 12, 30, 30.0).with_offset(-7.0);
        assert_eq!(golden.to_string(), "2003-10-17T12:30:30-07:00");
        let fraction = CivilDateTime::utc(2024, 3, 20, 16, 0, 0.25).with_offset(-7.5);
        assert_eq!(fraction.to_string(), "2024-03-20T16:00:00.250-07:30");
        assert_eq!(
            CivilDateTime::utc(2024, 3, 20, 16, 0, 0.0).to_string(),
            "2024-03-20T16:00:00Z"
        );
        assert_eq!(format_offset(5.75), "+05:45");
    }

    #[test]
    fn offsets_move_the_instant_to_utc() {
        // SPA's example: 2003-10-17 12:30:30 at −7 h is 19:30:30 UTC.
        let local = CivilDateTime::utc(2003, 10, 17, 12, 30, 30.0).with_offset(-7.0);
        let utc = CivilDateTime::utc(2003, 10, 17, 19, 30, 30.0);
        assert!((local.julian_date() - utc.julian_date()).abs() < 1e-9);
    }

    #[test]
    fn delta_t_is_close_to_measured_values() {
        // Measured ΔT (IERS): 1950.0 ≈ 29.1 s, 2000.0 ≈ 63.8 s, 2020.0 ≈ 69.4 s.
        assert!((delta_t_estimate(1950.0) - 29.1).abs() < 1.0);
        assert!((delta_t_estimate(2000.0) - 63.8).abs() < 1.0);
        assert!((delta_t_estimate(2020.0) - 69.4).abs() < 3.0);
    }

    #[test]
    fn bad_dates_name_the_field() {
        let bad = |c: CivilDateTime| match c.validate() {
            Err(CoreError::Invalid { field, .. }) => field,
            other => panic!("expected an error, got {other:?}"),
        };
        assert_eq!(bad(CivilDateTime::utc(2023, 2, 29, 0, 0, 0.0)), "day");
        assert_eq!(bad(CivilDateTime::utc(2023, 13, 1, 0, 0, 0.0)), "month");
        assert_eq!(bad(CivilDateTime::utc(2023, 1, 1, 24, 0, 0.0)), "hour");
        assert_eq!(bad(CivilDateTime::utc(2023, 1, 1, 0, 0, f64::NAN)), "second");
        assert!(CivilDateTime::utc(2024, 2, 29, 0, 0, 0.0).validate().is_ok());
    }
}
