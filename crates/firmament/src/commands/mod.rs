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

/// Runs a parsed command.
pub(crate) fn run(command: Command) -> Result<()> {
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
