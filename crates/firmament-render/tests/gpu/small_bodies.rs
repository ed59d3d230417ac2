//! Bodies a pixel or two across (`small_bodies` in `atmosphere/bodies.wgsl`): each pixel shows the
//! share of the body it covers, so the image holds the body's whole light wherever it stands
//! between pixel centres — checked against the light the f64 core sums over its disc
//! (`firmament_core::atmosphere::body::cast`).

use crate::bodies::airless_with;
use crate::support::{Gpu, gpu};
use firmament_core::atmosphere::body::Body;
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::{Camera, Frame};
use glam::DVec3;

const SIZE: u32 = 16;

/// The light (linear sRGB, the suns' irradiance units) of the `SIZE`² image seen from `eye`
/// along `look`, each pixel's radiance times its solid angle: the centre pixel's angle squared,
/// the field being a few degrees.
fn image_irradiance(gpu: &mut Gpu, sky: &AtmosphereSky, eye: DVec3, look: DVec3, pixel_rad: f64) -> DVec3 {
    let camera = Camera::looking_at(eye, eye + look, DVec3::Z).expect("a camera");
    let frame = Frame::new(
        Camera {
            fov_y: 2.0 * (0.5 * SIZE as f64 * pixel_rad.tan()).atan(),
            ..camera
        },
        Sky::Atmosphere(sky.clone()),
    );
    let Gpu { ctx, renderer } = gpu;
    let image = renderer.render_hdr(ctx, &frame, SIZE, SIZE).expect("render");
    let mut sum = DVec3::ZERO;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = image.pixel(x, y).expect("inside");
            sum += DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
        }
    }
    sum * pixel_rad * pixel_rad
}

/// A gibbous Moon (its maria, the lunar law) high over an air too thin to matter, under 1 pixel and
/// 2.4 pixels across, its centre at a pixel's centre, on an edge, at a corner and in between: the
/// image's light within 1 % of the core's sum over the disc. Drawn by where rays meet it, the
/// small one would fall to nothing between pixel centres.
#[test]
fn a_body_a_pixel_across_keeps_its_light_between_pixel_centres() {
    let mut gpu = gpu();
    let towards = DVec3::new(0.3, 0.4, 0.85).normalize();
    // 30° from opposite the Moon: a gibbous Moon, clear of the planet's shadow.
    let sun = (-towards + DVec3::new(0.5, -0.3, 0.0)).normalize();
    let sky = airless_with(sun, Vec::new());
    let eye = DVec3::new(0.0, 0.0, 2.0);
    let mut with_moon = sky.clone();
    with_moon.add_body(Body::moon(eye + towards * 384_400_000.0));
    let mut lit = with_moon.clone();
    lit.add_body_lights(eye, |_| true);
    let conversion = sky.atmosphere.spectral_conversion();
    let light = conversion.linear_srgb(lit.suns.last().expect("the Moon's light").irradiance);
    let want = DVec3::new(light.r, light.g, light.b);
    let moon_rad = (1_737_400.0_f64 / 384_400_000.0).asin();
    let right = towards.cross(DVec3::Z).normalize();
    let up = right.cross(towards);
    for radius_pixels in [0.4, 1.2] {
        let pixel_rad = moon_rad / radius_pixels;
        for (dx, dy) in [(0.0, 0.0), (0.5, 0.0), (0.5, 0.5), (0.37, 0.21)] {
            // The camera turned so the Moon's centre stands (dx, dy) pixels off a pixel's centre
            // (the image's centre is a corner of four pixels).
            let look = (towards - (right * (dx + 0.5) + up * (dy + 0.5)) * pixel_rad).normalize();
            let got = image_irradiance(&mut gpu, &with_moon, eye, look, pixel_rad)
                - image_irradiance(&mut gpu, &sky, eye, look, pixel_rad);
            let error = ((got - want) / want).abs().max_element();
            println!(
                "radius {radius_pixels} px, centre ({dx}, {dy}) px off: {:.4e} vs {:.4e} ({:.2} %)",
                got.y,
                want.y,
                100.0 * error
            );
            assert!(error < 0.01, "{got} vs {want}");
        }
    }
}
