//! Sun shadows of objects on the ground and on each other, against the f64 reference and closed
//! forms: the umbra gets the sky alone, the penumbra's width follows the sun's disc, edges stay
//! put as the camera moves, and undersides take the ground's bounce, not the sky's blue.

use std::sync::Arc;

use firmament_core::atmosphere::SpectralConversion;
use firmament_core::classic::lighting::{Material, SpecularModel};
use firmament_core::classic::mesh::Mesh;
use firmament_core::classic::scene::{ObjectLayer, ObjectLighting, SceneFog, SceneObject, Shading};
use firmament_core::classic::shadow::{ShadowSettings, Shadows};
use firmament_core::classic::sky_light::{SKY_IRRADIANCE_PATHS, SkyLight};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::{Camera, Frame};
use glam::{DMat4, DQuat, DVec2, DVec3, DVec4};

use crate::support;

const SIZE: (u32, u32) = (160, 120);

/// Settings for scenes a few metres across: fine texels, soft edges resolved.
fn settings() -> ShadowSettings {
    ShadowSettings {
        map_size: 1024,
        distance_m: 40.0,
        ..ShadowSettings::default()
    }
}

fn grey(albedo: f64) -> Material {
    Material {
        ambient: DVec4::new(albedo, albedo, albedo, 1.0),
        diffuse: DVec4::new(albedo, albedo, albedo, 1.0),
        specular: DVec4::new(0.0, 0.0, 0.0, 1.0),
        ..Material::default()
    }
}

/// `objects` lit by `sky` as the scene converter lights them, with the ground and shadows.
fn frame(sky: &AtmosphereSky, camera: Camera, mut objects: Vec<SceneObject>, settings: ShadowSettings) -> Frame {
    let light = SkyLight::new(sky);
    for object in &mut objects {
        object.light_colors = light.sun_colors(object.model.transform_point3(DVec3::ZERO));
    }
    let layer = ObjectLayer {
        objects,
        lighting: ObjectLighting::Sky(light.lighting(camera.position, Shading::Phong, SpecularModel::Blinn)),
        fog: SceneFog::None,
        shadows: Shadows {
            settings: Some(settings),
            lights: light.shadow_lights(camera.position, settings.max_lights),
        },
        ground: light.ground(camera.position),
    };
    Frame::new(camera, Sky::Atmosphere(sky.clone())).with_objects(layer)
}

fn looking_down(position: DVec3, fov_y_degrees: f64) -> Camera {
    Camera {
        position,
        // Down −z, north up the image.
        orientation: DQuat::IDENTITY,
        fov_y: fov_y_degrees.to_radians(),
        aspect: f64::from(SIZE.0) / f64::from(SIZE.1),
        near: 0.1,
        far: None,
    }
}

/// The pixel whose centre sees world point `p`, if on screen.
fn pixel_of(camera: &Camera, p: DVec3) -> Option<(u32, u32)> {
    let clip = camera.projection_matrix() * camera.view_matrix() * p.extend(1.0);
    let ndc = DVec2::new(clip.x, clip.y) / clip.w;
    let x = ((ndc.x + 1.0) * 0.5 * f64::from(SIZE.0)).floor();
    let y = ((1.0 - ndc.y) * 0.5 * f64::from(SIZE.1)).floor();
    (x >= 0.0 && y >= 0.0 && x < f64::from(SIZE.0) && y < f64::from(SIZE.1)).then_some((x as u32, y as u32))
}

/// Where the ray through pixel (x, y)'s centre meets the plane z = 0 (world, metres).
fn ground_point(camera: &Camera, x: f64, y: f64) -> DVec3 {
    let ndc = DVec2::new(
        (x + 0.5) / f64::from(SIZE.0) * 2.0 - 1.0,
        1.0 - (y + 0.5) / f64::from(SIZE.1) * 2.0,
    );
    let d = camera.view_direction(ndc);
    camera.position + d * (-camera.position.z / d.z)
}

