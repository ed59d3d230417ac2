//! `firmament timelapse`: a scene rendered at `N` real instants from `--from` to `--to` (both
//! included), one PNG per frame in an output folder, then an animated GIF and a contact sheet
//! built from the frames on disk.
//!
//! Every file is written to a temporary file in the output folder and renamed, so only complete
//! frames ever exist. The GPU renders the next frame while the last one is read back, and frames
//! are encoded on every core (`pipeline.rs`). Ctrl-C (or SIGTERM) stops after the frames in
//! flight; a second run with the same arguments skips the frames already there and renders the
//! rest (`--overwrite` renders all). `--shard I/N` renders one block of the frames and
//! `--assemble DIR` finishes a sharded time-lapse (`shards.rs`).

mod animation;
mod contact_sheet;
mod frames;
mod pipeline;
mod shards;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant as WallClock;

use anyhow::{Context, Result, bail};
use clap::CommandFactory;
use firmament_core::astro::CivilDateTime;
use firmament_render::GpuContext;
use firmament_render::headless::{HeadlessRenderer, Readback, SubmittedFrame};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

use crate::cli::TimelapseArgs;
use pipeline::{EncodeJob, EncodeQueue};

/// The animated GIF's name in the output folder.
const GIF_NAME: &str = "timelapse.gif";

/// The contact sheet's name in the output folder.
const SHEET_NAME: &str = "contact_sheet.png";

/// Exit status after Ctrl-C or SIGTERM (128 + SIGINT, as shells report it).
const EXIT_INTERRUPTED: i32 = 130;

/// How a run ended without an error.
enum Outcome {
    /// Every frame, the GIF and the contact sheet are written.
    Done,
    /// Stopped by a signal; the message says what is kept and how to resume.
    Interrupted(String),
}

/// What one run renders: the arguments clap requires unless `--assemble` is given.
struct Plan<'a> {
    from: CivilDateTime,
    to: CivilDateTime,
    frames: u32,
    output: &'a Path,
}

impl<'a> Plan<'a> {
    fn of(args: &'a TimelapseArgs) -> Result<Self> {
        let missing = |flag: &str| anyhow::anyhow!("timelapse needs {flag} (or --assemble DIR)");
        Ok(Self {
            from: args.from.ok_or_else(|| missing("--from"))?,
            to: args.to.ok_or_else(|| missing("--to"))?,
            frames: args.frames.ok_or_else(|| missing("--frames"))?,
            output: args.output.as_deref().ok_or_else(|| missing("--output"))?,
        })
    }
}

/// Renders the time-lapse (or assembles a sharded one). Bad arguments exit with status 2 (like
/// clap's own), an interruption with 130; every other failure is an error (status 1).
pub(crate) fn run(args: &TimelapseArgs) -> Result<()> {
    let outcome = match &args.assemble {
        Some(dir) => assemble(dir)?,
        None => render(args)?,
    };
    match outcome {
        Outcome::Done => Ok(()),
        Outcome::Interrupted(message) => {
            // Everything is dropped (the progress bar cleared, no temporary file open) by now.
            eprintln!("{message}");
            std::process::exit(EXIT_INTERRUPTED);
        }
    }
}

/// Renders the frames of `args` (checked first: a bad span exits like clap's own errors).
fn render(args: &TimelapseArgs) -> Result<Outcome> {
    let plan = Plan::of(args)?;
    let span =
        time_span(&plan.from, &plan.to, plan.frames).unwrap_or_else(|message| argument_error("timelapse", message));
    render_all(args, &plan, span)
}

/// Exits with status 2 and clap's usage for `subcommand`, like clap's own argument errors.
pub(crate) fn argument_error(subcommand: &str, message: String) -> ! {
    let mut command = crate::cli::Cli::command();
    command.build();
    let error = match command.find_subcommand_mut(subcommand) {
        Some(sub) => sub.error(clap::error::ErrorKind::ArgumentConflict, message),
        None => command.error(clap::error::ErrorKind::ArgumentConflict, message),
    };
    error.exit()
}

