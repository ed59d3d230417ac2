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

#[allow(dead_code, reason = "the example's `main` is not called here; `run` is")]
#[path = "../examples/custom_material.rs"]
mod custom_material;

/// The custom material example: a PNG that is not flat, where the box 5 km away is fogged towards
/// the horizon's colour more than the one 60 m away (same grey, same lighting on the faces seen).
#[test]
fn custom_material_fogs_the_far_box_more_than_the_near_one() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let output = dir.path().join("material.png");
    let output_arg = output.to_str().expect("UTF-8 temporary path").to_owned();
    let camera = custom_material::run([output_arg, "128".into(), "96".into()])
        .unwrap_or_else(|e| panic!("custom_material failed: {e}"));

    let image = image::open(&output).expect("the example wrote a PNG").to_rgb8();
    assert_eq!(image.dimensions(), (128, 96));
    let first = *image.get_pixel(0, 0);
    assert!(
        image.pixels().any(|p| *p != first),
        "the image is one flat colour {first:?}"
    );
    // The pixel where a world point lands.
    let pixel = |p: glam::DVec3| {
        let ndc = (camera.projection_matrix() * camera.view_matrix()).project_point3(p);
        let x = ((ndc.x + 1.0) / 2.0 * 128.0) as u32;
        let y = ((1.0 - ndc.y) / 2.0 * 96.0) as u32;
        image.get_pixel(x, y).0.map(f64::from)
    };
    // The middle of each box's south face (the one the camera sees).
    let face = |(base, size, _): ([f64; 3], [f64; 3], [f32; 3])| {
        glam::DVec3::new(base[0], base[1] - size[1] / 2.0, base[2] + size[2] / 2.0)
    };
    let [near_box, far_box] = custom_material::BOXES;
    let (near, far) = (pixel(face(near_box)), pixel(face(far_box)));
    // The sky beside the far box, at its height: the horizon's colour.
    let far_face = face(far_box);
    let horizon = pixel(far_face + glam::DVec3::new(1_500.0, 0.0, 0.0));
    let distance = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
    println!(
        "near box {near:?}, far box {far:?}, horizon {horizon:?}: distance to the horizon's colour {:.1} near, {:.1} far",
        distance(near, horizon),
        distance(far, horizon)
    );
    assert!(
        distance(far, horizon) < 0.9 * distance(near, horizon),
        "the far box {far:?} is not fogged towards the horizon {horizon:?} more than the near one {near:?}"
    );
    // The air is blue: the far box is bluer than the near one.
    assert!(
        far[2] - far[0] > near[2] - near[0] + 5.0,
        "far {far:?} not bluer than near {near:?}"
    );
    // The boxes are drawn (not the sky behind them) and lit.
    assert!(
        distance(near, horizon) > 10.0 && near.iter().any(|&c| c > 32.0),
        "near box {near:?}"
    );
}
