// atmosphere/aerial_lookup.wgsl — shared: the lookup into the aerial-perspective volume (its
// slice atlases, see aerial_perspective_volume.wgsl), used by firmament's own application pass
// (aerial_perspective.wgsl) and by users' shaders (include/firmament_aerial_perspective.wgsl), so
// both read the volume the same way.
//
// Conventions: imports nothing, and every name starts with `firmament_` or `FIRMAMENT_` (it goes
// into users' shaders). The volume covers the view frustum: x, y as the screen (u right, v down),
// z the distance travelled through the air from where the pixel's ray enters it, `range · w²` for
// w in [0, 1]. Slice k holds the light scattered towards the camera over the first
// `range · ((k + ½)/N)²` metres (spectral radiance) and the transmittance over them.

// Columns, rows and slices of the volume (the compute pass's AERIAL_PERSPECTIVE_SIZE).
const FIRMAMENT_AERIAL_PERSPECTIVE_SIZE: vec3<u32> = vec3<u32>(32u, 32u, 32u);

// Where a point lies in the volume: xyz = its texture coordinates (uv on the screen, w along
// the ray), w = the weight of the volume's values there (closer than the first slice's centre
// they scale down linearly with distance, from nothing at the camera).
fn firmament_aerial_coordinates(screen_uv: vec2<f32>, through_air: f32, range: f32) -> vec4<f32> {
    let n = f32(FIRMAMENT_AERIAL_PERSPECTIVE_SIZE.z);
    let w = sqrt(max(through_air, 0.0) / range);
    let near_fraction = min(w / (0.5 / n), 1.0);
    return vec4<f32>(screen_uv, w, near_fraction * near_fraction);
}

// Trilinear filtering of one of the volume's slice atlases at `coordinates.xyz`: bilinear in each
// of the two nearest slices (u kept half a texel inside its slice so it never bleeds into the
// next), linear between them. Not weighted by `coordinates.w`.
fn firmament_aerial_sample(atlas: texture_2d<f32>, atlas_sampler: sampler, coordinates: vec4<f32>) -> vec3<f32> {
    let n = f32(FIRMAMENT_AERIAL_PERSPECTIVE_SIZE.z);
    let width = f32(FIRMAMENT_AERIAL_PERSPECTIVE_SIZE.x);
    let slice = clamp(coordinates.z * n - 0.5, 0.0, n - 1.0);
    let k0 = floor(slice);
    let k1 = min(k0 + 1.0, n - 1.0);
    let u = clamp(coordinates.x, 0.5 / width, 1.0 - 0.5 / width);
    let a = textureSampleLevel(atlas, atlas_sampler, vec2<f32>((u + k0) / n, coordinates.y), 0.0);
    let b = textureSampleLevel(atlas, atlas_sampler, vec2<f32>((u + k1) / n, coordinates.y), 0.0);
    return mix(a, b, slice - k0).rgb;
}

// The transmittance from the camera to the point at `coordinates` (per wavelength, 680/550/440 nm
// for R/G/B).
fn firmament_aerial_transmittance_at(atlas: texture_2d<f32>, atlas_sampler: sampler, coordinates: vec4<f32>) -> vec3<f32> {
    return mix(vec3<f32>(1.0), firmament_aerial_sample(atlas, atlas_sampler, coordinates), coordinates.w);
}

// The light the air scatters towards the camera in front of the point at `coordinates`
// (spectral radiance, as the volume stores it).
fn firmament_aerial_scattering_at(atlas: texture_2d<f32>, atlas_sampler: sampler, coordinates: vec4<f32>) -> vec3<f32> {
    return firmament_aerial_sample(atlas, atlas_sampler, coordinates) * coordinates.w;
}
