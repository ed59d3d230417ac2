//! The flags of untrusted mode, shared by every command that reads a stranger's scene. What they
//! do: `crate::untrusted` and docs/RELIABILITY.md.

use std::path::PathBuf;

use clap::Args;

/// Untrusted mode and the wall-time limit.
#[derive(Debug, Clone, Default, Args)]
#[command(next_help_heading = "Untrusted mode (scenes from strangers; docs/RELIABILITY.md)")]
pub(crate) struct UntrustedArgs {
    /// Treat the scene as a stranger's: every file it names must resolve, links followed, inside
    /// the allowed folder (absolute paths, `..` out and links out are refused before anything is
    /// read), and the budgets below and a 120 s time limit apply.
    #[arg(long)]
    pub(crate) untrusted: bool,
    /// The allowed folder (default: the scene file's folder; the working directory for a preset
    /// or a scene on standard input).
    #[arg(long, value_name = "DIR", requires = "untrusted")]
    pub(crate) asset_root: Option<PathBuf>,
    /// Stop after this many seconds of wall time with exit status 124, writing nothing partial
    /// (a time-lapse keeps its finished frames). Default: none; 120 with --untrusted.
    #[arg(long, value_name = "SECONDS", value_parser = seconds)]
    pub(crate) time_limit: Option<f64>,
    /// Most pixels of an image or a time-lapse frame (untrusted default: 4194304, 2048x2048).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_pixels: Option<u64>,
    /// Most frames of a time-lapse (untrusted default: 240).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) max_frames: Option<u32>,
    /// Most Monte Carlo paths of a `--reference` render (pixels x paths per pixel) or sample
    /// (untrusted default: 4194304).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_paths: Option<u64>,
    /// Most triangles of the scene's objects together, built-in shapes and mesh files (untrusted
    /// default: 1048576).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_triangles: Option<u64>,
    /// Longest side of an image file the scene names, texels (untrusted default: 4096).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) max_texture_side: Option<u32>,
    /// Most bytes read for one mesh or image file and the files it names (untrusted default:
    /// 33554432, 32 MiB).
    #[arg(long, value_name = "N", requires = "untrusted", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_file_bytes: Option<u64>,
}

/// `--time-limit`: a positive, finite number of seconds, at most a year.
fn seconds(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 365.0 * 86_400.0 => Ok(v),
        _ => Err("must be a number of seconds > 0 (at most a year, 31536000)".to_owned()),
    }
}
