//! Aerial perspective (Hillaire 2020, section 5.3): a froxel volume of the light the air scatters
//! towards the camera and its transmittance, filled by a compute pass each frame, and applied to
//! whatever a depth buffer holds as `colour · T + S`, per channel.
//!
//! Per-channel `colour · T` and `+ S` cannot both be one blend without dual-source blending
//! (not on every adapter), so the application into callers' render passes is two full-screen
//! draws: multiply, then add. On the renderer's own targets it is one compute pass instead, from
//! the HDR target into a scratch texture copied back over it (`Rgba16Float` cannot be read and
//! written as storage in one pass everywhere).

use super::luts::{self, AERIAL_PERSPECTIVE_FORMAT, AERIAL_PERSPECTIVE_SIZE};
use super::stages::{
    ComputeKernel, ComputeStage, bind_group, binding, array_texture_entry, sampler_entry, storage_entry, texture_entry,
    uniform_entry,
};
use std::num::NonZeroU64;

use crate::gpu_types::{AtmosphereParamsUniforms, AtmosphereViewUniforms, codes};
use crate::passes::common::{PassPipeline, load_color_attachment};
use crate::shaders;

/// The five bind group layout entries of the aerial-perspective volume in a user's pipeline, at
/// `first_binding` … `first_binding + 4`, as `shaders::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`
/// declares them: the atmosphere pass's view uniforms, its medium uniforms, the volume's
/// scattering and transmittance atlases (filterable float 2D textures) and a filtering sampler,
/// all seen by the vertex, fragment and compute stages. Bind them with
/// [`AerialPerspectiveBindings::bind_group_entries`] at the same `first_binding`.
pub fn aerial_perspective_layout_entries(first_binding: u32) -> [wgpu::BindGroupLayoutEntry; 5] {
    let visibility = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let uniform = |offset: u32, size: usize| wgpu::BindGroupLayoutEntry {
        binding: first_binding + offset,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: NonZeroU64::new(size as u64),
        },
        count: None,
    };
    let texture = |offset: u32| wgpu::BindGroupLayoutEntry {
        binding: first_binding + offset,
        visibility,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    [
        uniform(0, std::mem::size_of::<AtmosphereViewUniforms>()),
        uniform(1, std::mem::size_of::<AtmosphereParamsUniforms>()),
        texture(2),
        texture(3),
        wgpu::BindGroupLayoutEntry {
            binding: first_binding + 4,
            visibility,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        },
    ]
}

/// What a user's shader binds to read the aerial-perspective volume
/// ([`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`](crate::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL)), from
/// [`Renderer::aerial_perspective_bindings`](crate::Renderer::aerial_perspective_bindings) (or the
/// atmosphere pass's own).
/// The objects live as long as the pass; their contents are the frame's once the volume was
/// encoded (`record_aerial_perspective_volume` or `record_aerial_perspective`).
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct AerialPerspectiveBindings<'a> {
    /// The pass's per-frame view uniforms (`AtmosphereViewUniforms`): the camera, its rays, the
    /// volume's range and the spectral → linear sRGB matrix.
    pub view: &'a wgpu::Buffer,
    /// The pass's medium uniforms (`AtmosphereParamsUniforms`; the include reads the planet's
    /// radii and atmosphere height).
    pub params: &'a wgpu::Buffer,
    /// The scattered light of the volume's slices, side by side in a 1024 × 32 `Rgba16Float`
    /// atlas (spectral radiance).
    pub scattering: &'a wgpu::TextureView,
    /// The transmittance of the volume's slices, laid out as `scattering`.
    pub transmittance: &'a wgpu::TextureView,
    /// A linear, clamp-to-edge sampler.
    pub sampler: &'a wgpu::Sampler,
}

impl<'a> AerialPerspectiveBindings<'a> {
    /// The five bind group entries at `first_binding` … `first_binding + 4`, matching
    /// [`aerial_perspective_layout_entries`] at the same `first_binding`.
    pub fn bind_group_entries(&self, first_binding: u32) -> [wgpu::BindGroupEntry<'a>; 5] {
        let resources = [
            self.view.as_entire_binding(),
            self.params.as_entire_binding(),
            wgpu::BindingResource::TextureView(self.scattering),
            wgpu::BindingResource::TextureView(self.transmittance),
            wgpu::BindingResource::Sampler(self.sampler),
        ];
        let mut binding = first_binding;
        resources.map(|resource| {
            let entry = wgpu::BindGroupEntry { binding, resource };
            binding += 1;
            entry
        })
    }
}

