use super::*;
use crate::atmosphere::planet_shadow::ShadowSettings;

/// A sun of Earth's size and limb darkening towards `direction` (also the air's tests').
pub(super) fn sun(direction: DVec3) -> Sun {
    Sun {
        direction,
        angular_radius: 0.004_65,
        irradiance: Spectrum::new(1.5, 1.8, 2.0),
        limb_darkening: 0.6,
        disc: true,
        from_body: None,
    }
}

/// The irradiance a far viewer along `to_viewer` gets from `body`, by summing its radiance over
/// the disc on an `n × n` grid (orthographic: the viewer is far), per unit `1/D²`.
fn disc_flux_times_d2(body: &Body, to_viewer: DVec3, suns: &[Sun], n: u32) -> Spectrum {
    let (e1, e2) = to_viewer.any_orthonormal_pair();
    let extent = body.radii.max_element() * 1.01;
    let cell = 2.0 * extent / f64::from(n);
    let mut sum = Spectrum::ZERO;
    for j in 0..n {
        for i in 0..n {
            let x = (f64::from(i) + 0.5) * cell - extent;
            let y = (f64::from(j) + 0.5) * cell - extent;
            let origin = body.center + e1 * x + e2 * y + to_viewer * (4.0 * extent);
            let ray = Ray::new(origin, -to_viewer).unwrap();
            if let Some(t) = body.hit(&ray) {
                sum += body.radiance(ray.at(t), to_viewer, suns, |_| Spectrum::ONE) * (cell * cell);
            }
        }
    }
    sum
}

#[test]
fn full_phase_flux_is_the_geometric_albedo_s() {
    // Seen from the sun's side a Lambert sphere's geometric albedo is 2A/3 and a
    // Lommel–Seeliger one's A: the viewer gets p·E·R² / D².
    let s = sun(DVec3::new(0.3, -0.4, 0.866).normalize());
    let radius = 1000.0;
    for (law, p) in [(Reflectance::Lambert, 2.0 / 3.0), (Reflectance::LommelSeeliger, 1.0)] {
        let body = Body {
            center: DVec3::new(5.0, -7.0, 3.0),
            radii: DVec3::splat(radius),
            orientation: DQuat::from_rotation_x(0.4),
            albedo: Spectrum::new(0.1, 0.2, 0.3),
            reflectance: law,
            surface: BodySurface::Uniform,
            planet_shadow: None,
            air: None,
        };
        let flux = disc_flux_times_d2(&body, s.direction, &[s], 600);
        let expected = s.irradiance * body.albedo * (p * radius * radius);
        let error = (flux / expected - 1.0).abs().max_element();
        assert!(error < 2e-3, "{law:?}: {flux:?} vs {expected:?}");
    }
}

#[test]
fn the_laws_are_one_at_normal_incidence_seen_face_on() {
    for law in [Reflectance::Lambert, Reflectance::LommelSeeliger] {
        assert_eq!(law.factor(1.0, 1.0), 1.0);
        assert_eq!(law.factor(-0.2, 1.0), 0.0);
    }
    assert_eq!(Reflectance::Lambert.factor(0.5, 0.1), 0.5);
    assert!((Reflectance::LommelSeeliger.factor(0.5, 0.25) - 4.0 / 3.0).abs() < 1e-15);
}

#[test]
fn a_posed_ellipsoid_is_hit_where_its_axes_say() {
    // Polar axis (z, 3 m) turned onto the frame's y: a ray down y meets it 3 m from the centre.
    let body = Body {
        center: DVec3::new(10.0, 20.0, 30.0),
        radii: DVec3::new(1.0, 2.0, 3.0),
        orientation: DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2),
        albedo: Spectrum::splat(0.5),
        reflectance: Reflectance::Lambert,
        surface: BodySurface::Uniform,
        planet_shadow: None,
        air: None,
    };
    let ray = Ray::new(DVec3::new(10.0, 30.0, 30.0), DVec3::NEG_Y).unwrap();
    let t = body.hit(&ray).unwrap();
    assert!((t - 7.0).abs() < 1e-9, "{t}");
    assert!((body.normal_at(ray.at(t)) - DVec3::Y).length() < 1e-12);
    // Behind the ray's origin: no hit.
    let away = Ray::new(DVec3::new(10.0, 30.0, 30.0), DVec3::Y).unwrap();
    assert_eq!(body.hit(&away), None);
}

