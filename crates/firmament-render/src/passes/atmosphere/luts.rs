//! The atmosphere's look-up tables: their sizes, formats and textures.
//!
//! | LUT | size | format | axes |
//! |---|---|---|---|
//! | transmittance (stored as the optical depth) | 256 × 64 | Rgba32Float | Bruneton's (x_mu, x_r) on the LUT sphere |
//! | multiple scattering (the moments Ψ, zz, xx, xz, x, z, stored as ln Ψ (alpha: a thick air's second difference of ln Ψ down the column) and the rest over Ψ; spherical-harmonic band 4 in the alphas of zz, xx, xz, x, z and band 3 in a seventh layer, over Ψ summed over wavelengths) | 32 × 32, seven layers of one array | Rgba16Float | mu_s ∈ [−1, 1] (√ mapping, dense at the horizon), h ∈ [0, H] (a thick air's rows at `lut_rows`) |
//! | sky irradiance (stored as its logarithm, as Ψ) | 32 × 32 | Rgba16Float | mu_s ∈ [−1, 1] (√ mapping), h ∈ [0, H] (as above) |
//! | sky view (rgb over 2^a) | 192·8 × 108 | Rgba16Float | one tile per sun: azimuth from the sun ∈ [0, π], Hillaire's zenith mapping |
//! | aerial perspective (scattering, transmittance) | 32 × 32 × 32, as 32 slices side by side | Rgba16Float | screen u, v; distance into the air = range · w² |
//!
//! Every LUT is written by a compute pass (the moments and the sky irradiance through a buffer and
//! copies, see `multiscattering.rs`). The sizes are mirrored by constants in `atmosphere/common.wgsl`,
//! `luts.wgsl`, `view.wgsl` and `multiscattering_lut.wgsl`.

use firmament_core::frame::MAX_SUNS;

use crate::gpu_types::AtmosphereParamsUniforms;

/// Transmittance LUT size (texels): x_mu × x_r.
pub const TRANSMITTANCE_SIZE: (u32, u32) = (256, 64);
/// Transmittance LUT format: half floats would take half of the 0.1 % error budget. Written by a
/// compute pass, since GL adapters cannot render to it.
pub const TRANSMITTANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// Multiple-scattering LUT size (texels): mu_s × h.
pub const MULTISCATTERING_SIZE: (u32, u32) = (32, 32);
const _: () = assert!(
    MULTISCATTERING_SIZE.1 as usize == crate::gpu_types::medium::LUT_ROWS,
    "the rows a thick air's LUT places (gpu_types::medium::multiscattering_lut_rows)"
);
/// Number of multiple-scattering moments, the layers of their array texture (`Moments` in
/// `atmosphere/luts.wgsl`).
pub const MULTISCATTERING_MOMENTS: usize = 7;

/// Multiple-scattering LUT format.
pub const MULTISCATTERING_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Sky irradiance LUT size (texels): mu_s × h, those of the multiple-scattering LUT (both are
/// written from the same rays).
pub const IRRADIANCE_SIZE: (u32, u32) = MULTISCATTERING_SIZE;
/// What the multiple-scattering Ψ and the sky irradiance LUT store for "none": the logarithm's
/// floor (mirrors `LOG_FLOOR` in `atmosphere/luts.wgsl`; both tables store logarithms).
pub const LOG_FLOOR: f64 = -69.0;
/// Sky irradiance LUT format.
pub const IRRADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// One sun's sky-view tile (texels): azimuth × zenith.
pub const SKY_VIEW_TILE: (u32, u32) = (192, 108);
/// Sky-view LUT format.
pub const SKY_VIEW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Aerial-perspective volume size (texels): screen x × screen y × distance slices. Stored as a
/// 2D atlas, the slices side by side (`x · z` × `y`): GL binds 3D storage textures one layer at
/// a time.
pub const AERIAL_PERSPECTIVE_SIZE: (u32, u32, u32) = (32, 32, 32);
/// Aerial-perspective volume format (written by a compute pass, filtered when read).
pub const AERIAL_PERSPECTIVE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// A LUT texture and its view.
#[derive(Debug)]
pub struct Lut {
    /// The texture (also copyable, for tests and tools).
    pub texture: wgpu::Texture,
    /// Its one view.
    pub view: wgpu::TextureView,
}

impl Lut {
    /// A 2D LUT of `format`, sampled and copyable both ways (a finished build is copied into the
    /// live set), written as `written_by` says.
    pub(super) fn new(
        device: &wgpu::Device,
        name: &str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        written_by: wgpu::TextureUsages,
    ) -> Self {
        Self::with_layers(device, name, size, 1, format, written_by)
    }

    /// The same with `layers` layers, viewed as a 2D array when there are several.
    pub(super) fn with_layers(
        device: &wgpu::Device,
        name: &str,
        (width, height): (u32, u32),
        layers: u32,
        format: wgpu::TextureFormat,
        written_by: wgpu::TextureUsages,
    ) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&format!("firmament AtmospherePass {name} LUT")),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: written_by
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(if layers > 1 {
                wgpu::TextureViewDimension::D2Array
            } else {
                wgpu::TextureViewDimension::D2
            }),
            ..Default::default()
        });
        Self { texture, view }
    }
}

