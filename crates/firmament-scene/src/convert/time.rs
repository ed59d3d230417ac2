//! `[time]` with a real date: ISO 8601 parsing, the scene's moment, and the real sun over the
//! scene's place (`[planet]`'s latitude and longitude) by NREL's SPA.
//!
//! # A scene's moment
//! Without `time.date_time` a scene has only a local solar time of day (`time.time_of_day`, or the
//! caller's). With it, a moment is that instant; asking for another time of day keeps its date
//! and clock offset and changes the clock time. The time of day that spins objects is the
//! instant's clock time; the gradient sky's keyframes read local apparent solar time (from the
//! real sun's hour angle) or, with `sky.gradient.by = "sun-elevation"`, the time at which
//! `[sun]`'s path has the real sun's elevation.

use chrono::format::{ParseError, ParseErrorKind};
use chrono::{DateTime, Datelike, NaiveDateTime, Timelike};
use firmament_core::TimeOfDay;
use firmament_core::astro::spa::{self, SolarPosition, SpaInput};
use firmament_core::astro::{CivilDateTime, Instant};

use crate::checks::{check, time_of_day};
use crate::error::SceneError;
use crate::model::{Body, Scene};

/// The forms [`parse_date_time`] takes after a trailing `Z` became `+00:00`, with an offset.
const WITH_OFFSET: [&str; 2] = ["%Y-%m-%dT%H:%M:%S%.f%#z", "%Y-%m-%dT%H:%M%#z"];

/// The forms [`parse_date_time`] takes without an offset (UTC).
const WITHOUT_OFFSET: [&str; 2] = ["%Y-%m-%dT%H:%M:%S%.f", "%Y-%m-%dT%H:%M"];

/// An ISO 8601 date and time: `2003-10-17T12:30:30-07:00`, `2003-10-17T19:30:30Z`, or
/// `2003-10-17T19:30:30` (no offset: UTC); seconds and their fraction may be left out, the offset
/// may be `±HH:MM`, `±HHMM` or `±HH`. The result keeps the offset, so that a caller can answer on
/// the same clock.
///
/// # Errors
/// A message saying what form was expected, or that the date or time does not exist.
pub fn parse_date_time(text: &str) -> Result<CivilDateTime, String> {
    let trimmed = text.trim();
    let zulu = trimmed.strip_suffix(['Z', 'z']).map(|t| format!("{t}+00:00"));
    let candidate = zulu.as_deref().unwrap_or(trimmed);
    let parsed = WITH_OFFSET
        .iter()
        .find_map(|f| DateTime::parse_from_str(candidate, f).ok())
        .map(|dt| (dt.naive_local(), dt.offset().local_minus_utc()))
        .or_else(|| {
            WITHOUT_OFFSET
                .iter()
                .find_map(|f| NaiveDateTime::parse_from_str(candidate, f).ok())
                .map(|naive| (naive, 0))
        });
    let Some((naive, offset_seconds)) = parsed else {
        // Say when the form was right but the date or time does not exist (month 13, Feb 30).
        let impossible = |e: ParseError| matches!(e.kind(), ParseErrorKind::OutOfRange | ParseErrorKind::Impossible);
        let out_of_range = WITH_OFFSET
            .iter()
            .filter_map(|f| DateTime::parse_from_str(candidate, f).err())
            .chain(
                WITHOUT_OFFSET
                    .iter()
                    .filter_map(|f| NaiveDateTime::parse_from_str(candidate, f).err()),
            )
            .any(impossible);
        let reason = if out_of_range { " (no such date or time)" } else { "" };
        return Err(format!(
            "`{text}` is not an ISO 8601 date and time{reason}: expected e.g. 2003-10-17T12:30:30-07:00, \
             2003-10-17T19:30:30Z, or 2003-10-17T19:30:30 for UTC"
        ));
    };
    let civil = from_naive(naive, f64::from(offset_seconds) / 3600.0);
    civil.validate().map_err(|e| format!("`{text}`: {e}"))?;
    Ok(civil)
}