/// `--assemble DIR`: the GIF and the contact sheet of the sharded time-lapse in `dir`, once
/// its manifest's frames are all there and whole.
fn assemble(dir: &Path) -> Result<Outcome> {
    let started = WallClock::now();
    let manifest = shards::read_manifest(dir)?.with_context(|| {
        format!(
            "--assemble {}: no {} there (a time-lapse's runs write it into their output folder)",
            dir.display(),
            shards::MANIFEST_NAME
        )
    })?;
    let n = manifest.frames;
    let pngs = png_paths(dir, n);
    let files = |k: u32| frame_files(dir, k, n, manifest.exr);
    let present: Vec<u32> = (0..n).filter(|&k| all_files(&files(k))).collect();
    let mut missing: Vec<u32> = (0..n).filter(|k| present.binary_search(k).is_err()).collect();
    missing.extend(incomplete_frames(&present, files, manifest.width, manifest.height)?);
    missing.sort_unstable();
    if let Some(&first) = missing.first() {
        bail!(
            "--assemble {}: {} of {n} frames are missing or incomplete (the first: {}); run the shards that \
             render them (again) first",
            dir.display(),
            missing.len(),
            frame_name(first, n, "png")
        );
    }
    // Every shard is done: temporary files left now are a killed run's.
    crate::output::remove_stale_temp_files(dir)?;
    let stop = install_stop_handler();
    write_summaries(
        dir,
        &pngs,
        manifest.fps,
        manifest.exr,
        &|| stop.load(Ordering::SeqCst),
        started,
    )
}

/// Seconds from `--from` to `--to`, checked: `--to` not before `--from`, and after it when more
/// than one of `frames` is asked for.
pub(crate) fn time_span(from: &CivilDateTime, to: &CivilDateTime, frames: u32) -> Result<f64, String> {
    let span = seconds_between(from, to);
    if span < 0.0 {
        return Err(format!(
            "--from {from} is after --to {to}: --from must not be later than --to"
        ));
    }
    if span == 0.0 && frames > 1 {
        return Err(format!(
            "--from and --to are the same instant ({from}): {frames} frames need --to later than --from \
             (or use --frames 1)"
        ));
    }
    Ok(span)
}

/// Seconds from `a` to `b` on the UTC time line (each on its own clock offset). Exact to the
/// microsecond and better: whole days from the dates, then the clock seconds.
fn seconds_between(a: &CivilDateTime, b: &CivilDateTime) -> f64 {
    let midnight = |c: &CivilDateTime| {
        CivilDateTime {
            hour: 0,
            minute: 0,
            second: 0.0,
            offset_hours: 0.0,
            ..*c
        }
        .julian_date()
    };
    let clock = |c: &CivilDateTime| {
        f64::from(c.hour) * 3600.0 + f64::from(c.minute) * 60.0 + c.second - c.offset_hours * 3600.0
    };
    (midnight(b) - midnight(a)) * 86_400.0 + (clock(b) - clock(a))
}

/// The instant of frame `k` (0-based) of `n`: `from + k·span/(n − 1)` on `from`'s clock.
pub(crate) fn frame_instant(from: &CivilDateTime, span: f64, k: u32, n: u32) -> CivilDateTime {
    if n <= 1 {
        return *from;
    }
    firmament_scene::add_seconds(from, span * f64::from(k) / f64::from(n - 1))
}

/// A duration in seconds for messages: `42 s`, `1 h 30 min`, `2 d 4 h`.
fn format_duration(seconds: f64) -> String {
    if seconds < 60.0 {
        return format!("{} s", trim_number(seconds));
    }
    let minutes = seconds / 60.0;
    if minutes < 60.0 {
        return format!("{} min", trim_number(minutes));
    }
    let hours = minutes / 60.0;
    if hours < 48.0 {
        return format!("{} h", trim_number(hours));
    }
    format!("{} d", trim_number(hours / 24.0))
}

