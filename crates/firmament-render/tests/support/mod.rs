//! Helpers shared by the GPU test binaries.

/// Clears `targets` to `color` and reversed-Z `depth` in a pass of its own.
pub(crate) fn clear_targets(
    encoder: &mut wgpu::CommandEncoder,
    targets: &firmament_render::FrameTargets,
    color: wgpu::Color,
    depth: f32,
) {
    let _clear = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("test clear"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &targets.hdr_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(color),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &targets.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(depth),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    });
}
