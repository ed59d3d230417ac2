//! The device firmament renders with: one of the caller's ([`GpuContext::from_device`]) or one
//! it opens itself ([`GpuContext::headless`]). One [`GpuContext`] per process is plenty.

use std::fmt;

use crate::error::RenderError;

/// Which graphics API to render with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// The best available: Vulkan, Metal or DX12 first, OpenGL (ES) last.
    #[default]
    Auto,
    /// Vulkan only (on Linux without a GPU: Mesa's lavapipe).
    Vulkan,
    /// OpenGL ES / WebGL through EGL or WGL (on Linux without a GPU: Mesa's llvmpipe).
    Gl,
    /// Metal only (macOS).
    Metal,
    /// DirectX 12 only (Windows).
    Dx12,
}

impl Backend {
    /// The wgpu backend set to search.
    pub fn backends(self) -> wgpu::Backends {
        match self {
            Self::Auto => wgpu::Backends::all(),
            Self::Vulkan => wgpu::Backends::VULKAN,
            Self::Gl => wgpu::Backends::GL,
            Self::Metal => wgpu::Backends::METAL,
            Self::Dx12 => wgpu::Backends::DX12,
        }
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Auto => "auto",
            Self::Vulkan => "vulkan",
            Self::Gl => "gl",
            Self::Metal => "metal",
            Self::Dx12 => "dx12",
        })
    }
}

/// The device and queue every firmament GPU object lives on, checked against
/// [`required_features`](crate::required_features) and [`required_limits`](crate::required_limits).
///
/// Made by [`from_device`](Self::from_device) from a device of your own (embedding), or by
/// [`headless`](Self::headless) / [`from_adapter`](Self::from_adapter), which open one and go
/// through `from_device` too. It holds no instance or adapter: `wgpu::Device` and `wgpu::Queue`
/// are shared handles, so the context and your renderer use the same device.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct GpuContext {
    /// The device every firmament GPU object lives on.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
}

impl GpuContext {
    /// Wraps a device and queue the caller created (its own renderer's), after checking that the
    /// device has firmament's [`required_features`](crate::required_features) and
    /// [`required_limits`](crate::required_limits): a device short of either gives
    /// [`RenderError::MissingFeatures`] or [`RenderError::LimitsTooLow`], naming what is missing.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue) -> Result<Self, RenderError> {
        crate::requirements::check_device(&device)?;
        Ok(Self { device, queue })
    }

    /// Finds an adapter for `backend` without a window and opens a device on it, with the
    /// adapter's own limits (so large images work where the hardware allows).
    pub fn headless(backend: Backend) -> Result<Self, RenderError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backend.backends();
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            // Limit bucketing hides real limits for fingerprinting reasons; we are trusted code.
            apply_limit_buckets: false,
        }))
        .map_err(|e| RenderError::NoAdapter {
            backend: backend.to_string(),
            reason: e.to_string(),
        })?;
        // The device keeps what it needs of the instance alive.
        Self::from_adapter(&adapter)
    }

    /// Opens a device on an adapter the caller chose (for example one compatible with a window's
    /// surface), with firmament's required features, the optional GPU timestamps where the
    /// adapter has them, and the adapter's own limits.
    pub fn from_adapter(adapter: &wgpu::Adapter) -> Result<Self, RenderError> {
        let info = adapter.get_info();
        tracing::info!(adapter = %info.name, backend = ?info.backend, driver = %info.driver, "GPU adapter");
        // Refuse an adapter that cannot meet the requirements before asking it for a device.
        crate::requirements::check(&info.name, adapter.features(), &adapter.limits())?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("firmament device"),
            // Optional: GPU timestamps for `firmament bench`, where the adapter has them.
            required_features: crate::requirements::required_features()
                | (adapter.features() & crate::requirements::TIMESTAMP_FEATURES),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| RenderError::RequestDevice {
            adapter: info.name.clone(),
            reason: e.to_string(),
        })?;
        Self::from_device(device, queue)
    }

    /// The largest image side the device can render, pixels.
    pub fn max_image_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Checks that an image of `width` × `height` can be rendered on this device.
    pub fn check_image_size(&self, width: u32, height: u32) -> Result<(), RenderError> {
        let max = self.max_image_side();
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::ImageSize { width, height, max });
        }
        Ok(())
    }

    /// A one-line description of the adapter, for logs and benchmarks.
    pub fn adapter_summary(&self) -> String {
        let info = self.device.adapter_info();
        format!("{} ({:?}, {})", info.name, info.backend, info.driver)
    }
}