/// The draws that apply the volume, in order: owner, `OUTPUT` and blending.
const APPLY_DRAWS: [(&str, u32, wgpu::BlendComponent); 2] = [
    (
        "AtmospherePass aerial perspective (transmittance)",
        codes::AERIAL_OUTPUT_TRANSMITTANCE,
        wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::Src,
            operation: wgpu::BlendOperation::Add,
        },
    ),
    (
        "AtmospherePass aerial perspective (scattering)",
        codes::AERIAL_OUTPUT_SCATTERING,
        wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        },
    ),
];

/// The volume's compute stage and the two draws that apply it.
#[derive(Debug)]
pub(super) struct AerialPerspectiveStages {
    volume: ComputeStage,
    /// The transmittance and scattering draws, with their bind group layouts.
    apply: Vec<(wgpu::RenderPipeline, wgpu::BindGroupLayout)>,
    /// One bind group per draw, for the depth view of the last `bind_depth`.
    bind_groups: Vec<wgpu::BindGroup>,
    /// The compute form, once a target is bound (`bind_target`).
    on_target: Option<OnTarget>,
}

/// The compute application bound to one HDR target.
#[derive(Debug)]
struct OnTarget {
    stage: ComputeStage,
    /// The same with the light shafts (`cs_shafts`), sampling the objects' shadow maps as its
    /// group 1.
    shafts: ComputeStage,
    /// The HDR target, copied over from `scratch` after the pass.
    target: wgpu::Texture,
    scratch: wgpu::Texture,
}

/// Everything the stages bind besides the depth buffer.
pub(super) struct AerialPerspectiveResources<'a> {
    pub(super) params: &'a wgpu::Buffer,
    pub(super) view: &'a wgpu::Buffer,
    pub(super) luts: &'a luts::AtmosphereLuts,
    pub(super) sampler: &'a wgpu::Sampler,
    pub(super) surface: &'a super::surface::SurfaceTexture,
}

impl<'a> AerialPerspectiveResources<'a> {
    /// What applying the volume over `depth` binds (the draws; the compute pass adds its target).
    fn apply(&self, depth: &'a wgpu::TextureView) -> Vec<(u32, wgpu::BindingResource<'a>)> {
        let luts = self.luts;
        let mut all = self.common().to_vec();
        all.extend([
            (
                binding::AERIAL_SCATTERING,
                wgpu::BindingResource::TextureView(&luts.aerial_scattering.view),
            ),
            (
                binding::AERIAL_TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.aerial_transmittance.view),
            ),
            (binding::SCENE_DEPTH, wgpu::BindingResource::TextureView(depth)),
        ]);
        all
    }

    fn common(&self) -> [(u32, wgpu::BindingResource<'a>); 3] {
        [
            (binding::PARAMS, self.params.as_entire_binding()),
            (binding::VIEW, self.view.as_entire_binding()),
            (binding::SAMPLER, wgpu::BindingResource::Sampler(self.sampler)),
        ]
    }
}

/// The layout entries of [`AerialPerspectiveResources::apply`]'s resources.
fn apply_entries() -> [wgpu::BindGroupLayoutEntry; 6] {
    [
        uniform_entry(binding::PARAMS),
        uniform_entry(binding::VIEW),
        sampler_entry(binding::SAMPLER),
        texture_entry(binding::AERIAL_SCATTERING, true),
        texture_entry(binding::AERIAL_TRANSMITTANCE, true),
        depth_entry(),
    ]
}

/// A texture of `target`'s size and HDR format that a compute pass writes and that is then copied
/// over `target` (`Rgba16Float` cannot be read and written as storage in one pass everywhere).
pub(super) fn scratch_for(device: &wgpu::Device, target: &wgpu::Texture, label: &str) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: target.size(),
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: crate::targets::HDR_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// The depth buffer, read as an unfilterable float texture: GLSL cannot `textureLoad` a depth
/// texture, and a depth view may be bound as unfilterable float anywhere.
fn depth_entry() -> wgpu::BindGroupLayoutEntry {
    texture_entry(binding::SCENE_DEPTH, false)
}

