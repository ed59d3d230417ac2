//! The camera passes on the GPU against the f64 core: the auto-exposure meter's EV100 against the
//! core's meter run on the same frame's HDR image (suns' discs masked); adaptation limited by the
//! speeds and byte-identical when run twice; a time-lapse from afternoon into night that stays
//! exposed; bloom keeping the image's total light; night vision against the core's model.

use crate::support;

use firmament_core::auto_exposure::{AutoExposure, ExposureMode, meter_image};
use firmament_core::color::{LinearRgb, srgb_to_linear};
use firmament_core::{Camera, Frame, TimeOfDay};
use firmament_render::headless::{Image, Readback};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn scene(preset: &str, overrides: &[&str]) -> firmament_scene::Scene {
    let overrides: Vec<String> = overrides.iter().map(|s| (*s).to_owned()).collect();
    firmament_scene::load(firmament_scene::SceneSource::Preset(preset), None, &overrides)
        .unwrap_or_else(|e| panic!("preset `{preset}`: {e}"))
}

fn frame(scene: &firmament_scene::Scene, time: Option<&str>) -> Frame {
    let time = time.map(|t| t.parse::<TimeOfDay>().expect("a time of day"));
    scene.frame_at(time).expect("a frame")
}

fn auto(frame: &Frame) -> AutoExposure {
    match frame.display.exposure_mode {
        ExposureMode::Auto(auto) => auto,
        ExposureMode::Manual => panic!("the scene should meter"),
    }
}

/// Renders `frame`; its display image, its HDR radiance and the EV100 the meter chose.
fn render(gpu: &mut support::Gpu, frame: &Frame) -> (Image<u8>, Vec<LinearRgb>, f64) {
    let readback = Readback { ldr: true, hdr: true };
    let pixels = gpu
        .renderer
        .submit(&gpu.ctx, frame, WIDTH, HEIGHT, readback)
        .and_then(|submitted| submitted.collect(&gpu.ctx))
        .expect("render");
    let hdr = pixels.hdr.expect("hdr").to_f32();
    let radiance = hdr
        .pixels
        .chunks_exact(4)
        .map(|p| LinearRgb::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])))
        .collect();
    let state = gpu.renderer.exposure_state(&gpu.ctx).expect("exposure state");
    (pixels.ldr.expect("ldr"), radiance, f64::from(state.ev100))
}

/// The f64 meter's EV100 for `radiance`, an image of `frame`.
fn reference_ev100(frame: &Frame, radiance: &[LinearRgb]) -> f64 {
    let camera = Camera {
        aspect: f64::from(WIDTH) / f64::from(HEIGHT),
        ..frame.camera
    };
    auto(frame).target_ev100(meter_image(frame, &camera, radiance, WIDTH))
}

/// The mean of the display image's encoded values (0 … 1) over RGB.
fn mean_display(image: &Image<u8>) -> f64 {
    let values: Vec<f64> = image
        .pixels
        .chunks_exact(4)
        .flat_map(|p| p[..3].iter().map(|&v| f64::from(v) / 255.0))
        .collect();
    values.iter().sum::<f64>() / values.len() as f64
}

#[test]
fn the_meter_chooses_the_ev100_of_the_f64_meter() {
    let mut gpu = support::gpu();
    gpu.renderer.set_exposure_interval(None);
    for (preset, expected) in [
        ("earth-noon", 10.0..16.0),
        ("earth-sunset", 8.0..13.0),
        ("earth-night", -8.0..-2.0),
        ("earth-orbit", 10.0..16.0),
    ] {
        let frame = frame(&scene(preset, &["display.exposure_mode=auto"]), None);
        let (_, radiance, ev100) = render(&mut gpu, &frame);
        let reference = reference_ev100(&frame, &radiance);
        eprintln!("{preset}: GPU EV100 {ev100:.3}, f64 meter {reference:.3}");
        assert!(
            (ev100 - reference).abs() <= 0.1,
            "{preset}: GPU {ev100}, f64 {reference}"
        );
        assert!(
            expected.contains(&ev100),
            "{preset}: EV100 {ev100} outside {expected:?}"
        );
    }
}

