// common/fullscreen.wgsl — shared: one triangle that covers the whole viewport.
//
// Conventions: `ndc` is normalised device coordinates, x right and y up, both in [-1, 1] on
// screen. Clip-space depth follows firmament's reversed-Z: 1 at the near plane, 0 at infinity,
// so `FAR_DEPTH` puts a primitive at the far plane behind everything already drawn. Pipelines
// drawing into a standard-Z depth buffer (near 0, far 1: an embedder's) override it with 1.

override FAR_DEPTH: f32 = 0.0;

struct FullscreenVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

// Vertex 0, 1, 2 → (-1, -1), (3, -1), (-1, 3): a triangle whose inside covers [-1, 1]².
fn fullscreen_vertex(index: u32, depth: f32) -> FullscreenVertex {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    let ndc = uv * 2.0 - 1.0;
    var out: FullscreenVertex;
    out.clip = vec4<f32>(ndc, depth, 1.0);
    out.ndc = ndc;
    return out;
}
