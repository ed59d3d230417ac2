//! GPU tests of planetary rings (`atmosphere/rings.wgsl`) against the f64 core
//! (`firmament_core::atmosphere::rings`): the sun's disc seen through them keeps
//! `e^(−τ/μ)`, their lit face shows `Rings::radiance`, the globe's shadow darkens them,
//! theirs darkens the globe and their light falls on it (`Rings::light_on_ground`).

use crate::support::{centre_radiance, far_view_difference, gpu};

use std::f64::consts::PI;

use firmament_core::atmosphere::planet::geodetic_normal;
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::atmosphere::rings::Rings;
use firmament_core::atmosphere::{Sun, presets};
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

/// Saturn unposed (the world frame is the planet frame: z its pole, the rings in z = 0) lit by a
/// sun towards `sun`, dimmed 10⁴-fold so the lit globe and rings sit in the half float's normal
/// range (in cd/m² they would pass its 65504).
fn saturn_sky(sun: DVec3, rings: Option<Rings>) -> AtmosphereSky {
    dimmed_saturn_sky(sun, rings, 1e-4)
}

/// [`saturn_sky`] with the sun's irradiance times `dimming`.
fn dimmed_saturn_sky(sun: DVec3, rings: Option<Rings>, dimming: f64) -> AtmosphereSky {
    let sun = Sun {
        irradiance: presets::saturn_sun(sun).irradiance * dimming,
        ..presets::saturn_sun(sun)
    };
    AtmosphereSky {
        atmosphere: presets::saturn(),
        suns: vec![sun],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings,
        surface: None,
    }
}

/// Looking at the sun from under the rings through each band: the disc keeps e^(−τ/μ) of its
/// light, within 0.5 % (the budget).
#[test]
fn the_sun_seen_through_the_rings_keeps_e_to_the_minus_tau_over_mu() {
    let mut gpu = gpu();
    let rings = Rings::saturn();
    let s = DVec3::new(1.0, 0.0, 0.8).normalize();
    for radius_km in [80_000.0, 95_000.0, 110_000.0, 119_000.0, 130_000.0] {
        let crossing = DVec3::new(0.0, radius_km * 1000.0, 0.0);
        let eye = crossing - s * 1.0e7;
        // The disc is as bright as seen from Earth (radiance does not fall with distance): dim it
        // 10⁶-fold to stay inside the half-float target.
        let clear = centre_radiance(&mut gpu, &dimmed_saturn_sky(s, None, 1e-6), eye, s);
        let through = centre_radiance(&mut gpu, &dimmed_saturn_sky(s, Some(rings.clone()), 1e-6), eye, s);
        let want = (-rings.optical_depth_at(radius_km * 1000.0) / s.z).exp();
        let got = through.y / clear.y;
        println!("{radius_km} km: {got:.5} vs e^(−τ/μ) {want:.5}");
        assert!(clear.y > 10.0, "the disc: {clear}");
        assert!((got / want - 1.0).abs() < 0.005, "{radius_km} km: {got} vs {want}");
    }
}

/// The rings' lit face from above, over empty space: what `Rings::radiance` gives, within 1 %;
/// a point the globe hides from the sun, dark.
#[test]
fn the_lit_rings_show_their_single_scattering_and_the_globe_s_shadow() {
    let mut gpu = gpu();
    let rings = Rings::saturn();
    let s = DVec3::new(1.0, 0.0, 0.6).normalize();
    let sky = saturn_sky(s, Some(rings.clone()));
    let conversion = sky.atmosphere.spectral_conversion();
    let towards_eye = DVec3::new(0.0, 0.3, 1.0).normalize();
    for radius_km in [85_000.0, 110_000.0, 130_000.0] {
        let point = DVec3::new(0.0, radius_km * 1000.0, 0.0);
        let eye = point + towards_eye * 5.0e7;
        let got = centre_radiance(&mut gpu, &sky, eye, -towards_eye);
        let r = radius_km * 1000.0;
        let want = conversion.linear_srgb(rings.radiance(r, -towards_eye, s, sky.suns[0].irradiance, true));
        let want = DVec3::new(want.r, want.g, want.b);
        let error = ((got - want) / want).abs().max_element();
        println!("{radius_km} km: gpu {got:.5} core {want:.5} relative {error:.5}");
        assert!(error < 0.01, "{radius_km} km: {got} vs {want}");
    }
    // Behind the globe from a sun 9° above the plane: the B ring in its shadow.
    let low = DVec3::new(1.0, 0.0, 0.15).normalize();
    let low_sky = saturn_sky(low, Some(rings.clone()));
    let shadowed = DVec3::new(-1.1e8, 0.0, 0.0);
    let eye = shadowed + DVec3::new(0.0, -0.3, 1.0).normalize() * 5.0e7;
    let view = (shadowed - eye).normalize();
    let dark = centre_radiance(&mut gpu, &low_sky, eye, view);
    let lit = conversion.linear_srgb(rings.radiance(1.1e8, view, low, low_sky.suns[0].irradiance, true));
    assert!(lit.g > 0.0 && dark.y < 1e-3 * lit.g, "{dark} vs lit {}", lit.g);
}

