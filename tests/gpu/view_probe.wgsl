// The cluster test's probe: red 1 where the shader found the view being drawn among the
// views that have clusters, green the first word of that view's record.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::scene::cluster_view_count
#import bevy_phong::shading::view_record
#import bevy_phong::types::CLUSTER_VIEW_WORDS

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    let record = view_record();
    let found = record < CLUSTER_VIEW_WORDS * cluster_view_count();
    return vec4<f32>(select(0.0, 1.0, found), f32(record), 0.0, 1.0);
}
