//! `firmament bench`: the atmosphere's per-pass times, the object pass's Gouraud and Phong
//! times (`--objects`), the lens-flare passes' (`--flares`), or a whole frame on the CLI's path
//! against the embedded path (`--embedded`), on this machine's adapter.

/// The fragment and compute baselines every mode is measured against.
mod baseline;
/// The measurements themselves, on the renderer's passes (its `internals`).
mod measure;

use anyhow::{Context, Result, bail};
use baseline::Baselines;
use firmament_core::frame::Sky;
use firmament_render::GpuContext;
use measure::{
    AtmosphereBench, CameraBench, EmbeddingBench, FlareBench, ObjectBench, bench_atmosphere, bench_camera,
    bench_embedding, bench_flares, bench_objects, sphere_grid,
};

use crate::cli::BenchArgs;

/// Loads the scene (an atmosphere preset by default), times the passes and prints the figures.
pub(crate) fn run(args: &BenchArgs) -> Result<()> {
    if let Some(count) = args.objects {
        crate::limits::check_pixels("the image", args.width, args.height)?;
        return run_objects(args, count);
    }
    if args.flares {
        crate::limits::check_pixels("the image", args.width, args.height)?;
        return run_flares(args);
    }
    let scene_args = super::scene_input::with_default_preset(&args.scene_args, args.scene.as_deref(), "earth-noon");
    let extra = vec![
        format!("render.width={}", args.width),
        format!("render.height={}", args.height),
    ];
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &scene_args, extra, None)
        .context("cannot build the scene")?;
    crate::limits::check_pixels("the image", args.width, args.height)?;
    let frame = scene.frame_at(None)?;
    if args.embedded {
        return run_embedded(args, &frame);
    }
    let Sky::Atmosphere(sky) = &frame.sky else {
        bail!("bench times the atmosphere passes: the scene needs sky.model = \"atmosphere\"");
    };
    let ctx = GpuContext::headless(args.backend.into())?;
    let result = bench_atmosphere(&ctx, sky, &frame.camera, args.width, args.height, args.frames)?;
    let camera = bench_camera(&ctx, &frame, args.width, args.height, args.frames)?;
    let baselines = Baselines::measure(&ctx, args.width, args.height, args.frames);
    if args.json {
        println!("{}", json(&result, &camera, &baselines));
    } else {
        print_table(&result, &camera, &baselines);
    }
    Ok(())
}

/// `object` with the baselines' fields and the ratio of each of `rows` (JSON key, milliseconds)
/// to each baseline, as one line of JSON.
fn with_baselines(mut object: serde_json::Value, baselines: &Baselines, rows: &[(impl AsRef<str>, f64)]) -> String {
    if let Some(map) = object.as_object_mut() {
        for (key, value) in baselines.json_fields(rows) {
            map.insert(key.to_owned(), value);
        }
    }
    object.to_string()
}

/// `--embedded`: the scene's frame on both paths.
fn run_embedded(args: &BenchArgs, frame: &firmament_core::Frame) -> Result<()> {
    let ctx = GpuContext::headless(args.backend.into())?;
    let b = bench_embedding(&ctx, frame, args.width, args.height, args.frames)?;
    let baselines = Baselines::measure(&ctx, args.width, args.height, args.frames);
    if args.json {
        println!("{}", embedding_json(&b, &baselines));
        return Ok(());
    }
    println!(
        "{} — {}x{}, median of {} frames, {}",
        b.adapter,
        b.width,
        b.height,
        b.frames,
        b.timing.describe()
    );
    let mut rows = vec![("CLI path: Renderer::record into an 8-bit view", b.cli_ms)];
    rows.extend(
        b.cli_no_shadows_ms
            .map(|ms| ("CLI path without sun shadows and light shafts", ms)),
    );
    rows.extend([
        (
            "embedded: caller's clear + record_into (HDR, no tone mapping)",
            b.embedded_hdr_ms,
        ),
        ("embedded: the same + firmament's output pass", b.embedded_output_ms),
        (
            "embedded: output pass, no aerial perspective",
            b.embedded_output_no_aerial_ms,
        ),
    ]);
    baselines.print_rows(&rows);
    println!(
        "  embedded with output / CLI: {:.2}x ({:.2}x without aerial perspective)",
        b.embedded_output_ms / b.cli_ms,
        b.embedded_output_no_aerial_ms / b.cli_ms
    );
    if let Some(ms) = b.cli_no_shadows_ms {
        println!("  CLI frame with shadows and shafts / without: {:.2}x", b.cli_ms / ms);
    }
    Ok(())
}

fn embedding_json(b: &EmbeddingBench, baselines: &Baselines) -> String {
    let object = serde_json::json!({
        "adapter": b.adapter,
        "width": b.width,
        "height": b.height,
        "frames": b.frames,
        "timing": b.timing.describe(),
        "cli_ms": b.cli_ms,
        "embedded_hdr_ms": b.embedded_hdr_ms,
        "embedded_output_ms": b.embedded_output_ms,
        "embedded_output_no_aerial_ms": b.embedded_output_no_aerial_ms,
        "cli_no_shadows_ms": b.cli_no_shadows_ms,
    });
    let rows = [
        ("cli_ms", b.cli_ms),
        ("embedded_hdr_ms", b.embedded_hdr_ms),
        ("embedded_output_ms", b.embedded_output_ms),
        ("embedded_output_no_aerial_ms", b.embedded_output_no_aerial_ms),
    ];
    with_baselines(object, baselines, &rows)
}

