// atmosphere/sky_lighting.wgsl — the light the sky and the suns give at the camera, for users'
// own materials: one dispatch of one workgroup into a buffer that
// shaders/include/firmament_lighting.wgsl reads (see passes/atmosphere/sky_lighting.rs).
//
// Conventions: as atmosphere/view.wgsl; output directions in the world frame.
// - Sky: the radiance the sky pass draws from the sky-view LUT (`sky_radiance`: every sun's tile,
//   sky and lit ground, no sun discs) at the centres of GRID_AZIMUTH × GRID_ROWS equal-area cells
//   around the camera's local up (rows uniform in cos θ, so every cell spans 4π / cells sr),
//   projected onto the real spherical harmonics of bands 0–2 of the *world* direction (Ramamoorthi
//   & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps", eq. 3):
//   L_lm = Σ L(ω)·Y_lm(ω)·ΔΩ. Converted to linear sRGB with Y in cd/m² by the same matrix as the
//   sky pass's output (`to_linear_srgb`), without its half-float clamp.
// - Suns: each one's world direction and its irradiance at the camera through the atmosphere,
//   E·T, converted by the same matrix (linear sRGB with Y in lux).

#import atmosphere/bindings
#import atmosphere/common
#import atmosphere/luts
#import atmosphere/view
#import atmosphere/eclipse
#import atmosphere/sky_view

const GRID_AZIMUTH: u32 = 256u;
const GRID_ROWS: u32 = 128u;
const THREADS: u32 = 256u;
const SH_COEFFICIENTS: u32 = 9u;

var<workgroup> partial_sums: array<vec3<f32>, THREADS>;

// The real spherical harmonics Y_lm(d) of bands 0–2 at index l(l + 1) + m, d a unit vector
// (Ramamoorthi & Hanrahan 2001, eq. 3; the constants are 1/(2√π), √(3/4π), √(15/4π), √(5/16π),
// √(15/16π)).
fn sh_basis(d: vec3<f32>) -> array<f32, 9> {
    return array<f32, 9>(
        0.28209479,
        0.48860251 * d.y,
        0.48860251 * d.z,
        0.48860251 * d.x,
        1.09254843 * d.x * d.y,
        1.09254843 * d.y * d.z,
        0.31539157 * (3.0 * d.z * d.z - 1.0),
        1.09254843 * d.x * d.z,
        0.54627422 * (d.x * d.x - d.y * d.y),
    );
}

// Transmittance from the camera to sun i (planet-frame direction s, angular radius alpha) on the
// LUT sphere: the partly set disc inside the atmosphere (`transmittance_to_sun`); above it, the
// shell the ray crosses on its way (1 when it misses the air, 0 when the planet hides the sun).
fn sun_transmittance(s: vec3<f32>, alpha: f32) -> vec3<f32> {
    let up = view.local_up.xyz;
    let h = view.camera.w;
    let mu_s = dot(up, s);
    if h < atmosphere.radii.w {
        return transmittance_to_sun(h, mu_s, alpha);
    }
    let r = atmosphere.lut.x + h;
    // The radius of the ray's closest approach to the centre (cross product: exact far away).
    let closest = r * length(cross(up, s));
    if mu_s >= 0.0 || closest >= atmosphere.lut.y {
        return vec3<f32>(1.0);
    }
    if closest <= atmosphere.lut.x {
        return vec3<f32>(0.0);
    }
    // The ray enters the shell at the top going down with this cosine and leaves it to space.
    let q = closest / atmosphere.lut.y;
    return transmittance_to_top(atmosphere.lut.y, -safe_sqrt(1.0 - q * q));
}

@compute @workgroup_size(256, 1, 1)
fn cs_main(@builtin(local_invocation_index) t: u32) {
    var sums: array<vec3<f32>, 9>;
    if lighting.flags.x < 0.5 && view.sun_count.x > 0u {
        // The grid's frame: the camera's local up and any horizontal axis.
        let up = view.local_up.xyz;
        let other = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(up.x) > 0.9);
        let tangent = normalize(cross(other, up));
        let bitangent = cross(up, tangent);
        for (var cell = t; cell < GRID_AZIMUTH * GRID_ROWS; cell += THREADS) {
            let row = cell / GRID_AZIMUTH;
            let column = cell % GRID_AZIMUTH;
            let z = 1.0 - (f32(row) + 0.5) * (2.0 / f32(GRID_ROWS));
            let phi = (f32(column) + 0.5) * (2.0 * PI / f32(GRID_AZIMUTH));
            let d = up * z + (tangent * cos(phi) + bitangent * sin(phi)) * safe_sqrt(1.0 - z * z);
            let radiance = sky_radiance(d);
            let basis = sh_basis(normalize((lighting.planet_to_world * vec4<f32>(d, 0.0)).xyz));
            for (var k = 0u; k < SH_COEFFICIENTS; k++) {
                sums[k] += radiance * basis[k];
            }
        }
    }
    // Sum the threads' partial projections, one coefficient at a time.
    let cell_solid_angle = 4.0 * PI / f32(GRID_AZIMUTH * GRID_ROWS);
    for (var k = 0u; k < SH_COEFFICIENTS; k++) {
        partial_sums[t] = sums[k];
        workgroupBarrier();
        for (var stride = THREADS / 2u; stride > 0u; stride /= 2u) {
            if t < stride {
                partial_sums[t] += partial_sums[t + stride];
            }
            workgroupBarrier();
        }
        if t == 0u {
            sky_lighting.sky_sh[k] = vec4<f32>(to_linear_srgb(partial_sums[0] * cell_solid_angle), 0.0);
        }
        workgroupBarrier();
    }
    if t < MAX_SUNS {
        var out: SkyLightingSun;
        if t < view.sun_count.x {
            let sun = view.suns[t];
            let s = sun.direction.xyz;
            let alpha = abs(sun.direction.w);
            let world = normalize((lighting.planet_to_world * vec4<f32>(s, 0.0)).xyz);
            out.direction = vec4<f32>(world, alpha);
            let irradiance = sun_irradiance_at(view.camera.xyz, t);
            out.color = vec4<f32>(to_linear_srgb(irradiance * sun_transmittance(s, alpha)), 0.0);
        }
        sky_lighting.suns[t] = out;
    }
    if t == 0u {
        sky_lighting.sun_count = vec4<u32>(min(view.sun_count.x, MAX_SUNS), 0u, 0u, 0u);
    }
}