/// A number with at most 3 decimals and no trailing zeros.
fn trim_number(v: f64) -> String {
    let text = format!("{v:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// The file name of frame `k` (0-based) of `n`: `frame_0001.png`, numbered from 1 and zero-padded
/// to the digits of `n`, at least 4.
pub(crate) fn frame_name(k: u32, n: u32, extension: &str) -> String {
    let digits = n.to_string().len().max(4);
    format!("frame_{:0digits$}.{extension}", k + 1)
}

/// The files of frame `k` of `n` in `dir`: its PNG, and its EXR when `exr`.
fn frame_files(dir: &Path, k: u32, n: u32, exr: bool) -> Vec<PathBuf> {
    let mut files = vec![dir.join(frame_name(k, n, "png"))];
    if exr {
        files.push(dir.join(frame_name(k, n, "exr")));
    }
    files
}

/// Whether every one of `files` is a file.
fn all_files(files: &[PathBuf]) -> bool {
    files.iter().all(|f| f.is_file())
}

/// The frames' PNG paths, in order.
fn png_paths(dir: &Path, n: u32) -> Vec<PathBuf> {
    (0..n).map(|k| dir.join(frame_name(k, n, "png"))).collect()
}

/// Fails unless `dir` is a folder or could be created as one (its nearest existing ancestor is a
/// folder); creates nothing.
pub(crate) fn check_output_dir(dir: &Path) -> Result<()> {
    if dir.exists() {
        if !dir.is_dir() {
            bail!(
                "output {}: exists and is not a folder (a time-lapse writes its frames into a folder)",
                dir.display()
            );
        }
        return Ok(());
    }
    let mut ancestor = dir.parent();
    while let Some(a) = ancestor {
        let a = if a.as_os_str().is_empty() { Path::new(".") } else { a };
        if a.exists() {
            if !a.is_dir() {
                bail!(
                    "output {}: cannot create the folder: {} is not a folder",
                    dir.display(),
                    a.display()
                );
            }
            return Ok(());
        }
        ancestor = a.parent();
    }
    Ok(())
}

/// Creates the output folder and proves it writable with a temporary file (removed at once).
pub(crate) fn create_output_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("output {}: cannot create the folder", dir.display()))?;
    crate::output::temp_file_in(dir)
        .with_context(|| format!("output {}: cannot write in the folder", dir.display()))?;
    Ok(())
}

/// The stop flag: set by the first Ctrl-C or SIGTERM, which lets the frames in flight finish; a
/// second one exits at once, removing the temporary files of the frames being written (never a
/// partial frame).
fn install_stop_handler() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let installed = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            crate::output::abandon_and_exit("\ninterrupted again: stopping now", EXIT_INTERRUPTED);
        }
    });
    if let Err(error) = installed {
        tracing::warn!("cannot catch Ctrl-C ({error}): an interruption will not be reported");
    }
    stop
}

