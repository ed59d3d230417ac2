//! End-to-end tests of `firmament sun`: the SPA paper's example as text and JSON, polar days and
//! nights, and one clear message with exit status 2 for each bad argument.

use std::process::{Command, Output};

/// The paper's example (Reda & Andreas 2004, Table A5.1): Golden, Colorado.
const PAPER: [&str; 14] = [
    "sun",
    "--time",
    "2003-10-17T12:30:30-07:00",
    "--lat",
    "39.742476",
    "--lon",
    "-105.1786",
    "--elevation",
    "1830.14",
    "--pressure",
    "820",
    "--temperature",
    "11",
    "--delta-t=67",
];

fn firmament(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_firmament"))
        .args(args)
        .env_remove("FIRMAMENT_LOG")
        .output()
        .expect("the firmament binary runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = firmament(&[args, &["--json"]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("JSON")
}

#[test]
fn the_papers_example_as_text() {
    let out = firmament(&PAPER);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for expected in [
        "50.11162°  refracted",
        "50.12795°  geometric",
        "194.34024°",
        "-9.31434°",
        "14.64151 min",
        "sunrise           06:12:43",
        "solar noon        11:46:04",
        "sunset            17:20:19",
        "UTC-07:00",
    ] {
        assert!(text.contains(expected), "`{expected}` missing from\n{text}");
    }
}

#[test]
fn the_papers_example_as_json() {
    let v = json(&PAPER);
    let number = |key: &str| v[key].as_f64().unwrap_or_else(|| panic!("{key} missing from {v}"));
    let near = |key: &str, want: f64, tolerance: f64| {
        let got = number(key);
        assert!((got - want).abs() <= tolerance, "{key}: {got}, expected {want}");
    };
    near("julian_date", 2_452_930.312_847, 5e-7);
    near("zenith_deg", 50.111_622, 5e-7);
    near("zenith_no_refraction_deg", 50.127_954, 5e-7);
    near("azimuth_deg", 194.340_241, 5e-7);
    near("declination_deg", -9.314_34, 5e-6);
    near("right_ascension_deg", 202.227_41, 5e-6);
    near("equation_of_time_min", 14.641_503, 1e-5);
    near("utc_offset_hours", -7.0, 0.0);
    assert_eq!(v["time"], "2003-10-17T12:30:30-07:00");
    assert_eq!(v["day"], "rise_and_set");
    assert_eq!(v["sunrise"], "06:12:43");
    assert_eq!(v["solar_noon"], "11:46:04");
    assert_eq!(v["sunset"], "17:20:19");
}

#[test]
fn utc_with_z_or_without_offset_is_the_same_instant() {
    let at = |time: &str| {
        json(&[
            "sun",
            "--time",
            time,
            "--lat",
            "39.742476",
            "--lon",
            "-105.1786",
            "--delta-t",
            "67",
        ])
    };
    let local = at("2003-10-17T12:30:30-07:00");
    let zulu = at("2003-10-17T19:30:30Z");
    let bare = at("2003-10-17T19:30:30");
    assert_eq!(zulu["julian_date"], local["julian_date"]);
    assert_eq!(bare["zenith_deg"], zulu["zenith_deg"]);
    assert_eq!(zulu["utc_offset_hours"], 0.0);
    // The same day's events, on the UTC clock: 06:12:43 at −7 h is 13:12:43 UTC.
    assert_eq!(zulu["sunrise"], "13:12:43");
}

#[test]
fn polar_day_and_night_say_so() {
    let svalbard = |time: &str| firmament(&["sun", "--time", time, "--lat", "78.22", "--lon", "15.65"]);
    let summer = svalbard("2024-06-21T12:00:00+02:00");
    assert!(summer.status.success(), "{}", stderr(&summer));
    assert!(
        stdout(&summer).contains("sunrise           none (polar day)"),
        "{}",
        stdout(&summer)
    );
    let winter = svalbard("2024-12-21T12:00:00+01:00");
    assert!(
        stdout(&winter).contains("sunset            none (polar night)"),
        "{}",
        stdout(&winter)
    );
    let v = json(&[
        "sun",
        "--time",
        "2024-12-21T12:00:00+01:00",
        "--lat",
        "78.22",
        "--lon",
        "15.65",
    ]);
    assert_eq!(v["day"], "polar_night");
    assert!(v["sunrise"].is_null() && v["sunset"].is_null());
    assert!(v["solar_noon_elevation_deg"].as_f64().is_some_and(|e| e < -10.0), "{v}");
}

#[test]
fn every_bad_argument_names_the_flag_and_the_rule() {
    let place = ["--lat", "0", "--lon", "0"];
    let cases: &[(&[&str], &str)] = &[
        (
            &["--time", "yesterday"],
            "invalid value 'yesterday' for '--time <ISO8601>': `yesterday` is not an ISO 8601 date and time",
        ),
        (
            &["--time", "2023-02-29T12:00:00Z"],
            "is not an ISO 8601 date and time (no such date or time)",
        ),
        (
            &["--time", "2024-01-01T00:00:00+19:00"],
            "offset_hours = 19: must be in [-18, 18]",
        ),
        (
            &["--time", "7000-01-01T00:00:00Z"],
            "must lie in the years -2000 to 6000",
        ),
        (
            &["--lat", "90.5"],
            "invalid value '90.5' for '--lat <DEG>': must be in [-90, 90] degrees",
        ),
        (
            &["--lat", "NaN"],
            "invalid value 'NaN' for '--lat <DEG>': must be in [-90, 90] degrees",
        ),
        (
            &["--lat", "north"],
            "invalid value 'north' for '--lat <DEG>': `north` is not a number",
        ),
        (
            &["--lon", "-180.5"],
            "invalid value '-180.5' for '--lon <DEG>': must be in [-180, 180] degrees",
        ),
        (&["--lon", "inf"], "'--lon <DEG>': must be in [-180, 180] degrees"),
        (&["--elevation", "NaN"], "'--elevation <M>': must be finite"),
        (
            &["--pressure", "0"],
            "invalid value '0' for '--pressure <MBAR>': must be in (0, 5000] mbar",
        ),
        (
            &["--pressure", "-1013"],
            "'--pressure <MBAR>': must be in (0, 5000] mbar",
        ),
        (
            &["--temperature", "-300"],
            "'--temperature <C>': must be in (-273, 6000] °C",
        ),
        (&["--delta-t", "1e6"], "'--delta-t <S>': must be finite, within ±8000 s"),
    ];
    for (args, expected) in cases {
        // The case's own flags come first; clap takes the first of a repeated flag as an error,
        // so the defaults fill in only the flags the case leaves out.
        let mut full = vec!["sun"];
        full.extend_from_slice(args);
        if !args.contains(&"--time") {
            full.extend_from_slice(&["--time", "2024-01-01T00:00:00Z"]);
        }
        for pair in place.chunks(2) {
            if !args.contains(&pair[0]) {
                full.extend_from_slice(pair);
            }
        }
        let out = firmament(&full);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{full:?}: {err}");
        assert!(
            err.contains(expected),
            "{full:?}\n  got:      {err}\n  expected: {expected}"
        );
        assert!(!err.contains("panicked"), "{full:?} panicked: {err}");
        assert!(stdout(&out).is_empty(), "{full:?} printed {}", stdout(&out));
    }
    let out = firmament(&["sun", "--lat", "0", "--lon", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--time <ISO8601>"), "{}", stderr(&out));
}

/// Dallas City Hall on 2024-04-08: the total eclipse's local circumstances on the clock of
/// `--time`, against NASA's (totality 13:40:43 to 13:44:34 CDT, partial 12:23 to 15:02).
#[test]
fn a_solar_eclipse_prints_its_local_circumstances() {
    let args = [
        "sun",
        "--time",
        "2024-04-08T13:42:00-05:00",
        "--lat",
        "32.7763",
        "--lon",
        "-96.7969",
        "--elevation",
        "140",
    ];
    let out = firmament(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("solar eclipse here, total"), "{text}");
    assert!(text.contains("totality         13:40:4"), "{text}");
    assert!(text.contains("to 13:44:3"), "{text}");
    let report = json(&args);
    let eclipse = &report["solar_eclipse"];
    assert_eq!(eclipse["kind"], "total");
    let duration = eclipse["central_duration_s"].as_f64().expect("a duration");
    assert!((duration - 231.0).abs() < 5.0, "{duration}");
    assert!(
        eclipse["first_contact"]
            .as_str()
            .is_some_and(|t| t.starts_with("12:23"))
    );
    // A week later, none.
    let later = json(&[
        "sun",
        "--time",
        "2024-04-15T13:42:00-05:00",
        "--lat",
        "32.7763",
        "--lon",
        "-96.7969",
    ]);
    assert!(later["solar_eclipse"].is_null());
}
