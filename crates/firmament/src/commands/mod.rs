//! One module per subcommand.

mod bench;
mod check;
mod completions;
mod envmap;
mod presets;
mod render;
mod scene_input;
mod sky_sample;
pub(crate) mod sun;
pub(crate) mod timelapse;
mod view;

use anyhow::Result;

use crate::cli::Command;

/// What a reporting command (`sun`, `sky-sample`) prints with `--json`, computed in-process
/// (without a time limit, which would end the process: `--time-limit` is refused).
pub(crate) fn json_report(command: &Command) -> Result<serde_json::Value> {
    if command.untrusted().is_some_and(|u| u.time_limit.is_some()) {
        anyhow::bail!("--time-limit stops the process: give it to the command line, not in-process");
    }
    match command {
        Command::Sun(args) => sun::report_json(args),
        Command::SkySample(args) => sky_sample::report_json(args),
        _ => anyhow::bail!("in-process reports are those of `sun` and `sky-sample`"),
    }
}

/// Runs a parsed command.
pub(crate) fn run(command: Command) -> Result<()> {
    if let Some(seconds) = command.untrusted().and_then(crate::untrusted::time_limit) {
        crate::time_limit::start(seconds);
    }
    match command {
        Command::Render(args) => render::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::SkySample(args) => sky_sample::run(&args),
        Command::Sun(args) => sun::run(&args),
        Command::Timelapse(args) => timelapse::run(&args),
        Command::Envmap(args) => envmap::run(&args),
        Command::View(args) => view::run(&args),
        Command::Completions(args) => completions::run_completions(&args),
        Command::Manpages(args) => completions::run_manpages(&args),
        Command::Presets => {
            presets::run();
            Ok(())
        }
    }
}