/// The LUTs that depend on the medium alone — transmittance, the multiple-scattering moments, the
/// sky irradiance — for the set the sky reads or the one a rebuild writes (`suffix` ends their
/// labels).
pub(super) fn medium_luts(device: &wgpu::Device, suffix: &str) -> (Lut, Lut, Lut) {
    let transmittance = Lut::new(
        device,
        &format!("transmittance{suffix}"),
        TRANSMITTANCE_SIZE,
        TRANSMITTANCE_FORMAT,
        wgpu::TextureUsages::STORAGE_BINDING,
    );
    let multiscattering = Lut::with_layers(
        device,
        &format!("multiple-scattering moments{suffix}"),
        MULTISCATTERING_SIZE,
        MULTISCATTERING_MOMENTS as u32,
        MULTISCATTERING_FORMAT,
        wgpu::TextureUsages::empty(),
    );
    let irradiance = Lut::new(
        device,
        &format!("sky irradiance{suffix}"),
        IRRADIANCE_SIZE,
        IRRADIANCE_FORMAT,
        wgpu::TextureUsages::empty(),
    );
    (transmittance, multiscattering, irradiance)
}

/// Every LUT of the atmosphere pass.
#[derive(Debug)]
pub struct AtmosphereLuts {
    /// Transmittance to the top of the atmosphere.
    pub transmittance: Lut,
    /// Multiple scattering: moments of the radiance (orders ≥ 1) arriving at each point, one per
    /// layer of a 2D array texture — the mean Ψ, then the means of radiance × ωz², × ωx², × ωx·ωz,
    /// × ωx, × ωz (x towards the sun's azimuth, z up), then band 3 (layout in the table above).
    pub multiscattering: Lut,
    /// Sky irradiance on a horizontal surface per unit sun irradiance (its logarithm).
    pub irradiance: Lut,
    /// Sky-view radiance, one tile per sun.
    pub sky_view: Lut,
    /// Aerial perspective: light scattered towards the camera (spectral radiance, all suns).
    pub aerial_scattering: Lut,
    /// Aerial perspective: transmittance from the camera.
    pub aerial_transmittance: Lut,
}

impl AtmosphereLuts {
    /// Creates the textures (contents undefined until the pass renders them).
    pub fn new(device: &wgpu::Device) -> Self {
        let (transmittance, multiscattering, irradiance) = medium_luts(device, "");
        let (x, y, z) = AERIAL_PERSPECTIVE_SIZE;
        let aerial_atlas = (x * z, y);
        Self {
            transmittance,
            multiscattering,
            irradiance,
            sky_view: Lut::new(
                device,
                "sky-view",
                (SKY_VIEW_TILE.0 * MAX_SUNS as u32, SKY_VIEW_TILE.1),
                SKY_VIEW_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING,
            ),
            aerial_scattering: Lut::new(
                device,
                "aerial-perspective scattering",
                aerial_atlas,
                AERIAL_PERSPECTIVE_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING,
            ),
            aerial_transmittance: Lut::new(
                device,
                "aerial-perspective transmittance",
                aerial_atlas,
                AERIAL_PERSPECTIVE_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING,
            ),
        }
    }
}

/// The textures and the medium uniform the build stages write and read.
#[derive(Debug)]
pub(super) struct MediumLuts {
    pub(super) transmittance: Lut,
    pub(super) multiscattering: Lut,
    pub(super) irradiance: Lut,
    /// The medium being built (an `AtmosphereParamsUniforms`).
    pub(super) params: wgpu::Buffer,
}

impl MediumLuts {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let (transmittance, multiscattering, irradiance) = medium_luts(device, " (building)");
        Self {
            transmittance,
            multiscattering,
            irradiance,
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("firmament AtmospherePass params (building)"),
                size: std::mem::size_of::<AtmosphereParamsUniforms>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
        }
    }

    /// Encodes the copy of the finished set into `live` and of the medium into `live_params`.
    pub(super) fn copy_into(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        live: &AtmosphereLuts,
        live_params: &wgpu::Buffer,
    ) {
        let pairs = [
            (&self.transmittance, &live.transmittance),
            (&self.multiscattering, &live.multiscattering),
            (&self.irradiance, &live.irradiance),
        ];
        for (from, to) in pairs {
            encoder.copy_texture_to_texture(
                from.texture.as_image_copy(),
                to.texture.as_image_copy(),
                from.texture.size(),
            );
        }
        encoder.copy_buffer_to_buffer(&self.params, 0, live_params, 0, self.params.size());
    }
}
