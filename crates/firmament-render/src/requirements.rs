//! What firmament needs of a device, stated up front: [`required_features`], [`required_limits`]
//! and [`check_device`], which [`GpuContext::from_device`](crate::GpuContext::from_device) runs so
//! that a device short of something fails with a [`RenderError`] naming it, never with a wgpu
//! validation panic halfway through building the passes.

use crate::error::{LimitShortfall, RenderError};

/// The device features firmament must have: none.
///
/// Every pass runs on core WebGPU features (the transmittance LUT is `Rgba32Float`, written by a
/// compute pass and read unfiltered, so not even `FLOAT32_FILTERABLE`; the lens flares'
/// indirect dispatches and draws are core, `DownlevelFlags::INDIRECT_EXECUTION` on GL ES 3.1).
/// Optional: GPU timestamps ([`TIMESTAMP_FEATURES`]), used by pass timing and the benchmarks only
/// when the device has them.
pub fn required_features() -> wgpu::Features {
    wgpu::Features::empty()
}

/// The optional device features GPU timestamps need: queries written between the commands of an
/// encoder ([`Renderer::enable_pass_timing`](crate::Renderer::enable_pass_timing)).
pub const TIMESTAMP_FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);

/// The device limits firmament needs: `wgpu::Limits::downlevel_defaults()` with each limit that
/// firmament's passes consume set to exactly what they use — so that [`check_device`] refuses a
/// device below any of them, and a device at them renders every scene (a test renders every
/// preset on one; lowering any of these by one made wgpu's validation fail when they were
/// measured).
///
/// | limit | firmament's use | where |
/// |---|---|---|
/// | `max_bind_groups` | 2 | objects: their own group and the sun shadow maps' |
/// | `max_sampled_textures_per_shader_stage` | 9 | the clouds' march: their coverage maps and shadow map, the transmittance and irradiance LUTs, the aerial-perspective volume's two atlases, the depth buffer, the HDR image and the planet's surface map (WebGPU's default is 16) |
/// | `max_samplers_per_shader_stage` | 2 | objects: their texture's sampler and the shadow maps' comparison sampler |
/// | `max_storage_buffers_per_shader_stage` | 2 | lens flares: their records and their state (occlusion, binning, elements) |
/// | `max_storage_textures_per_shader_stage` | 2 | the aerial-perspective volume: scattering and transmittance |
/// | `max_uniform_buffers_per_shader_stage` | 3 | the atmosphere's sky lighting |
/// | `max_vertex_buffers` | 2 | objects: geometry and per-vertex shading |
/// | `max_vertex_attributes` | 6 | objects |
/// | `max_inter_stage_shader_variables` | 9 | objects: eight varyings and `front_facing` |
/// | `max_compute_workgroup_size_x`, `_y`, `_z` | 256, 8, 1 | sky lighting and the transmittance LUT (256 × 1), the LUTs (8 × 8) |
/// | `max_compute_invocations_per_workgroup` | 256 | sky lighting, the transmittance LUT |
/// | `max_texture_dimension_2d` | 2048 | the default sun shadow map (`shadows.map_size`, clamped to the device's largest texture); the sky-view LUT takes 1536, a 192-texel tile for each of 8 suns |
///
/// The others keep `downlevel_defaults()`' values: sizes that depend on the scene (buffers and
/// bindings, flare-image layers, object textures), workgroup memory (which wgpu does not check)
/// and limits firmament does not use. Those are the limits wgpu guarantees on OpenGL ES 3.1, the
/// oldest API with the compute shaders firmament needs.
///
/// Images wider or taller than the device's `max_texture_dimension_2d` are refused per frame
/// ([`RenderError::ImageSize`]). Ask for the adapter's texture sizes, or merge in your own
/// renderer's needs, when you create the device:
///
/// ```no_run
/// # fn limits(adapter: &wgpu::Adapter, mine: &wgpu::Limits) -> wgpu::Limits {
/// firmament_render::required_limits()
///     .using_resolution(adapter.limits()) // images as large as the adapter allows
///     .or_better_values_from(mine) // and whatever your own passes need
/// # }
/// ```
pub fn required_limits() -> wgpu::Limits {
    wgpu::Limits {
        max_bind_groups: 2,
        max_sampled_textures_per_shader_stage: 9,
        max_samplers_per_shader_stage: 2,
        max_storage_buffers_per_shader_stage: 2,
        max_storage_textures_per_shader_stage: 2,
        max_uniform_buffers_per_shader_stage: 3,
        max_vertex_buffers: 2,
        max_vertex_attributes: 6,
        max_inter_stage_shader_variables: 9,
        max_compute_workgroup_size_x: 256,
        max_compute_workgroup_size_y: 8,
        max_compute_workgroup_size_z: 1,
        max_compute_invocations_per_workgroup: 256,
        max_texture_dimension_2d: 2048,
        ..wgpu::Limits::downlevel_defaults()
    }
}

/// Checks that `device` has [`required_features`] and [`required_limits`]; the error names
/// every missing feature, or every limit that falls short with its value and firmament's.
pub fn check_device(device: &wgpu::Device) -> Result<(), RenderError> {
    check(&device.adapter_info().name, device.features(), &device.limits())
}

/// [`check_device`] for features and limits not yet on a device (an adapter's, before asking it
/// for one).
pub(crate) fn check(adapter: &str, features: wgpu::Features, limits: &wgpu::Limits) -> Result<(), RenderError> {
    let missing = required_features() - features;
    if !missing.is_empty() {
        return Err(RenderError::MissingFeatures {
            adapter: adapter.to_owned(),
            missing,
        });
    }
    let mut shortfalls = Vec::new();
    required_limits().check_limits_with_fail_fn(limits, false, |name, required, available| {
        shortfalls.push(LimitShortfall {
            name,
            required,
            available,
        });
    });
    if !shortfalls.is_empty() {
        return Err(RenderError::LimitsTooLow {
            adapter: adapter.to_owned(),
            shortfalls,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn required_limits_pass_their_own_check() {
        assert!(check("test adapter", required_features(), &required_limits()).is_ok());
    }

    #[test]
    fn webgpu_default_limits_suffice() {
        // Since the multiple-scattering LUT is a compute pass (it drew seven targets at once).
        assert!(check("test adapter", required_features(), &wgpu::Limits::default()).is_ok());
    }

    #[test]
    fn every_shortfall_is_named_with_both_values() {
        let limits = wgpu::Limits {
            max_storage_buffers_per_shader_stage: 0,
            max_texture_dimension_2d: 512,
            min_uniform_buffer_offset_alignment: 512,
            ..required_limits()
        };
        let Err(RenderError::LimitsTooLow { adapter, shortfalls }) =
            check("test adapter", required_features(), &limits)
        else {
            panic!("limits below firmament's must be refused");
        };
        assert_eq!(adapter, "test adapter");
        let named: Vec<_> = shortfalls.iter().map(|s| (s.name, s.required, s.available)).collect();
        assert_eq!(
            named,
            [
                ("max_texture_dimension_2d", 2048, 512),
                ("max_storage_buffers_per_shader_stage", 2, 0),
                ("min_uniform_buffer_offset_alignment", 256, 512),
            ]
        );
        let message = RenderError::LimitsTooLow { adapter, shortfalls }.to_string();
        assert!(
            message.contains("`max_storage_buffers_per_shader_stage` is 0, firmament needs at least 2"),
            "{message}"
        );
        assert!(
            message.contains("`min_uniform_buffer_offset_alignment` is 512, firmament needs at most 256"),
            "{message}"
        );
    }
}