impl AerialPerspectiveStages {
    /// Builds the compute stage and the two draws into targets of `color`.
    pub(super) fn new(
        device: &wgpu::Device,
        resources: &AerialPerspectiveResources<'_>,
        color: wgpu::TextureFormat,
    ) -> Self {
        let luts = resources.luts;
        let storage = |binding| storage_entry(binding, AERIAL_PERSPECTIVE_FORMAT);
        let mut volume_resources = resources.common().to_vec();
        volume_resources.push((
            binding::MULTISCATTERING,
            wgpu::BindingResource::TextureView(&luts.multiscattering.view),
        ));
        volume_resources.extend([
            (
                binding::TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.transmittance.view),
            ),
            (
                binding::AERIAL_SCATTERING_OUT,
                wgpu::BindingResource::TextureView(&luts.aerial_scattering.view),
            ),
            (
                binding::AERIAL_TRANSMITTANCE_OUT,
                wgpu::BindingResource::TextureView(&luts.aerial_transmittance.view),
            ),
        ]);
        let mut volume_entries = vec![
            uniform_entry(binding::PARAMS),
            uniform_entry(binding::VIEW),
            sampler_entry(binding::SAMPLER),
            texture_entry(binding::TRANSMITTANCE, false),
            storage(binding::AERIAL_SCATTERING_OUT),
            storage(binding::AERIAL_TRANSMITTANCE_OUT),
        ];
        volume_entries.push(array_texture_entry(binding::MULTISCATTERING));
        let volume = ComputeStage::new(
            device,
            "AtmospherePass aerial-perspective volume",
            &shaders::ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME,
            &volume_entries,
            &volume_resources,
        );
        let apply_entries = apply_entries();
        let apply = APPLY_DRAWS
            .iter()
            .map(|&(owner, output, component)| {
                PassPipeline {
                    owner,
                    source: &shaders::ATMOSPHERE_AERIAL_PERSPECTIVE,
                    entries: &apply_entries,
                    color,
                    depth_stencil: None,
                    vertex_buffers: &[],
                    primitive: wgpu::PrimitiveState::default(),
                    constants: &[("OUTPUT", f64::from(output))],
                }
                .build_blended(
                    device,
                    Some(wgpu::BlendState {
                        color: component,
                        alpha: wgpu::BlendComponent {
                            src_factor: wgpu::BlendFactor::Zero,
                            dst_factor: wgpu::BlendFactor::One,
                            operation: wgpu::BlendOperation::Add,
                        },
                    }),
                )
            })
            .collect();
        Self {
            volume,
            apply,
            bind_groups: Vec::new(),
            on_target: None,
        }
    }

    /// Binds `target` (an [`HDR_FORMAT`](crate::targets::HDR_FORMAT) texture with
    /// `TEXTURE_BINDING | COPY_DST`) and its depth buffer for [`record_on_target`](Self::record_on_target).
    pub(super) fn bind_target(
        &mut self,
        device: &wgpu::Device,
        resources: &AerialPerspectiveResources<'_>,
        target: &wgpu::Texture,
        depth: &wgpu::TextureView,
    ) {
        let scratch = scratch_for(device, target, "firmament AtmospherePass aerial-perspective scratch");
        let scratch_view = scratch.create_view(&wgpu::TextureViewDescriptor::default());
        let target_view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut all = resources.apply(depth);
        all.extend([
            (binding::HDR_IN, wgpu::BindingResource::TextureView(&target_view)),
            (binding::HDR_OUT, wgpu::BindingResource::TextureView(&scratch_view)),
        ]);
        let mut entries = apply_entries().to_vec();
        entries.extend([
            texture_entry(binding::HDR_IN, false),
            storage_entry(binding::HDR_OUT, crate::targets::HDR_FORMAT),
        ]);
        // The shafts also look the sun's transmittance up.
        let mut shaft_resources = all.clone();
        shaft_resources.push((
            binding::TRANSMITTANCE,
            wgpu::BindingResource::TextureView(&resources.luts.transmittance.view),
        ));
        let mut shaft_entries = entries.clone();
        shaft_entries.push(texture_entry(binding::TRANSMITTANCE, false));
        let (stage, shafts) = match self.on_target.take() {
            Some(OnTarget {
                mut stage, mut shafts, ..
            }) => {
                stage.rebind(device, &all);
                shafts.rebind(device, &shaft_resources);
                (stage, shafts)
            }
            None => {
                let stage = ComputeStage::new(
                    device,
                    "AtmospherePass compute aerial perspective",
                    &shaders::ATMOSPHERE_AERIAL_PERSPECTIVE,
                    &entries,
                    &all,
                );
                let kernel = ComputeKernel::with_groups(
                    device,
                    "AtmospherePass aerial perspective with light shafts",
                    (&shaders::ATMOSPHERE_AERIAL_PERSPECTIVE, "cs_shafts"),
                    &shaft_entries,
                    &[],
                    &[&crate::passes::objects::shadow_sampling_layout(device)],
                );
                (stage, ComputeStage::of_kernel(device, kernel, &shaft_resources))
            }
        };
        self.on_target = Some(OnTarget {
            stage,
            shafts,
            target: target.clone(),
            scratch,
        });
    }

    /// Whether a target is bound (`bind_target`).
    pub(super) fn bound_to_target(&self) -> bool {
        self.on_target.is_some()
    }

    /// Encodes the compute application over the target bound by `bind_target` and the copy back,
    /// with the light shafts of the objects' shadow maps when `shadows` binds them; false,
    /// encoding nothing, when no target is bound.
    pub(super) fn record_on_target(&self, encoder: &mut wgpu::CommandEncoder, shadows: Option<&wgpu::BindGroup>) -> bool {
        let Some(on) = &self.on_target else {
            return false;
        };
        let size = on.target.size();
        let workgroups = (size.width.div_ceil(8), size.height.div_ceil(8), 1);
        match shadows {
            Some(group) => on.shafts.dispatch_with(encoder, &[group], workgroups),
            None => on.stage.dispatch(encoder, workgroups),
        }
        encoder.copy_texture_to_texture(on.scratch.as_image_copy(), on.target.as_image_copy(), size);
        true
    }

    /// Encodes the volume's compute pass (after the transmittance and multiple-scattering LUTs).
    pub(super) fn record_volume(&self, encoder: &mut wgpu::CommandEncoder) {
        // One workgroup per froxel column (aerial_perspective_volume.wgsl).
        let (x, y, _) = AERIAL_PERSPECTIVE_SIZE;
        self.volume.dispatch(encoder, (x, y, 1));
    }

    /// Binds `depth` (a depth view of the colour target's size) for the next applications.
    pub(super) fn bind_depth(
        &mut self,
        device: &wgpu::Device,
        resources: &AerialPerspectiveResources<'_>,
        depth: &wgpu::TextureView,
    ) {
        let all = resources.apply(depth);
        self.bind_groups = self
            .apply
            .iter()
            .zip(APPLY_DRAWS)
            .map(|((_, layout), (owner, ..))| bind_group(device, owner, layout, &all))
            .collect();
    }

    /// Encodes the two draws over `color` (loaded, not cleared). Does nothing before
    /// `bind_depth`.
    pub(super) fn record_apply(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) {
        if self.bind_groups.is_empty() {
            tracing::warn!("AtmospherePass aerial perspective recorded before a depth view was bound: skipped");
            return;
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("firmament AtmospherePass aerial perspective"),
            color_attachments: &[Some(load_color_attachment(color))],
            ..Default::default()
        });
        for ((pipeline, _), bind_group) in self.apply.iter().zip(&self.bind_groups) {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders;

    #[test]
    fn the_layout_entries_are_the_include_s_five_bindings_in_order() {
        let entries = aerial_perspective_layout_entries(10);
        assert_eq!(entries.map(|e| e.binding), [10, 11, 12, 13, 14]);
    }

    #[test]
    fn the_shaders_declare_the_volume_s_size() {
        let (x, y, z) = AERIAL_PERSPECTIVE_SIZE;
        let declared = format!("vec3<u32>({x}u, {y}u, {z}u)");
        assert!(shaders::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL.contains(&format!(
            "const FIRMAMENT_AERIAL_PERSPECTIVE_SIZE: vec3<u32> = {declared};"
        )));
        assert!(
            shaders::ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME
                .contains(&format!("const AERIAL_PERSPECTIVE_SIZE: vec3<u32> = {declared};"))
        );
        // One invocation per sample of a column: two per slice.
        assert!(
            shaders::ATMOSPHERE_AERIAL_PERSPECTIVE_VOLUME.contains(&format!("const SAMPLES: u32 = {}u;", 2 * z))
        );
    }
}