#[test]
fn adaptation_moves_at_the_speeds_and_repeats_bit_for_bit() {
    let mut gpu = support::gpu();
    let scene = scene(
        "earth-night",
        &[
            "display.exposure_mode=auto",
            "display.auto_speed_up=2.0",
            "display.auto_speed_down=0.5",
        ],
    );
    let (noon, night) = (frame(&scene, Some("12:00")), frame(&scene, Some("23:00")));
    let run = |gpu: &mut support::Gpu| {
        gpu.renderer.set_exposure_interval(None);
        let (_, _, noon_ev) = render(gpu, &noon);
        gpu.renderer.set_exposure_interval(Some(0.5));
        let mut evs = vec![noon_ev];
        let mut images = Vec::new();
        for f in [&night, &night, &noon] {
            let (image, _, ev) = render(gpu, f);
            evs.push(ev);
            images.push(image);
        }
        (evs, images)
    };
    let (evs, images) = run(&mut gpu);
    eprintln!("EV100s: {evs:?}");
    // Darker: down at 0.5 EV/s for 0.5 s, twice; brighter again: up at 2 EV/s for 0.5 s.
    assert!((evs[1] - (evs[0] - 0.25)).abs() < 1e-4, "{evs:?}");
    assert!((evs[2] - (evs[0] - 0.5)).abs() < 1e-4, "{evs:?}");
    assert!((evs[3] - (evs[0] - 0.5 + 1.0).min(evs[0])).abs() < 1e-4, "{evs:?}");
    let (again, images_again) = run(&mut gpu);
    assert_eq!(evs, again);
    assert!(images == images_again, "the same frames gave different pixels");
    gpu.renderer.set_exposure_interval(None);
}

#[test]
fn a_time_lapse_into_night_stays_exposed() {
    let mut gpu = support::gpu();
    let scene = scene(
        "earth-night",
        &[
            "display.exposure_mode=auto",
            "time.date_time=\"2025-06-21T12:00:00Z\"",
            "camera.heading=290.0",
            "camera.pitch=15.0",
            "planet.latitude=52.0",
        ],
    );
    let auto_speeds = auto(&frame(&scene, None));
    // Every 20 minutes from 16:00 to 22:00: the interval is the scene's time between frames.
    let seconds = 20.0 * 60.0;
    gpu.renderer.set_exposure_interval(None);
    let mut previous: Option<f64> = None;
    for k in 0..=18 {
        let minutes = 16 * 60 + 20 * k;
        let time = format!("{:02}:{:02}", minutes / 60, minutes % 60);
        let (image, _, ev) = render(&mut gpu, &frame(&scene, Some(&time)));
        let mean = mean_display(&image);
        eprintln!("{time}: EV100 {ev:.2}, mean display value {mean:.3}");
        assert!((0.25..=0.65).contains(&mean), "{time}: mean display value {mean}");
        if let Some(before) = previous {
            let step = ev - before;
            assert!(
                step <= auto_speeds.speed_up_ev_per_s * seconds + 1e-4
                    && -step <= auto_speeds.speed_down_ev_per_s * seconds + 1e-4,
                "{time}: EV100 moved {step}"
            );
        }
        previous = Some(ev);
        gpu.renderer.set_exposure_interval(Some(seconds));
    }
    gpu.renderer.set_exposure_interval(None);
}

#[test]
fn bloom_keeps_the_total_light() {
    let mut gpu = support::gpu();
    // Objects and the sky, no sun disc in view: every pixel within the half float's range.
    let totals: Vec<[f64; 3]> = [0.0, 0.3, 1.0]
        .iter()
        .map(|bloom| {
            let scene = scene(
                "earth-objects",
                &[
                    &format!("display.bloom={bloom}"),
                    "display.tone_curve=\"none\"",
                    "display.ev100=16.0",
                ],
            );
            let frame = frame(&scene, None);
            let (image, radiance, _) = render(&mut gpu, &frame);
            let peak = radiance.iter().map(|c| c.r.max(c.g).max(c.b)).fold(0.0, f64::max);
            assert!(peak * frame.display.exposure.multiplier < 1.0, "a pixel clips: {peak}");
            // Linear display values: exposure × the bloomed radiance, for curve "none".
            let mut total = [0.0; 3];
            for p in image.pixels.chunks_exact(4) {
                for (t, v) in total.iter_mut().zip(p) {
                    *t += srgb_to_linear(f64::from(*v) / 255.0);
                }
            }
            total
        })
        .collect();
    eprintln!("totals without bloom, at 0.3 and 1.0: {totals:?}");
    for bloomed in &totals[1..] {
        for (a, b) in totals[0].iter().zip(bloomed) {
            assert!((b / a - 1.0).abs() < 0.005, "{totals:?}");
        }
    }
}