/// Linear sRGB radiance (cd/m²) of a spectral irradiance reflected by a Lambertian `albedo`
/// (spectral), `ρ·E/π`.
fn reflected(conversion: &SpectralConversion, albedo: DVec3, irradiance: DVec3) -> DVec3 {
    let c = conversion.linear_srgb(albedo * irradiance / std::f64::consts::PI);
    DVec3::new(c.r, c.g, c.b)
}

fn hdr(frame: &Frame) -> firmament_render::headless::Image<f32> {
    let mut gpu = support::gpu();
    let gpu = &mut *gpu;
    gpu.renderer
        .render_hdr(&gpu.ctx, frame, SIZE.0, SIZE.1)
        .expect("the frame renders")
}

fn rgb(image: &firmament_render::headless::Image<f32>, (x, y): (u32, u32)) -> DVec3 {
    let p = image.pixel(x, y).expect("on the image");
    DVec3::new(p[0].into(), p[1].into(), p[2].into())
}

fn relative(a: DVec3, b: DVec3) -> f64 {
    ((a - b).abs() / b.abs().max(DVec3::splat(1e-9))).max_element()
}

#[test]
fn the_umbra_gets_the_sky_alone_and_the_rest_full_sun() {
    // A sphere of 1 m radius 3 m over the ground, the sun at the zenith, seen from above.
    let sky = support::street_sky(0.0, 90.0);
    let sphere = Arc::new(Mesh::glt_sphere(1.0, 48, 24).expect("a sphere"));
    let camera = looking_down(DVec3::new(0.0, -2.5, 8.0), 50.0);
    let object = SceneObject::new(sphere, DMat4::from_translation(DVec3::new(0.0, 0.0, 3.0)), grey(0.5));
    // The sphere hides the point right under it: look at the umbra beside the sphere's image.
    let image = hdr(&frame(&sky, camera, vec![object], settings()));

    let reference = support::sky_reference(&sky, SKY_IRRADIANCE_PATHS);
    let conversion = sky.atmosphere.spectral_conversion();
    let albedo = sky.atmosphere.medium.ground_albedo;
    // In the umbra (0.9 m from its centre, which is 0.986 m across): the sky alone.
    let umbra = DVec3::new(0.0, -0.9, 0.0);
    let irradiance = reference.ground_irradiance(umbra);
    let want = reflected(&conversion, albedo, irradiance.sky);
    let got = rgb(&image, pixel_of(&camera, umbra).expect("the umbra is on screen"));
    eprintln!("umbra: GPU {got}, f64 sky × albedo / π {want}");
    assert!(relative(got, want) < 0.02, "umbra {got} vs {want}");
    // Outside the penumbra: the sun and the sky.
    for p in [DVec3::new(2.0, -1.0, 0.0), DVec3::new(-1.8, 1.0, 0.0)] {
        let irradiance = reference.ground_irradiance(p);
        let want = reflected(&conversion, albedo, irradiance.sky + irradiance.direct);
        let got = rgb(&image, pixel_of(&camera, p).expect("on screen"));
        eprintln!("lit {p}: GPU {got}, f64 {want}");
        assert!(relative(got, want) < 0.02, "lit {p}: {got} vs {want}");
    }
}

/// The fraction of a uniform disc of unit radius on the lit side of a straight edge at signed
/// distance `s` (in disc radii) from its centre: the visible share of the sun.
fn disc_fraction(s: f64) -> f64 {
    let s = s.clamp(-1.0, 1.0);
    (s.acos() - s * (1.0 - s * s).sqrt()) / std::f64::consts::PI
}