/// chrono's date and clock time as a [`CivilDateTime`] on a clock `offset_hours` from UTC.
fn from_naive(naive: NaiveDateTime, offset_hours: f64) -> CivilDateTime {
    let (date, clock) = (naive.date(), naive.time());
    CivilDateTime {
        year: date.year(),
        month: date.month(),
        day: date.day(),
        hour: clock.hour(),
        minute: clock.minute(),
        // chrono keeps a leap second as nanoseconds past 1e9.
        second: f64::from(clock.second()) + f64::from(clock.nanosecond()) / 1e9,
        offset_hours,
    }
}

/// `civil` moved by `seconds` (negative: earlier), on the same clock offset: the date, hour and
/// minute carry (`23:59:30` plus 45 s is `00:00:15` the next day). The date arithmetic is the
/// proleptic Gregorian calendar's (chrono's); the result is rounded to the nanosecond. A `civil`
/// whose year and month chrono cannot represent, or a result outside chrono's range, comes back
/// unchanged (every date [`parse_date_time`] accepts is far inside it).
pub fn add_seconds(civil: &CivilDateTime, seconds: f64) -> CivilDateTime {
    let moved = || -> Option<CivilDateTime> {
        // From the first of the month, so that any day, hour, minute or second (a leap second's
        // 60.x included) carries instead of failing.
        let start = chrono::NaiveDate::from_ymd_opt(civil.year, civil.month, 1)?.and_hms_opt(0, 0, 0)?;
        let total = f64::from(civil.day.checked_sub(1)?) * 86_400.0
            + f64::from(civil.hour) * 3600.0
            + f64::from(civil.minute) * 60.0
            + civil.second
            + seconds;
        if !total.is_finite() {
            return None;
        }
        let whole = total.floor();
        let nanos = ((total - whole) * 1e9).round();
        // |whole| beyond ~1.5e16 s is beyond chrono's dates anyway; the cast saturates.
        let delta =
            chrono::TimeDelta::try_seconds(whole as i64)?.checked_add(&chrono::TimeDelta::nanoseconds(nanos as i64))?;
        Some(from_naive(start.checked_add_signed(delta)?, civil.offset_hours))
    };
    moved().unwrap_or(*civil)
}

/// The time of day on `civil`'s own clock.
pub(crate) fn clock_time(civil: &CivilDateTime) -> TimeOfDay {
    let seconds = f64::from(civil.hour) * 3600.0 + f64::from(civil.minute) * 60.0 + civil.second;
    TimeOfDay::from_seconds(seconds).unwrap_or(TimeOfDay::MIDNIGHT)
}

/// `civil` with its clock time replaced by `time` (same date and offset).
fn at_clock_time(civil: &CivilDateTime, time: TimeOfDay) -> CivilDateTime {
    let seconds = time.seconds();
    let hour = (seconds / 3600.0).floor();
    let minute = ((seconds - hour * 3600.0) / 60.0).floor();
    CivilDateTime {
        hour: hour as u32,
        minute: minute as u32,
        second: seconds - hour * 3600.0 - minute * 60.0,
        ..*civil
    }
}

/// When a frame is: a time of day, and the instant when the scene has a date.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Moment {
    /// The clock time of day (spins objects; the gradient's keyframes without a date).
    pub(crate) clock: TimeOfDay,
    /// The instant, when the scene has `time.date_time` (or the caller gave one).
    pub(crate) instant: Option<Instant>,
}

impl Scene {
    /// `time.date_time`, parsed, or `None` when the scene has no date.
    pub fn date_time(&self) -> Result<Option<CivilDateTime>, SceneError> {
        let Some(text) = &self.time.date_time else {
            return Ok(None);
        };
        parse_date_time(text)
            .map(Some)
            .map_err(|rule| SceneError::invalid("time.date_time", format!("{text:?}"), rule))
    }