fn print_table(b: &AtmosphereBench, camera: &CameraBench, baselines: &Baselines) {
    println!(
        "{} — {}x{}, {} sun(s), median of {} frames, {}",
        b.adapter,
        b.width,
        b.height,
        b.suns,
        b.frames,
        b.timing.describe()
    );
    let mut rows = vec![
        (
            "medium LUTs (transmittance, multiple scattering, irradiance)",
            b.medium_luts_ms,
        ),
        (
            "longest step of an incremental rebuild (one per frame)",
            b.medium_lut_step_max_ms,
        ),
        ("sky-view LUT", b.sky_view_lut_ms),
        ("sky pass (compute, the renderer's own targets)", b.sky_ms),
        ("sky pass (fragment, callers' render passes)", b.sky_fragment_ms),
        ("aerial-perspective volume", b.aerial_volume_ms),
        (
            "aerial perspective applied, geometry everywhere (compute, own targets)",
            b.aerial_apply_ms,
        ),
        (
            "aerial perspective applied, geometry everywhere (fragment, callers')",
            b.aerial_apply_fragment_ms,
        ),
        ("LUT-path frame (sky-view LUT + sky)", b.lut_frame_ms),
        (
            "whole frame, every LUT rebuilt (+ sky-view LUT, sky, aerial vol.)",
            b.rebuild_frame_ms,
        ),
        ("brute-force frame (per-pixel march)", b.march_frame_ms),
        ("auto-exposure (histogram and adaptation)", camera.exposure_ms),
        ("bloom (the dual-filter pyramid, down and up)", camera.bloom_ms),
    ];
    if let Some(ms) = b.clouds_ms {
        rows.push(("clouds (march and composite over the image)", ms));
    }
    baselines.print_rows(&rows);
    let steps: Vec<String> = b.medium_lut_steps_ms.iter().map(|ms| format!("{ms:.3}")).collect();
    println!(
        "  medium LUT build steps (transmittance, each order of multiple scattering; the last with the sums): {} ms",
        steps.join(", ")
    );
    println!(
        "  brute force / LUT path: {:.1}x; LUT vs march: median {:.2} %, worst {:.2} %",
        b.march_frame_ms / b.lut_frame_ms,
        b.difference.0 * 100.0,
        b.difference.1 * 100.0
    );
}

fn json(b: &AtmosphereBench, camera: &CameraBench, baselines: &Baselines) -> String {
    let object = serde_json::json!({
        "adapter": b.adapter,
        "width": b.width,
        "height": b.height,
        "suns": b.suns,
        "frames": b.frames,
        "timing": b.timing.describe(),
        "medium_luts_ms": b.medium_luts_ms,
        "medium_lut_step_max_ms": b.medium_lut_step_max_ms,
        "medium_lut_steps_ms": b.medium_lut_steps_ms,
        "sky_view_lut_ms": b.sky_view_lut_ms,
        "sky_ms": b.sky_ms,
        "sky_fragment_ms": b.sky_fragment_ms,
        "aerial_volume_ms": b.aerial_volume_ms,
        "aerial_apply_ms": b.aerial_apply_ms,
        "aerial_apply_fragment_ms": b.aerial_apply_fragment_ms,
        "lut_frame_ms": b.lut_frame_ms,
        "march_frame_ms": b.march_frame_ms,
        "rebuild_frame_ms": b.rebuild_frame_ms,
        "clouds_ms": b.clouds_ms,
        "difference_median": b.difference.0,
        "difference_worst": b.difference.1,
        "exposure_ms": camera.exposure_ms,
        "bloom_ms": camera.bloom_ms,
    });
    let mut rows = vec![
        ("medium_luts_ms", b.medium_luts_ms),
        ("medium_lut_step_max_ms", b.medium_lut_step_max_ms),
        ("sky_view_lut_ms", b.sky_view_lut_ms),
        ("sky_ms", b.sky_ms),
        ("sky_fragment_ms", b.sky_fragment_ms),
        ("aerial_volume_ms", b.aerial_volume_ms),
        ("aerial_apply_ms", b.aerial_apply_ms),
        ("aerial_apply_fragment_ms", b.aerial_apply_fragment_ms),
        ("lut_frame_ms", b.lut_frame_ms),
        ("march_frame_ms", b.march_frame_ms),
        ("rebuild_frame_ms", b.rebuild_frame_ms),
        ("exposure_ms", camera.exposure_ms),
        ("bloom_ms", camera.bloom_ms),
    ];
    if let Some(ms) = b.clouds_ms {
        rows.push(("clouds_ms", ms));
    }
    with_baselines(object, baselines, &rows)
}

