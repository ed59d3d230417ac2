// shadow/shadow_map.wgsl — the depth of every caster seen from a sun, one cascade per draw.
//
// Conventions: `caster.model_to_clip` maps the mesh's object space to the cascade's light clip
// space (computed in f64: the cascade's world → clip × the object's model matrix); depth 0 is
// nearest the light. No colour target; only the position attribute of the object pass's vertex
// buffer (slot 0) is read.

struct ShadowCaster {
    model_to_clip: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> caster: ShadowCaster;

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return caster.model_to_clip * vec4<f32>(position, 1.0);
}