#[test]
fn the_planet_and_other_bodies_shade_a_body() {
    let planet = Planet::sphere(6_371_000.0, 100_000.0);
    let s = sun(DVec3::X);
    let moon = Body::moon(DVec3::new(-384_400_000.0, 0.0, 0.0));
    let near_side = moon.center + DVec3::X * MOON_RADIUS_M;
    // Straight behind the planet: inside its umbra.
    let suns = [s];
    assert_eq!(
        sunlight_share(near_side, &suns, 0, &planet, None, std::slice::from_ref(&moon), 0),
        Spectrum::ZERO
    );
    // Far off the shadow's axis: full sunlight; the body itself does not count.
    let aside = Body::moon(DVec3::new(-384_400_000.0, 30_000_000.0, 0.0));
    let p = aside.center + DVec3::X * MOON_RADIUS_M;
    assert_eq!(
        sunlight_share(p, &suns, 0, &planet, None, std::slice::from_ref(&aside), 0),
        Spectrum::ONE
    );
    // Another body sunward on the line: its share is the eclipse's.
    let blocker = Body::moon(p + DVec3::X * 1.0e8);
    let bodies = [aside.clone(), blocker.clone()];
    let expected = blocker.eclipser().visible_fraction(p, &s);
    assert!(expected < 1.0);
    assert_eq!(
        sunlight_share(p, &suns, 0, &planet, None, &bodies, 0),
        Spectrum::splat(expected)
    );
}

/// A moon in the planet's shadow with the shadow's light: red, as the profile gives it at the
/// point's distance from the axis, and the profile only behind the planet and for its own sun.
#[test]
fn a_moon_in_the_shadow_takes_the_shadow_s_light() {
    let earth = crate::atmosphere::presets::earth();
    let planet = earth.planet;
    let s = sun(DVec3::X);
    let mut moon = Body::moon(DVec3::new(-384_400_000.0, 0.0, 0.0));
    let (sun_index, behind) = moon.shadowing_sun(&[s], &planet).expect("in the shadow");
    assert_eq!(sun_index, 0);
    assert!((behind - 384_400_000.0).abs() < 1.0);
    let profile = PlanetShadow::new(&earth, &s, behind, &ShadowSettings::default());
    moon.planet_shadow = Some(BodyInShadow {
        sun: 0,
        axis: DVec3::NEG_X,
        profile: profile.clone(),
    });
    let p = moon.center + DVec3::new(MOON_RADIUS_M, 1_000_000.0, 0.0);
    let share = sunlight_share(p, &[s], 0, &planet, None, std::slice::from_ref(&moon), 0);
    let across = DVec3::new(0.0, 1_000_000.0, 0.0).length();
    assert_eq!(share, profile.at(across));
    assert!(share.x > 2.0 * share.z && share.x > 0.0, "the umbra is red: {share}");
    // A second sun the shadow is not for, and a point sunward of the planet.
    let other = sun(DVec3::Y);
    let second = sunlight_share(p, &[s, other], 1, &planet, None, std::slice::from_ref(&moon), 0);
    assert_eq!(second, Spectrum::ONE);
    let shadow = moon.planet_shadow.as_ref().unwrap();
    assert_eq!(shadow.light_at(DVec3::new(1.0e8, 0.0, 0.0)), Spectrum::ONE);
    // Clear of the penumbra: no sun shadows it.
    let aside = Body::moon(DVec3::new(-384_400_000.0, 30_000_000.0, 0.0));
    assert_eq!(aside.shadowing_sun(&[s], &planet), None);
    // A bad shadow names its field.
    assert!(moon.validate().is_ok());
    let mut bent = moon.clone();
    bent.planet_shadow.as_mut().unwrap().axis = DVec3::new(0.0, 2.0, 0.0);
    assert!(matches!(
        bent.validate(),
        Err(CoreError::Invalid {
            field: "body.planet_shadow.axis",
            ..
        })
    ));
    let mut flat = moon;
    flat.planet_shadow.as_mut().unwrap().profile.step_m = 0.0;
    assert!(matches!(
        flat.validate(),
        Err(CoreError::Invalid {
            field: "body.planet_shadow.profile",
            ..
        })
    ));
}

