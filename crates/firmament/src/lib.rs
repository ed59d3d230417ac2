//! The `firmament` command as a library: [`main`] runs it on the process's arguments, and
//! [`json_report`] runs a reporting command (`sun`, `sky-sample`) on given arguments and returns
//! what it prints with `--json`, for bindings (the Python package) that want the command's values,
//! checks and messages without a process. Everything else is the command's own (`pub(crate)`).

mod cli;
mod commands;
mod limits;
mod output;
mod time_limit;
mod untrusted;

use std::process::ExitCode;

use clap::Parser;

/// Runs the command line the process was given; the process's exit status.
pub fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    init_logging(cli.quiet);
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // One clear message: the outermost context first, then each cause.
            eprintln!("error: {}", shorten_lines(&format!("{error:#}")));
            ExitCode::FAILURE
        }
    }
}

/// The longest line an error message prints: a hostile input echoed back (a TOML parser's
/// snippet of a megabyte-long line, a value of a million characters) keeps its start and end.
const MAX_LINE_CHARS: usize = 400;

/// `text` with every line over [`MAX_LINE_CHARS`] cut in the middle, saying how much was left out.
fn shorten_lines(text: &str) -> String {
    let keep = MAX_LINE_CHARS / 2;
    text.split('\n')
        .map(|line| {
            let count = line.chars().count();
            if count <= MAX_LINE_CHARS {
                return line.to_owned();
            }
            let head: String = line.chars().take(keep).collect();
            let tail: String = line.chars().skip(count - keep).collect();
            format!("{head} … ({} characters left out) … {tail}", count - 2 * keep)
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn init_logging(quiet: bool) {
    let from_env = tracing_subscriber::EnvFilter::try_from_env("FIRMAMENT_LOG").ok();
    let explicit = from_env.is_some();
    let filter = from_env.unwrap_or_else(|| {
        tracing_subscriber::EnvFilter::new(if quiet {
            "error"
        } else {
            // winit warns about harmless quirks of virtual displays (no XSETTINGS, a 0 mm screen),
            // egui-wgpu about an sRGB window (the viewer's choice on GL, where views can't differ).
            "warn,winit=error,egui_wgpu=error,firmament=info,firmament_render=info"
        })
    });
    let subscriber = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_target(false)
        .finish();
    // Logging is a convenience: if another logger is already installed, keep going without ours.
    let _ = tracing::subscriber::set_global_default(subscriber);
    // wgpu logs through `log`. Its hal layer reports failed probes of backends it then skips
    // (an EGL platform without a driver) as errors, which alarm users for nothing: firmament
    // reports a real failure to find an adapter itself. FIRMAMENT_LOG shows everything.
    let mut bridge = tracing_log::LogTracer::builder();
    if !explicit {
        bridge = bridge.ignore_crate("wgpu_hal");
    }
    let _ = bridge.init();
}

/// Runs `args` (a command and its flags, without the program's name: `["sun", "--time", …]`)
/// as the command line would, for the commands that report values (`sun`, `sky-sample`), and
/// returns what `--json` makes them print.
///
/// # Errors
/// The message the command line would print (without `error: `): a bad flag or value (clap's
/// own message), a bad scene, or a failure, naming the flag, key or rule.
pub fn json_report(args: &[String]) -> Result<serde_json::Value, String> {
    let argv = std::iter::once("firmament".to_owned()).chain(args.iter().cloned());
    let cli = cli::Cli::try_parse_from(argv).map_err(|e| e.to_string().trim_end().to_owned())?;
    commands::json_report(&cli.command).map_err(|e| format!("{e:#}"))
}

/// Fails unless a `width` × `height` GPU render fits the pixel limit (`FIRMAMENT_MAX_PIXELS`,
/// default 8192²) and the memory free now, with the command line's message.
///
/// # Errors
/// The message naming the size, the limit and how to raise it.
pub fn check_render_pixels(width: u32, height: u32) -> Result<(), String> {
    limits::check_pixels("the image", width, height).map_err(|e| format!("{e:#}"))
}