/// The command line, quoted for a POSIX shell, to tell the user how to resume.
fn command_line() -> String {
    std::env::args()
        .map(|arg| {
            let plain = !arg.is_empty()
                && arg
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_./:=+,@%".contains(c));
            if plain {
                arg
            } else {
                format!("'{}'", arg.replace('\'', r"'\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The progress bar on stderr: frames done of all, frames per second, time left. Hidden with
/// `-q`, and by indicatif when stderr is not a terminal. The rate is this run's plain average
/// (frames rendered ÷ time since the bar appeared): indicatif's own estimator weighs the first
/// seconds as if nothing had happened before them, which undercounts a short run badly.
fn progress_bar(total: u32, skipped: u32) -> ProgressBar {
    // `-q` (or FIRMAMENT_LOG=error) turns info off, and the bar with it.
    if !tracing::enabled!(tracing::Level::INFO) {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(u64::from(total)), ProgressDrawTarget::stderr());
    let skipped = u64::from(skipped);
    let rate = move |state: &ProgressState| {
        let rendered = state.pos().saturating_sub(skipped) as f64;
        let seconds = state.elapsed().as_secs_f64();
        (rendered > 0.0 && seconds > 0.0).then(|| rendered / seconds)
    };
    let template = "{msg} {wide_bar:.cyan/blue} {pos}/{len} frames  {fps}  ETA {left}";
    match ProgressStyle::with_template(template) {
        Ok(style) => bar.set_style(
            style
                .with_key("fps", move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = match rate(state) {
                        Some(r) => write!(w, "{r:.2} frames/s"),
                        None => write!(w, "– frames/s"),
                    };
                })
                .with_key("left", move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let left = state.len().unwrap_or(0).saturating_sub(state.pos()) as f64;
                    let _ = match rate(state) {
                        Some(r) => write!(w, "{}", format_eta(left / r)),
                        None => write!(w, "–"),
                    };
                })
                .progress_chars("█▉▊▋▌▍▎▏ "),
        ),
        Err(error) => tracing::debug!("progress bar template: {error}"),
    }
    bar.set_position(skipped);
    bar
}

/// Seconds as a countdown: `42s`, `3m05s`, `2h07m`.
fn format_eta(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    match s {
        0..60 => format!("{s}s"),
        60..3600 => format!("{}m{:02}s", s / 60, s % 60),
        _ => format!("{}h{:02}m", s / 3600, s / 60 % 60),
    }
}

/// The frames already on disk (`done`, 0-based) that must be rendered again: each is decoded
/// whole (in parallel), and one that does not decode — cut short, by a crash before firmament
/// synced its frames or by a copy — is rendered again. A complete frame of another size is an
/// error, so that a resumed run never mixes sizes (the GIF and the contact sheet need one).
fn incomplete_frames(
    done: &[u32],
    files: impl Fn(u32) -> Vec<PathBuf> + Sync,
    width: u32,
    height: u32,
) -> Result<Vec<u32>> {
    use rayon::prelude::*;
    let checked: Vec<Result<Option<u32>>> = done
        .par_iter()
        .map(|&k| {
            for path in files(k) {
                let image = match image::open(&path) {
                    Ok(image) => image,
                    Err(error) => {
                        tracing::warn!(
                            "{} is not a complete frame ({error}): rendering it again",
                            path.display()
                        );
                        return Ok(Some(k));
                    }
                };
                let size = (image.width(), image.height());
                if size != (width, height) {
                    bail!(
                        "{} is {}x{} but this run renders {width}x{height}: use --overwrite to render every \
                         frame again, or another output folder",
                        path.display(),
                        size.0,
                        size.1
                    );
                }
            }
            Ok(None)
        })
        .collect();
    let mut again = Vec::new();
    for result in checked {
        again.extend(result?);
    }
    Ok(again)
}

/// Renders the missing frames, then the GIF and the contact sheet.
fn render_all(args: &TimelapseArgs, plan: &Plan<'_>, span: f64) -> Result<Outcome> {
    let dir = plan.output;
    check_output_dir(dir)?;

    let extra = super::scene_input::size_overrides(args.width, args.height);
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &args.scene_args);
    let policy = crate::untrusted::Policy::new(&args.untrusted, args.scene.as_deref())?;
    policy.check_frames(plan.frames)?;
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &args.scene_args, extra, policy.confinement())
        .with_context(|| format!("cannot build {what}"))?;
    let (width, height) = (scene.render.width, scene.render.height);
    policy.check_pixels("each frame", width, height)?;
    crate::limits::check_pixels("each frame", width, height)?;
    let n = plan.frames;
    let instants: Vec<CivilDateTime> = (0..n).map(|k| frame_instant(&plan.from, span, k, n)).collect();
    let (Some(first), Some(last)) = (instants.first(), instants.last()) else {
        bail!("--frames must be at least 1");
    };
    // The first and last frames are built up front, so that a scene that cannot be placed at a
    // real date (a planet without an ephemeris) fails before anything is written.
    for civil in [first, last] {
        scene
            .frame_at_date_time(civil)
            .with_context(|| format!("cannot build {what} at {}", civil))?;
    }

    // The frames of this run: all, or its shard's block.
    let mine = match args.shard {
        Some((shard, shards)) => {
            shards::check_shard(shard, shards, n)?;
            shards::shard_frames(shard, shards, n)
        }
        None => 0..n,
    };
    let manifest = shards::Manifest {
        frames: n,
        width,
        height,
        exr: args.exr,
        fps: args.fps,
        from: plan.from.to_string(),
        to: plan.to.to_string(),
    };
    shards::check_manifest(dir, &manifest, args.overwrite)?;

    let pngs = png_paths(dir, n);
    let exr_path = |k: u32| dir.join(frame_name(k, n, "exr"));
    let files = |k: u32| frame_files(dir, k, n, args.exr);
    let mut todo: Vec<u32> = mine
        .clone()
        .filter(|&k| args.overwrite || !all_files(&files(k)))
        .collect();
    let done: Vec<u32> = mine.clone().filter(|k| todo.binary_search(k).is_err()).collect();
    todo.extend(incomplete_frames(&done, files, width, height)?);
    todo.sort_unstable();
    let mine_count = mine.len() as u32;
    let skipped = mine_count - todo.len() as u32;

    let step = if n > 1 { span / f64::from(n - 1) } else { 0.0 };
    tracing::info!(
        "time-lapse of {what}: {n} frame{} at {width}x{height} from {} to {}{} → {}",
        if n == 1 { "" } else { "s" },
        first,
        last,
        if n > 1 {
            format!(", one every {}", format_duration(step))
        } else {
            String::new()
        },
        dir.display()
    );
    if let Some((shard, shards)) = args.shard {
        tracing::info!(
            "shard {shard}/{shards}: frames {} to {} of {n}",
            mine.start + 1,
            mine.end
        );
    }
    if skipped > 0 {
        tracing::info!(
            "{skipped} of {mine_count} frames skipped: already in {} (--overwrite renders them again)",
            dir.display()
        );
    }

    // A run killed while it wrote a file (SIGKILL) left its temporary file; shards leave the
    // folder's to --assemble, as another shard may be writing its own.
    let stale = if args.shard.is_some() {
        0
    } else {
        crate::output::remove_stale_temp_files(dir)?
    };
    if stale > 0 {
        tracing::info!(
            "removed {stale} temporary file{} that an interrupted run left in {}",
            if stale == 1 { "" } else { "s" },
            dir.display()
        );
    }

    let stop = install_stop_handler();
    let started = WallClock::now();
    let mut rendered = 0_u32;
    let (mut setup_seconds, mut render_seconds) = (0.0, 0.0);
    if !todo.is_empty() {
        // The GPU before the folder: a machine without an adapter leaves nothing behind.
        let ctx = GpuContext::headless(args.backend.into())?;
        create_output_dir(dir)?;
        shards::write_manifest(dir, &manifest)?;
        let mut renderer = HeadlessRenderer::new(&ctx);
        setup_seconds = started.elapsed().as_secs_f64();
        let loop_started = WallClock::now();
        let bar = progress_bar(mine_count, skipped);
        let depth = pipeline::queue_depth(width, height, args.exr);
        tracing::debug!(
            "encoding on {} threads, at most {depth} frames queued",
            rayon::current_num_threads()
        );
        let mut queue = EncodeQueue::new(depth);
        let mut done = |_: u32| {
            rendered += 1;
            bar.inc(1);
        };
        let readback = Readback {
            ldr: true,
            hdr: args.exr,
        };
        let compression = args.exr_compression.unwrap_or_default();
        let job = |k: u32, submitted: SubmittedFrame| -> Result<EncodeJob> {
            Ok(EncodeJob {
                index: k,
                pixels: submitted.collect(&ctx)?,
                png: pngs[k as usize].clone(),
                exr: args.exr.then(|| (exr_path(k), compression)),
            })
        };
        // Frame k is submitted before frame k − 1 is collected: the GPU renders one while the
        // other comes back, and the encoders work on the ones before.
        let mut in_flight: Option<(u32, SubmittedFrame)> = None;
        // Auto-exposure adapts over the scene time between frames; a frame after a gap (frames
        // kept from an earlier run) meters afresh.
        let step_seconds = if n > 1 { span / f64::from(n - 1) } else { 0.0 };
        let mut previous: Option<u32> = None;
        for &k in &todo {
            if stop.load(Ordering::SeqCst) {
                break;
            }
            let civil = &instants[k as usize];
            bar.set_message(civil.to_string());
            let frame = scene
                .frame_at_date_time(civil)
                .with_context(|| format!("cannot build {what} at {}", civil))?;
            let follows = previous.is_some_and(|p| p + 1 == k);
            renderer.set_exposure_interval(follows.then_some(step_seconds));
            previous = Some(k);
            let submitted = renderer.submit(&ctx, &frame, width, height, readback)?;
            if let Some((previous, submitted)) = in_flight.replace((k, submitted)) {
                queue.push(job(previous, submitted)?, &mut done)?;
            }
            queue.poll(&mut done)?;
        }
        if let Some((last, submitted)) = in_flight.take() {
            queue.push(job(last, submitted)?, &mut done)?;
        }
        queue.finish(&mut done)?;
        bar.finish_and_clear();
        render_seconds = loop_started.elapsed().as_secs_f64();
    }
    let done = skipped + rendered;
    if done < mine_count {
        return Ok(Outcome::Interrupted(format!(
            "interrupted: {done} of {mine_count} frames are in {} ({rendered} rendered by this run, every one \
             complete); to resume, run the same command again — the frames already there are \
             skipped:\n  {}",
            dir.display(),
            command_line()
        )));
    }
    if todo.is_empty() {
        shards::write_manifest(dir, &manifest)?;
    }
    if rendered > 0 {
        tracing::info!(
            "{rendered} frame{} rendered in {render_seconds:.2} s ({:.2} frames/s; GPU set-up {setup_seconds:.2} s \
             before them), {skipped} skipped",
            if rendered == 1 { "" } else { "s" },
            f64::from(rendered) / render_seconds.max(1e-9)
        );
    }
    if let Some((shard, shards)) = args.shard {
        tracing::info!(
            "shard {shard}/{shards} done: frames {} to {} of {n} are in {}; once every shard is, write the GIF \
             and the contact sheet with: firmament timelapse --assemble {}",
            mine.start + 1,
            mine.end,
            dir.display(),
            dir.display()
        );
        return Ok(Outcome::Done);
    }
    write_summaries(dir, &pngs, args.fps, args.exr, &|| stop.load(Ordering::SeqCst), started)
}

/// Writes the GIF and the contact sheet of the finished frames `pngs` in `dir`; `interrupted`
/// says when to abandon the GIF.
fn write_summaries(
    dir: &Path,
    pngs: &[PathBuf],
    fps: u32,
    exr: bool,
    interrupted: &dyn Fn() -> bool,
    started: WallClock,
) -> Result<Outcome> {
    let n = pngs.len() as u32;
    let gif = dir.join(GIF_NAME);
    let gif_started = WallClock::now();
    if !animation::write_gif(&gif, pngs, fps, interrupted)? {
        return Ok(Outcome::Interrupted(format!(
            "interrupted while writing {}: all {n} frames are in {}; run the same command again to \
             build the GIF and the contact sheet:\n  {}",
            gif.display(),
            dir.display(),
            command_line()
        )));
    }
    let gif_seconds = gif_started.elapsed().as_secs_f64();
    let sheet_started = WallClock::now();
    let sheet = dir.join(SHEET_NAME);
    contact_sheet::write_contact_sheet(&sheet, pngs)?;
    let sheet_seconds = sheet_started.elapsed().as_secs_f64();
    tracing::info!(
        "wrote {} in {:.1} s (the GIF {gif_seconds:.2} s, the contact sheet {sheet_seconds:.2} s)",
        if n == 1 {
            format!("{}, {} and {}", pngs[0].display(), gif.display(), sheet.display())
        } else {
            format!(
                "{} … {}{}, {} and {}",
                pngs[0].display(),
                frame_name(n - 1, n, "png"),
                if exr { " (and .exr)" } else { "" },
                gif.display(),
                sheet.display()
            )
        },
        started.elapsed().as_secs_f64()
    );
    Ok(Outcome::Done)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn civil(text: &str) -> CivilDateTime {
        firmament_scene::parse_date_time(text).expect("valid")
    }

    #[test]
    fn frames_span_both_ends_on_the_first_clock() {
        let from = civil("2024-03-20T23:00:00+02:00");
        let to = civil("2024-03-20T23:00:00Z");
        let span = seconds_between(&from, &to);
        assert_eq!(span, 7200.0);
        let last = frame_instant(&from, span, 4, 5);
        assert_eq!((last.day, last.hour, last.minute, last.offset_hours), (21, 1, 0, 2.0));
        assert!(last.second.abs() < 1e-9);
        let middle = frame_instant(&from, span, 2, 5);
        assert_eq!((middle.day, middle.hour, middle.minute), (21, 0, 0));
        assert_eq!(frame_instant(&from, span, 0, 1), from);
    }

    #[test]
    fn names_pad_to_the_frame_count() {
        assert_eq!(frame_name(0, 3, "png"), "frame_0001.png");
        assert_eq!(frame_name(99_999, 100_000, "exr"), "frame_100000.exr");
        assert_eq!(frame_name(41, 12_345, "png"), "frame_00042.png");
    }

    #[test]
    fn arguments_are_checked() {
        assert_eq!(civil("2024-03-20T16:00:00Z").to_string(), "2024-03-20T16:00:00Z");
        assert_eq!(
            civil("2024-03-20T16:00:00.25-07:30").to_string(),
            "2024-03-20T16:00:00.250-07:30"
        );
        assert_eq!(format_duration(121.0), "2.017 min");
        assert_eq!(format_duration(7200.0), "2 h");
        assert_eq!(format_eta(185.2), "3m05s");
        assert_eq!(format_eta(7620.0), "2h07m");
    }
}
