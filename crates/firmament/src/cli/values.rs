//! Value parsers for clap: each checks a flag's value by the rule the library applies to it, so a
//! bad value is refused with that rule before any command runs.

use firmament_core::CoreError;
use firmament_core::astro::spa::SpaInput;
use firmament_core::astro::time::J2000;
use firmament_core::astro::{CivilDateTime, Instant};

/// The most frames one time-lapse may have.
pub(crate) const MAX_FRAMES: u32 = 100_000;

/// Checks one value by SPA's own rules ([`SpaInput::validate`]): `set` puts it into an input
/// that is otherwise valid. The error is the rule it breaks, which clap prints after the flag and
/// the value.
fn check(set: impl FnOnce(&mut SpaInput)) -> Result<(), String> {
    let mut input = SpaInput::new(Instant::from_jd(J2000), 0.0, 0.0);
    set(&mut input);
    input.validate().map_err(|e| match e {
        CoreError::Invalid { rule, .. } => rule.to_owned(),
        other => other.to_string(),
    })
}

/// A number, as clap's value parsers want it.
fn number(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{text}` is not a number"))
}

/// `--time`: ISO 8601, within SPA's years −2000 to 6000.
pub(crate) fn spa_time(text: &str) -> Result<CivilDateTime, String> {
    let civil = firmament_scene::parse_date_time(text)?;
    check(|input| input.instant.jd = civil.julian_date())?;
    Ok(civil)
}

/// `--lat`: degrees, [−90, 90].
pub(crate) fn latitude(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.latitude_deg = v).map(|()| v)
}

/// `--lon`: degrees, [−180, 180].
pub(crate) fn longitude(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.longitude_deg = v).map(|()| v)
}

/// `--elevation`: metres, finite.
pub(crate) fn elevation(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.elevation_m = v).map(|()| v)
}

/// `--pressure`: millibars, (0, 5000].
pub(crate) fn pressure(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.pressure_mbar = v).map(|()| v)
}

/// `--temperature`: °C, (−273, 6000].
pub(crate) fn temperature(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.temperature_c = v).map(|()| v)
}

/// `--delta-t`: seconds, within ±8000.
pub(crate) fn delta_t(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    check(|input| input.instant.delta_t = v).map(|()| v)
}

/// `--from` and `--to`: ISO 8601 (see [`firmament_scene::parse_date_time`]), within the years the
/// sun's ephemeris (NREL SPA) covers.
pub(crate) fn date_time(text: &str) -> Result<CivilDateTime, String> {
    let civil = firmament_scene::parse_date_time(text)?;
    let instant = Instant::from_civil(&civil, None).map_err(|e| format!("`{text}`: {e}"))?;
    SpaInput::new(instant, 0.0, 0.0)
        .validate()
        .map_err(|e| format!("`{text}`: {e}"))?;
    Ok(civil)
}

/// `--frames`: 1 to [`MAX_FRAMES`].
/// `--shard I/N`: shard `I` of `N`, 1 <= I <= N <= [`MAX_FRAMES`].
pub(crate) fn shard(text: &str) -> Result<(u32, u32), String> {
    let rule = || format!("must be I/N, shard I of N, with 1 <= I <= N <= {MAX_FRAMES} (e.g. 3/8)");
    let (i, n) = text.split_once('/').ok_or_else(rule)?;
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| rule());
    let (i, n) = (number(i)?, number(n)?);
    if i >= 1 && i <= n && n <= MAX_FRAMES {
        Ok((i, n))
    } else {
        Err(rule())
    }
}

pub(crate) fn frame_count(text: &str) -> Result<u32, String> {
    let rule = format!(
        "must be a whole number of frames from 1 to {MAX_FRAMES} (a fixed limit: for more, split the span over \
         several runs, each with its own --from, --to and output folder)"
    );
    match text.trim().parse::<u64>() {
        Ok(n) if (1..=u64::from(MAX_FRAMES)).contains(&n) => Ok(n as u32),
        _ => Err(rule),
    }
}

/// `envmap --width`: an even number of pixels from 4 to 16384 (the height is half of it).
pub(crate) fn equirect_width(text: &str) -> Result<u32, String> {
    match text.trim().parse::<u32>() {
        Ok(n) if (4..=16_384).contains(&n) && n.is_multiple_of(2) => Ok(n),
        _ => Err("must be an even number of pixels from 4 to 16384 (the height is half of it)".to_owned()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equirect_widths_are_even_and_bounded() {
        assert_eq!(equirect_width("2048"), Ok(2048));
        assert_eq!(equirect_width("4"), Ok(4));
        for bad in ["2", "2047", "16386", "-4", "wide", ""] {
            assert!(equirect_width(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn time_lapse_arguments_are_checked() {
        assert!(frame_count("0").is_err());
        assert!(frame_count("100001").is_err());
        assert!(frame_count("-1").is_err());
        assert_eq!(frame_count("100000"), Ok(100_000));
        assert_eq!(shard("3/8"), Ok((3, 8)));
        for bad in ["0/4", "5/4", "1/0", "2", "a/b", "1/100001"] {
            assert!(shard(bad).is_err(), "{bad}");
        }
        assert!(date_time("2024-13-01T00:00Z").is_err());
        assert!(date_time("7000-01-01T00:00Z").is_err(), "beyond SPA's years");
    }
}
