// The cluster test's probe: red 1 where the shader found the view being drawn among the
// views that have clusters, green the first word of that view's record.
#import bevy_pbr::forward_io::VertexOutput
#import bevy_phong::shading::{NO_VIEW_RECORD, view_record}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    let record = view_record();
    let found = record != NO_VIEW_RECORD;
    return vec4<f32>(select(0.0, 1.0, found), f32(record), 0.0, 1.0);
}
