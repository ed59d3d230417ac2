//! The cloud layers (`shaders/clouds/march.wgsl`): a compute pass after the sky, the objects and
//! their aerial perspective, that marches each pixel's ray through the layers in front of its
//! geometry and lays the clouds over the image. On the renderer's own HDR target it reads the
//! target and writes a scratch copy that is copied back, like the compute aerial perspective; on
//! a caller's target (which it may not write) it writes the clouds as a layer of its own and a
//! full-screen draw blends that over the caller's colour.

use firmament_core::atmosphere::clouds::{CloudLayer, CoverageMap};
use firmament_core::frame::AtmosphereSky;

use super::aerial_perspective::{AerialPerspectiveResources, scratch_for};
use super::stages::{
    ComputeStage, bind_group, binding, sampler_entry, storage_entry, texture_entry, uniform_entry,
};
use crate::gpu_types::clouds::CloudsGpu;
use crate::passes::common::{PassPipeline, load_color_attachment, uniform_buffer};
use crate::shaders;

/// Texels across one sun's square of the clouds' shadow map (`CLOUD_SHADOW_SIZE` in
/// `shaders/clouds/shadow.wgsl`; a test compares the two).
pub(super) const CLOUD_SHADOW_SIZE: u32 = 256;

/// Texels of the GPU's copy of each coverage map (longitude, latitude): maps of any size are
/// resampled to it (about 39 km per texel on Earth's equator), so all fit one array texture.
pub(super) const COVERAGE_MAP_SIZE: (u32, u32) = (1024, 512);

/// The layers' uniforms and the compute stage bound to the renderer's target.
#[derive(Debug)]
pub(super) struct CloudStages {
    uniforms: wgpu::Buffer,
    /// One layer per layer slot with a map (`CloudLayerGpu::codes.w`), `R16Float`.
    maps: wgpu::Texture,
    maps_view: wgpu::TextureView,
    /// Linear, repeating in longitude, clamped at the poles.
    map_sampler: wgpu::Sampler,
    /// The maps last uploaded, in slot order.
    uploaded_maps: Vec<CoverageMap>,
    /// Layers in the frame last prepared.
    layers: usize,
    /// Suns in the frame last prepared (the shadow map's squares).
    suns: u32,
    /// The clouds' shadow map: one [`CLOUD_SHADOW_SIZE`]² square per sun, side by side,
    /// `Rgba32Float` (`shaders/clouds/shadow.wgsl`); the view keeps the texture.
    shadow_map_view: wgpu::TextureView,
    /// Its compute stage, built with the first bound target.
    shadow_stage: Option<ComputeStage>,
    /// Set when the map was encoded ahead of the march (for the objects, which read it too):
    /// the next march then does not encode it again.
    shadow_map_ahead: std::cell::Cell<bool>,
    on_target: Option<OnTarget>,
    /// The stages for a caller's target, once one with clouds was bound.
    into_caller: Option<IntoCaller>,
}

/// The stage bound to one HDR target.
#[derive(Debug)]
struct OnTarget {
    stage: ComputeStage,
    /// The HDR target, copied over from `scratch` after the pass.
    target: wgpu::Texture,
    scratch: wgpu::Texture,
}

/// The stages for a caller's target: the march writing the clouds as a layer, and the draw that
/// blends the layer over the caller's colour (`src + dst · src.a`).
#[derive(Debug)]
struct IntoCaller {
    stage: ComputeStage,
    /// The clouds' light (rgb) and transmittance (a) at the caller's size, [`HDR_FORMAT`].
    ///
    /// [`HDR_FORMAT`]: crate::targets::HDR_FORMAT
    layer: wgpu::Texture,
    /// Its view, read by the blend (`HDR_IN` of its group).
    layer_view: wgpu::TextureView,
    /// What the march reads as `HDR_IN`, which its layer form never reads.
    placeholder: wgpu::TextureView,
    blend: wgpu::RenderPipeline,
    blend_layout: wgpu::BindGroupLayout,
    blend_group: wgpu::BindGroup,
}

/// The owner of the caller's blend draw, for labels.
const BLEND_OWNER: &str = "AtmospherePass clouds blend";

/// The layout entries every cloud stage has: the medium, the view, the layers, their maps.
fn layer_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        uniform_entry(binding::PARAMS),
        uniform_entry(binding::VIEW),
        uniform_entry(binding::CLOUDS),
        texture_array_entry(binding::CLOUD_COVERAGE_MAPS),
        sampler_entry(binding::MAP_SAMPLER),
    ]
}

