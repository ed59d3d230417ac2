//! What the GPU path gives for one view ray, in the reference's terms: spectral radiance,
//! transmittance to space and ground irradiance (for `firmament sky-sample` and checks).
//!
//! The radiance is a 1 × 1 render of the atmosphere pass converted back from linear sRGB to the
//! model wavelengths; the transmittance and irradiances are read from the pass's own LUTs with
//! the shaders' mappings (mirrored here in `f64`, `atmosphere/common.wgsl` and `luts.wgsl` being
//! the originals).
//!
//! The radiance by order comes from renders whose multiple-scattering LUTs hold fewer orders
//! ([`firmament_render::passes::AtmospherePass::record_medium_luts_to_order`]): holding the
//! light arriving at a point after at most `n` scattering or reflection events, the view (which
//! adds one more) sees orders up to `n + 1`; differences of such renders, and of the whole
//! build, give each band of orders. The part reflected by the ground is what a black ground
//! removes. These renders march the view ray (`SkyMethod::March`): the sky-view LUT scales its
//! texels by the multiple-scattering LUT's level, which is zero without orders. The LUT path's
//! radiance differs from the march's by the sky-view LUT's filtering.

use firmament_core::Camera;
use firmament_core::atmosphere::Spectrum;
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

use firmament_render::FrameTargets;
use firmament_render::GpuContext;
use firmament_render::RenderError;
use firmament_render::gpu_types::atmosphere::lut_bottom_radius;
use firmament_render::passes::atmosphere::luts::{IRRADIANCE_SIZE, LOG_FLOOR, TRANSMITTANCE_SIZE};
use firmament_render::passes::{AtmospherePass, SkyMethod};
use firmament_render::readback::{decode_f16, read_texture};
use firmament_render::wgpu;

/// The GPU path's answer for one view ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GpuSkySample {
    /// Spectral radiance along the view, W·m⁻²·sr⁻¹·nm⁻¹ (sun discs included).
    pub(crate) radiance: Spectrum,
    /// The marched radiance by the number of times its light was scattered or reflected: once
    /// (with any sun disc in view), twice, three or four times, five times or more.
    pub(crate) by_order: [Spectrum; 4],
    /// The part of the marched radiance reflected by the ground at least once.
    pub(crate) via_ground: Spectrum,
    /// Transmittance from the eye along the view to space (0 when the view meets the ground).
    pub(crate) transmittance: Spectrum,
    /// Sky irradiance on the horizontal ground below the eye, W·m⁻²·nm⁻¹.
    pub(crate) sky_irradiance: Spectrum,
    /// Direct sun irradiance on the horizontal ground below the eye, W·m⁻²·nm⁻¹.
    pub(crate) sun_irradiance: Spectrum,
}

/// A LUT read back as RGBA `f64` texels, sampled bilinearly like `load_bilinear`.
struct CpuLut {
    size: (u32, u32),
    texels: Vec<[f64; 4]>,
}

impl CpuLut {
    fn read(ctx: &GpuContext, texture: &wgpu::Texture, size: (u32, u32)) -> Result<Self, RenderError> {
        let bytes = read_texture(ctx, texture)?;
        let channels: Vec<f64> = match texture.format() {
            wgpu::TextureFormat::Rgba32Float => bytes
                .chunks_exact(4)
                .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
                .collect(),
            _ => decode_f16(&bytes).into_iter().map(f64::from).collect(),
        };
        let texels = channels.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
        Ok(Self { size, texels })
    }

    fn sample(&self, u: f64, v: f64) -> Spectrum {
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let x = (u * w - 0.5).clamp(0.0, w - 1.0);
        let y = (v * h - 0.5).clamp(0.0, h - 1.0);
        let (i, j) = (x.floor() as u32, y.floor() as u32);
        let (fx, fy) = (x - x.floor(), y - y.floor());
        let (i1, j1) = ((i + 1).min(self.size.0 - 1), (j + 1).min(self.size.1 - 1));
        let at = |i: u32, j: u32| {
            let t = self.texels[(j * self.size.0 + i) as usize];
            Spectrum::new(t[0], t[1], t[2])
        };
        let top = at(i, j).lerp(at(i1, j), fx);
        let bottom = at(i, j1).lerp(at(i1, j1), fx);
        top.lerp(bottom, fy)
    }
}

fn unit_to_texel(x: f64, size: u32) -> f64 {
    let n = f64::from(size);
    0.5 / n + x * (1.0 - 1.0 / n)
}

/// The LUT sphere: bottom and top radius, metres.
struct LutSphere {
    bottom: f64,
    top: f64,
}

impl LutSphere {
    fn hits_ground(&self, r: f64, mu: f64) -> bool {
        mu < 0.0 && r * r * (mu * mu - 1.0) + self.bottom * self.bottom >= 0.0
    }

    /// Bruneton's transmittance-LUT coordinates of (r, mu).
    fn transmittance_uv(&self, r: f64, mu: f64) -> (f64, f64) {
        let big_h = (self.top * self.top - self.bottom * self.bottom).sqrt();
        let rho = (r * r - self.bottom * self.bottom).max(0.0).sqrt();
        let d = (-r * mu + (r * r * (mu * mu - 1.0) + self.top * self.top).max(0.0).sqrt()).max(0.0);
        let (d_min, d_max) = (self.top - r, rho + big_h);
        let x_mu = (d - d_min) / (d_max - d_min).max(1e-3);
        (
            unit_to_texel(x_mu, TRANSMITTANCE_SIZE.0),
            unit_to_texel(rho / big_h, TRANSMITTANCE_SIZE.1),
        )
    }
}