#[test]
fn night_vision_matches_the_f64_model() {
    let mut gpu = support::gpu();
    // Moonlight (the preset's full moon), twilight and day: the rods' share from 1 to 0.
    for time in ["23:30", "20:30", "12:00"] {
        let scene = scene(
            "earth-night",
            &["display.night_vision=true", "display.tone_curve=\"aces_fitted\""],
        );
        let mut frame = frame(&scene, Some(time));
        if time == "12:00" {
            frame.display.exposure = firmament_core::display::Exposure::from_ev100(14.0);
        }
        let (image, radiance, _) = render(&mut gpu, &frame);
        let mut worst = 0.0_f64;
        for (pixel, c) in image.pixels.chunks_exact(4).zip(&radiance) {
            let d = frame.display.display_linear(*c);
            for (v, reference) in pixel.iter().zip([d.r, d.g, d.b]) {
                let expected = firmament_core::color::linear_to_srgb(reference) * 255.0;
                worst = worst.max((f64::from(*v) - expected).abs());
            }
        }
        eprintln!("{time}: worst difference {worst:.2} of 255");
        assert!(worst <= 1.5, "{time}: {worst}");
    }
    // Under the Moon colour fades into the rods' bluish grey: saturation falls, blue stays above
    // red.
    let saturation = |night_vision: bool, gpu: &mut support::Gpu| {
        let vision = format!("display.night_vision={night_vision}");
        let (image, _, _) = render(gpu, &frame(&scene("earth-night", &[&vision]), None));
        let (mut sum, mut bluer, mut n) = (0.0, 0, 0);
        for p in image.pixels.chunks_exact(4).filter(|p| p[..3].iter().any(|&v| v > 20)) {
            let (hi, lo) = (p[..3].iter().max().unwrap(), p[..3].iter().min().unwrap());
            sum += f64::from(hi - lo) / f64::from(*hi);
            bluer += usize::from(p[2] >= p[0]);
            n += 1;
        }
        (sum / n as f64, bluer as f64 / n as f64)
    };
    let (day_eyes, night_eyes) = (saturation(false, &mut gpu), saturation(true, &mut gpu));
    eprintln!("saturation, share bluer than red: {day_eyes:?} → {night_eyes:?}");
    assert!(night_eyes.0 < 0.7 * day_eyes.0, "{day_eyes:?} → {night_eyes:?}");
    assert!(night_eyes.1 > 0.95, "{night_eyes:?}");
}

#[test]
fn glare_spikes_follow_the_iris_blades() {
    let mut gpu = support::gpu();
    // The low sun straight ahead, at the image centre; the subtle flare's six-bladed iris at 15°
    // puts spikes at 45°, 105°, 165°, … (the edges' normals) and none at 75°, 135°, ….
    let base = [
        "camera.heading=262.0",
        "camera.pitch=2.0",
        "flare.enabled=true",
        "flare.preset=subtle",
    ];
    let hdr = |gpu: &mut support::Gpu, glare: &str| {
        let mut overrides = base.to_vec();
        overrides.push(glare);
        let (_, radiance, _) = render(gpu, &frame(&scene("earth-sunset", &overrides), None));
        radiance
    };
    let (with, without) = (hdr(&mut gpu, "flare.glare=1.0"), hdr(&mut gpu, "flare.glare=0.0"));
    let added = |angle_deg: f64| {
        // A quarter of the half-height out from the centre, y down in the image.
        let r = 0.25 * f64::from(HEIGHT) / 2.0;
        let (s, c) = angle_deg.to_radians().sin_cos();
        let x = (f64::from(WIDTH) / 2.0 + r * c).floor() as usize;
        let y = (f64::from(HEIGHT) / 2.0 - r * s).floor() as usize;
        let i = y * WIDTH as usize + x;
        firmament_core::auto_exposure::luminance(with[i]) - firmament_core::auto_exposure::luminance(without[i])
    };
    for spike in [45.0, 105.0, 165.0, 225.0] {
        let (on, off) = (added(spike), added(spike + 30.0));
        eprintln!("glare at {spike}°: {on:.1}, at {}°: {off:.1}", spike + 30.0);
        assert!(on > 3.0 * off && off >= 0.0, "spike at {spike}°: {on} vs {off}");
    }
}
