//! `firmament render --png-bits 16`: 16-bit PNGs for grading, against the GPU's 8-bit tonemap.

use crate::support::{firmament, stderr};

/// Renders `earth-sunset` small with `extra` arguments into `name` in `dir`.
fn render(dir: &std::path::Path, name: &str, extra: &[&str]) {
    let mut args = vec![
        "render",
        "--preset",
        "earth-sunset",
        "--set",
        "display.tone_curve=agx",
        "--width",
        "96",
        "--height",
        "54",
        "-o",
        name,
    ];
    args.extend_from_slice(extra);
    let out = firmament(dir, &args);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn a_16_bit_png_holds_what_the_8_bit_one_rounds() {
    let dir = tempfile::tempdir().expect("temp dir");
    render(dir.path(), "eight.png", &[]);
    render(dir.path(), "sixteen.png", &["--png-bits", "16"]);
    let eight = image::open(dir.path().join("eight.png")).expect("a PNG");
    let sixteen = image::open(dir.path().join("sixteen.png")).expect("a PNG");
    assert_eq!(sixteen.color(), image::ColorType::Rgb16);
    let (eight, sixteen) = (eight.to_rgb8(), sixteen.to_rgb16());
    assert_eq!(eight.dimensions(), sixteen.dimensions());
    // The GPU's f32 tonemap rounded to 8 bits and the core's f64 one to 16 bits, from the same
    // half-float radiance: within one 8-bit level (and rounding).
    let mut finer = 0;
    for (a, b) in eight.pixels().zip(sixteen.pixels()) {
        for c in 0..3 {
            let wide = f64::from(b.0[c]) / 257.0;
            assert!((wide - f64::from(a.0[c])).abs() <= 1.0, "{a:?} vs {b:?}");
            finer += usize::from(b.0[c] % 257 != 0);
        }
    }
    // And more than 8 bits' worth: most samples fall between 8-bit levels.
    assert!(finer > 96 * 54 * 3 / 2, "only {finer} samples use the 16 bits");
}

#[test]
fn png_bits_other_than_8_and_16_are_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = firmament(dir.path(), &["render", "--png-bits", "12", "-o", "x.png"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("8 or 16 bits"), "{}", stderr(&out));
    assert!(!dir.path().join("x.png").exists());
}