#[test]
fn the_penumbra_is_as_wide_as_the_sun_s_disc_makes_it() {
    // A thin plate 10 m up, its edge at x = 3 m, under a sun of 1° angular radius at the zenith:
    // on the ground the edge is blurred over ±10 m · tan 1° = ±17.5 cm.
    let mut sky = support::street_sky(0.0, 90.0);
    let radius = 1f64.to_radians();
    sky.suns[0].angular_radius = radius;
    let plate = Arc::new(Mesh::cube(1.0).expect("a cube"));
    let model = DMat4::from_translation(DVec3::new(0.0, 0.0, 10.0)) * DMat4::from_scale(DVec3::new(6.0, 6.0, 0.05));
    let camera = looking_down(DVec3::new(3.0, 0.0, 4.0), 30.0);
    // Coarser texels than the other tests so the widest penumbra fits the filter.
    let coarse = ShadowSettings {
        map_size: 512,
        ..settings()
    };
    let image = hdr(&frame(
        &sky,
        camera,
        vec![SceneObject::new(plate, model, grey(0.5))],
        coarse,
    ));

    // The row through the middle of the image: ground x against luminance.
    let row = SIZE.1 / 2;
    let samples: Vec<(f64, f64)> = (0..SIZE.0)
        .map(|x| {
            let p = ground_point(&camera, f64::from(x), f64::from(row));
            let c = rgb(&image, (x, row));
            (p.x, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z)
        })
        .collect();
    let shade = samples.first().expect("a row").1;
    let lit = samples.last().expect("a row").1;
    assert!(lit > 3.0 * shade, "shade {shade} lit {lit}");
    let crossing = |level: f64| {
        let target = shade + level * (lit - shade);
        let i = samples.iter().position(|s| s.1 >= target).expect("the row crosses");
        let (a, b) = (samples[i - 1], samples[i]);
        a.0 + (target - a.1) / (b.1 - a.1) * (b.0 - a.0)
    };
    let measured = crossing(0.9) - crossing(0.1);
    // The closed form: where the visible share of a uniform disc reaches 10 % and 90 %.
    let half_width = (10.0 - 0.025) * radius.tan();
    let solve = |f: f64| {
        let (mut lo, mut hi) = (-1.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            // disc_fraction falls from 1 to 0 as s goes from −1 to 1.
            if disc_fraction(mid) > f { lo = mid } else { hi = mid }
        }
        lo
    };
    let expected = (solve(0.1) - solve(0.9)) * half_width;
    eprintln!("penumbra 10–90 %: measured {measured:.4} m, disc {expected:.4} m");
    assert!((measured / expected - 1.0).abs() < 0.2, "{measured} vs {expected}");
}

#[test]
fn a_moving_camera_moves_no_shadow_edge() {
    // A low sun: a block's long shadow, its edge found on the ground from two camera positions
    // 1 m apart. Where each image puts the edge (in metres on the ground) must agree to within
    // one pixel's footprint there.
    let sky = support::street_sky(100.0, 25.0);
    let block = Arc::new(Mesh::cube(1.0).expect("a cube"));
    let model = DMat4::from_translation(DVec3::new(0.0, 0.0, 1.5)) * DMat4::from_scale(DVec3::new(1.0, 1.0, 3.0));
    let edge = |camera: Camera| {
        let image = hdr(&frame(
            &sky,
            camera,
            vec![SceneObject::new(block.clone(), model, grey(0.5))],
            settings(),
        ));
        // Along the line y = −0.2 m the shadow (cast west by north, away from the sun) covers
        // x from about −2.2 m to the block: find where the lit ground (x = −7 m) turns to shade
        // (x = −1.2 m), halfway between the two.
        let luminance = |x: f64| rgb(&image, pixel_of(&camera, DVec3::new(x, -0.2, 0.0)).expect("on screen")).y;
        let (lit, shade) = (luminance(-7.0), luminance(-1.2));
        assert!(lit > 3.0 * shade, "lit {lit} shade {shade}");
        let half = 0.5 * (lit + shade);
        let mut previous = (-7.0, lit);
        for i in 1..=290 {
            let x = -7.0 + f64::from(i) * 0.02;
            let y = luminance(x);
            if y < half {
                return previous.0 + (previous.1 - half) / (previous.1 - y) * (x - previous.0);
            }
            previous = (x, y);
        }
        panic!("no edge between x = −7 m and −1.2 m");
    };
    let a = looking_down(DVec3::new(-3.0, -1.0, 7.0), 60.0);
    let b = looking_down(DVec3::new(-3.0 + 0.6, -1.0 + 0.8, 7.0), 60.0);
    let (ea, eb) = (edge(a), edge(b));
    let footprint = 2.0 * 7.0 * (30f64.to_radians()).tan() / f64::from(SIZE.1);
    eprintln!("edge at {ea:.4} m and {eb:.4} m; a pixel is {footprint:.4} m");
    assert!((ea - eb).abs() <= footprint, "{ea} vs {eb}");
}

