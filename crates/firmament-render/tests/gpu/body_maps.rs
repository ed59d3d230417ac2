//! GPU tests of a body's albedo map (`atmosphere/bodies.wgsl`, `passes/atmosphere/body_maps.rs`)
//! against the f64 core (`firmament_core::atmosphere::body::map`, checked there against the map's
//! texels and its mean): the radiance of a posed, coloured map at points where its texels differ.

use std::sync::Arc;

use crate::bodies::{airless_with, as_srgb, planet_center};
use crate::support::{centre_radiance, centre_radiance_in_pixel, gpu};

use firmament_core::atmosphere::Spectrum;
use firmament_core::atmosphere::body::{Body, BodySurface, Reflectance};
use firmament_core::atmosphere::surface::SurfaceMap;
use glam::{DQuat, DVec3};

const RADIUS_M: f64 = 1_000_000.0;

/// A Lambert ball of `surface` at `center`, sunlit from +x.
fn ball(center: DVec3, orientation: DQuat, surface: BodySurface) -> Body {
    Body {
        center,
        radii: DVec3::splat(RADIUS_M),
        orientation,
        albedo: Spectrum::splat(0.3),
        reflectance: Reflectance::Lambert,
        surface,
        planet_shadow: None,
        air: None,
    }
}

/// The unit normal at geodetic `latitude_deg`, `longitude_deg` in a ball's axes.
fn normal(latitude_deg: f64, longitude_deg: f64) -> DVec3 {
    let (lat, lon) = (latitude_deg.to_radians(), longitude_deg.to_radians());
    DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin())
}

/// A 4 × 2 map of eight colours (texel centres at ±45° latitude, ±45° and ±135° longitude).
fn eight_colours() -> SurfaceMap {
    let texels = [
        [0.9, 0.2, 0.2],
        [0.2, 0.9, 0.2],
        [0.2, 0.2, 0.9],
        [0.6, 0.6, 0.6],
        [0.3, 0.3, 0.3],
        [0.8, 0.5, 0.2],
        [0.2, 0.5, 0.8],
        [0.5, 0.5, 0.5],
    ];
    SurfaceMap::new(4, 2, texels.map(|[r, g, b]| [r, g, b, 0.0]).to_vec()).expect("a valid map")
}

/// A Lambert ball with the map, turned so its axes are not the frame's, sunlit from +x, seen from
/// 300 km above points across its day side (a pixel spans 5 km there, finer than a texel): the
/// GPU within 1 % of the brightest channel of the core's radiance (`Body::radiance`, the map's
/// albedo at the point; the texture's 8 bits, which the conversion to sRGB mixes into the dim
/// channels, account for the rest).
#[test]
fn a_body_s_map_shows_its_texels_where_the_core_puts_them() {
    let mut gpu = gpu();
    let center = planet_center() + DVec3::new(0.0, 384_400_000.0, 0.0);
    let orientation = DQuat::from_rotation_y(0.4) * DQuat::from_rotation_z(0.3);
    let body = ball(center, orientation, BodySurface::Map(Arc::new(eight_colours())));
    let sky = airless_with(DVec3::X, vec![body.clone()]);
    let mut worst: f64 = 0.0;
    for (latitude_deg, longitude_deg) in [(45.0, 45.0), (-45.0, -45.0), (20.0, 0.0), (-30.0, 20.0), (10.0, -40.0)] {
        let n = body.orientation * normal(latitude_deg, longitude_deg);
        assert!(n.dot(DVec3::X) > 0.2, "({latitude_deg}, {longitude_deg}) is lit");
        let p = center + n * RADIUS_M;
        let eye = p + (n + DVec3::Z * 0.2).normalize() * 300_000.0;
        let got = centre_radiance(&mut gpu, &sky, eye, p - eye);
        let want = as_srgb(
            &sky,
            body.radiance(p, (eye - p).normalize(), &sky.suns, |_| Spectrum::ONE),
        );
        let error = (got - want).abs().max_element() / want.max_element();
        println!(
            "({latitude_deg}°, {longitude_deg}°): gpu {got:.3} core {want:.3} ({:.2} %)",
            error * 100.0
        );
        worst = worst.max(error);
    }
    assert!(worst < 0.01, "worst {:.2} %", worst * 100.0);
}

/// A checkerboard of 0.1 and 0.9 squares 98 km wide on the same ball: from 300 km a pixel shows
/// its square's albedo (within 2 % of the core's radiance there), from 60 000 km (a pixel 310 km
/// across) the squares' mean, as if the map were uniform (within 3 %), where the map's finest
/// level alone would show one square or the other.
#[test]
fn a_far_body_s_map_reads_a_level_as_coarse_as_its_pixels() {
    let mut gpu = gpu();
    // At the texture's own size, so its texels are the map's (resampling a map clips the peaks of
    // the bilinear surface between its texel centres).
    let (width, height) = (1024, 512);
    let texels = (0..width * height)
        .map(|k| {
            if (k % width / 16 + k / width / 16) % 2 == 0 {
                0.1
            } else {
                0.9
            }
        })
        .map(|v| [v, v, v, 0.0])
        .collect();
    let checker = SurfaceMap::new(width, height, texels).expect("a valid map");
    let center = planet_center() + DVec3::new(0.0, 384_400_000.0, 0.0);
    let body = ball(center, DQuat::IDENTITY, BodySurface::Map(Arc::new(checker)));
    let uniform = ball(center, DQuat::IDENTITY, BodySurface::Uniform);
    let sky = airless_with(DVec3::X, vec![body.clone()]);
    // The centre of the dark square (40, 10), 16 texels a side: 47.8° E, 30.9° N.
    let n = normal(90.0 - 168.0 * 180.0 / 512.0, -180.0 + 648.0 * 360.0 / 1024.0);
    let p = center + n * RADIUS_M;
    // From afar a pixel 0.3° across: the ball 3.2 pixels in radius, not drawn by coverage.
    for (distance_m, reference, budget, pixel_deg) in
        [(300_000.0, &body, 0.02, 0.01_f64), (60_000_000.0, &uniform, 0.03, 0.3)]
    {
        let eye = p + n * distance_m;
        let got = centre_radiance_in_pixel(&mut gpu, &sky, eye, p - eye, pixel_deg.to_radians());
        let want = as_srgb(&sky, reference.radiance(p, n, &sky.suns, |_| Spectrum::ONE));
        let error = ((got - want) / want).abs().max_element();
        println!(
            "from {} km: gpu {got:.1} reference {want:.1} ({:.2} %)",
            distance_m / 1000.0,
            error * 100.0
        );
        assert!(error < budget, "from {distance_m} m: {got} vs {want}");
    }
}
