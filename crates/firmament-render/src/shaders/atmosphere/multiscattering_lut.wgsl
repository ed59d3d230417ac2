// atmosphere/multiscattering_lut.wgsl — Hillaire 2020's multiple-scattering LUT ("A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020, section 5.2).
// Includes: common/fullscreen.wgsl, common/ellipsoid.wgsl, atmosphere/common.wgsl, atmosphere/luts.wgsl.
//
// Texel (u, v) ↦ mu_s = unit_to_mu_s(u) (crowded at the horizon), h = v · atmosphere height,
// on the LUT sphere. For a unit sun it integrates second-order light L₂ and the transfer f_ms over 64 directions with the isotropic
// phase, ground bounce included, and stores Ψ_ms = L₂ / (1 − f_ms): the sum of every order ≥ 2
// under Hillaire's assumption that the light arriving at a point is isotropic beyond order 2.

const DIRECTIONS_SQRT: i32 = 8;
const STEPS: i32 = 20;
const ISOTROPIC_PHASE: f32 = 1.0 / (4.0 * PI);

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    return fullscreen_vertex(index, FAR_DEPTH);
}

@fragment
fn fs_main(in: FullscreenVertex) -> @location(0) vec4<f32> {
    let uv = in.clip.xy / MULTISCATTERING_LUT_SIZE;
    let mu_s_h = uv_to_mu_s_h(uv, MULTISCATTERING_LUT_SIZE);
    let mu_s = mu_s_h.x;
    let h = mu_s_h.y;
    let r = atmosphere.lut.x + h;
    let origin = vec3<f32>(0.0, 0.0, r);
    let sun = vec3<f32>(safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    let albedo = atmosphere.ground_albedo.rgb;

    var second_order = vec3<f32>(0.0);
    var transfer = vec3<f32>(0.0);
    for (var i = 0; i < DIRECTIONS_SQRT; i++) {
        for (var j = 0; j < DIRECTIONS_SQRT; j++) {
            // Stratified, uniform over the sphere.
            let phi = 2.0 * PI * (f32(i) + 0.5) / f32(DIRECTIONS_SQRT);
            let cos_theta = 1.0 - 2.0 * (f32(j) + 0.5) / f32(DIRECTIONS_SQRT);
            let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
            let dir = vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
            let mu = cos_theta;
            let ground = ray_hits_ground(r, mu);
            var ray_length = distance_to_top(r, mu);
            if ground {
                let bottom = atmosphere.lut.x;
                ray_length = max(-r * mu - safe_sqrt(r * r * (mu * mu - 1.0) + bottom * bottom), 0.0);
            }
            let dt = ray_length / f32(STEPS);
            var throughput = vec3<f32>(1.0);
            var light = vec3<f32>(0.0);
            var light_as_one = vec3<f32>(0.0);
            for (var k = 0; k < STEPS; k++) {
                let t = (f32(k) + 0.5) * dt;
                let p = origin + dir * t;
                let r_t = length(p);
                let h_t = r_t - atmosphere.lut.x;
                let c = coefficients_at(h_t);
                let scattering = c.rayleigh + c.mie;
                let step_transmittance = exp(-c.extinction * dt);
                let sun_transmittance = transmittance_to_sun(h_t, dot(p, sun) / r_t, 0.0);
                let source = scattering * sun_transmittance * ISOTROPIC_PHASE;
                light += throughput * integrate_step(source, c.extinction, step_transmittance, dt);
                light_as_one += throughput * integrate_step(scattering, c.extinction, step_transmittance, dt);
                throughput *= step_transmittance;
            }
            if ground {
                let p = origin + dir * ray_length;
                let up = normalize(p);
                let mu_ground = dot(up, sun);
                light += throughput * transmittance_to_sun(0.0, mu_ground, 0.0) * max(mu_ground, 0.0) * albedo / PI;
            }
            second_order += light;
            transfer += light_as_one;
        }
    }
    let n = f32(DIRECTIONS_SQRT * DIRECTIONS_SQRT);
    // The mean over the sphere is the integral with the isotropic phase 1/4π.
    second_order /= n;
    transfer /= n;
    return vec4<f32>(second_order / (1.0 - transfer), 1.0);
}