#[test]
fn undersides_get_the_ground_s_bounce_not_the_sky_s_blue() {
    // A white sphere 3 m over grey ground, its lowest point seen from below. Its normal points
    // straight down: it sees the ground alone, never the sky. With the sun at the zenith the
    // ground under it is in its umbra (lit by the sky alone); with the sun 50° up the shadow
    // falls 2.5 m away and the ground under it is sunlit.
    let sphere = Arc::new(Mesh::glt_sphere(1.0, 64, 32).expect("a sphere"));
    let camera = Camera {
        position: DVec3::new(0.0, 0.0, 0.5),
        orientation: DQuat::from_rotation_x(std::f64::consts::PI),
        fov_y: 40f64.to_radians(),
        aspect: f64::from(SIZE.0) / f64::from(SIZE.1),
        near: 0.1,
        far: None,
    };
    let bottom = DVec3::new(0.0, 0.0, 2.0);
    for (elevation, shadowed) in [(90.0, true), (50.0, false)] {
        let sky = support::street_sky(0.0, elevation);
        let object = SceneObject::new(sphere.clone(), DMat4::from_translation(DVec3::Z * 3.0), grey(0.8));
        let image = hdr(&frame(&sky, camera, vec![object], settings()));
        let got = rgb(&image, pixel_of(&camera, bottom).expect("the underside is on screen"));

        let reference = support::sky_reference(&sky, SKY_IRRADIANCE_PATHS);
        let conversion = sky.atmosphere.spectral_conversion();
        let albedo = sky.atmosphere.medium.ground_albedo;
        let irradiance = reference.ground_irradiance(DVec3::ZERO);
        let on_ground = if shadowed {
            irradiance.sky
        } else {
            irradiance.sky + irradiance.direct
        };
        let want = 0.8 * reflected(&conversion, albedo, on_ground);
        let sky_leak = 0.8 * reflected(&conversion, DVec3::ONE, irradiance.sky);
        eprintln!("sun {elevation}°: underside GPU {got}, ground bounce {want}, the sky's would be {sky_leak}");
        assert!(relative(got, want) < 0.03, "sun {elevation}°: {got} vs {want}");
        if !shadowed {
            // Sunlit ground bounces a whiter light than the blue sky's.
            assert!(got.z / got.x < sky_leak.z / sky_leak.x, "{got} vs the sky's {sky_leak}");
        }
    }
}

