// flare.wgsl — lens-flare elements: seed 003's glows, streaks and halos, plus aperture ghosts,
// drawn procedurally so no texture files are needed — or, for image elements, pictures from a 2D
// array texture (one layer per image file, RGB × alpha as stored, like NeHe's sprites) — summed
// per pixel by a compute pass into the flare's own target, then added to the HDR target before
// tone mapping by one quad.
//
// Each element lights only the pixels where its light can be above FLARE_NEGLIGIBLE (the radius
// `prepare` put in its record) and only while its source is seen: the binning pass
// (flare_occlusion.wgsl) marks, per bin of pixels, the elements that may reach it; each pixel
// sums its bin's, in element order (so a hidden source changes no bit of the others' light).
// Both passes here cover only the rectangle the occlusion pass found, through indirect
// arguments: nothing runs when no source is seen. Why compute: fragment work costs ten times
// compute work on some data-centre GPUs (docs/PERFORMANCE.md, "Lens flares").
//
// Conventions: NDC as in flare/bindings.wgsl; an element's `uv` runs over [-1, 1]^2 of its quad,
// r = |uv| = 1 at its radius. A radius is in units of half the screen height, divided by the
// aspect in x so elements stay round (times `stretch`). The colour is scaled by the source's
// visibility, written by flare_occlusion.wgsl earlier in the same frame.

#import flare/bindings
#import generated/constants

// Polygon "radius" of uv for a regular n-gon turned by `rotation`: 1 on its edge (a disc for
// n = 0).
fn ghost_edge(uv: vec2<f32>, sides: f32, rotation: f32) -> f32 {
    let r = length(uv);
    if sides < 3.0 {
        return r;
    }
    let sector = 6.2831853 / sides;
    let a = atan2(uv.y, uv.x) - rotation;
    let local = a - sector * floor(a / sector) - 0.5 * sector;
    return r * cos(local) / cos(0.5 * sector);
}

// The image element's texel at `uv`, turned by `rotation` (radians, counter-clockwise), at mip
// `level`: RGB × alpha. Image row 0 is the picture's bottom (GL's t = 0), which is v = 0 here, at
// uv.y = -1.
fn image_texel(uv: vec2<f32>, layer: f32, rotation: f32, level: f32) -> vec3<f32> {
    let c = cos(rotation);
    let s = sin(rotation);
    let turned = vec2<f32>(c * uv.x + s * uv.y, -s * uv.x + c * uv.y);
    let st = turned * 0.5 + 0.5;
    let inside = all(st >= vec2<f32>(0.0)) && all(st <= vec2<f32>(1.0));
    let texel = textureSampleLevel(images, image_sampler, clamp(st, vec2<f32>(0.0), vec2<f32>(1.0)), i32(layer + 0.5), level);
    return select(vec3<f32>(0.0), texel.rgb * texel.a, inside);
}

// Element `e`'s light at `ndc` with `seen` of it showing, for the procedural shapes: none
// beyond its cut radius.
fn shape_light(e: InstanceIn, ndc: vec2<f32>, seen: f32) -> vec3<f32> {
    let uv = element_uv(e, ndc);
    let r = length(uv);
    if r >= bitcast<f32>(e.source.w) {
        return vec3<f32>(0.0);
    }
    let kind = u32(e.shape.x + 0.5);
    var f = 0.0;
    if kind == FLARE_GLOW {
        let g = max(1.0 - r, 0.0);
        f = g * g;
    } else if kind == FLARE_STREAKS {
        let a = atan2(uv.y, uv.x) - e.shape.z;
        let rays = pow(abs(cos(0.5 * e.shape.y * a)), e.shape.w);
        let g = max(1.0 - r, 0.0);
        f = rays * g * g;
    } else if kind == FLARE_HALO {
        let half_width = 0.5 * e.shape.y;
        let t = (r - (1.0 - half_width)) / half_width;
        f = max(1.0 - t * t, 0.0);
    } else if kind == FLARE_GHOST {
        let edge = ghost_edge(uv, e.shape.y, e.shape.z);
        f = 1.0 - smoothstep(1.0 - e.shape.w, 1.0, edge);
    }
    return e.color.rgb * (f * seen);
}

