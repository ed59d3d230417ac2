//! The multiple-scattering LUTs, order by order (see `atmosphere/multiscattering_lut.wgsl`).
//!
//! Each order is one compute dispatch (a workgroup per texel, an invocation per direction) that
//! reads the previous order's moments (Ψ, zz, xx, xz, x, z, bands 3 and 4) from the build set's
//! textures and its ground sky irradiance row E, and writes its own into a buffer of packed
//! `Rgba16Float` texels — copied into those textures for the next order — while adding them, in
//! `f32`, into a buffer of per-texel sums. A last dispatch (`atmosphere/multiscattering_sum.wgsl`)
//! writes the sum of the orders, and the geometric tail of those after the last (in a thick air
//! instead one more order, marched from the last plus its discrete-ordinates tail, which a
//! dispatch of `atmosphere/multiscattering_ordinates.wgsl` wrote as an order's moments), into the
//! build set's textures ([`MediumLuts`], copied into
//! [`AtmosphereLuts::multiscattering`](super::AtmosphereLuts::multiscattering) when done). A
//! buffer rather than storage textures: seven moments are more storage textures than GL-class
//! devices bind at once.

use super::luts::MediumLuts;
use super::luts::{Lut, MULTISCATTERING_FORMAT, MULTISCATTERING_MOMENTS, MULTISCATTERING_SIZE};
use super::stages::{
    ComputeStage, binding, array_texture_entry, sampler_entry, storage_buffer_entry, texture_entry,
    uniform_entry,
};
use crate::gpu_types::OrderSumsGpu;
use crate::shaders;

/// Orders of scattering the LUTs march (the light arriving at a point after 1 to this many
/// scattering or reflection events; a view adds one more); the orders after them are summed as a
/// geometric series (`atmosphere/multiscattering_sum.wgsl`). docs/ATMOSPHERE.md ("Multiple
/// scattering") measures the choice against more orders marched.
pub const MULTISCATTERING_ORDERS: u32 = 4;

/// How the light of the orders after the last marched one is added to the sums.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) enum Tail {
    /// Not at all: the LUTs hold exactly the orders marched.
    None,
    /// As a geometric series from the last two orders (`atmosphere/multiscattering_sum.wgsl`).
    #[default]
    Geometric,
    /// As one more order marched from the last one plus the later orders by discrete ordinates
    /// in a plane-parallel column (`atmosphere/multiscattering_ordinates.wgsl`).
    Ordinates,
}

impl Tail {
    /// The tail of an air: discrete ordinates when it is thick
    /// ([`is_thick_air`](crate::gpu_types::medium::is_thick_air)).
    pub(super) fn for_thickness(thick: bool) -> Self {
        if thick { Self::Ordinates } else { Self::Geometric }
    }
}

/// Bytes of one `Rgba16Float` texel.
const TEXEL_BYTES: u32 = 8;

/// Texels of one moment texture.
const MOMENT_TEXELS: u32 = MULTISCATTERING_SIZE.0 * MULTISCATTERING_SIZE.1;

/// The first texel of the ground row in the output, after the seven moment textures (the layout
/// of `multiscattering_out` in `atmosphere/moments_out.wgsl`).
const GROUND_ROW_START: u32 = MULTISCATTERING_MOMENTS as u32 * MOMENT_TEXELS;

/// The first texel of the sky irradiance LUT in the output, after the ground row.
const IRRADIANCE_START: u32 = GROUND_ROW_START + MULTISCATTERING_SIZE.0;

/// Bytes of the output: an order's moments and ground row, or the sums' moments and sky
/// irradiance.
const OUTPUT_BYTES: u64 = ((IRRADIANCE_START + MOMENT_TEXELS) * TEXEL_BYTES) as u64;

/// Bytes of one texel's `OrderSums` (`atmosphere/bindings.wgsl`).
const ORDER_SUMS_BYTES: u64 = std::mem::size_of::<OrderSumsGpu>() as u64;

/// Invocations per workgroup of the sum (`atmosphere/multiscattering_sum.wgsl`).
const SUM_WORKGROUP: u32 = 256;