/// Samples the GPU path for the view ray from world `position` along `view` (unit, world),
/// with the ground irradiances taken at `ground` (a world point on the surface).
pub(crate) fn sample_sky(
    ctx: &GpuContext,
    sky: &AtmosphereSky,
    position: DVec3,
    view: DVec3,
    ground: DVec3,
) -> Result<GpuSkySample, RenderError> {
    let camera = Camera::looking_at(position, position + view, DVec3::Z)
        .or_else(|| Camera::looking_at(position, position + view, DVec3::Y))
        .ok_or_else(|| RenderError::Readback("the view direction must be finite and non-zero".into()))?;
    let camera = Camera {
        fov_y: 0.01f64.to_radians(),
        aspect: 1.0,
        ..camera
    };
    let mut pass = AtmospherePass::new(&ctx.device);
    let atmosphere = &sky.atmosphere;
    let to_spectrum = atmosphere.spectral_conversion().to_linear_srgb_matrix().inverse();
    let mut render = |sky: &AtmosphereSky, method: SkyMethod, luts: Luts| -> Result<Spectrum, RenderError> {
        pass.set_method(method);
        pass.prepare(&ctx.queue, sky, &camera);
        Ok(to_spectrum * render_pixel(ctx, &pass, luts)?)
    };
    let mut black_ground = sky.clone();
    black_ground.atmosphere.medium.ground_albedo = Spectrum::ZERO;
    black_ground.surface = None;
    let without_ground = render(&black_ground, SkyMethod::March, Luts::Whole)?;
    let mut marched = [Spectrum::ZERO; 3];
    for (radiance, orders) in marched.iter_mut().zip([0, 1, 3]) {
        *radiance = render(sky, SkyMethod::March, Luts::ToOrder(orders))?;
    }
    let [up_to_1, up_to_2, up_to_4] = marched;
    let total = render(sky, SkyMethod::March, Luts::Whole)?;
    // The same LUTs through the sky-view LUT; also those read below.
    let radiance = render(sky, SkyMethod::Lut, Luts::Built)?;
    let by_order = [up_to_1, up_to_2 - up_to_1, up_to_4 - up_to_2, total - up_to_4];

    let transmittance_lut = CpuLut::read(ctx, &pass.luts().transmittance.texture, TRANSMITTANCE_SIZE)?;
    let irradiance_lut = CpuLut::read(ctx, &pass.luts().irradiance.texture, IRRADIANCE_SIZE)?;

    let planet = &atmosphere.planet;
    let sphere = LutSphere {
        bottom: lut_bottom_radius(atmosphere),
        top: lut_bottom_radius(atmosphere) + planet.atmosphere_height,
    };
    let transmittance_to_top = |h: f64, mu: f64| {
        let r = sphere.bottom + h.max(0.0);
        if sphere.hits_ground(r, mu) {
            return Spectrum::ZERO;
        }
        let (u, v) = sphere.transmittance_uv(r, mu);
        // The LUT holds the optical depth (`transmittance_to_top` in the shaders).
        (-transmittance_lut.sample(u, v)).exp()
    };
    let eye = planet.to_planet_frame(position);
    let eye_up = planet.up(eye);
    let transmittance = transmittance_to_top(planet.altitude(eye), planet.direction_to_planet_frame(view).dot(eye_up));

    let foot = planet.to_planet_frame(ground);
    let up = planet.up(foot);
    let (mut sky_irradiance, mut sun_irradiance) = (Spectrum::ZERO, Spectrum::ZERO);
    for sun in &sky.suns {
        let mu_s = planet.direction_to_planet_frame(sun.direction).normalize().dot(up);
        // The shaders' `mu_s_to_unit`.
        let u = unit_to_texel(0.5 + 0.5 * mu_s.signum() * mu_s.abs().sqrt(), IRRADIANCE_SIZE.0);
        // Stored as its logarithm (`decode_log` in the shaders).
        let stored = irradiance_lut.sample(u, unit_to_texel(0.0, IRRADIANCE_SIZE.1));
        let decoded = Spectrum::from(stored.to_array().map(|v| if v <= LOG_FLOOR { 0.0 } else { v.exp() }));
        sky_irradiance += sun.irradiance * decoded;
        sun_irradiance += sun.irradiance * transmittance_to_top(0.0, mu_s) * mu_s.max(0.0);
    }
    Ok(GpuSkySample {
        radiance,
        by_order,
        via_ground: total - without_ground,
        transmittance,
        sky_irradiance,
        sun_irradiance,
    })
}

/// Which medium LUTs a render of [`render_pixel`] draws from.
#[derive(Debug, Clone, Copy)]
enum Luts {
    /// Those built before.
    Built,
    /// A whole build.
    Whole,
    /// A build holding the orders up to this one alone.
    ToOrder(u32),
}

/// Renders the pixel of the view `pass` was last prepared with, linear sRGB, from `luts`.
fn render_pixel(ctx: &GpuContext, pass: &AtmospherePass, luts: Luts) -> Result<DVec3, RenderError> {
    // New textures start zeroed: black, and depth at the far plane, so the sky fills the pixel.
    let targets = FrameTargets::new(&ctx.device, 1, 1);
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("firmament sample_sky encoder"),
    });
    match luts {
        Luts::Built => {}
        Luts::Whole => pass.record_medium_luts(&mut encoder),
        Luts::ToOrder(orders) => pass.record_medium_luts_to_order(&mut encoder, orders),
    }
    pass.record_sky_view_lut(&mut encoder);
    pass.record(&mut encoder, &targets.hdr_view, &targets.depth_view);
    ctx.queue.submit([encoder.finish()]);
    let pixel = decode_f16(&read_texture(ctx, &targets.hdr)?);
    Ok(DVec3::new(
        f64::from(pixel[0]),
        f64::from(pixel[1]),
        f64::from(pixel[2]),
    ))
}
