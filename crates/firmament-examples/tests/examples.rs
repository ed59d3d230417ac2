//! The headless examples run: each is compiled into this test as a module and called like its
//! `main`, at a tiny size, and what it wrote is checked.

#[allow(dead_code, reason = "the example's `main` is not called here; `run` is")]
#[path = "../examples/headless_still.rs"]
mod headless_still;

#[test]
fn headless_still_writes_a_png_that_is_not_blank() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let output = dir.path().join("still.png");
    let output_arg = output.to_str().expect("UTF-8 temporary path").to_owned();
    headless_still::run([output_arg, "64".into(), "36".into(), "default".into()])
        .unwrap_or_else(|e| panic!("headless_still failed: {e}"));

    let image = image::open(&output).expect("the example wrote a PNG").to_rgba8();
    assert_eq!(image.dimensions(), (64, 36));
    let first = *image.get_pixel(0, 0);
    assert!(
        image.pixels().any(|p| *p != first),
        "the still is one flat colour {first:?}: nothing was drawn"
    );
    assert!(
        image.pixels().any(|p| p.0[..3].iter().any(|&c| c > 32)),
        "the still is black"
    );
}
