// flare.wgsl — lens-flare elements: camera-facing quads blended additively into the HDR target
// before tone mapping (seed 003's glows, streaks and halos, plus aperture ghosts), shapes drawn
// procedurally so no texture files are needed — or, for image elements, pictures from a 2D array
// texture (one layer per image file, RGB × alpha as stored, like NeHe's sprites).
//
// Conventions: NDC as in flare/bindings.wgsl; an element's `uv` runs over [-1, 1]^2 of its quad,
// r = |uv| = 1 at its radius. A radius is in units of half the screen height, divided by the
// aspect in x so elements stay round (times `stretch`). The colour is scaled by the source's
// visibility, written by flare_occlusion.wgsl earlier in the same frame.

#import flare/bindings
#import generated/constants

struct InstanceIn {
    // xy = centre (NDC), z = radius, w = horizontal stretch
    @location(0) placement: vec4<f32>,
    // rgb = colour at full visibility, a = the source's edge fade
    @location(1) color: vec4<f32>,
    // x = shape (FLARE_*, generated/constants), yzw = its parameters
    @location(2) shape: vec4<f32>,
    // x = source index
    @location(3) source: vec4<u32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) color: vec4<f32>,
    @location(2) shape: vec4<f32>,
    @location(3) @interpolate(flat) source: u32,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32, instance: InstanceIn) -> VertexOut {
    // A triangle strip over the corners (-1,-1), (1,-1), (-1,1), (1,1).
    let corner = vec2<f32>(f32(v & 1u) * 2.0 - 1.0, f32((v >> 1u) & 1u) * 2.0 - 1.0);
    let radius = instance.placement.z;
    let half_size = vec2<f32>(radius * instance.placement.w / frame.view.w, radius);
    var out: VertexOut;
    out.clip = vec4<f32>(instance.placement.xy + corner * half_size, 0.0, 1.0);
    out.uv = corner;
    out.color = instance.color;
    out.shape = instance.shape;
    out.source = instance.source.x;
    return out;
}

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

// The image element's texel at `uv`, turned by `rotation` (radians, counter-clockwise): RGB ×
// alpha. Image row 0 is the picture's bottom (GL's t = 0), which is v = 0 here, at uv.y = -1.
fn image_texel(uv: vec2<f32>, layer: f32, rotation: f32) -> vec3<f32> {
    let c = cos(rotation);
    let s = sin(rotation);
    let turned = vec2<f32>(c * uv.x + s * uv.y, -s * uv.x + c * uv.y);
    let st = turned * 0.5 + 0.5;
    let inside = all(st >= vec2<f32>(0.0)) && all(st <= vec2<f32>(1.0));
    // Sampled in uniform control flow (derivatives for the mip level), used only where inside.
    let texel = textureSample(images, image_sampler, clamp(st, vec2<f32>(0.0), vec2<f32>(1.0)), i32(layer + 0.5));
    return select(vec3<f32>(0.0), texel.rgb * texel.a, inside);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let r = length(in.uv);
    let kind = u32(in.shape.x + 0.5);
    let picture = image_texel(in.uv, in.shape.y, in.shape.z);
    var f = 0.0;
    if kind == FLARE_GLOW {
        let g = max(1.0 - r, 0.0);
        f = g * g;
    } else if kind == FLARE_STREAKS {
        let a = atan2(in.uv.y, in.uv.x) - in.shape.z;
        let rays = pow(abs(cos(0.5 * in.shape.y * a)), in.shape.w);
        let g = max(1.0 - r, 0.0);
        f = rays * g * g;
    } else if kind == FLARE_HALO {
        let half_width = 0.5 * in.shape.y;
        let t = (r - (1.0 - half_width)) / half_width;
        f = max(1.0 - t * t, 0.0);
    } else if kind == FLARE_GHOST {
        let e = ghost_edge(in.uv, in.shape.y, in.shape.z);
        f = 1.0 - smoothstep(1.0 - in.shape.w, 1.0, e);
    }
    let seen = element_visibility[in.source] * in.color.a;
    if kind == FLARE_IMAGE {
        return vec4<f32>(in.color.rgb * picture * seen, 0.0);
    }
    return vec4<f32>(in.color.rgb * (f * seen), 0.0);
}