/// `--objects`: the scene's objects (if a scene is given and has some), else the sphere grid.
fn run_objects(args: &BenchArgs, count: u32) -> Result<()> {
    let (layer, camera) = if args.scene.is_some() || args.scene_args.preset.is_some() {
        let scene = super::scene_input::load_scene(args.scene.as_deref(), &args.scene_args, Vec::new(), None)
            .context("cannot build the scene")?;
        let frame = scene.frame_at(None)?;
        if frame.objects.objects.is_empty() {
            bail!("bench --objects times the object pass: the scene has no [[objects]]");
        }
        (frame.objects, frame.camera)
    } else {
        sphere_grid(count as usize, 25, 20)?
    };
    let ctx = GpuContext::headless(args.backend.into())?;
    let result = bench_objects(&ctx, &layer, &camera, args.width, args.height, args.frames)?;
    let baselines = Baselines::measure(&ctx, args.width, args.height, args.frames);
    if args.json {
        println!(
            "{}",
            with_baselines(
                serde_json::json!({
                "adapter": result.adapter,
                "width": result.width,
                "height": result.height,
                "frames": result.frames,
                "objects": result.objects,
                "triangles": result.triangles,
                "lights": result.lights,
                "timing": result.timing.describe(),
                "gouraud_ms": result.gouraud_ms,
                "phong_ms": result.phong_ms,
                "shadows_ms": result.shadows_ms,
                }),
                &baselines,
                &[("gouraud_ms", result.gouraud_ms), ("phong_ms", result.phong_ms)],
            )
        );
    } else {
        print_objects(&result, &baselines);
    }
    Ok(())
}

fn print_objects(b: &ObjectBench, baselines: &Baselines) {
    println!(
        "{} — {}x{}, {} objects, {} triangles, {} lights, median of {} frames, {}",
        b.adapter,
        b.width,
        b.height,
        b.objects,
        b.triangles,
        b.lights,
        b.frames,
        b.timing.describe()
    );
    let mut rows = vec![
        ("Gouraud (lit per vertex)", b.gouraud_ms),
        ("Phong (lit per fragment)", b.phong_ms),
    ];
    rows.extend(
        b.shadows_ms
            .map(|ms| ("Phong with sun shadows (maps drawn and sampled)", ms)),
    );
    baselines.print_rows(&rows);
    println!("  Phong / Gouraud: {:.2}x", b.phong_ms / b.gouraud_ms);
    if let Some(ms) = b.shadows_ms {
        println!("  with shadows / without: {:.2}x", ms / b.phong_ms);
    }
}

/// `--flares`: the occlusion and element passes with 1, 8 and 64 sources.
fn run_flares(args: &BenchArgs) -> Result<()> {
    let ctx = GpuContext::headless(args.backend.into())?;
    let result = bench_flares(&ctx, args.width, args.height, args.frames, 32)?;
    let baselines = Baselines::measure(&ctx, args.width, args.height, args.frames);
    if args.json {
        let ratio_rows = flare_rows(&result, |sources, pass| format!("sources_{sources}_{pass}_ms"));
        let rows: Vec<_> = result
            .rows
            .iter()
            .map(
                |r| serde_json::json!({ "sources": r.sources, "occlusion_ms": r.occlusion_ms, "total_ms": r.total_ms }),
            )
            .collect();
        println!(
            "{}",
            with_baselines(
                serde_json::json!({
                    "adapter": result.adapter,
                    "width": result.width,
                    "height": result.height,
                    "frames": result.frames,
                    "elements": result.elements,
                    "samples": result.samples,
                    "timing": result.timing.describe(),
                    "rows": rows,
                }),
                &baselines,
                &ratio_rows,
            )
        );
    } else {
        print_flares(&result);
        let labels = flare_rows(&result, |sources, pass| match pass {
            "occlusion" => format!("{sources} sources: occlusion"),
            _ => format!("{sources} sources: occlusion and elements"),
        });
        baselines.print_rows(&labels);
    }
    Ok(())
}

/// Each source count's two times (occlusion, total), named by `name(sources, "occlusion" |
/// "total")`, for the baseline ratios.
fn flare_rows(result: &FlareBench, name: impl Fn(usize, &str) -> String) -> Vec<(String, f64)> {
    result
        .rows
        .iter()
        .flat_map(|r| {
            [
                (name(r.sources, "occlusion"), r.occlusion_ms),
                (name(r.sources, "total"), r.total_ms),
            ]
        })
        .collect()
}

fn print_flares(b: &FlareBench) {
    println!(
        "{} — {}x{}, {} elements per flare, {} samples per source, median of {} frames, {}",
        b.adapter,
        b.width,
        b.height,
        b.elements,
        b.samples,
        b.frames,
        b.timing.describe()
    );
    println!("{:>8}  {:>13}  {:>13}", "sources", "occlusion ms", "total ms");
    for r in &b.rows {
        println!("{:>8}  {:>13.3}  {:>13.3}", r.sources, r.occlusion_ms, r.total_ms);
    }
}
