//! The multiple-scattering LUTs by fixed-point iteration (see `atmosphere/multiscattering_lut.wgsl`).
//!
//! Each iterate is one compute dispatch (a workgroup per texel, an invocation per direction) that
//! reads the build set's moments (Ψ, zz, xx, xz, x, z, bands 3 and 4) and the ground sky
//! irradiance row E, and writes the next ones into a buffer of packed `Rgba16Float` texels; copies
//! then move the buffer into those textures, so the last iterate leaves its moments in the build
//! set ([`MediumLuts`], copied into
//! [`AtmosphereLuts::multiscattering`](super::AtmosphereLuts::multiscattering) when done). A
//! buffer rather than storage textures: seven moments are more storage textures than GL-class
//! devices bind at once.

use half::f16;
use wgpu::util::DeviceExt;

use super::luts::MediumLuts;
use super::luts::{LOG_FLOOR, Lut, MULTISCATTERING_FORMAT, MULTISCATTERING_MOMENTS, MULTISCATTERING_SIZE};
use super::stages::{
    ComputeStage, binding, moment_entries, moment_resources, sampler_entry, storage_buffer_entry, texture_entry,
    uniform_entry,
};
use crate::shaders;

/// Iterates after the first (single scattering and the sunlit ground): iterate k holds orders up
/// to k + 1, so the LUTs hold orders 1 to 10 of the light arriving at a point (the issue asks for
/// at least 10; a view adds one more scattering).
pub const MULTISCATTERING_ITERATIONS: u32 = 9;

/// Bytes of one `Rgba16Float` texel.
const TEXEL_BYTES: u32 = 8;

/// Texels of one moment texture.
const MOMENT_TEXELS: u32 = MULTISCATTERING_SIZE.0 * MULTISCATTERING_SIZE.1;

/// Bytes of an iterate's output: the seven moment textures, then the ground row (the layout of
/// `multiscattering_out` in `multiscattering_lut.wgsl`).
const OUTPUT_BYTES: u64 = ((MULTISCATTERING_MOMENTS as u32 * MOMENT_TEXELS + MULTISCATTERING_SIZE.0) * TEXEL_BYTES) as u64;

/// The iteration: its compute stage, its output buffer, the start (zero as stored) and the ground
/// irradiance row.
#[derive(Debug)]
pub(super) struct MultiscatteringStages {
    iterate: ComputeStage,
    /// An iterate's output, packed texels.
    output: wgpu::Buffer,
    /// The iteration's start in the same layout: zero as each texture stores it.
    start: wgpu::Buffer,
    /// E, the ground's sky irradiance row the next iterate reads.
    ground: Lut,
}

