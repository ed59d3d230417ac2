//! Auto-exposure on the GPU, with no read-back in the frame: `camera/exposure_meter.wgsl` bins the
//! HDR image's luminance into a histogram (the suns' discs left out), `camera/exposure_adapt.wgsl`
//! turns it into the metered luminance, the EV100 that puts it on middle grey and the step towards
//! it, and writes the exposure multiplier into a 1 × 1 texture the output pass reads. The state
//! (the EV100 in use) stays on the GPU between frames. Reference: [`firmament_core::auto_exposure`].

use firmament_core::Camera;
use firmament_core::Frame;
use firmament_core::auto_exposure::AutoExposure;

use super::binding;
use crate::gpu_types::camera::METERING_BINS;
use crate::gpu_types::{ExposureStateGpu, MeteringUniforms};
use crate::passes::common::{uniform_buffer, uniform_entry_in};
use crate::passes::compute::{ComputeStage, storage_buffer_entry, storage_entry, texture_entry};
use crate::shaders;
use crate::targets::texture_2d;

/// The meter's pixels per workgroup side (`METERING_TILE` in WGSL): 16 cells.
const METERING_TILE: u32 = 16 * firmament_core::auto_exposure::METERING_CELL;

/// The format of the exposure texture: one `f32`, the multiplier.
const EXPOSURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// Meters each frame and keeps the exposure it chose.
#[derive(Debug)]
pub struct ExposurePass {
    meter: ComputeStage,
    adapt: ComputeStage,
    uniforms: wgpu::Buffer,
    histogram: wgpu::Buffer,
    state: wgpu::Buffer,
    exposure_view: wgpu::TextureView,
    size: (u32, u32),
    interval: Option<f64>,
}

impl ExposurePass {
    /// Builds both pipelines, the histogram, the state and the exposure texture.
    pub fn new(device: &wgpu::Device) -> Self {
        let uniforms = uniform_buffer::<MeteringUniforms>(device, "firmament ExposurePass uniforms");
        let histogram = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament ExposurePass histogram"),
            size: u64::from(2 * METERING_BINS * 4),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let state = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament ExposurePass state"),
            size: std::mem::size_of::<ExposureStateGpu>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let exposure = texture_2d(device, "firmament ExposurePass exposure", (1, 1), EXPOSURE_FORMAT, usage);
        let exposure_view = exposure.create_view(&wgpu::TextureViewDescriptor::default());
        // The meter binds the frame's HDR view in `prepare`; until then, a texel of its own.
        let placeholder = crate::targets::hdr_placeholder(device, "firmament ExposurePass placeholder");
        let compute = wgpu::ShaderStages::COMPUTE;
        let meter = ComputeStage::new(
            device,
            "ExposurePass meter",
            &shaders::EXPOSURE_METER,
            &[
                uniform_entry_in(binding::METERING, compute),
                texture_entry(binding::HDR_IN, false),
                storage_buffer_entry(binding::HISTOGRAM),
            ],
            &[
                (binding::METERING, uniforms.as_entire_binding()),
                (binding::HDR_IN, wgpu::BindingResource::TextureView(&placeholder)),
                (binding::HISTOGRAM, histogram.as_entire_binding()),
            ],
        );
        let adapt = ComputeStage::new(
            device,
            "ExposurePass adapt",
            &shaders::EXPOSURE_ADAPT,
            &[
                uniform_entry_in(binding::METERING, compute),
                storage_buffer_entry(binding::HISTOGRAM),
                storage_buffer_entry(binding::EXPOSURE_STATE),
                storage_entry(binding::EXPOSURE_OUT, EXPOSURE_FORMAT),
            ],
            &[
                (binding::METERING, uniforms.as_entire_binding()),
                (binding::HISTOGRAM, histogram.as_entire_binding()),
                (binding::EXPOSURE_STATE, state.as_entire_binding()),
                (binding::EXPOSURE_OUT, wgpu::BindingResource::TextureView(&exposure_view)),
            ],
        );
        Self {
            meter,
            adapt,
            uniforms,
            histogram,
            state,
            exposure_view,
            size: (0, 0),
            interval: None,
        }
    }

    /// Sets the time between frames over which the exposure adapts at `auto`'s speeds (a
    /// viewer's frame interval, a time-lapse's frame time, seconds); `None` (the default) meters
    /// each frame afresh, as stills should.
    pub fn set_interval(&mut self, seconds: Option<f64>) {
        self.interval = seconds;
    }

    /// Uploads the meter's uniforms for `frame` seen by `camera` (aspect set) and binds `hdr`
    /// (the image of `size` pixels it meters).
    #[expect(clippy::too_many_arguments, reason = "the frame's parts a pass reads, each once")]
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        frame: &Frame,
        camera: &Camera,
        auto: &AutoExposure,
        hdr: &wgpu::TextureView,
        size: (u32, u32),
    ) {
        let uniforms = MeteringUniforms::new(frame, camera, auto, size, self.interval);
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
        self.meter.rebind(
            device,
            &[
                (binding::METERING, self.uniforms.as_entire_binding()),
                (binding::HDR_IN, wgpu::BindingResource::TextureView(hdr)),
                (binding::HISTOGRAM, self.histogram.as_entire_binding()),
            ],
        );
        self.size = size;
    }

    /// Encodes the meter and the adaptation (after everything is drawn into the HDR image).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let groups = |side: u32| side.div_ceil(METERING_TILE);
        self.meter.dispatch(encoder, (groups(self.size.0), groups(self.size.1), 1));
        self.adapt.dispatch(encoder, (1, 1, 1));
    }

    /// The 1 × 1 `R32Float` texture holding the exposure multiplier the last recorded frame chose.
    pub fn exposure_view(&self) -> &wgpu::TextureView {
        &self.exposure_view
    }

    /// The state buffer ([`ExposureStateGpu`]; for read-back by tests and tools).
    pub fn state_buffer(&self) -> &wgpu::Buffer {
        &self.state
    }
}