#[test]
fn light_shafts_take_away_the_single_scattering_the_reference_s_occluders_do() {
    // A black wall 10 m high and 20 m wide with a 4 m gap in the middle, running north-south
    // 30 m west of the origin, the Sun 10° up in the west behind it, hazy air (Mie 25 times the
    // clear day's) over black ground. The camera stands 12 m east of the wall, just north of its
    // shadow, and looks south along it and down at the ground: each ray crosses the shadow of
    // the northern half, the beam through the gap, the shadow of the southern half, and sunlit
    // air again — its edges across the ray, not along it. What the shafts take from a pixel (the
    // frame without shadows less the frame with them) against what the reference loses to the
    // same walls as occluders: single scattering along the ray, without less with. Black
    // surfaces leave nothing else to differ.
    let mut sky = support::street_sky(270.0, 10.0);
    sky.atmosphere.medium.terms[1].scattering *= 25.0;
    sky.atmosphere.medium.terms[1].absorption *= 25.0;
    sky.atmosphere.medium.ground_albedo = DVec3::ZERO;
    let camera = Camera {
        aspect: f64::from(SIZE.0) / f64::from(SIZE.1),
        ..Camera::from_heading_pitch(DVec3::new(-18.0, 14.0, 1.7), 180f64.to_radians(), (-9f64).to_radians())
            .with_fov_y(16f64.to_radians())
    };
    let halves = [
        (DVec3::new(-30.0, -6.0, 5.0), DVec3::new(0.25, 4.0, 5.0)),
        (DVec3::new(-30.0, 6.0, 5.0), DVec3::new(0.25, 4.0, 5.0)),
    ];
    let cube = Arc::new(Mesh::cube(1.0).expect("a cube"));
    let walls = halves
        .iter()
        .map(|&(centre, half)| {
            SceneObject::new(
                cube.clone(),
                DMat4::from_translation(centre) * DMat4::from_scale(half * 2.0),
                grey(0.0),
            )
        })
        .collect();
    let shafts = ShadowSettings {
        distance_m: 80.0,
        ..settings()
    };
    let lit = frame(&sky, camera, walls, shafts);
    let mut unshadowed = lit.clone();
    unshadowed.objects.shadows = Shadows::default();
    let (with, without) = (hdr(&lit), hdr(&unshadowed));

    let conversion = sky.atmosphere.spectral_conversion();
    let occluders: Vec<_> = halves
        .iter()
        .map(|&(center, half_extents)| firmament_core::occluder::Occluder::Box {
            center,
            half_extents,
            orientation: DQuat::IDENTITY,
        })
        .collect();
    // Single scattering only (no paths), 64 Simpson panels: the reference splits them at every
    // shadow edge, and the air between edges is smooth.
    let settings = firmament_core::atmosphere::reference::ReferenceSettings {
        view_steps: 64,
        paths: 1,
        ..Default::default()
    };
    let plain = firmament_core::atmosphere::reference::Reference::new(sky.atmosphere.clone(), &sky.suns, settings);
    let occluded = plain.clone().with_occluders(&occluders);
    let luminance = |c: DVec3| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let mut errors = Vec::new();
    for y in (0..SIZE.1).step_by(4) {
        for x in (0..SIZE.0).step_by(5) {
            let ndc = DVec2::new(
                (f64::from(x) + 0.5) / f64::from(SIZE.0) * 2.0 - 1.0,
                1.0 - (f64::from(y) + 0.5) / f64::from(SIZE.1) * 2.0,
            );
            let ray = firmament_core::geometry::Ray {
                origin: camera.position,
                direction: camera.view_direction(ndc),
            };
            // Both rays end where the GPU's do: at a wall, or on the ground.
            let wall = occluders
                .iter()
                .filter_map(|o| o.hit(&ray))
                .filter(|&(_, far)| far > 0.0)
                .map(|(near, _)| near.max(0.0))
                .fold(f64::INFINITY, f64::min);
            let single = |r: &firmament_core::atmosphere::reference::Reference| {
                let c = conversion.linear_srgb(r.single_scattering_before(&ray, wall).0);
                DVec3::new(c.r, c.g, c.b)
            };
            let want = luminance(single(&plain) - single(&occluded));
            let got = luminance(rgb(&without, (x, y)) - rgb(&with, (x, y)));
            // Rays that pass through shadow: at least a tenth of their sunlight lost to it (a
            // ray grazing an edge loses a sliver, whose ratio says little), and a loss the
            // half-float target resolves (64 of its steps at the pixel's value).
            let pixel = luminance(rgb(&without, (x, y)));
            let half_float_step = 2f64.powi(pixel.max(1e-3).log2().floor() as i32 - 10);
            if want > 0.1 * luminance(single(&plain)) && want > 64.0 * half_float_step {
                errors.push((got / want - 1.0).abs());
            }
        }
    }
    errors.sort_by(f64::total_cmp);
    assert!(errors.len() > 200, "only {} rays cross a shadow", errors.len());
    let median = errors[errors.len() / 2];
    let worst = errors[errors.len() - 1];
    eprintln!(
        "shafts: {} rays, lost light vs the reference: median {:.2} %, worst {:.2} %",
        errors.len(),
        100.0 * median,
        100.0 * worst
    );
    assert!(median < 0.03 && worst < 0.08, "median {median}, worst {worst}");
}

