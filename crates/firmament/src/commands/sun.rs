//! `firmament sun`: the sun's position by NREL's SPA for a date, time and place, that day's
//! sunrise, solar noon and sunset, and a solar eclipse seen there within three hours of the time
//! (its local circumstances: `firmament_core::astro::eclipse`).

use anyhow::{Context, Result};
use firmament_core::astro::Instant;
use firmament_core::astro::eclipse::{LocalCircumstances, local_circumstances};
use firmament_core::astro::spa::{self, RiseSet, SpaInput};
use firmament_core::astro::time::format_offset;

use crate::cli::SunArgs;

/// `HH:MM:SS` of local hours in [0, 24), truncated to the second as NREL's `spa_tester.c`
/// prints its times.
fn format_hours(hours: f64) -> String {
    let seconds = (hours * 3600.0).floor().clamp(0.0, 86_399.0) as u32;
    format!("{:02}:{:02}:{:02}", seconds / 3600, seconds / 60 % 60, seconds % 60)
}

/// An instant's time of day on the clock `offset_hours` from UT, `HH:MM:SS.S`.
fn format_clock(instant: &Instant, offset_hours: f64) -> String {
    let seconds = ((instant.jd + 0.5 + offset_hours / 24.0).fract() * 86_400.0).clamp(0.0, 86_399.9);
    let whole = seconds.floor() as u32;
    format!(
        "{:02}:{:02}:{:04.1}",
        whole / 3600,
        whole / 60 % 60,
        seconds - f64::from(whole / 60 * 60)
    )
}

/// How far from `--time` a solar eclipse's maximum is looked for, hours.
const ECLIPSE_SEARCH_HOURS: f64 = 3.0;

/// The sun's position, the day's events and any solar eclipse for `args`.
struct Report {
    instant: Instant,
    position: spa::SolarPosition,
    times: spa::SunTimes,
    eclipse: Option<LocalCircumstances>,
}

impl Report {
    fn of(args: &SunArgs) -> Result<Self> {
        let instant = Instant::from_civil(&args.time, args.delta_t).context("invalid --time or --delta-t")?;
        let input = SpaInput {
            elevation_m: args.elevation,
            pressure_mbar: args.pressure,
            temperature_c: args.temperature,
            ..SpaInput::new(instant, args.lat, args.lon)
        };
        input.validate().context("invalid input for the sun's position")?;
        Ok(Self {
            instant,
            position: spa::solar_position(&input),
            times: spa::sun_times(&input, args.time.offset_hours),
            eclipse: local_circumstances(&instant, ECLIPSE_SEARCH_HOURS, args.lat, args.lon, args.elevation),
        })
    }
}

/// What `firmament sun --json` prints.
pub(crate) fn report_json(args: &SunArgs) -> Result<serde_json::Value> {
    let Report {
        instant,
        position: p,
        times,
        eclipse,
    } = Report::of(args)?;
    let clock = |i: &Instant| format_clock(i, args.time.offset_hours);
    let eclipse = eclipse.map(|e| {
        serde_json::json!({
            "kind": eclipse_kind(&e),
            "magnitude": e.at_maximum.magnitude(),
            "first_contact": clock(&e.first_contact),
            "second_contact": e.second_contact.as_ref().map(clock),
            "maximum": clock(&e.maximum),
            "third_contact": e.third_contact.as_ref().map(clock),
            "fourth_contact": clock(&e.fourth_contact),
            "central_duration_s": central_duration(&e),
        })
    });
    let day = match times.rise_set {
        RiseSet::RiseAndSet { .. } => "rise_and_set",
        RiseSet::PolarDay => "polar_day",
        RiseSet::PolarNight => "polar_night",
    };
    Ok(serde_json::json!({
        "time": args.time.to_string(),
        "julian_date": instant.jd,
        "delta_t_s": instant.delta_t,
        "latitude_deg": args.lat,
        "longitude_deg": args.lon,
        "elevation_m": args.elevation,
        "pressure_mbar": args.pressure,
        "temperature_c": args.temperature,
        "zenith_deg": p.zenith_deg,
        "zenith_no_refraction_deg": p.zenith_no_refraction_deg,
        "azimuth_deg": p.azimuth_deg,
        "elevation_deg": p.elevation_deg,
        "elevation_no_refraction_deg": p.elevation_no_refraction_deg,
        "declination_deg": p.geocentric.declination_deg,
        "right_ascension_deg": p.geocentric.right_ascension_deg,
        "hour_angle_deg": p.hour_angle_deg,
        "equation_of_time_min": p.equation_of_time_min,
        "utc_offset_hours": args.time.offset_hours,
        "day": day,
        "sunrise": times.sunrise_h().map(format_hours),
        "solar_noon": format_hours(times.transit_h),
        "sunset": times.sunset_h().map(format_hours),
        "sunrise_h": times.sunrise_h(),
        "solar_noon_h": times.transit_h,
        "sunset_h": times.sunset_h(),
        "solar_noon_elevation_deg": times.transit_elevation_deg,
        "solar_eclipse": eclipse,
    }))
}

