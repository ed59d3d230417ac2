//! The multiple-scattering LUTs by fixed-point iteration (see `atmosphere/multiscattering_lut.wgsl`):
//! each iterate reads the previous moments (Ψ, zz, xx, xz, x, z, bands 3 and 4) and ground sky
//! irradiance E and writes the next, ping-ponging between two sets of textures so that the last
//! iterate lands in the build set's moments ([`MediumLuts`](super::luts::MediumLuts), copied into
//! [`AtmosphereLuts::multiscattering`](super::AtmosphereLuts::multiscattering) when done).

use super::luts::{
    LOG_FLOOR, Lut, MOMENT_NAMES, MULTISCATTERING_FORMAT, MULTISCATTERING_MOMENTS, MULTISCATTERING_SIZE, moment_views,
};
use super::luts::MediumLuts;
use super::stages::{
    Stage, bind_group, binding, moment_entries, moment_resources, sampler_entry, texture_entry, uniform_entry,
};
use crate::gpu_types::codes;
use crate::passes::common::PassPipeline;
use crate::shaders;

/// Iterates after the first (single scattering and the sunlit ground): iterate k holds orders up
/// to k + 1, so the LUTs hold orders 1 to 10 of the light arriving at a point (the issue asks for
/// at least 10; a view adds one more scattering).
pub const MULTISCATTERING_ITERATIONS: u32 = 9;

/// One set of the iteration's textures: the four moments and the ground irradiance row E.
#[derive(Debug)]
struct Iterate<'a> {
    moments: [&'a wgpu::TextureView; MULTISCATTERING_MOMENTS],
    irradiance: &'a wgpu::TextureView,
}

/// The scratch textures: the other set of moments, both ground irradiance rows and the rows
/// nothing reads (the irradiance draw's other targets).
#[derive(Debug)]
struct Scratch {
    moments: [Lut; MULTISCATTERING_MOMENTS],
    irradiance: [Lut; 2],
    unused: [Lut; MULTISCATTERING_MOMENTS - 1],
}

/// The iteration's stages: `[parity][output]`, parity 0 reading the scratch set and writing the
/// LUTs, parity 1 the other way; output 0 = the moments, 1 = (E, unused rows).
#[derive(Debug)]
pub(super) struct MultiscatteringStages {
    stages: [[Stage; 2]; 2],
    scratch: Scratch,
}