#[test]
fn a_classic_scene_s_shadow_hides_a_light_s_diffuse_term_not_its_ambient_one() {
    // GL lighting (clamped colours) with one world-space directional light straight down: a
    // sphere over a grey quad, seen from above. Under the sphere the quad keeps the light's
    // ambient term and the scene's; beside it, the diffuse term too (the normal faces the light).
    use firmament_core::classic::lighting::{Light, LightModel};
    use firmament_core::classic::scene::{ClassicLighting, LightSpace, SceneLight};
    use firmament_core::classic::shadow::ShadowLight;
    let light = SceneLight {
        light: Light {
            ambient: DVec4::new(0.1, 0.1, 0.1, 1.0),
            diffuse: DVec4::new(0.6, 0.6, 0.6, 1.0),
            specular: DVec4::new(0.0, 0.0, 0.0, 1.0),
            position: DVec4::new(0.0, 0.0, 1.0, 0.0),
            ..Light::gl_default(0)
        },
        space: LightSpace::World,
    };
    let lighting = ClassicLighting {
        lights: vec![light],
        model: LightModel {
            ambient: DVec4::new(0.2, 0.2, 0.2, 1.0),
            ..LightModel::default()
        },
        shading: Shading::Phong,
        specular: SpecularModel::Blinn,
    };
    let material = Material {
        ambient: DVec4::new(0.5, 0.5, 0.5, 1.0),
        diffuse: DVec4::new(0.5, 0.5, 0.5, 1.0),
        specular: DVec4::new(0.0, 0.0, 0.0, 1.0),
        ..Material::default()
    };
    let quad = SceneObject::new(
        Arc::new(Mesh::quad(10.0, 4).expect("a quad")),
        DMat4::IDENTITY,
        material,
    );
    let sphere = SceneObject::new(
        Arc::new(Mesh::glt_sphere(1.0, 32, 16).expect("a sphere")),
        DMat4::from_translation(DVec3::new(0.0, 0.0, 3.0)),
        material,
    );
    let settings = settings();
    let layer = ObjectLayer {
        objects: vec![quad, sphere],
        shadows: Shadows {
            settings: Some(settings),
            lights: ShadowLight::from_classic(&lighting, settings.max_lights),
        },
        lighting: ObjectLighting::Classic(lighting),
        fog: SceneFog::None,
        ground: None,
    };
    let camera = looking_down(DVec3::new(0.0, -2.5, 8.0), 50.0);
    let frame = Frame::new(camera, Sky::Clear(firmament_core::LinearRgb::new(0.0, 0.0, 0.0))).with_objects(layer);
    let image = hdr(&frame);
    // GL: emission 0 + 0.5·0.2 (scene) + 0.5·0.1 (light's ambient) [+ 0.5·0.6·(n·l = 1) lit].
    let (shade, lit) = (0.5 * 0.2 + 0.5 * 0.1, 0.5 * 0.2 + 0.5 * 0.1 + 0.5 * 0.6);
    let umbra = rgb(
        &image,
        pixel_of(&camera, DVec3::new(0.0, -0.9, 0.0)).expect("on screen"),
    );
    let open = rgb(
        &image,
        pixel_of(&camera, DVec3::new(2.5, -1.0, 0.0)).expect("on screen"),
    );
    eprintln!("classic: umbra {umbra}, lit {open}; GL {shade} and {lit}");
    assert!((umbra - DVec3::splat(shade)).abs().max_element() < 2e-3, "{umbra}");
    assert!((open - DVec3::splat(lit)).abs().max_element() < 2e-3, "{open}");
}
