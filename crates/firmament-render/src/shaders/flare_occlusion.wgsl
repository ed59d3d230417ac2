// flare_occlusion.wgsl — how much of each lens-flare source can be seen, on the GPU, with no
// read-back (NeHe lesson 44's to-do; Unity's SRP lens flare samples a disc the same way); the
// indirect arguments that keep the element and composite passes off unseen sources; and the
// bins that tell each tile of the element pass which elements may light it.
//
// Conventions: as flare/bindings.wgsl. One workgroup, one invocation per source
// (MAX_FLARE_SOURCES = the workgroup size): `counts.y` points of Vogel's golden-angle spiral over
// its disc (r = sqrt((k + 1/2)/n), theta = k * golden angle:
// `firmament_core::flare::sample_pattern`), each hidden when the depth buffer holds something
// nearer than the source, or when the planet lies in front of it along that view ray (a sun
// setting behind the limb). Samples off the screen count as seen (the edge fade handles those
// sources). The visible share, moved towards at the fade rates
// (`firmament_core::flare::smoothed_visibility`), is written to `state.visibility`, where the
// element pass reads it in the same frame; the union of the seen sources' pixel rectangles
// sizes that pass's dispatch and the composite draw (none when nothing is seen).
//
// Binning (cs_bin, after the occlusion pass, over bins `prepare` cleared): one invocation per
// element whose light can matter (its source's visibility times its peak colour above
// NEGLIGIBLE) marks the bins its cut ellipse reaches. OR-ing bits is order-free, so the bins,
// and the image, do not depend on the order invocations run in.

#import common/ellipsoid
#import flare/bindings
#import generated/constants

const GOLDEN_ANGLE: f32 = 2.3999632;
// Linear colour (display units, 1 = white) below which an element's light is not drawn:
// `FLARE_NEGLIGIBLE` of gpu_types/flare.rs, which explains the value.
const NEGLIGIBLE: f32 = 1.0 / 8192.0;

// The seen sources' rectangle: 0xffff - x0, 0xffff - y0 (so that zero, the initial value, is
// "nothing yet" for atomicMax), x1, y1.
var<workgroup> seen_rect: array<atomic<u32>, 4>;

// Whether the planet hides the view ray through `ndc` before `distance` metres.
fn planet_hides(ndc: vec2<f32>, distance: f32) -> bool {
    if frame.planet_radii.w == 0.0 {
        return false;
    }
    let d_view = normalize(vec3<f32>(ndc.x * frame.view.x, ndc.y * frame.view.y, -1.0));
    let d = (frame.view_to_planet * vec4<f32>(d_view, 0.0)).xyz;
    let t = ellipsoid_hits(frame.planet_origin.xyz, d, frame.planet_radii.xyz, frame.planet_origin.w);
    return t.x <= t.y && t.y > 0.0 && max(t.x, 0.0) < distance;
}

// Source `i`'s visible share this frame, smoothed towards from the last frame's.
fn source_visibility(i: u32, source: FlareSource) -> f32 {
    let n = max(frame.counts.y, 1u);
    let size = vec2<f32>(f32(frame.counts.z), f32(frame.counts.w));
    var seen = 0u;
    for (var k = 0u; k < n; k = k + 1u) {
        let r = sqrt((f32(k) + 0.5) / f32(n));
        let theta = f32(k) * GOLDEN_ANGLE;
        let p = source.disc.xy + vec2<f32>(r * cos(theta), r * sin(theta)) * source.disc.zw;
        var hidden = planet_hides(p, source.depth.y);
        let pixel = vec2<f32>((p.x * 0.5 + 0.5) * size.x, (0.5 - p.y * 0.5) * size.y);
        if !hidden && all(pixel >= vec2<f32>(0.0)) && all(pixel < size) {
            let depth = textureLoad(depth_buffer, vec2<i32>(pixel), 0).x;
            hidden = select((depth > source.depth.x), (depth < source.depth.x), (u32(frame.fade.z) == DEPTH_STANDARD));
        }
        if !hidden {
            seen = seen + 1u;
        }
    }
    let target_share = f32(seen) / f32(n);
    var v = target_share;
    let dt = frame.view.z;
    if dt > 0.0 {
        let previous = state.visibility[i];
        let step = target_share - previous;
        let limit = select(frame.fade.y, frame.fade.x, step >= 0.0);
        if limit > 0.0 {
            v = previous + clamp(step, -limit * dt, limit * dt);
        }
    }
    return v;
}