/// The march's layout entries.
fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut all = layer_entries();
    all.extend([
        texture_entry(binding::TRANSMITTANCE, false),
        texture_entry(binding::IRRADIANCE, true),
        sampler_entry(binding::SAMPLER),
        texture_entry(binding::AERIAL_SCATTERING, true),
        texture_entry(binding::AERIAL_TRANSMITTANCE, true),
        texture_entry(binding::SCENE_DEPTH, false),
        texture_entry(binding::HDR_IN, false),
        storage_entry(binding::HDR_OUT, crate::targets::HDR_FORMAT),
        texture_entry(binding::CLOUD_SHADOW_MAP, false),
    ]);
    all.push(super::surface::SurfaceTexture::texture_entry());
    all
}

/// The shadow map stage's layout entries.
fn shadow_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut all = layer_entries();
    all.push(storage_entry(binding::CLOUD_SHADOW_OUT, SHADOW_MAP_FORMAT));
    all
}

/// The shadow map's texel format: metres along the rays need `f32`.
const SHADOW_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The draw that blends the clouds' layer over a colour target of `color`: `src + dst · src.a`
/// in colour, the target's alpha kept.
fn blend_pipeline(device: &wgpu::Device, color: wgpu::TextureFormat) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
    PassPipeline {
        owner: BLEND_OWNER,
        source: &shaders::CLOUDS_MARCH,
        entries: &[texture_entry(binding::HDR_IN, false)],
        color,
        depth_stencil: None,
        vertex_buffers: &[],
        primitive: wgpu::PrimitiveState::default(),
        constants: &[],
    }
    .build_blended(
        device,
        Some(wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::SrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        }),
    )
}

/// A filterable 2D-array texture.
fn texture_array_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    let mut entry = texture_entry(binding, true);
    if let wgpu::BindingType::Texture { view_dimension, .. } = &mut entry.ty {
        *view_dimension = wgpu::TextureViewDimension::D2Array;
    }
    entry
}

/// `map` resampled to [`COVERAGE_MAP_SIZE`] (bilinear at the new texel centres), as half floats'
/// bits.
fn resampled(map: &CoverageMap) -> Vec<u16> {
    let (width, height) = COVERAGE_MAP_SIZE;
    firmament_core::atmosphere::surface::map::texel_centres(width, height)
        .map(|(latitude, longitude)| half::f16::from_f64(map.sample(latitude, longitude)).to_bits())
        .collect()
}

impl CloudStages {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let (width, height) = COVERAGE_MAP_SIZE;
        let maps = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("firmament AtmospherePass cloud coverage maps"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: firmament_core::atmosphere::clouds::MAX_CLOUD_LAYERS as u32,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let maps_view = maps.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let map_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("firmament AtmospherePass cloud coverage map sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let shadow_map_view = crate::targets::texture_2d(
            device,
            "firmament AtmospherePass cloud shadow map",
            (CLOUD_SHADOW_SIZE * firmament_core::frame::MAX_SUNS as u32, CLOUD_SHADOW_SIZE),
            SHADOW_MAP_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            uniforms: uniform_buffer::<CloudsGpu>(device, "firmament AtmospherePass clouds"),
            suns: 0,
            shadow_map_view,
            shadow_stage: None,
            shadow_map_ahead: std::cell::Cell::new(false),
            maps,
            maps_view,
            map_sampler,
            uploaded_maps: Vec::new(),
            layers: 0,
            on_target: None,
            into_caller: None,
        }
    }