impl MultiscatteringStages {
    pub(super) fn new(device: &wgpu::Device, luts: &MediumLuts, sampler: &wgpu::Sampler) -> Self {
        let ground = Lut::new(
            device,
            "multiple-scattering ground irradiance",
            (MULTISCATTERING_SIZE.0, 1),
            MULTISCATTERING_FORMAT,
            wgpu::TextureUsages::empty(),
        );
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament AtmospherePass multiple-scattering iterate"),
            size: OUTPUT_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let start = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("firmament AtmospherePass multiple-scattering start"),
            contents: &start_texels(),
            usage: wgpu::BufferUsages::COPY_SRC,
        });

        let mut entries = vec![
            uniform_entry(binding::PARAMS),
            texture_entry(binding::TRANSMITTANCE, false),
            sampler_entry(binding::SAMPLER),
            texture_entry(binding::PREVIOUS_GROUND_IRRADIANCE, true),
            storage_buffer_entry(binding::MULTISCATTERING_OUT),
        ];
        entries.extend(moment_entries(binding::MULTISCATTERING_MOMENTS));
        let mut resources = vec![
            (binding::PARAMS, luts.params.as_entire_binding()),
            (
                binding::TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.transmittance.view),
            ),
            (binding::SAMPLER, wgpu::BindingResource::Sampler(sampler)),
            (
                binding::PREVIOUS_GROUND_IRRADIANCE,
                wgpu::BindingResource::TextureView(&ground.view),
            ),
            (binding::MULTISCATTERING_OUT, output.as_entire_binding()),
        ];
        resources.extend(moment_resources(
            binding::MULTISCATTERING_MOMENTS,
            luts.multiscattering_views(),
        ));
        let iterate = ComputeStage::new(
            device,
            "AtmospherePass multiple-scattering LUT",
            &shaders::ATMOSPHERE_MULTISCATTERING_LUT,
            &entries,
            &resources,
        );
        Self {
            iterate,
            output,
            start,
            ground,
        }
    }

    /// Encodes the iteration's start: the build set's moments and the ground row set to zero
    /// (after the transmittance LUT).
    pub(super) fn record_start(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts) {
        self.record_copy(encoder, &self.start, luts);
    }

    /// Encodes the next iterate (after [`record_start`](Self::record_start) and the iterates
    /// before it): it leaves its moments in `luts`.
    pub(super) fn record_iterate(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts) {
        let (width, height) = MULTISCATTERING_SIZE;
        // One workgroup per texel, and a row more for the ground's irradiance.
        self.iterate.dispatch(encoder, (width, height + 1, 1));
        self.record_copy(encoder, &self.output, luts);
    }

    /// Encodes the copies of `texels` (an iterate's layout) into the moments and the ground row.
    fn record_copy(&self, encoder: &mut wgpu::CommandEncoder, texels: &wgpu::Buffer, luts: &MediumLuts) {
        let (width, height) = MULTISCATTERING_SIZE;
        let targets = luts.multiscattering.iter().map(|lut| (lut, height));
        for (k, (lut, rows)) in targets.chain(std::iter::once((&self.ground, 1))).enumerate() {
            encoder.copy_buffer_to_texture(
                wgpu::TexelCopyBufferInfo {
                    buffer: texels,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: u64::from(k as u32 * MOMENT_TEXELS * TEXEL_BYTES),
                        bytes_per_row: Some(width * TEXEL_BYTES),
                        rows_per_image: Some(rows),
                    },
                },
                lut.texture.as_image_copy(),
                wgpu::Extent3d {
                    width,
                    height: rows,
                    depth_or_array_layers: 1,
                },
            );
        }
    }
}

/// The iteration's start as packed `Rgba16Float` texels: zero as each texture stores it — Ψ and
/// E (logarithms) as (LOG_FLOOR, LOG_FLOOR, LOG_FLOOR, 1), the other moments (over Ψ) as 0.
fn start_texels() -> Vec<u8> {
    let log_zero = [LOG_FLOOR, LOG_FLOOR, LOG_FLOOR, 1.0].map(|v| f16::from_f64(v).to_bits());
    let texel_bytes = |texel: [u16; 4]| texel.into_iter().flat_map(u16::to_le_bytes);
    let psi = (0..MOMENT_TEXELS).flat_map(|_| texel_bytes(log_zero));
    let ratios = (0..(MULTISCATTERING_MOMENTS as u32 - 1) * MOMENT_TEXELS).flat_map(|_| texel_bytes([0; 4]));
    let ground = (0..MULTISCATTERING_SIZE.0).flat_map(|_| texel_bytes(log_zero));
    psi.chain(ratios).chain(ground).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_start_fills_the_output_layout_with_zero_as_stored() {
        let texels = start_texels();
        assert_eq!(texels.len() as u64, OUTPUT_BYTES);
        let texel = |index: usize| -> [f32; 4] {
            let bytes = &texels[index * TEXEL_BYTES as usize..][..TEXEL_BYTES as usize];
            [0, 1, 2, 3].map(|c| f16::from_le_bytes([bytes[2 * c], bytes[2 * c + 1]]).to_f32())
        };
        let log_zero = [LOG_FLOOR as f32, LOG_FLOOR as f32, LOG_FLOOR as f32, 1.0];
        assert_eq!(texel(0), log_zero);
        assert_eq!(texel(MOMENT_TEXELS as usize), [0.0; 4]);
        assert_eq!(texel(MULTISCATTERING_MOMENTS * MOMENT_TEXELS as usize), log_zero);
    }
}
