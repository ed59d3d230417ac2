//! Helpers shared by the GPU tests: one context and renderer for the whole binary, the device an
//! embedder makes, and the skies and references several modules need.

/// Clears `targets` to `color` and reversed-Z `depth` in a pass of its own.
pub(crate) fn clear_targets(
    encoder: &mut wgpu::CommandEncoder,
    targets: &firmament_render::FrameTargets,
    color: wgpu::Color,
    depth: f32,
) {
    let _clear = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("test clear"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &targets.hdr_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(color),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &targets.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(depth),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    });
}

/// A context and headless renderer shared by the whole test binary.
pub(crate) struct Gpu {
    pub(crate) ctx: firmament_render::GpuContext,
    pub(crate) renderer: firmament_render::headless::HeadlessRenderer,
}

/// One context for the whole test binary; tests take turns (software rasterizers fight). Tests that
/// make devices of their own hold it too, for their turn.
pub(crate) fn gpu() -> std::sync::MutexGuard<'static, Gpu> {
    use std::sync::{Mutex, OnceLock};
    static GPU: OnceLock<Mutex<Gpu>> = OnceLock::new();
    GPU.get_or_init(|| {
        let ctx = firmament_render::GpuContext::headless(firmament_render::Backend::Auto)
            .unwrap_or_else(|e| panic!("GPU tests need an adapter and found none: {e}"));
        let renderer = firmament_render::headless::HeadlessRenderer::new(&ctx);
        Mutex::new(Gpu { ctx, renderer })
    })
    .lock()
    .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A device of the caller's own, made the way an embedder makes it: firmament's required features
/// and limits, nothing optional (no GPU timestamps). `label` names the test.
pub(crate) fn user_context(label: &str) -> firmament_render::GpuContext {
    let instance = wgpu::Instance::default();
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .unwrap_or_else(|e| panic!("GPU tests need an adapter and found none: {e}"));
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some(label),
        required_features: firmament_render::required_features(),
        required_limits: firmament_render::required_limits().using_resolution(adapter.limits()),
        ..Default::default()
    }))
    .unwrap_or_else(|e| panic!("the adapter refused a device with firmament's requirements: {e}"));
    firmament_render::GpuContext::from_device(device, queue).expect("a device with firmament's requirements")
}

/// A unit direction at `azimuth` (from north, clockwise) and `elevation`, degrees, East-North-Up.
pub(crate) fn direction(azimuth: f64, elevation: f64) -> glam::DVec3 {
    firmament_core::camera::direction_from_heading_elevation(azimuth.to_radians(), elevation.to_radians())
}

/// Earth on Bruneton's sphere, posed so the world is ENU at (0°, 0°), one sun at `sun_azimuth`,
/// `sun_elevation` degrees.
pub(crate) fn street_sky(sun_azimuth: f64, sun_elevation: f64) -> firmament_core::frame::AtmosphereSky {
    use firmament_core::atmosphere::{Planet, presets};
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0).posed_at(0.0, 0.0);
    firmament_core::frame::AtmosphereSky {
        atmosphere,
        suns: vec![presets::earth_sun(direction(sun_azimuth, sun_elevation))],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    }
}

/// The f64 reference for `sky`'s atmosphere and suns with `paths` Monte Carlo paths per radiance.
pub(crate) fn sky_reference(
    sky: &firmament_core::frame::AtmosphereSky,
    paths: usize,
) -> firmament_core::atmosphere::reference::Reference {
    use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
    Reference::new(
        sky.atmosphere.clone(),
        &sky.suns,
        ReferenceSettings {
            paths,
            ..Default::default()
        },
    )
}

/// At the origin looking down −z with a 45° vertical field of view (NeHe's lesson 44), near plane
/// 0.5 m, far plane 1 km, for a `width` × `height` image.
pub(crate) fn origin_camera_45(width: u32, height: u32) -> firmament_core::Camera {
    firmament_core::Camera {
        position: glam::DVec3::ZERO,
        orientation: glam::DQuat::IDENTITY,
        fov_y: 45f64.to_radians(),
        aspect: f64::from(width) / f64::from(height),
        near: 0.5,
        far: Some(1000.0),
    }
}