/// "total", "annular" or "partial".
fn eclipse_kind(e: &LocalCircumstances) -> &'static str {
    match e.second_contact {
        None => "partial",
        Some(_) if e.at_maximum.moon_radius_umbral > e.at_maximum.sun_radius => "total",
        Some(_) => "annular",
    }
}

/// Seconds from second to third contact, if the eclipse is central here.
fn central_duration(e: &LocalCircumstances) -> Option<f64> {
    Some((e.third_contact?.jd - e.second_contact?.jd) * 86_400.0)
}

/// Computes and prints the sun's position and the day's events.
pub(crate) fn run(args: &SunArgs) -> Result<()> {
    if args.json {
        println!("{}", report_json(args)?);
        return Ok(());
    }
    let Report {
        instant,
        position: p,
        times,
        eclipse,
    } = Report::of(args)?;
    let time = args.time.to_string();
    let zone = match format_offset(args.time.offset_hours).as_str() {
        "Z" => "UTC".to_owned(),
        offset => format!("UTC{offset}"),
    };
    println!(
        "sun at {time}, latitude {}°, longitude {}°, {} m ({} mbar, {} °C, ΔT {:.1} s)",
        args.lat, args.lon, args.elevation, args.pressure, args.temperature, instant.delta_t
    );
    println!(
        "  zenith            {:>10.5}°  refracted   {:>10.5}°  geometric",
        p.zenith_deg, p.zenith_no_refraction_deg
    );
    println!(
        "  elevation         {:>10.5}°  refracted   {:>10.5}°  geometric",
        p.elevation_deg, p.elevation_no_refraction_deg
    );
    println!("  azimuth           {:>10.5}°  eastward from north", p.azimuth_deg);
    println!("  declination       {:>10.5}°", p.geocentric.declination_deg);
    println!("  right ascension   {:>10.5}°", p.geocentric.right_ascension_deg);
    println!("  hour angle        {:>10.5}°", p.hour_angle_deg);
    println!("  equation of time  {:>10.5} min", p.equation_of_time_min);
    let event = |hours: Option<f64>| match (hours, times.rise_set) {
        (Some(h), _) => format_hours(h),
        (None, RiseSet::PolarDay) => "none (polar day)".to_owned(),
        (None, _) => "none (polar night)".to_owned(),
    };
    println!("  sunrise           {}", event(times.sunrise_h()));
    println!(
        "  solar noon        {}  (elevation {:.2}°)",
        format_hours(times.transit_h),
        times.transit_elevation_deg
    );
    println!("  sunset            {}", event(times.sunset_h()));
    println!(
        "sunrise, solar noon and sunset on the clock of --time ({zone}); as in NREL's SPA, those of the UT day of its date"
    );
    if let Some(e) = eclipse {
        let clock = |i: &Instant| format_clock(i, args.time.offset_hours);
        let kind = eclipse_kind(&e);
        println!(
            "solar eclipse here, {kind}: magnitude {:.4} at {} (geometric contacts, NASA's radii)",
            e.at_maximum.magnitude(),
            clock(&e.maximum)
        );
        println!("  partial begins    {}", clock(&e.first_contact));
        if let (Some(second), Some(third), Some(seconds)) = (e.second_contact, e.third_contact, central_duration(&e)) {
            let phase = if kind == "total" { "totality" } else { "annularity" };
            println!(
                "  {phase:<16} {} to {}  ({} min {:.1} s)",
                clock(&second),
                clock(&third),
                (seconds / 60.0).floor(),
                seconds % 60.0
            );
        }
        println!("  partial ends      {}", clock(&e.fourth_contact));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use firmament_core::astro::CivilDateTime;

    #[test]
    fn times_print_on_the_given_clock() {
        let civil = CivilDateTime::utc(2003, 10, 17, 12, 30, 30.0).with_offset(-7.0);
        assert_eq!(civil.to_string(), "2003-10-17T12:30:30-07:00");
        assert_eq!(format_hours(11.768_045), "11:46:04");
        assert_eq!(format_hours(23.999_999_99), "23:59:59");
    }
}
