//! `--time-limit`: a watchdog thread that stops the command once its wall time is up, with exit
//! status [`EXIT_TIME_LIMIT`], leaving nothing partial (`output::abandon_and_exit` removes the
//! temporary files being written; every file renamed into place before is whole).

use std::time::Duration;

/// Exit status at the time limit: 124, as `timeout(1)` reports it.
pub(crate) const EXIT_TIME_LIMIT: i32 = 124;

/// Starts the watchdog: after `seconds` of wall time the process stops, whatever it is doing.
pub(crate) fn start(seconds: f64) {
    let limit = Duration::from_secs_f64(seconds);
    let spawned = std::thread::Builder::new()
        .name("time-limit".to_owned())
        .spawn(move || {
            std::thread::sleep(limit);
            crate::output::abandon_and_exit(
                &format!("error: stopped at the time limit of {seconds} s (--time-limit): nothing partial was written"),
                EXIT_TIME_LIMIT,
            );
        });
    if let Err(error) = spawned {
        // Without the watchdog the command would run unbounded: better not to run it.
        eprintln!("error: cannot start the --time-limit watchdog: {error}");
        std::process::exit(1);
    }
}