    /// Uploads `sky`'s cloud layers.
    pub(super) fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky) {
        self.layers = sky.clouds.len();
        self.suns = sky.suns.len().min(firmament_core::frame::MAX_SUNS) as u32;
        if self.layers > 0 {
            let uniforms = CloudsGpu::new(&sky.clouds, &sky.atmosphere.planet);
            queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
            self.upload_maps(queue, &sky.clouds);
        }
    }

    /// Uploads the layers' coverage maps, in slot order, when they changed.
    fn upload_maps(&mut self, queue: &wgpu::Queue, layers: &[CloudLayer]) {
        let maps: Vec<&CoverageMap> = layers.iter().filter_map(|l| l.coverage_map.as_ref()).collect();
        if maps.iter().copied().eq(self.uploaded_maps.iter()) {
            return;
        }
        let (width, height) = COVERAGE_MAP_SIZE;
        for (slot, map) in maps.iter().enumerate() {
            queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &self.maps,
                    mip_level: 0,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: slot as u32,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                bytemuck::cast_slice(&resampled(map)),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(width * 2),
                    rows_per_image: Some(height),
                },
                wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
            );
        }
        self.uploaded_maps = maps.into_iter().cloned().collect();
    }

    /// Whether the frame last prepared has clouds.
    pub(super) fn any(&self) -> bool {
        self.layers > 0
    }

    /// What every cloud stage reads: the medium, the view, the layers and their coverage maps.
    fn layer_resources<'a>(&'a self, resources: &AerialPerspectiveResources<'a>) -> Vec<(u32, wgpu::BindingResource<'a>)> {
        vec![
            (binding::PARAMS, resources.params.as_entire_binding()),
            (binding::VIEW, resources.view.as_entire_binding()),
            (binding::CLOUDS, self.uniforms.as_entire_binding()),
            (
                binding::CLOUD_COVERAGE_MAPS,
                wgpu::BindingResource::TextureView(&self.maps_view),
            ),
            (
                binding::MAP_SAMPLER,
                wgpu::BindingResource::Sampler(&self.map_sampler),
            ),
        ]
    }

    /// Every resource of the march: `hdr_in` and `hdr_out` as given, the depth buffer `depth`.
    fn resources<'a>(
        &'a self,
        resources: &AerialPerspectiveResources<'a>,
        depth: &'a wgpu::TextureView,
        hdr_in: &'a wgpu::TextureView,
        hdr_out: &'a wgpu::TextureView,
    ) -> Vec<(u32, wgpu::BindingResource<'a>)> {
        let luts = resources.luts;
        let mut all = self.layer_resources(resources);
        all.extend([
            (
                binding::TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.transmittance.view),
            ),
            (
                binding::IRRADIANCE,
                wgpu::BindingResource::TextureView(&luts.irradiance.view),
            ),
            (binding::SAMPLER, wgpu::BindingResource::Sampler(resources.sampler)),
            (
                binding::AERIAL_SCATTERING,
                wgpu::BindingResource::TextureView(&luts.aerial_scattering.view),
            ),
            (
                binding::AERIAL_TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.aerial_transmittance.view),
            ),
            (binding::SCENE_DEPTH, wgpu::BindingResource::TextureView(depth)),
            (binding::HDR_IN, wgpu::BindingResource::TextureView(hdr_in)),
            (binding::HDR_OUT, wgpu::BindingResource::TextureView(hdr_out)),
            (
                binding::CLOUD_SHADOW_MAP,
                wgpu::BindingResource::TextureView(&self.shadow_map_view),
            ),
        ]);
        all.push(resources.surface.texture_resource());
        all
    }

    /// Builds the shadow map's stage on first use (its resources never change).
    fn build_shadow_stage(&mut self, device: &wgpu::Device, resources: &AerialPerspectiveResources<'_>) {
        if self.shadow_stage.is_some() {
            return;
        }
        let mut all = self.layer_resources(resources);
        all.push((
            binding::CLOUD_SHADOW_OUT,
            wgpu::BindingResource::TextureView(&self.shadow_map_view),
        ));
        self.shadow_stage = Some(ComputeStage::new(
            device,
            "AtmospherePass cloud shadow map",
            &shaders::CLOUD_SHADOW_MAP,
            &shadow_entries(),
            &all,
        ));
    }

    /// Encodes the shadow map of this frame's suns ahead of the march (before the objects that
    /// read it): the next march does not encode it again. Nothing without layers.
    pub(super) fn record_shadow_map_ahead(&self, encoder: &mut wgpu::CommandEncoder) {
        if self.any() {
            self.dispatch_shadow_map(encoder);
            self.shadow_map_ahead.set(true);
        }
    }

    /// Encodes the shadow map for the march, unless it was encoded ahead for this one.
    fn record_shadow_map(&self, encoder: &mut wgpu::CommandEncoder) {
        if !self.shadow_map_ahead.take() {
            self.dispatch_shadow_map(encoder);
        }
    }

    fn dispatch_shadow_map(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(stage) = &self.shadow_stage
            && self.suns > 0
        {
            let side = CLOUD_SHADOW_SIZE.div_ceil(8);
            stage.dispatch(encoder, (side * self.suns, side, 1));
        }
    }

    /// The clouds' shadow map (`shaders/clouds/shadow.wgsl`), for the object pass.
    pub(super) fn shadow_map_view(&self) -> &wgpu::TextureView {
        &self.shadow_map_view
    }

    /// Binds `target` (an HDR texture with `TEXTURE_BINDING | COPY_DST`) and its depth buffer.
    pub(super) fn bind_target(
        &mut self,
        device: &wgpu::Device,
        resources: &AerialPerspectiveResources<'_>,
        target: &wgpu::Texture,
        depth: &wgpu::TextureView,
    ) {
        self.build_shadow_stage(device, resources);
        let scratch = scratch_for(device, target, "firmament AtmospherePass clouds scratch");
        let scratch_view = scratch.create_view(&wgpu::TextureViewDescriptor::default());
        let target_view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let previous = self.on_target.take();
        let all = self.resources(resources, depth, &target_view, &scratch_view);
        let stage = match previous {
            Some(OnTarget { mut stage, .. }) => {
                stage.rebind(device, &all);
                stage
            }
            None => ComputeStage::new(
                device,
                "AtmospherePass clouds",
                &shaders::CLOUDS_MARCH,
                &entries(),
                &all,
            ),
        };
        self.on_target = Some(OnTarget {
            stage,
            target: target.clone(),
            scratch,
        });
    }

    /// Binds a caller's depth buffer `depth` (its colour target's size) for
    /// [`record_into`](Self::record_into) a colour target of `color`: the layer at that size (kept
    /// while the size does not change) and the blend's pipeline for that format (built once).
    /// Nothing without clouds in the frame last prepared.
    pub(super) fn bind_caller(
        &mut self,
        device: &wgpu::Device,
        resources: &AerialPerspectiveResources<'_>,
        depth: &wgpu::TextureView,
        color: wgpu::TextureFormat,
    ) {
        if !self.any() {
            return;
        }
        self.build_shadow_stage(device, resources);
        let size = depth.texture().size();
        let previous = self.into_caller.take();
        let (layer, layer_view) = match &previous {
            Some(caller) if caller.layer.size() == size => (caller.layer.clone(), caller.layer_view.clone()),
            _ => {
                let layer = crate::targets::texture_2d(
                    device,
                    "firmament AtmospherePass clouds layer",
                    (size.width, size.height),
                    crate::targets::HDR_FORMAT,
                    wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                );
                let view = layer.create_view(&wgpu::TextureViewDescriptor::default());
                (layer, view)
            }
        };
        let placeholder = match &previous {
            Some(caller) => caller.placeholder.clone(),
            None => crate::targets::hdr_placeholder(device, "firmament AtmospherePass clouds unread input"),
        };
        let all = self.resources(resources, depth, &placeholder, &layer_view);
        let (stage, blend, blend_layout) = match previous {
            Some(IntoCaller {
                mut stage,
                blend,
                blend_layout,
                ..
            }) => {
                stage.rebind(device, &all);
                (stage, blend, blend_layout)
            }
            None => {
                let stage = ComputeStage::with_constants(
                    device,
                    "AtmospherePass clouds layer",
                    &shaders::CLOUDS_MARCH,
                    &entries(),
                    &all,
                    &[("CLOUD_LAYER", 1.0)],
                );
                let (blend, blend_layout) = blend_pipeline(device, color);
                (stage, blend, blend_layout)
            }
        };
        let blend_group = bind_group(
            device,
            BLEND_OWNER,
            &blend_layout,
            &[(binding::HDR_IN, wgpu::BindingResource::TextureView(&layer_view))],
        );
        self.into_caller = Some(IntoCaller {
            stage,
            layer,
            layer_view,
            placeholder,
            blend,
            blend_layout,
            blend_group,
        });
    }

    /// Encodes the clouds over a caller's `color` (loaded, not cleared), bound by
    /// [`bind_caller`](Self::bind_caller) (after the aerial-perspective volume); false, encoding
    /// nothing, without layers or a bound target.
    pub(super) fn record_into(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) -> bool {
        let Some(caller) = self.into_caller.as_ref().filter(|_| self.any()) else {
            return false;
        };
        self.record_shadow_map(encoder);
        let size = caller.layer.size();
        caller
            .stage
            .dispatch(encoder, (size.width.div_ceil(8), size.height.div_ceil(8), 1));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("firmament AtmospherePass clouds blend"),
            color_attachments: &[Some(load_color_attachment(color))],
            ..Default::default()
        });
        pass.set_pipeline(&caller.blend);
        pass.set_bind_group(0, &caller.blend_group, &[]);
        pass.draw(0..3, 0..1);
        true
    }

    /// Encodes the clouds over the bound target and the copy back (after the aerial-perspective
    /// volume); false, encoding nothing, without layers or a bound target.
    pub(super) fn record_on_target(&self, encoder: &mut wgpu::CommandEncoder) -> bool {
        let Some(on) = self.on_target.as_ref().filter(|_| self.any()) else {
            return false;
        };
        self.record_shadow_map(encoder);
        let size = on.target.size();
        on.stage
            .dispatch(encoder, (size.width.div_ceil(8), size.height.div_ceil(8), 1));
        encoder.copy_texture_to_texture(on.scratch.as_image_copy(), on.target.as_image_copy(), size);
        true
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_shadow_map_side_is_the_shaders() {
        let source = crate::shaders::module_source("clouds/shadow").expect("the module");
        assert!(
            source.contains(&format!("const CLOUD_SHADOW_SIZE: u32 = {}u;", super::CLOUD_SHADOW_SIZE)),
            "clouds/shadow.wgsl declares another CLOUD_SHADOW_SIZE"
        );
    }
}
