//! Bloom: light spread around bright pixels as a lens and an eye spread it, energy-conserving —
//! the dual-filter pyramid of Bjørge ("Bandwidth-Efficient Rendering", SIGGRAPH 2015) as compute
//! passes. The way down halves the HDR image [`BLOOM_LEVELS`] times (`camera/bloom_from_image.wgsl`,
//! then `camera/bloom_down.wgsl`);
//! the way up mixes each level with the coarser level's bloom (`camera/bloom_up.wgsl`), so the
//! finest level holds a wide blur whose weights sum to one. The output pass mixes it in:
//! `(1 − s) · image + s · bloom` for a strength `s` (`display.bloom`), which moves light and keeps
//! the picture's total.

use super::binding;
use crate::passes::compute::{ComputeKernel, sampler_entry, storage_entry, texture_entry};
use crate::shaders;
use crate::passes::common::linear_clamp_sampler;
use crate::targets::{HDR_FORMAT, texture_2d};

/// The most levels of the pyramid, each half the size of the one before (the first half the
/// image's): at 1920 × 1080 the coarsest is 30 × 17 texels.
pub const BLOOM_LEVELS: usize = 6;

/// The coarser level's share in each step up (`BLOOM_SPREAD` in WGSL): level `i` of `n` weighs
/// `(1 − k)·kⁱ` in the bloom (the coarsest `kⁿ⁻¹`); larger spreads the light wider.
pub const BLOOM_SPREAD: f64 = 0.6;

/// One level of the pyramid: its image on the way down and its bloom on the way up.
#[derive(Debug)]
struct Level {
    size: (u32, u32),
    down: wgpu::TextureView,
    /// `None` for the coarsest level, whose bloom is its own image.
    up: Option<wgpu::TextureView>,
    /// Down from the finer level (for the first, bound per frame in `prepare`).
    down_bind: Option<wgpu::BindGroup>,
    up_bind: Option<wgpu::BindGroup>,
}

/// The bloom pyramid for images of one size.
#[derive(Debug)]
pub struct BloomPass {
    /// The first step down, from the image; the others, from a level.
    from_image: ComputeKernel,
    down: ComputeKernel,
    up: ComputeKernel,
    sampler: wgpu::Sampler,
    levels: Vec<Level>,
    size: (u32, u32),
    placeholder: wgpu::TextureView,
}

impl BloomPass {
    /// Builds both pipelines; the pyramid is made by the first `prepare`.
    pub fn new(device: &wgpu::Device) -> Self {
        let from_image = ComputeKernel::new(
            device,
            "BloomPass down from the image",
            &shaders::BLOOM_FROM_IMAGE,
            &[
                texture_entry(binding::BLOOM_IN, false),
                storage_entry(binding::BLOOM_OUT, HDR_FORMAT),
            ],
            &[],
        );
        let down = ComputeKernel::new(
            device,
            "BloomPass down",
            &shaders::BLOOM_DOWN,
            &[
                texture_entry(binding::BLOOM_IN, true),
                sampler_entry(binding::BLOOM_SAMPLER),
                storage_entry(binding::BLOOM_OUT, HDR_FORMAT),
            ],
            &[],
        );
        let up = ComputeKernel::new(
            device,
            "BloomPass up",
            &shaders::BLOOM_UP,
            &[
                texture_entry(binding::BLOOM_IN, false),
                texture_entry(binding::BLOOM_COARSER, true),
                sampler_entry(binding::BLOOM_SAMPLER),
                storage_entry(binding::BLOOM_OUT, HDR_FORMAT),
            ],
            &[("BLOOM_SPREAD", BLOOM_SPREAD)],
        );
        let sampler = linear_clamp_sampler(device, "firmament BloomPass sampler");
        Self {
            from_image,
            down,
            up,
            sampler,
            levels: Vec::new(),
            size: (0, 0),
            placeholder: crate::targets::hdr_placeholder(device, "firmament BloomPass placeholder"),
        }
    }