impl MultiscatteringStages {
    pub(super) fn new(device: &wgpu::Device, luts: &MediumLuts, sampler: &wgpu::Sampler) -> Self {
        let (width, height) = MULTISCATTERING_SIZE;
        let scratch_lut = |name: &str, size| {
            Lut::new(
                device,
                name,
                size,
                MULTISCATTERING_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
        };
        let scratch = Scratch {
            moments: MOMENT_NAMES.map(|moment| {
                scratch_lut(
                    &format!("multiple-scattering {moment} (previous iterate)"),
                    (width, height),
                )
            }),
            irradiance: ["A", "B"]
                .map(|row| scratch_lut(&format!("multiple-scattering ground irradiance {row}"), (width, 1))),
            unused: MOMENT_NAMES[1..]
                .try_into()
                .map(|names: [&str; MULTISCATTERING_MOMENTS - 1]| {
                    names.map(|name| scratch_lut(&format!("multiple-scattering unused row ({name})"), (width, 1)))
                })
                .expect("one name per moment"),
        };
        let mut entries = vec![
            uniform_entry(binding::PARAMS),
            texture_entry(binding::TRANSMITTANCE, false),
            sampler_entry(binding::SAMPLER),
            texture_entry(binding::PREVIOUS_GROUND_IRRADIANCE, true),
        ];
        entries.extend(moment_entries(binding::PREVIOUS_MULTISCATTERING_MOMENTS));
        let pipelines = [
            ("AtmospherePass multiple-scattering LUT", codes::MULTISCATTERING_OUTPUT_MOMENTS),
            (
                "AtmospherePass multiple-scattering ground irradiance",
                codes::MULTISCATTERING_OUTPUT_GROUND_IRRADIANCE,
            ),
        ]
        .map(|(owner, output)| {
            PassPipeline {
                owner,
                source: &shaders::ATMOSPHERE_MULTISCATTERING_LUT,
                entries: &entries,
                color: MULTISCATTERING_FORMAT,
                depth_stencil: None,
                vertex_buffers: &[],
                primitive: wgpu::PrimitiveState::default(),
                constants: &[("OUTPUT", f64::from(output))],
            }
            .build_with_targets(device, None, MULTISCATTERING_MOMENTS)
        });
        let stages = [0, 1].map(|parity| {
            let read = Self::iterate_of(luts, &scratch, 1 - parity);
            let mut resources = vec![
                (binding::PARAMS, luts.params.as_entire_binding()),
                (
                    binding::TRANSMITTANCE,
                    wgpu::BindingResource::TextureView(&luts.transmittance.view),
                ),
                (binding::SAMPLER, wgpu::BindingResource::Sampler(sampler)),
                (
                    binding::PREVIOUS_GROUND_IRRADIANCE,
                    wgpu::BindingResource::TextureView(read.irradiance),
                ),
            ];
            resources.extend(moment_resources(
                binding::PREVIOUS_MULTISCATTERING_MOMENTS,
                read.moments,
            ));
            [0, 1].map(|output| {
                let (pipeline, layout) = &pipelines[output];
                Stage {
                    pipeline: pipeline.clone(),
                    bind_group: bind_group(device, "AtmospherePass multiple-scattering LUT", layout, &resources),
                }
            })
        });
        Self { stages, scratch }
    }

    /// The set iterates of `parity` write: 0 the LUTs (and E row A), 1 the scratch set (E row B).
    fn iterate_of<'a>(luts: &'a MediumLuts, scratch: &'a Scratch, parity: usize) -> Iterate<'a> {
        if parity == 0 {
            Iterate {
                moments: luts.multiscattering_views(),
                irradiance: &scratch.irradiance[0].view,
            }
        } else {
            Iterate {
                moments: moment_views(&scratch.moments),
                irradiance: &scratch.irradiance[1].view,
            }
        }
    }

    /// Encodes the iteration's start: the set the first iterate reads, cleared to zero (after the
    /// transmittance LUT).
    pub(super) fn record_start(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts) {
        // Ψ and E (stored as logarithms) hold zero as LOG_FLOOR, the other moments (over Ψ) as 0.
        let start = Self::iterate_of(luts, &self.scratch, 1 - parity_of(0));
        let (psi, ratios) = start.moments.split_at(1);
        render_targets(encoder, None, psi, LOG_ZERO);
        render_targets(encoder, None, ratios, wgpu::Color::TRANSPARENT);
        render_targets(encoder, None, &[start.irradiance], LOG_ZERO);
    }

    /// Encodes iterate `iterate` (0 to [`MULTISCATTERING_ITERATIONS`], in order after
    /// [`record_start`](Self::record_start)); the last one writes `luts`' moments.
    pub(super) fn record_iterate(&self, encoder: &mut wgpu::CommandEncoder, luts: &MediumLuts, iterate: u32) {
        let parity = parity_of(iterate);
        let write = Self::iterate_of(luts, &self.scratch, parity);
        let [moments, irradiance] = &self.stages[parity];
        render_targets(encoder, Some(moments), &write.moments, wgpu::Color::TRANSPARENT);
        let irradiance_targets: Vec<&wgpu::TextureView> = std::iter::once(write.irradiance)
            .chain(self.scratch.unused.iter().map(|lut| &lut.view))
            .collect();
        render_targets(encoder, Some(irradiance), &irradiance_targets, wgpu::Color::TRANSPARENT);
    }
}

/// Zero as Ψ and E are stored: their logarithm's floor (`LOG_FLOOR` in `atmosphere/luts.wgsl`).
const LOG_ZERO: wgpu::Color = wgpu::Color {
    r: LOG_FLOOR,
    g: LOG_FLOOR,
    b: LOG_FLOOR,
    a: 1.0,
};

/// Clears `targets` (all of one size) to `clear` and draws `stage`'s full-screen triangle into
/// them (only clears without one).
fn render_targets(
    encoder: &mut wgpu::CommandEncoder,
    stage: Option<&Stage>,
    targets: &[&wgpu::TextureView],
    clear: wgpu::Color,
) {
    let attachments: Vec<_> = targets
        .iter()
        .map(|view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("firmament AtmospherePass multiple-scattering iterate"),
        color_attachments: &attachments,
        ..Default::default()
    });
    if let Some(stage) = stage {
        pass.set_pipeline(&stage.pipeline);
        pass.set_bind_group(0, &stage.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The parity of `iterate` (which set it writes, see [`MultiscatteringStages`]): alternating so
/// that the last iterate has parity 0 and writes the LUTs the other stages read. (Counting from
/// the first instead once left the last iterate in the scratch set, one order short.)
fn parity_of(iterate: u32) -> usize {
    ((MULTISCATTERING_ITERATIONS - iterate) % 2) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_iterate_writes_the_luts_and_each_reads_the_one_before() {
        assert_eq!(parity_of(MULTISCATTERING_ITERATIONS), 0);
        for iterate in 1..=MULTISCATTERING_ITERATIONS {
            assert_ne!(parity_of(iterate), parity_of(iterate - 1));
        }
    }
}