    /// The instant of a civil date and time with the scene's `time.delta_t`.
    pub(crate) fn instant(&self, civil: &CivilDateTime) -> Result<Instant, SceneError> {
        Instant::from_civil(civil, self.time.delta_t)
            .map_err(|e| SceneError::invalid("time.date_time", format!("{civil:?}"), e.to_string()))
    }

    /// The moment of a frame at `time` (the scene's own when `None`): see the module docs.
    pub(crate) fn moment(&self, time: Option<TimeOfDay>) -> Result<Moment, SceneError> {
        match (self.date_time()?, time) {
            (None, Some(clock)) => Ok(Moment { clock, instant: None }),
            (None, None) => Ok(Moment {
                clock: self.time_of_day()?,
                instant: None,
            }),
            (Some(civil), time) => {
                let civil = time.map_or(civil, |t| at_clock_time(&civil, t));
                self.moment_at(&civil)
            }
        }
    }

    /// The moment of a civil date and time, whether or not the scene has a date.
    pub(crate) fn moment_at(&self, civil: &CivilDateTime) -> Result<Moment, SceneError> {
        Ok(Moment {
            clock: clock_time(civil),
            instant: Some(self.instant(civil)?),
        })
    }

    /// The observer of the real sky at `instant`: `[planet]`'s latitude and longitude, the
    /// camera's height, air of `time.pressure` and `time.temperature`.
    pub(crate) fn spa_input(&self, instant: &Instant) -> SpaInput {
        SpaInput {
            elevation_m: self.camera.position[2].clamp(0.0, 1.0e7),
            pressure_mbar: self.time.pressure,
            temperature_c: self.time.temperature,
            ..SpaInput::new(*instant, self.planet.latitude_deg, self.planet.longitude_deg)
        }
    }

    /// The real sun at `instant` over `[planet]`'s latitude and longitude, from the camera's
    /// height, through air of `time.pressure` and `time.temperature`.
    pub(crate) fn real_sun(&self, instant: &Instant) -> Result<SolarPosition, SceneError> {
        check(
            self.planet.body == Body::Earth,
            "planet.body",
            format!("\"{}\"", self.planet.body.name()),
            "a real date places Earth's sun (NREL SPA); there is no ephemeris for other bodies here",
        )?;
        let input = self.spa_input(instant);
        input.validate().map_err(|e| match e {
            firmament_core::CoreError::Invalid { field, value, rule } => {
                let key = match field {
                    "latitude" => "planet.latitude",
                    "longitude" => "planet.longitude",
                    "pressure" => "time.pressure",
                    "temperature" => "time.temperature",
                    "elevation" => "camera.position",
                    "delta_t" => "time.delta_t",
                    other => other,
                };
                SceneError::invalid(key, value, rule)
            }
            other => SceneError::invalid("time", "[time]", other.to_string()),
        })?;
        Ok(spa::solar_position(&input))
    }
}