@compute @workgroup_size(64)
fn cs_main(@builtin(local_invocation_index) i: u32) {
    if i < frame.counts.x {
        let source = records.sources[i];
        let v = source_visibility(i, source);
        state.visibility[i] = v;
        let corners = bitcast<vec2<u32>>(source.depth.zw);
        let lo = vec2<u32>(corners.x & 0xffffu, corners.x >> 16u);
        let hi = vec2<u32>(corners.y & 0xffffu, corners.y >> 16u);
        if v > 0.0 && all(lo < hi) {
            atomicMax(&seen_rect[0], 0xffffu - lo.x);
            atomicMax(&seen_rect[1], 0xffffu - lo.y);
            atomicMax(&seen_rect[2], hi.x);
            atomicMax(&seen_rect[3], hi.y);
        }
    }
    workgroupBarrier();
    if i == 0u {
        // Tiles start at multiples of FLARE_TILE, so each lies in one bin.
        let unaligned = vec2<u32>(0xffffu) - vec2<u32>(atomicLoad(&seen_rect[0]), atomicLoad(&seen_rect[1]));
        let lo = unaligned - unaligned % FLARE_TILE;
        let hi = vec2<u32>(atomicLoad(&seen_rect[2]), atomicLoad(&seen_rect[3]));
        if all(lo < hi) {
            let tiles = (hi - lo + vec2<u32>(FLARE_TILE - 1u)) / FLARE_TILE;
            state.dispatch = vec4<u32>(tiles, 1u, 0u);
            state.draw = vec4<u32>(4u, 1u, 0u, 0u);
            state.rect = vec4<u32>(lo, hi);
        } else {
            state.dispatch = vec4<u32>(0u);
            state.draw = vec4<u32>(4u, 0u, 0u, 0u);
            state.rect = vec4<u32>(0u);
        }
    }
}

// Whether element `e` may light pixel centres in [lo, hi] (pixels): its cut ellipse, with a
// pixel's margin, reaches that box (images: their rectangle does).
fn reaches(e: InstanceIn, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    if u32(e.shape.x + 0.5) == FLARE_IMAGE {
        return true;
    }
    let size = vec2<f32>(frame.counts.zw);
    let center = vec2<f32>((e.placement.x * 0.5 + 0.5) * size.x, (0.5 - e.placement.y * 0.5) * size.y);
    let radius = e.placement.z * 0.5 * size.y * bitcast<f32>(e.source.w);
    let axes = vec2<f32>(radius * e.placement.w, radius) + vec2<f32>(1.0);
    let d = (clamp(center, lo, hi) - center) / axes;
    return dot(d, d) < 1.0;
}

@compute @workgroup_size(64)
fn cs_bin(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = id.x;
    if k >= min(u32(frame.fade.w), MAX_INSTANCES) {
        return;
    }
    let e = records.elements[k];
    let peak = max(e.color.r, max(e.color.g, e.color.b));
    if state.visibility[e.source.x] * e.color.a * peak <= NEGLIGIBLE {
        return;
    }
    let side = state.grid.x;
    let word = k / 32u;
    let bit = 1u << (k % 32u);
    let first = corner(e.source.y) / side;
    let last = (corner(e.source.z) - vec2<u32>(1u)) / side;
    for (var y = first.y; y <= last.y; y = y + 1u) {
        for (var x = first.x; x <= last.x; x = x + 1u) {
            let lo = vec2<f32>(vec2<u32>(x, y) * side) + 0.5;
            if reaches(e, lo, lo + f32(side - 1u)) {
                atomicOr(&state.bins[(y * state.grid.y + x) * state.grid.w + word], bit);
            }
        }
    }
}
