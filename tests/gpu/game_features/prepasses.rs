//! The depth, normal and motion-vector prepasses and the deferred renderer's prepass on a
//! camera drawing `PhongMaterial`.

use bevy::{
    asset::uuid_handle,
    core_pipeline::prepass::{DeferredPrepass, DepthPrepass, MotionVectorPrepass, NormalPrepass},
    pbr::{Material, MaterialPlugin},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::{
    prelude::*,
    reference::{self, normalize_or_zero},
};
use bevy_phong_headless::{
    Comparison, Expected, Harness,
    pixel_model::{face_normal_at, world_triangles},
};
use glam::DVec3;

use super::{assert_same_frame, bright_scene};
use crate::{
    frames::SIZE,
    texture_maps::{float_map, lit_normal, loaded_images, normal_map},
};

/// Two renders of one scene that differ only in the camera's prepasses: the main pass shades
/// the same fragments with the same inputs, so the colors are equal up to `f32` rounding
/// noise (none is expected; 1e-6 allows for a reordered sum).
const SAME_FRAME: f64 = 1e-6;

/// The scene of the frames with a square in front of the sphere, cut out by an alpha mask
/// (a checkerboard of alpha 0 and 1, cutoff 0.5), a normal- and bump-mapped cube, a
/// sphere displaced inward (a prepass that did not move its vertices would hide it behind
/// their undisplaced depth), a flat-shaded icosphere and a double-sided square showing its
/// back face: what the prepasses must get right.
fn masked_and_mapped_scene(harness: &mut Harness) {
    bright_scene(harness);
    let world = harness.world_mut();
    let mut images = world.resource_mut::<Assets<Image>>();
    let checker = images.add(float_map(|x, y| [1.0, 1.0, 1.0, ((x + y) % 2) as f32]));
    let normals = images.add(normal_map());
    let heights = images.add(float_map(|x, y| {
        [((x + 2 * y) % 3) as f32 / 2.0, 0.0, 0.0, 1.0]
    }));
    let half = images.add(float_map(|_, _| [0.5, 0.0, 0.0, 1.0]));
    let mut meshes = world.resource_mut::<Assets<Mesh>>();
    let sphere = meshes.add(Sphere::new(0.7).mesh().uv(24, 16));
    let square = meshes.add(Plane3d::new(Vec3::Z, Vec2::splat(0.9)));
    let cube = meshes.add(
        Mesh::from(Cuboid::new(0.9, 0.9, 0.9))
            .with_generated_tangents()
            .expect("a cuboid has UVs and normals"),
    );
    let faceted = meshes.add(Sphere::new(0.5).mesh().ico(1).expect("a small icosphere"));
    let back = meshes.add(Plane3d::new(Vec3::Z, Vec2::splat(0.45)));
    let mut materials = world.resource_mut::<Assets<PhongMaterial>>();
    let flat = materials.add(PhongMaterial {
        base_color: Color::srgb(0.8, 0.7, 0.5),
        flat_shading: true,
        shininess: 12.0,
        ..default()
    });
    let two_sided = materials.add(PhongMaterial {
        base_color: Color::srgb(0.5, 0.8, 0.7),
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    let masked = materials.add(PhongMaterial {
        base_color: Color::srgb(0.9, 0.5, 0.2),
        base_color_texture: Some(checker),
        alpha_mode: AlphaMode::Mask(0.5),
        ..default()
    });
    let mapped = materials.add(PhongMaterial {
        base_color: Color::srgb(0.6, 0.8, 0.3),
        normal_map_texture: Some(normals),
        bump_map_texture: Some(heights),
        bump_scale: 0.7,
        shininess: 30.0,
        ..default()
    });
    let displaced = materials.add(PhongMaterial {
        base_color: Color::srgb(0.3, 0.5, 0.9),
        displacement_map: Some(half),
        displacement_scale: -0.4,
        displacement_bias: 0.0,
        ..default()
    });
    world.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(displaced),
        Transform::from_xyz(-1.5, 1.4, 1.0),
    ));
    world.spawn((
        Mesh3d(faceted),
        MeshMaterial3d(flat),
        Transform::from_xyz(-2.3, 0.6, 2.2),
    ));
    // Its front faces away from the camera, turned a little so that its normal is not
    // the view direction.
    world.spawn((
        Mesh3d(back),
        MeshMaterial3d(two_sided),
        Transform::from_xyz(2.3, 0.7, 2.2).with_rotation(Quat::from_euler(
            EulerRot::YXZ,
            std::f32::consts::PI + 0.5,
            0.3,
            0.0,
        )),
    ));
    world.spawn((
        Mesh3d(square),
        MeshMaterial3d(masked),
        Transform::from_xyz(0.0, 0.2, 1.6),
    ));
    world.spawn((
        Mesh3d(cube),
        MeshMaterial3d(mapped),
        Transform::from_xyz(1.2, 1.3, 1.0).with_rotation(Quat::from_euler(
            EulerRot::XYZ,
            0.5,
            0.7,
            0.0,
        )),
    ));
}

/// With a depth prepass, with the depth, normal and motion-vector prepasses, and with the
/// deferred renderer's prepass, the frame is the one drawn without any: the alpha mask's
/// holes stay open (the prepass discards what the main pass discards) and `PhongMaterial`,
/// drawn forward, looks the same beside a deferred camera's G-buffer.
#[test]
fn prepasses_and_the_deferred_renderer_leave_the_phong_frame_unchanged() {
    let mut harness = Harness::new(SIZE, SIZE);
    masked_and_mapped_scene(&mut harness);
    harness.settle();
    let baseline = harness.render_next_frame();

    harness.camera_mut().insert(DepthPrepass);
    harness.settle();
    assert_same_frame(
        "depth_prepass",
        &harness.render_next_frame(),
        &baseline,
        SAME_FRAME,
    );

    harness
        .camera_mut()
        .insert((NormalPrepass, MotionVectorPrepass));
    harness.settle();
    assert_same_frame(
        "depth_normal_motion_prepasses",
        &harness.render_next_frame(),
        &baseline,
        SAME_FRAME,
    );

    // A camera that turns its prepasses off keeps a stale motion-vector pipeline in Bevy
    // 0.19 (a wgpu validation error); a deferred camera starts as one.
    drop(harness);
    let mut harness = Harness::new(SIZE, SIZE);
    masked_and_mapped_scene(&mut harness);
    harness.camera_mut().insert((DepthPrepass, DeferredPrepass));
    harness.settle();
    assert_same_frame(
        "deferred_prepass",
        &harness.render_next_frame(),
        &baseline,
        SAME_FRAME,
    );
}

/// The normal prepass holds, at each Phong pixel, the unit normal the main pass lights it
/// with: the normal and bump maps' on the mapped cube, each face's own on the flat-shaded
/// icosphere, and on the double-sided square's back face its normal turned toward the
/// viewer. Read back through a translucent full-view
/// square (translucent meshes are not in the prepass) that shows the prepass normal.
/// Tolerance: the prepass stores `n/2 + 1/2` in 10 bits per channel (`Rgb10a2Unorm`), so
/// each decoded component is within one step of 2/1023, doubled for the normalization of
/// the decoded vector.
#[test]
fn the_normal_prepass_holds_the_normal_mapped_normal() {
    let mut harness = Harness::with_plugins(SIZE, SIZE, |app| {
        app.add_plugins(MaterialPlugin::<ShowNormalPrepass>::default());
        app.world_mut()
            .resource_mut::<Assets<Shader>>()
            .insert(
                SHOW_NORMAL_PREPASS_SHADER.id(),
                Shader::from_wesl(SHOW_NORMAL_PREPASS_WESL, "show_normal_prepass.wesl"),
            )
            .expect("a uuid handle is always valid");
    });
    masked_and_mapped_scene(&mut harness);
    harness.settle();
    let inputs = harness.capture_inputs_with_maps();
    let camera = harness.camera_position();
    let images = loaded_images(&mut harness);

    let forward = (Vec3::ZERO - camera.as_vec3()).normalize();
    let world = harness.world_mut();
    let screen = world
        .resource_mut::<Assets<Mesh>>()
        .add(Rectangle::new(4.0, 4.0));
    let show = world
        .resource_mut::<Assets<ShowNormalPrepass>>()
        .add(ShowNormalPrepass {});
    world.spawn((
        Mesh3d(screen),
        MeshMaterial3d(show),
        Transform::from_translation(camera.as_vec3() + forward).looking_to(forward, Vec3::Y),
    ));
    harness.camera_mut().insert((DepthPrepass, NormalPrepass));
    harness.settle();
    let rendered = harness.render_next_frame();

    let world = harness.world_mut();
    let flat_triangles: Vec<[DVec3; 3]> = {
        let placed: Vec<(Handle<Mesh>, GlobalTransform)> = world
            .query::<(&Mesh3d, &MeshMaterial3d<PhongMaterial>, &GlobalTransform)>()
            .iter(world)
            .filter(|(_, material, _)| {
                world
                    .resource::<Assets<PhongMaterial>>()
                    .get(&material.0)
                    .is_some_and(|material| material.flat_shading)
            })
            .map(|(mesh, _, transform)| (mesh.0.clone(), *transform))
            .collect();
        let meshes = world.resource::<Assets<Mesh>>();
        placed
            .iter()
            .flat_map(|(mesh, transform)| world_triangles(meshes.get(mesh).unwrap(), transform))
            .collect()
    };
    let materials = world.resource::<Assets<PhongMaterial>>();
    let comparison = Comparison::of(&rendered, |index| {
        let Some((material, mut surface)) = inputs.surface_at(index, camera) else {
            return Expected::Unjudged;
        };
        let material = materials.get(material).unwrap();
        // Alpha-masked pixels are judged where the mask leaves them: off the square's holes.
        if material.alpha_mode != AlphaMode::Opaque {
            return Expected::Unjudged;
        }
        // A flat-shaded pixel's frame normal is its face's, on the side of the interpolated
        // one (which the capture negates on a double-sided back face).
        if material.flat_shading {
            let Some(face) = face_normal_at(&flat_triangles, surface.position) else {
                return Expected::Unjudged;
            };
            surface.normal = reference::face_normal(face, surface.normal);
        }
        match lit_normal(material, &surface, index, &inputs, &images) {
            Some(normal) => Expected::Lit(normalize_or_zero(normal)),
            None => Expected::Unjudged,
        }
    });
    comparison.assert_within("normal_prepass", 2.0 * 2.0 / 1023.0);
    // The flat-shaded icosphere and the double-sided square's back are in view and judged.
    let judged_with = |wanted: &dyn Fn(&PhongMaterial) -> bool| {
        (0..inputs.positions.pixels.len())
            .filter_map(|index| inputs.surface_at(index, camera))
            .filter(|(material, surface)| {
                let material = materials.get(*material).unwrap();
                wanted(material)
                    && (!material.flat_shading
                        || face_normal_at(&flat_triangles, surface.position).is_some())
            })
            .count()
    };
    let flat = judged_with(&|material| material.flat_shading);
    let back = judged_with(&|material| material.double_sided);
    println!("normal_prepass: {flat} flat-shaded pixels, {back} on the double-sided back face");
    // About 200 and 120 pixels at this size (206 and 119 measured): at least 50 says each
    // is in view.
    assert!(
        flat >= 50 && back >= 50,
        "{flat} flat, {back} back-face pixels"
    );
}

const SHOW_NORMAL_PREPASS_SHADER: Handle<Shader> =
    uuid_handle!("8f0b8f52-4d6a-4c1e-9f5e-2b7d3c1a6e90");

/// Shows the normal prepass's normal at each pixel, as Bevy's `prepass_utils` decodes it.
const SHOW_NORMAL_PREPASS_WESL: &str = r"
import bevy_pbr::render::forward_io::VertexOutput;
import bevy_pbr::prepass::utils::prepass_normal;

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    return vec4<f32>(prepass_normal(in.position, 0u), 1.0);
}
";

/// A translucent material that shows the normal prepass (see `SHOW_NORMAL_PREPASS_WESL`).
#[derive(Asset, TypePath, AsBindGroup, Clone)]
struct ShowNormalPrepass {}

impl Material for ShowNormalPrepass {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(SHOW_NORMAL_PREPASS_SHADER)
    }

    fn alpha_mode(&self) -> AlphaMode {
        AlphaMode::Blend
    }
}