/// The orders' compute stages (order 1, later orders, the discrete-ordinates tail, the sums with and
/// without the geometric tail), their buffers and the ground irradiance row.
#[derive(Debug)]
pub(super) struct MultiscatteringStages {
    first: ComputeStage,
    /// Order 1 with the forward peaks split off (`SPLIT_PEAK`), for a thick air.
    first_thick: ComputeStage,
    next: ComputeStage,
    ordinates: ComputeStage,
    /// ln Ψ's curvature down a thick air's columns, for the lookups between rows.
    curvature: ComputeStage,
    sum: ComputeStage,
    sum_without_tail: ComputeStage,
    /// An order's output, or the sums', packed texels.
    output: wgpu::Buffer,
    /// Each texel's orders so far, `f32`.
    orders: wgpu::Buffer,
    /// E, the ground's sky irradiance row the next order reads.
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
            label: Some("firmament AtmospherePass multiple-scattering order"),
            size: OUTPUT_BYTES,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let orders = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament AtmospherePass multiple-scattering orders"),
            size: ORDER_SUMS_BYTES * u64::from(MOMENT_TEXELS),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });

        let mut entries = vec![
            uniform_entry(binding::PARAMS),
            texture_entry(binding::TRANSMITTANCE, false),
            sampler_entry(binding::SAMPLER),
            texture_entry(binding::PREVIOUS_GROUND_IRRADIANCE, true),
            storage_buffer_entry(binding::MULTISCATTERING_OUT),
            storage_buffer_entry(binding::MULTISCATTERING_ORDERS),
        ];
        entries.push(array_texture_entry(binding::MULTISCATTERING));
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
            (binding::MULTISCATTERING_ORDERS, orders.as_entire_binding()),
        ];
        resources.push((
            binding::MULTISCATTERING,
            wgpu::BindingResource::TextureView(&luts.multiscattering.view),
        ));
        let order = |owner, first: bool, split_peak: bool| {
            ComputeStage::with_constants(
                device,
                owner,
                &shaders::ATMOSPHERE_MULTISCATTERING_LUT,
                &entries,
                &resources,
                &[
                    ("FIRST_ORDER", f64::from(u8::from(first))),
                    ("SPLIT_PEAK", f64::from(u8::from(split_peak))),
                ],
            )
        };
        let sum_entries = [
            storage_buffer_entry(binding::MULTISCATTERING_OUT),
            storage_buffer_entry(binding::MULTISCATTERING_ORDERS),
        ];
        let sum_resources = [
            (binding::MULTISCATTERING_OUT, output.as_entire_binding()),
            (binding::MULTISCATTERING_ORDERS, orders.as_entire_binding()),
        ];
        let sum = |owner, tail: bool| {
            ComputeStage::with_constants(
                device,
                owner,
                &shaders::ATMOSPHERE_MULTISCATTERING_SUM,
                &sum_entries,
                &sum_resources,
                &[("TAIL", f64::from(u8::from(tail)))],
            )
        };
        let ordinates_entries = [
            uniform_entry(binding::PARAMS),
            texture_entry(binding::PREVIOUS_GROUND_IRRADIANCE, true),
            storage_buffer_entry(binding::MULTISCATTERING_OUT),
            storage_buffer_entry(binding::MULTISCATTERING_ORDERS),
        ];
        let ordinates_resources = [
            (binding::PARAMS, luts.params.as_entire_binding()),
            (
                binding::PREVIOUS_GROUND_IRRADIANCE,
                wgpu::BindingResource::TextureView(&ground.view),
            ),
            (binding::MULTISCATTERING_OUT, output.as_entire_binding()),
            (binding::MULTISCATTERING_ORDERS, orders.as_entire_binding()),
        ];
        let ordinates = ComputeStage::with_constants(
            device,
            "AtmospherePass multiple-scattering discrete-ordinates tail",
            &shaders::ATMOSPHERE_MULTISCATTERING_ORDINATES,
            &ordinates_entries,
            &ordinates_resources,
            &[],
        );
        let curvature = ComputeStage::with_constants(
            device,
            "AtmospherePass multiple-scattering curvature of a thick air",
            &shaders::ATMOSPHERE_MULTISCATTERING_CURVATURE,
            &[storage_buffer_entry(binding::MULTISCATTERING_OUT)],
            &[(binding::MULTISCATTERING_OUT, output.as_entire_binding())],
            &[],
        );
        Self {
            first: order("AtmospherePass multiple-scattering LUT, order 1", true, false),
            first_thick: order(
                "AtmospherePass multiple-scattering LUT, order 1 of a thick air",
                true,
                true,
            ),
            next: order("AtmospherePass multiple-scattering LUT, later orders", false, false),
            ordinates,
            curvature,
            sum: sum("AtmospherePass multiple-scattering sum", true),
            sum_without_tail: sum("AtmospherePass multiple-scattering sum without the tail", false),
            output,
            orders,
            ground,
        }
    }

    /// Encodes the build's start: no orders yet (after the transmittance LUT).
    pub(super) fn record_start(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.clear_buffer(&self.orders, 0, None);
    }

    /// Encodes the next order (order 1 when `first`; after [`record_start`](Self::record_start)
    /// and the orders before it) of an air with `tail`: it leaves its moments in `luts` for the
    /// next. A thick air's order 1 splits off the forward peaks (`SPLIT_PEAK` in
    /// `atmosphere/multiscattering_lut.wgsl`).
    pub(super) fn record_order(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts, first: bool, tail: Tail) {
        let (width, height) = MULTISCATTERING_SIZE;
        // One workgroup per texel, and a row more for the ground's irradiance.
        let stage = match (first, tail) {
            (true, Tail::Ordinates) => &self.first_thick,
            (true, _) => &self.first,
            (false, _) => &self.next,
        };
        stage.dispatch(encoder, (width, height + 1, 1));
        self.record_curvature(encoder, tail);
        self.record_copy(encoder, luts, true);
    }

    /// Encodes ln Ψ's curvature down the columns of the output in a thick air (its rows are far
    /// apart in optical depth); a thin air's stays 0.
    fn record_curvature(&self, encoder: &mut wgpu::CommandEncoder, tail: Tail) {
        if tail == Tail::Ordinates {
            self.curvature.dispatch(encoder, (1, 1, 1));
        }
    }

    /// Encodes the sum of the orders so far into `luts`' moments and sky irradiance, with `tail`,
    /// the light of the orders after them.
    pub(super) fn record_sum(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts, tail: Tail) {
        if tail == Tail::Ordinates {
            // One invocation per column of mu_s: the last order and the tail as an order's
            // moments, from which one more order is marched (the transport sweep) and summed.
            self.ordinates.dispatch(encoder, (1, 1, 1));
            self.record_curvature(encoder, tail);
            self.record_copy(encoder, luts, true);
            let (width, height) = MULTISCATTERING_SIZE;
            self.next.dispatch(encoder, (width, height + 1, 1));
        }
        let stage = if tail == Tail::Geometric {
            &self.sum
        } else {
            &self.sum_without_tail
        };
        stage.dispatch(encoder, (MOMENT_TEXELS.div_ceil(SUM_WORKGROUP), 1, 1));
        self.record_curvature(encoder, tail);
        self.record_copy(encoder, luts, false);
    }

    /// Encodes the copies of the output buffer into the moments and then, after an order, the
    /// ground row or, after the sum, the sky irradiance.
    fn record_copy(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts, order: bool) {
        let (width, height) = MULTISCATTERING_SIZE;
        // The moments' layers in one copy (each copy costs the GPU a few microseconds).
        let moments = (&luts.multiscattering, height, MULTISCATTERING_MOMENTS as u32, 0);
        let then = if order {
            (&self.ground, 1, 1, GROUND_ROW_START)
        } else {
            (&luts.irradiance, height, 1, IRRADIANCE_START)
        };
        for (lut, rows, layers, first_texel) in [moments, then] {
            encoder.copy_buffer_to_texture(
                wgpu::TexelCopyBufferInfo {
                    buffer: &self.output,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: u64::from(first_texel * TEXEL_BYTES),
                        bytes_per_row: Some(width * TEXEL_BYTES),
                        rows_per_image: Some(rows),
                    },
                },
                lut.texture.as_image_copy(),
                wgpu::Extent3d {
                    width,
                    height: rows,
                    depth_or_array_layers: layers,
                },
            );
        }
    }
}
