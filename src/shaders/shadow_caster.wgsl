// Draws a shadow caster into a shadow map: depth only, from the mesh's positions placed by
// the draw's `clip_from_local` matrix (an instance attribute, one column per location).

struct Caster {
    @location(0) position: vec3<f32>,
    @location(1) clip_from_local_0: vec4<f32>,
    @location(2) clip_from_local_1: vec4<f32>,
    @location(3) clip_from_local_2: vec4<f32>,
    @location(4) clip_from_local_3: vec4<f32>,
}

@vertex
fn vertex(caster: Caster) -> @builtin(position) vec4<f32> {
    let clip_from_local = mat4x4<f32>(
        caster.clip_from_local_0,
        caster.clip_from_local_1,
        caster.clip_from_local_2,
        caster.clip_from_local_3,
    );
    return clip_from_local * vec4<f32>(caster.position, 1.0);
}