/// Checks `[time]`'s values (the date, the air, the star limit) without building a frame.
pub(crate) fn validate(scene: &Scene) -> Result<(), SceneError> {
    let t = &scene.time;
    time_of_day("time.time_of_day", &t.time_of_day)?;
    check(
        t.pressure.is_finite() && t.pressure > 0.0 && t.pressure <= 5000.0,
        "time.pressure",
        t.pressure,
        "must be in (0, 5000] millibars",
    )?;
    check(
        t.temperature.is_finite() && t.temperature > -273.0 && t.temperature < 6000.0,
        "time.temperature",
        t.temperature,
        "must be in (-273, 6000) degrees C",
    )?;
    check(
        t.star_limit.is_finite() && t.star_limit <= 6.5,
        "time.star_limit",
        t.star_limit,
        "must be a visual magnitude <= 6.5 (the catalogue's faintest)",
    )?;
    if let Some(dt) = t.delta_t {
        check(
            dt.is_finite() && dt.abs() <= 10_000.0,
            "time.delta_t",
            dt,
            "must be finite seconds within ±10000",
        )?;
    }
    if let Some(civil) = scene.date_time()? {
        let instant = scene.instant(&civil)?;
        scene.real_sun(&instant)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_8601_with_an_offset_z_or_nothing() {
        let local = parse_date_time("2003-10-17T12:30:30-07:00").expect("parses");
        assert_eq!(local, CivilDateTime::utc(2003, 10, 17, 12, 30, 30.0).with_offset(-7.0));
        let z = parse_date_time("2003-10-17T19:30:30Z").expect("parses");
        let bare = parse_date_time("2003-10-17T19:30:30").expect("parses");
        assert_eq!(z, CivilDateTime::utc(2003, 10, 17, 19, 30, 30.0));
        assert_eq!(bare, z);
        assert!((local.julian_date() - z.julian_date()).abs() < 1e-9);
        let short = parse_date_time("2024-06-21T06:15+0530").expect("parses");
        assert_eq!(short, CivilDateTime::utc(2024, 6, 21, 6, 15, 0.0).with_offset(5.5));
        let fraction = parse_date_time("2024-06-21T06:15:01.25+02").expect("parses");
        assert_eq!(fraction.second, 1.25);
        assert_eq!(fraction.offset_hours, 2.0);
    }

    #[test]
    fn bad_dates_say_why() {
        for text in [
            "yesterday",
            "2003-13-01T00:00:00",
            "2023-02-29T12:00:00Z",
            "2003-10-17",
            "",
        ] {
            let message = parse_date_time(text).expect_err(text);
            assert!(message.contains("ISO 8601"), "{text}: {message}");
        }
        let message = parse_date_time("2003-10-17T12:00:00+19:00").expect_err("offset");
        assert!(message.contains("offset_hours"), "{message}");
    }

    #[test]
    fn add_seconds_carries_across_midnight_months_and_years_on_the_same_clock() {
        let c = parse_date_time("2024-12-31T23:59:30-05:00").expect("valid");
        let moved = add_seconds(&c, 45.25);
        assert_eq!((moved.year, moved.month, moved.day), (2025, 1, 1));
        assert_eq!((moved.hour, moved.minute, moved.offset_hours), (0, 0, -5.0));
        assert!((moved.second - 15.25).abs() < 1e-9, "{moved:?}");
        let back = add_seconds(&moved, -45.25);
        assert_eq!(
            (back.year, back.month, back.day, back.hour, back.minute),
            (2024, 12, 31, 23, 59)
        );
        assert!((back.second - 30.0).abs() < 1e-9, "{back:?}");
        // A leap day, and a whole day from a leap second.
        let leap = add_seconds(&parse_date_time("2024-02-28T12:00:00Z").expect("valid"), 86_400.0);
        assert_eq!((leap.month, leap.day, leap.hour), (2, 29, 12));
        let from_leap_second = CivilDateTime::utc(2016, 12, 31, 23, 59, 60.5);
        let next = add_seconds(&from_leap_second, 0.0);
        assert_eq!(
            (next.year, next.month, next.day, next.hour, next.minute),
            (2017, 1, 1, 0, 0)
        );
        assert!((next.second - 0.5).abs() < 1e-9);
        // The instant moves by exactly the seconds asked for.
        let far = add_seconds(&c, 1.0e6);
        assert!(((far.julian_date() - c.julian_date()) * 86_400.0 - 1.0e6).abs() < 1e-3);
        assert_eq!(add_seconds(&c, f64::NAN), c);
    }

    #[test]
    fn a_new_clock_time_keeps_the_date() {
        let c = parse_date_time("2024-06-21T22:00:00+02:00").expect("valid");
        let t = TimeOfDay::from_hours(5.5 + 1.0 / 3600.0).expect("finite");
        let moved = at_clock_time(&c, t);
        assert_eq!(
            (moved.day, moved.hour, moved.minute, moved.offset_hours),
            (21, 5, 30, 2.0)
        );
        assert!((moved.second - 1.0).abs() < 1e-6);
        assert!((clock_time(&moved).seconds() - t.seconds()).abs() < 1e-6);
    }
}