/// The ground under the B ring, the sun behind the ring: the rings' shadow dims it by about
/// e^(−τ/μ) (the direct light exactly; the thin H₂ air's own light alike), with the rings' own
/// light ([`ringshine`]) on top.
#[test]
fn the_rings_shadow_the_globe() {
    let mut gpu = gpu();
    let rings = Rings::saturn();
    let s = DVec3::new(-1.0, 0.0, 0.55).normalize();
    // A point on the globe whose ray towards the sun crosses the B ring core.
    let planet = presets::saturn().planet;
    let mut point = DVec3::ZERO;
    let mut found = false;
    for k in 0..2000 {
        let latitude = -(k as f64) * 0.05f64.to_radians();
        let surface = DVec3::new(-planet.radii.x * latitude.cos(), 0.0, planet.radii.z * latitude.sin());
        if let Some((_, r)) = rings.crossing(surface, s)
            && (100_000_000.0..115_000_000.0).contains(&r)
        {
            point = surface;
            found = true;
            break;
        }
    }
    assert!(found, "a shadowed point");
    let (_, r) = rings.crossing(point, s).expect("crosses");
    let want = (-rings.optical_depth_at(r) / s.z.abs()).exp();
    let normal = (point / (planet.radii * planet.radii)).normalize();
    let eye = point + normal * 2.0e7;
    let view = -normal;
    let clear = centre_radiance(&mut gpu, &saturn_sky(s, None), eye, view);
    let shaded = centre_radiance(&mut gpu, &saturn_sky(s, Some(rings.clone())), eye, view);
    // The rings' own light on the ground comes on top of the sunlight they let through.
    let lit_by_rings = ringshine(&rings, s, 1e-4, point, normal).y / clear.y;
    let got = shaded.y / clear.y - lit_by_rings;
    println!(
        "ground at {:.0} km from the pole axis: {got:.5} vs e^(−τ/μ) {want:.5} (and the rings' light {lit_by_rings:.5})",
        point.x.abs() / 1000.0
    );
    assert!(clear.y > 0.0);
    assert!((got / want - 1.0).abs() < 0.02, "{got} vs {want}");
}

/// The rings' light (linear sRGB) that the ground at `p` with normal `n` sends straight up under
/// [`dimmed_saturn_sky`]: the core's `Rings::light_on_ground` on the ground's albedo, each ring
/// element's light dimmed by the air (the core's transmittance on Saturn's ellipsoid) on its way
/// down, and all of it on the way out.
fn ringshine(rings: &Rings, s: DVec3, dimming: f64, p: DVec3, n: DVec3) -> DVec3 {
    let atmosphere = presets::saturn();
    let reference = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
    // A metre up: a point a rounding inside the ground would see no sky.
    let above = p + n;
    let air = |view| reference.transmittance_to_space(above, view);
    let light = rings.light_on_ground(atmosphere.planet.radii, p, n, s, air) * air(n);
    let irradiance = presets::saturn_sun(s).irradiance * dimming;
    let spectral = atmosphere.medium.ground_albedo / PI * irradiance * light;
    let rgb = atmosphere.spectral_conversion().linear_srgb(spectral);
    DVec3::new(rgb.r, rgb.g, rgb.b)
}

/// Saturn's night side under the rings' lit face (north, the sun 24° above the ring plane) and
/// under their far face (south): the ground shows the rings' light within 2 % of the brightest
/// channel of [`ringshine`].
#[test]
fn the_rings_light_the_night_side() {
    let mut gpu = gpu();
    let rings = Rings::saturn();
    let s = DVec3::new(1.0, 0.0, 0.45).normalize();
    let radii = presets::saturn().planet.radii;
    let dimming = 1e-3;
    for (latitude, longitude) in [(35.0_f64, 180.0_f64), (20.0, 150.0), (-30.0, 180.0)] {
        let n = geodetic_normal(latitude.to_radians(), longitude.to_radians());
        let p = radii * radii * n / (radii * n).length();
        let (eye, view) = (p + n * 2.0e7, -n);
        let lit = centre_radiance(&mut gpu, &dimmed_saturn_sky(s, Some(rings.clone()), dimming), eye, view);
        let dark = centre_radiance(&mut gpu, &dimmed_saturn_sky(s, None, dimming), eye, view);
        let want = ringshine(&rings, s, dimming, p, n);
        let got = lit - dark;
        let error = (got - want).abs().max_element() / want.max_element();
        println!(
            "latitude {latitude}°, longitude {longitude}° from the sun: {:.4e} vs {:.4e} ({:.2} %; without the rings {:.2e})",
            got.y,
            want.y,
            100.0 * error,
            dark.max_element()
        );
        assert!(want.max_element() > 0.0);
        assert!(error < 0.02, "{got} vs {want}");
    }
}

/// Saturn and its rings seen from 1 AU and from 100 AU with a field of view 100× narrower: the
/// same image, every pixel within 1/255 of the brightest (f32 positions would lose the rings at
/// 100 AU; the view ray starts at its closest approach to the centre).
#[test]
fn rings_from_100_au_look_as_from_1_au() {
    let mut gpu = gpu();
    let s = DVec3::new(1.0, 0.3, 0.6).normalize();
    let sky = saturn_sky(s, Some(Rings::saturn()));
    let size = 32;
    let (worst, ringed) = far_view_difference(&mut gpu, &sky, DVec3::new(0.0, 0.94, 0.34), 1.37e8, size);
    println!(
        "worst {:.2}/255 of the brightest pixel over {ringed} lit pixels",
        worst * 255.0
    );
    assert!(ringed > size * size / 8, "{ringed} lit pixels");
    assert!(worst < 1.0 / 255.0, "worst {worst}");
}