#[test]
fn bodies_must_not_overlap_or_outnumber_the_limit() {
    let planet = Planet::sphere(6_371_000.0, 100_000.0);
    let far = |x: f64| Body::moon(DVec3::new(x, 0.0, 0.0));
    assert!(validate_bodies(&[far(4.0e8), far(4.1e8)], &planet).is_ok());
    let grazing = far(6_471_000.0 + MOON_RADIUS_M);
    assert!(matches!(
        validate_bodies(&[grazing], &planet),
        Err(CoreError::Invalid {
            field: "body.center",
            ..
        })
    ));
    let touching = [far(4.0e8), far(4.0e8 + MOON_RADIUS_M)];
    assert!(validate_bodies(&touching, &planet).is_err());
    let many: Vec<Body> = (0..5).map(|i| far(4.0e8 + f64::from(i) * 1.0e7)).collect();
    assert!(matches!(
        validate_bodies(&many, &planet),
        Err(CoreError::Invalid { field: "bodies", .. })
    ));
    let mut dark = far(4.0e8);
    dark.albedo = Spectrum::new(0.1, 1.2, 0.1);
    assert!(validate_bodies(&[dark], &planet).is_err());
}

/// The planet-shine's closed form against the light of a Lambert sphere summed over its lit face:
/// a planet of albedo `A` (geometric albedo `2A/3`) seen from 1000 radii (the closed form is the
/// far limit: from 60 radii, the Moon's distance, it is 4 % high at 120°) at phase angles 0–150°.
#[test]
fn planetshine_is_a_lambert_sphere_s_light() {
    let radius = 1.0;
    let albedo = 0.3;
    let planet = Planet::sphere(radius, 0.01).with_geometric_albedo(2.0 * albedo / 3.0);
    let distance = 1000.0;
    for alpha_deg in [0.0f64, 30.0, 60.0, 90.0, 120.0, 150.0] {
        let alpha = alpha_deg.to_radians();
        let sun = DVec3::new(alpha.cos(), alpha.sin(), 0.0);
        let p = DVec3::X * distance;
        let (_, closed) = planetshine(p, sun, &planet);
        // Σ over the sphere's surface of (A/π)·μ₀ radiance × the solid angle from p × cos at p.
        let n = 400;
        let mut sum = 0.0;
        for j in 0..n {
            let theta = (f64::from(j) + 0.5) / f64::from(n) * PI;
            for i in 0..2 * n {
                let phi = (f64::from(i) + 0.5) / f64::from(2 * n) * 2.0 * PI;
                let normal = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                let area = theta.sin() * (PI / f64::from(n)) * (PI / f64::from(n)) * radius * radius;
                let to_p = p - normal * radius;
                let (mu0, mu) = (normal.dot(sun), normal.dot(to_p.normalize()));
                if mu0 > 0.0 && mu > 0.0 {
                    let face_on = to_p.normalize().dot(DVec3::X);
                    sum += albedo / PI * mu0 * mu * area / to_p.length_squared() * face_on;
                }
            }
        }
        let error = (closed - sum).abs() / sum.max(1e-30);
        assert!(error < 0.01, "{alpha_deg}°: closed form {closed} vs sum {sum}");
    }
}

