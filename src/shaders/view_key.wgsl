// Which view a fragment is drawn for: the key by which the shader finds its view's light
// clusters and its directional lights' cascades in data that every view shares.
#define_import_path bevy_phong::view_key

#import bevy_pbr::mesh_view_bindings::view

// The key of the view being drawn (src/render/view_key.rs): FNV-1a over the bits of its six
// frustum half-spaces, which Bevy's view uniform holds as the camera's `Frustum` has them.
fn view_key() -> u32 {
    var key = 2166136261u;
    for (var plane = 0u; plane < 6u; plane += 1u) {
        let bits = bitcast<vec4<u32>>(view.frustum[plane]);
        key = (key ^ bits.x) * 16777619u;
        key = (key ^ bits.y) * 16777619u;
        key = (key ^ bits.z) * 16777619u;
        key = (key ^ bits.w) * 16777619u;
    }
    return key;
}