    /// Makes the pyramid for images of `size` (when it changed) and binds `hdr`, the image to
    /// bloom.
    pub fn prepare(&mut self, device: &wgpu::Device, hdr: &wgpu::TextureView, size: (u32, u32)) {
        if size != self.size {
            self.levels = self.make_levels(device, size);
            self.size = size;
        }
        if let Some(first) = self.levels.first_mut() {
            first.down_bind = Some(self.from_image.bind(
                device,
                &[
                    (binding::BLOOM_IN, wgpu::BindingResource::TextureView(hdr)),
                    (binding::BLOOM_OUT, wgpu::BindingResource::TextureView(&first.down)),
                ],
            ));
        }
    }

    /// The levels for an image of `size`, their bind groups made (but the first's way down).
    fn make_levels(&self, device: &wgpu::Device, size: (u32, u32)) -> Vec<Level> {
        let mut sizes = Vec::new();
        let mut at = size;
        while sizes.len() < BLOOM_LEVELS && at.0.min(at.1) >= 2 {
            at = (at.0.div_ceil(2), at.1.div_ceil(2));
            sizes.push(at);
        }
        let coarsest = sizes.len().saturating_sub(1);
        let mut levels: Vec<Level> = sizes
            .iter()
            .enumerate()
            .map(|(i, &size)| Level {
                size,
                down: level_texture(device, size, &format!("firmament BloomPass down {i}")),
                up: (i < coarsest).then(|| level_texture(device, size, &format!("firmament BloomPass up {i}"))),
                down_bind: None,
                up_bind: None,
            })
            .collect();
        for i in 1..levels.len() {
            let bind = self.down.bind(
                device,
                &[
                    (binding::BLOOM_IN, wgpu::BindingResource::TextureView(&levels[i - 1].down)),
                    (binding::BLOOM_SAMPLER, wgpu::BindingResource::Sampler(&self.sampler)),
                    (binding::BLOOM_OUT, wgpu::BindingResource::TextureView(&levels[i].down)),
                ],
            );
            levels[i].down_bind = Some(bind);
        }
        for i in 0..coarsest {
            let coarser = levels[i + 1].up.as_ref().unwrap_or(&levels[i + 1].down);
            let Some(up) = &levels[i].up else { continue };
            let bind = self.up.bind(
                device,
                &[
                    (binding::BLOOM_IN, wgpu::BindingResource::TextureView(&levels[i].down)),
                    (binding::BLOOM_COARSER, wgpu::BindingResource::TextureView(coarser)),
                    (binding::BLOOM_SAMPLER, wgpu::BindingResource::Sampler(&self.sampler)),
                    (binding::BLOOM_OUT, wgpu::BindingResource::TextureView(up)),
                ],
            );
            levels[i].up_bind = Some(bind);
        }
        levels
    }

    /// Encodes the way down and the way up (after everything is drawn into the HDR image).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let groups = |size: (u32, u32)| (size.0.div_ceil(8), size.1.div_ceil(8), 1);
        for (i, level) in self.levels.iter().enumerate() {
            let kernel = if i == 0 { &self.from_image } else { &self.down };
            if let Some(bind) = &level.down_bind {
                kernel.dispatch(encoder, bind, groups(level.size));
            }
        }
        for level in self.levels.iter().rev() {
            if let Some(bind) = &level.up_bind {
                self.up.dispatch(encoder, bind, groups(level.size));
            }
        }
    }

    /// The bloom at half the image's size, for the output pass to sample (a black texel before
    /// the first `prepare`, or for images too small to bloom).
    pub fn bloom_view(&self) -> &wgpu::TextureView {
        match self.levels.first() {
            Some(level) => level.up.as_ref().unwrap_or(&level.down),
            None => &self.placeholder,
        }
    }
}

/// A level's texture: written by one dispatch, read by the next.
fn level_texture(device: &wgpu::Device, size: (u32, u32), label: &str) -> wgpu::TextureView {
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
    texture_2d(device, label, size, HDR_FORMAT, usage).create_view(&wgpu::TextureViewDescriptor::default())
}