/// The GPU's linear sRGB (cd/m²) along the centre of a 1×1 image of `sky` from `eye` towards
/// `view` (world frame): a point's radiance, the pixel 0.01° across (a body under a few pixels
/// across is drawn by its coverage of the pixel; none is that small here).
pub(crate) fn centre_radiance(
    gpu: &mut Gpu,
    sky: &firmament_core::frame::AtmosphereSky,
    eye: glam::DVec3,
    view: glam::DVec3,
) -> glam::DVec3 {
    centre_radiance_in_pixel(gpu, sky, eye, view, 0.01f64.to_radians())
}

/// [`centre_radiance`] with a pixel `pixel_rad` radians across.
pub(crate) fn centre_radiance_in_pixel(
    gpu: &mut Gpu,
    sky: &firmament_core::frame::AtmosphereSky,
    eye: glam::DVec3,
    view: glam::DVec3,
    pixel_rad: f64,
) -> glam::DVec3 {
    use firmament_core::Camera;
    let camera = Camera::looking_at(eye, eye + view, glam::DVec3::Z)
        .or_else(|| Camera::looking_at(eye, eye + view, glam::DVec3::X))
        .expect("a view direction");
    let frame = firmament_core::Frame::new(
        Camera {
            fov_y: pixel_rad,
            ..camera
        },
        firmament_core::frame::Sky::Atmosphere(sky.clone()),
    );
    let Gpu { ctx, renderer } = gpu;
    let image = renderer.render_hdr(ctx, &frame, 1, 1).expect("render");
    let p = image.pixel(0, 0).expect("inside");
    glam::DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// `sky` seen from `towards_eye` × 1 AU and × 100 AU (world frame, towards the origin), each with
/// a field of view of 2.4 body radii `radius_m` at its distance, `size` pixels square: the
/// largest difference of any pixel over the near image's brightest, and how many of its pixels
/// are brighter than 5 % of that.
pub(crate) fn far_view_difference(
    gpu: &mut Gpu,
    sky: &firmament_core::frame::AtmosphereSky,
    towards_eye: glam::DVec3,
    radius_m: f64,
    size: u32,
) -> (f64, u32) {
    use firmament_core::{Camera, Frame};
    let au = firmament_core::atmosphere::presets::ASTRONOMICAL_UNIT;
    let mut image = |distance: f64| {
        let eye = towards_eye * distance;
        let camera = Camera::looking_at(eye, glam::DVec3::ZERO, glam::DVec3::Z).expect("a camera");
        let fov = 2.4 * radius_m / distance;
        let frame = Frame::new(
            Camera { fov_y: fov, ..camera },
            firmament_core::frame::Sky::Atmosphere(sky.clone()),
        );
        let Gpu { ctx, renderer } = &mut *gpu;
        renderer.render_hdr(ctx, &frame, size, size).expect("render")
    };
    let near = image(au);
    let far = image(100.0 * au);
    let value = |image: &firmament_render::headless::Image<f32>, x, y| {
        let p = image.pixel(x, y).expect("inside");
        glam::DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
    };
    let pixels = || (0..size).flat_map(move |y| (0..size).map(move |x| (x, y)));
    let brightest = pixels()
        .map(|(x, y)| value(&near, x, y).max_element())
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    let mut lit = 0;
    for (x, y) in pixels() {
        let (a, b) = (value(&near, x, y), value(&far, x, y));
        if a.max_element() > 0.05 * brightest {
            lit += 1;
        }
        worst = worst.max((a - b).abs().max_element() / brightest);
    }
    (worst, lit)
}

/// An equirectangular map's flux through a horizontal plane: `∫ L·|cos θ| dω` over the upper
/// hemisphere (the irradiance on an upward normal) or the lower one, each pixel weighted by its
/// exact `∫ |cos θ| dω` (`(2π/W)·|sin² θ₁ − sin² θ₀|/2`).
pub(crate) fn hemisphere_flux(map: &firmament_render::headless::Image<f32>, upper: bool) -> glam::DVec3 {
    let (w, h) = (map.width, map.height);
    let theta = |j: u32| std::f64::consts::PI * f64::from(j) / f64::from(h);
    let rows = if upper { 0..h / 2 } else { h / 2..h };
    rows.map(|j| {
        let weight =
            std::f64::consts::TAU / f64::from(w) * 0.5 * (theta(j + 1).sin().powi(2) - theta(j).sin().powi(2)).abs();
        (0..w)
            .map(|i| {
                let p = map.pixel(i, j).expect("inside");
                glam::DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
            })
            .sum::<glam::DVec3>()
            * weight
    })
    .sum()
}