// The same for an image element: none outside its quad.
fn image_light(e: InstanceIn, ndc: vec2<f32>, seen: f32) -> vec3<f32> {
    let uv = element_uv(e, ndc);
    if any(abs(uv) > vec2<f32>(1.0)) {
        return vec3<f32>(0.0);
    }
    // The mip level a fragment's derivatives would pick: image texels per pixel, the larger of
    // the two screen directions (rotation does not change it).
    let pixels_across = f32(frame.counts.w) * e.placement.z * min(e.placement.w, 1.0);
    let level = log2(f32(textureDimensions(images).x) / pixels_across);
    return e.color.rgb * image_texel(uv, e.shape.y, e.shape.z, level) * seen;
}

// Where `ndc` lies on element `e`'s quad (uv).
fn element_uv(e: InstanceIn, ndc: vec2<f32>) -> vec2<f32> {
    let radius = e.placement.z;
    let half_size = vec2<f32>(radius * e.placement.w / frame.view.w, radius);
    return (ndc - e.placement.xy) / half_size;
}

// One tile of FLARE_TILE x FLARE_TILE pixels of the lit rectangle: each pixel sums the elements
// of its bin in element order, the procedural shapes and the images in loops of their own (a
// software rasterizer runs both sides of a branch, and an image costs a texture sample). The
// bin's words are the same for the whole workgroup.
@compute @workgroup_size(256)
fn cs_elements(@builtin(workgroup_id) tile: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let rect = element_state.rect;
    let origin = rect.xy + tile.xy * FLARE_TILE;
    let pixel = origin + vec2<u32>(lane % FLARE_TILE, lane / FLARE_TILE);
    if any(pixel >= rect.zw) {
        return;
    }
    let grid = element_state.grid;
    let bin = origin / grid.x;
    let words = (bin.y * grid.y + bin.x) * grid.w;
    let size = vec2<f32>(frame.counts.zw);
    let ndc = vec2<f32>((f32(pixel.x) + 0.5) / size.x * 2.0 - 1.0, 1.0 - (f32(pixel.y) + 0.5) / size.y * 2.0);
    var light = vec3<f32>(0.0);
    for (var word = 0u; word < grid.w; word = word + 1u) {
        let marked = element_state.bins[words + word];
        var bits = marked & ~element_state.images[word];
        while bits != 0u {
            let e = records.elements[word * 32u + countTrailingZeros(bits)];
            bits = bits & (bits - 1u);
            light = light + shape_light(e, ndc, element_state.visibility[e.source.x] * e.color.a);
        }
        bits = marked & element_state.images[word];
        while bits != 0u {
            let e = records.elements[word * 32u + countTrailingZeros(bits)];
            bits = bits & (bits - 1u);
            light = light + image_light(e, ndc, element_state.visibility[e.source.x] * e.color.a);
        }
    }
    textureStore(accumulated_out, pixel, vec4<f32>(light, 0.0));
}

// One quad over the occlusion pass's rectangle (pixel corners, from `state.rect` as an instance
// attribute), drawn as a triangle strip.
@vertex
fn vs_composite(@builtin(vertex_index) v: u32, @location(0) rect: vec4<u32>) -> @builtin(position) vec4<f32> {
    let far = vec2<bool>((v & 1u) != 0u, (v & 2u) != 0u);
    let pixel = vec2<f32>(select(rect.xy, rect.zw, far));
    let size = vec2<f32>(frame.counts.zw);
    return vec4<f32>(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0, 0.0, 1.0);
}

@fragment
fn fs_composite(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(textureLoad(accumulated, vec2<i32>(at.xy), 0).rgb, 0.0);
}
