//! Motion vectors (`MotionVectorPrepass`), which TAA and motion blur read: the crate's
//! prepass writes each fragment's screen motion since the last frame, read back in the main
//! pass by a probe (`motion_probe.wesl`) as Bevy's own passes read it.

use crate::probes::harness_with_probe;
use bevy::{
    asset::uuid_handle,
    core_pipeline::prepass::{DepthPrepass, MotionVectorPrepass},
    pbr::{ExtendedMaterial, MaterialExtension},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::prelude::*;
use bevy_phong_headless::CAMERA_POSITION;

/// The extension whose fragment shader shows the motion vector under it.
#[derive(Asset, AsBindGroup, Reflect, Clone, Debug, Default)]
struct MotionProbe {}

const MOTION_PROBE_SHADER: Handle<Shader> = uuid_handle!("c41f7a2e-9d3b-4e58-8a06-2b7e1f5c9d40");

impl MaterialExtension for MotionProbe {
    fn fragment_shader() -> ShaderRef {
        MOTION_PROBE_SHADER.into()
    }
}

type ProbedMaterial = ExtendedMaterial<PhongMaterial, MotionProbe>;

/// A plane facing the camera, moved across the view by 0.3 units right and 0.2 up between
/// two frames: every fragment on it moved on screen by the same amount, the plane being at
/// one view depth `d`: `(½ · P₀₀ · 0.3, −½ · P₁₁ · 0.2) / d` of the target (`P` the
/// camera's projection; Bevy's prepass writes `(ndc − previous ndc) · (½, −½)`). Tolerance:
/// half an ulp of the half float the prepass stores it in (Bevy's
/// `MOTION_VECTOR_PREPASS_FORMAT`, `Rg16Float`: 2⁻¹¹ of the value), plus 1e-6 for the `f32`
/// projections.
#[test]
fn a_moved_mesh_writes_its_screen_motion() {
    assert_screen_motion(0.0);
}

/// The same plane displaced toward the camera by 0.5 (a displacement map of one texel of 1,
/// scale 0.5): its previous position is displaced as its current one, so it moves on screen
/// as a plane at depth `d − 0.5` does.
#[test]
fn a_moved_displaced_mesh_writes_the_motion_of_its_displaced_surface() {
    assert_screen_motion(0.5);
}

/// Renders the plane of [`a_moved_mesh_writes_its_screen_motion`] displaced toward the
/// camera by `displacement` (none for 0), moves it, and checks the motion of every fragment.
fn assert_screen_motion(displacement: f32) {
    let mut harness = harness_with_probe::<ProbedMaterial>(
        &MOTION_PROBE_SHADER,
        include_str!("motion_probe.wesl"),
        "tests/gpu/game_features/motion_probe.wesl",
    );
    harness
        .camera_mut()
        .insert((DepthPrepass, MotionVectorPrepass));
    let world = harness.world_mut();
    let displacement_map = (displacement != 0.0).then(|| {
        world
            .resource_mut::<Assets<Image>>()
            .add(crate::texture_maps::float_map(|_, _| [1.0; 4]))
    });
    let material = world
        .resource_mut::<Assets<ProbedMaterial>>()
        .add(ProbedMaterial {
            base: PhongMaterial {
                displacement_map,
                displacement_scale: displacement,
                ..default()
            },
            extension: MotionProbe {},
        });
    let facing = Dir3::new(CAMERA_POSITION).unwrap();
    let plane = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::new(*facing, Vec2::splat(1.0)).mesh());
    let moved = world
        .spawn((
            Mesh3d(plane),
            MeshMaterial3d(material),
            Transform::default(),
        ))
        .id();
    harness.settle();
    harness.render_next_frame();
    // Across the view: along the camera's right and up.
    let right = Vec3::Y.cross(*facing).normalize();
    let up = facing.cross(right);
    let shift = Vec2::new(0.3, 0.2);
    harness
        .world_mut()
        .get_mut::<Transform>(moved)
        .unwrap()
        .translation = right * shift.x + up * shift.y;
    let rendered = harness.render_next_frame();

    let world = harness.world_mut();
    let clip_from_view = world
        .query::<&Camera>()
        .iter(world)
        .map(|camera| camera.clip_from_view())
        .find(|matrix| *matrix != Mat4::ZERO)
        .expect("the harness camera's projection");
    let depth = CAMERA_POSITION.length() - displacement;
    let expected = Vec2::new(
        0.5 * clip_from_view.x_axis.x * shift.x,
        -0.5 * clip_from_view.y_axis.y * shift.y,
    ) / depth;
    let covered: Vec<&[f32; 4]> = rendered
        .pixels
        .iter()
        .filter(|pixel| pixel[3] == 1.0)
        .collect();
    assert!(
        covered.len() > 1_000,
        "{} pixels of the plane",
        covered.len()
    );
    let tolerance = expected.abs() * 2f32.powi(-11) + Vec2::splat(1e-6);
    for pixel in covered {
        let motion = Vec2::new(pixel[0], pixel[1]);
        assert!(
            (motion - expected).abs().cmple(tolerance).all(),
            "motion {motion}, expected {expected}"
        );
    }
}