/// A ball of radius 1000 m at the origin turned a quarter about z (its x axis along the frame's
/// y), Lambert, its surface `surface`.
fn mapped_ball(albedo: f64, surface: BodySurface) -> Body {
    Body {
        center: DVec3::ZERO,
        radii: DVec3::splat(1000.0),
        orientation: DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
        albedo: Spectrum::splat(albedo),
        reflectance: Reflectance::Lambert,
        surface,
        planet_shadow: None,
        air: None,
    }
}

#[test]
fn an_albedo_map_patterns_the_albedo_in_the_body_s_axes() {
    // West half 0.8, east half 0.2 (texel centres at 90° W and 90° E): brightness 0.5.
    let halves = SurfaceMap::new(2, 1, vec![[0.8, 0.8, 0.8, 0.0], [0.2, 0.2, 0.2, 0.0]]).unwrap();
    let body = mapped_ball(0.1, BodySurface::Map(Arc::new(halves)));
    body.validate().unwrap();
    // The body's +y (90° E) lies along the frame's −x, its −y (90° W) along +x.
    let east = body.albedo_at(DVec3::new(-1000.0, 0.0, 0.0));
    let west = body.albedo_at(DVec3::new(1000.0, 0.0, 0.0));
    let meridian = body.albedo_at(DVec3::new(0.0, 1000.0, 0.0));
    assert!((east - Spectrum::splat(0.04)).abs().max_element() < 1e-12, "{east:?}");
    assert!((west - Spectrum::splat(0.16)).abs().max_element() < 1e-12, "{west:?}");
    assert!(
        (meridian - Spectrum::splat(0.1)).abs().max_element() < 1e-12,
        "{meridian:?}"
    );
    // A texel brighter than the level allows stops at 1.
    let bright = mapped_ball(0.9, body.surface.clone());
    assert_eq!(bright.albedo_at(DVec3::new(1000.0, 0.0, 0.0)), Spectrum::ONE);
}

#[test]
fn a_mapped_body_s_mean_albedo_is_its_albedo() {
    // Colours and a pattern in latitude and longitude; the mean over the sphere (Fibonacci points,
    // equal areas) of the albedo is the body's albedo times each channel's share of brightness.
    let (width, height) = (16, 8);
    let texels = (0..width * height)
        .map(|k| {
            let (i, j) = (f64::from(k % width), f64::from(k / width));
            let v = 0.3 + 0.2 * (i * 0.7).sin() * (j * 0.9).cos();
            [v as f32, (0.8 * v) as f32, (0.5 * v) as f32, 0.0]
        })
        .collect();
    let map = SurfaceMap::new(width, height, texels).unwrap();
    let [r, g, b, _] = map.mean();
    let level = (r + g + b) / 3.0;
    let body = mapped_ball(0.12, BodySurface::Map(Arc::new(map)));
    let n = 200_000;
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut sum = Spectrum::ZERO;
    for k in 0..n {
        let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
        let (s, c) = (golden * f64::from(k)).sin_cos();
        let rho = (1.0 - z * z).sqrt();
        sum += body.albedo_at(DVec3::new(rho * c, rho * s, z) * 1000.0);
    }
    let mean = sum / f64::from(n);
    let expected = Spectrum::new(r, g, b) * (0.12 / level);
    assert!(
        ((mean / expected) - 1.0).abs().max_element() < 0.01,
        "{mean:?} vs {expected:?}"
    );
}

#[test]
fn a_black_albedo_map_is_refused() {
    let black = SurfaceMap::uniform([0.0, 0.0, 0.0, 0.0]).unwrap();
    let body = mapped_ball(0.1, BodySurface::Map(Arc::new(black)));
    assert!(body.validate().is_err());
}
