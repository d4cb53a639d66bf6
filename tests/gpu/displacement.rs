//! Displacement maps: spheres whose vertices the map moves along their normals, rendered on
//! the render device. The captured world positions lie on the displaced sphere (the radius
//! plus `red · scale + bias`), and each pixel is lit as the reference model says on those
//! positions; the prepass tests (`game_features::prepasses`) check that the prepasses move
//! the vertices alike.
//!
//! The map has two heights, a half each, read nearest; each sphere's UV transform squeezes its
//! UVs into one half, so every vertex moves by one known distance. A UV sphere's flat triangles lie
//! inside its vertices' sphere by at most `1 − cos(θ)` of its radius (θ the angle from a
//! grid cell's middle to its corners, under 0.14 rad here): the radius is judged within
//! [`SAG`] below and `f32` rounding (10⁻⁵) above.
//!
//! Displacement follows the pose: a morphed and a skinned mesh move their posed vertices
//! along their normals (`displacement_follows_the_morph_and_the_skin`).

use crate::frames::{SIZE, TOLERANCE};
use crate::texture_maps::{expected_color, float_map, loaded_images, spawn_map_lights};
use bevy::{
    math::Affine2,
    mesh::{
        UvChannel, VertexAttributeValues,
        morph::{MeshMorphWeights, MorphAttributes},
        skinning::{SkinnedMesh, SkinnedMeshInverseBindposes},
    },
    prelude::*,
};
use bevy_phong::prelude::*;
use bevy_phong_headless::Harness;

/// The largest share of a vertex's radius a triangle's interior lies inside it (sectors 33,
/// stacks 16: cells of 0.19 × 0.2 rad, 1 − cos(0.14) < 0.01).
const SAG: f64 = 0.01;

/// The map's two texels' red values, as stored (8 bits).
const HEIGHTS: [u8; 2] = [51, 204];

/// A map whose left half (texel columns 0–1) holds `HEIGHTS[0]` in red and right half
/// `HEIGHTS[1]`, nearest-sampled.
fn two_height_map() -> Image {
    float_map(|x, _| {
        let red = f32::from(HEIGHTS[(x / 2) as usize]) / 255.0;
        [red, 0.0, 0.0, 1.0]
    })
}

/// UVs squeezed into the map's half `texel` (0 left, 1 right).
fn into_texel(texel: usize) -> Affine2 {
    Affine2::from_scale_angle_translation(
        Vec2::splat(0.3),
        0.0,
        Vec2::new(0.1 + 0.5 * texel as f32, 0.2),
    )
}

#[test]
fn displaced_vertices_move_along_their_normals_by_the_map() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let map = world.resource_mut::<Assets<Image>>().add(two_height_map());
    // (center, radius, texel, scale, bias); the third is not displaced; the last reads the
    // map at its second UV set, which holds its first squeezed into `texel` (its UV
    // transform, which squeezes the first set into the other texel, moving nothing there).
    let spheres = [
        (Vec3::new(-1.6, 0.3, 0.0), 0.9, 0, 0.5, 0.1),
        (Vec3::new(1.4, 0.3, 0.0), 1.1, 1, -0.4, 0.05),
        (Vec3::new(0.0, -1.6, 0.5), 0.6, 0, 0.0, 0.0),
        (Vec3::new(0.0, 1.9, -0.5), 0.6, 1, 0.4, 0.0),
    ];
    let second_set = 3;
    for (index, &(center, radius, texel, scale, bias)) in spheres.iter().enumerate() {
        let mut mesh = Sphere::new(radius).mesh().uv(33, 16);
        let material = if index == second_set {
            let Some(VertexAttributeValues::Float32x2(uvs)) = mesh.attribute(Mesh::ATTRIBUTE_UV_0)
            else {
                panic!("a UV sphere has UVs");
            };
            let squeezed: Vec<[f32; 2]> = uvs
                .iter()
                .map(|&uv| into_texel(texel).transform_point2(Vec2::from(uv)).into())
                .collect();
            mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, squeezed);
            PhongMaterial {
                base_color: Color::srgb(0.3, 0.7, 0.5),
                displacement_map: Some(map.clone()),
                displacement_map_channel: UvChannel::Uv1,
                displacement_scale: scale,
                displacement_bias: bias,
                uv_transform: into_texel(1 - texel),
                ..default()
            }
        } else {
            PhongMaterial {
                base_color: Color::srgb(0.8, 0.6 - 0.2 * index as f32, 0.4),
                displacement_map: (index < 2).then(|| map.clone()),
                displacement_scale: scale,
                displacement_bias: bias,
                uv_transform: into_texel(texel),
                shininess: 24.0,
                ..default()
            }
        };
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world.resource_mut::<Assets<PhongMaterial>>().add(material);
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_translation(center),
        ));
    }
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    let lights = harness.reference_lights();
    let images = loaded_images(&mut harness);
    let comparison = harness.compare_pixels(&rendered, &inputs, |material, surface, pixel| {
        expected_color(material, surface, pixel, &inputs, &images, &lights)
    });
    comparison.assert_within("displacement", TOLERANCE);

    // Each pixel's position is on its sphere, the radius moved by the map.
    let camera = harness.camera_position();
    let world = harness.world_mut();
    let materials = world.resource::<Assets<PhongMaterial>>();
    let mut judged = [0usize; 4];
    for pixel in 0..inputs.positions.pixels.len() {
        let Some((handle, surface)) = inputs.surface_at(pixel, camera) else {
            continue;
        };
        let material = materials.get(handle).expect("a spawned material");
        let (index, &(center, radius, texel, scale, bias)) = spheres
            .iter()
            .enumerate()
            .min_by(|a, b| {
                let distance = |c: Vec3| (surface.position - c.as_dvec3()).length();
                distance(a.1.0).total_cmp(&distance(b.1.0))
            })
            .expect("four spheres");
        let moved = match material.displacement_map {
            Some(_) => f64::from(HEIGHTS[texel]) / 255.0 * f64::from(scale) + f64::from(bias),
            None => 0.0,
        };
        let expected = f64::from(radius) + moved;
        let actual = (surface.position - center.as_dvec3()).length();
        assert!(
            actual <= expected * (1.0 + 1e-5) && actual >= expected * (1.0 - SAG),
            "sphere {index}, pixel {pixel}: radius {actual}, expected {expected} (less its \
             triangles' sag)"
        );
        judged[index] += 1;
    }
    assert!(
        judged.iter().all(|&count| count > 200),
        "every sphere covers pixels: {judged:?}"
    );
}

/// The morph target of [`displacement_follows_the_morph_and_the_skin`]: every vertex lifted
/// by this much at weight 1.
const MORPH_LIFT: Vec3 = Vec3::new(0.0, 0.8, 0.0);
/// The constant map's red (stored exactly in `f32`) and the scale it is read at: every vertex
/// moves `HEIGHT · DISPLACEMENT_SCALE` = 0.2 along its normal.
const HEIGHT: f32 = 0.5;
const DISPLACEMENT_SCALE: f32 = 0.4;
/// An icosahedron's inradius over its circumradius: its faces lie between the two spheres.
const ICOSAHEDRON_INRADIUS: f64 = 0.794_654_472_291_766_1;

/// Displacement after the pose: a morphed and a skinned icosahedron (12 vertices, each with
/// its radial normal, so that it holds together when displaced) each move their vertices
/// along their normals by the map. Each pixel lies between the inscribed and the
/// circumscribed sphere of the displaced icosahedron, posed as its weight or its joint
/// places it (closed forms, no shader), and is lit as the reference model says on its
/// inputs. Undisplaced, the icosahedra would reach 0.5 from their centres, under the
/// displaced ones' inradius (0.556); posed wrongly, 0.4 (the morph) or 1.2 (the joint) from
/// where they belong.
#[test]
fn displacement_follows_the_morph_and_the_skin() {
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let map = world
        .resource_mut::<Assets<Image>>()
        .add(float_map(|_, _| [HEIGHT, 0.0, 0.0, 1.0]));
    let radius = 0.5;
    let icosahedron = || {
        Sphere::new(radius)
            .mesh()
            .ico(0)
            .expect("an icosahedron of 12 vertices")
    };
    let material = |color: Color| PhongMaterial {
        base_color: color,
        shininess: 24.0,
        displacement_map: Some(map.clone()),
        displacement_scale: DISPLACEMENT_SCALE,
        ..default()
    };

    // Morphed: half of `MORPH_LIFT`.
    let weight = 0.5;
    let unposed = Vec3::new(-1.2, -0.3, 0.0);
    let morphed = icosahedron();
    let vertices = morphed.count_vertices();
    let morphed =
        morphed.with_morph_targets(vec![
            MorphAttributes::new(MORPH_LIFT, Vec3::ZERO, Vec3::ZERO);
            vertices
        ]);
    let morphed = world.resource_mut::<Assets<Mesh>>().add(morphed);
    let morphed_material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(material(Color::srgb(0.9, 0.4, 0.3)));
    world.spawn((
        Mesh3d(morphed),
        MeshMaterial3d(morphed_material.clone()),
        MeshMorphWeights::Value {
            weights: vec![weight],
        },
        Transform::from_translation(unposed),
    ));

    // Skinned: every vertex bound to one joint, with the identity as its inverse bind pose;
    // the mesh entity stays at the origin, the joint stands where the icosahedron belongs.
    let joint_at = Vec3::new(1.2, 0.3, 0.0);
    let mut skinned = icosahedron();
    let vertices = skinned.count_vertices();
    skinned.insert_attribute(
        Mesh::ATTRIBUTE_JOINT_INDEX,
        VertexAttributeValues::Uint16x4(vec![[0; 4]; vertices]),
    );
    skinned.insert_attribute(
        Mesh::ATTRIBUTE_JOINT_WEIGHT,
        vec![[1.0_f32, 0.0, 0.0, 0.0]; vertices],
    );
    let skinned = world.resource_mut::<Assets<Mesh>>().add(skinned);
    let inverse_bindposes = world
        .resource_mut::<Assets<SkinnedMeshInverseBindposes>>()
        .add(SkinnedMeshInverseBindposes::from(vec![Mat4::IDENTITY]));
    let joint = world.spawn(Transform::from_translation(joint_at)).id();
    let skinned_material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(material(Color::srgb(0.3, 0.5, 0.9)));
    world.spawn((
        Mesh3d(skinned),
        MeshMaterial3d(skinned_material.clone()),
        SkinnedMesh {
            inverse_bindposes,
            joints: vec![joint],
        },
        Transform::IDENTITY,
    ));

    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs_with_maps();
    harness
        .compare(&rendered, &inputs)
        .assert_within("displaced after the pose", TOLERANCE);

    let displaced = f64::from(radius) + f64::from(HEIGHT * DISPLACEMENT_SCALE);
    let centres = [
        (
            "morphed",
            morphed_material,
            (unposed + weight * MORPH_LIFT).as_dvec3(),
        ),
        ("skinned", skinned_material, joint_at.as_dvec3()),
    ];
    let camera = harness.camera_position();
    for (name, material, centre) in centres {
        let mut on_it = 0;
        for pixel in 0..inputs.positions.pixels.len() {
            let Some((drawn, surface)) = inputs.surface_at(pixel, camera) else {
                continue;
            };
            if *drawn != material {
                continue;
            }
            let distance = (surface.position - centre).length();
            // Within `f32` rounding (10⁻⁵) of the two spheres.
            assert!(
                distance >= ICOSAHEDRON_INRADIUS * displaced * (1.0 - 1e-5)
                    && distance <= displaced * (1.0 + 1e-5),
                "{name}: pixel {pixel} lies {distance:.4} from {centre}, outside the displaced \
                 icosahedron (between {:.4} and {displaced:.4})",
                ICOSAHEDRON_INRADIUS * displaced
            );
            on_it += 1;
        }
        println!("{name}: {on_it} pixels on the displaced icosahedron");
        assert!(on_it >= 200, "{name}: {on_it} pixels");
    }
}

/// A vertex whose normal has no length has no direction to move along: it stays where it
/// is while its neighbours move (SPEC.md, "Displacement"), and nothing drawn from it is NaN.
/// A floor of 4 × 4 one-unit cells at `y = −1`, every vertex lifted 0.3 by the map but the
/// middle one, whose normal is zero: the pixels outside that vertex's cells lie at
/// `y = −0.7`, its cells dip toward it (many pixels below −0.71), down to −1 at it.
#[test]
fn a_vertex_without_a_normal_stays_where_it_is() {
    const LIFT: f32 = 0.3;
    let mut harness = Harness::new(SIZE, SIZE);
    let world = harness.world_mut();
    spawn_map_lights(world);
    let map = world
        .resource_mut::<Assets<Image>>()
        .add(float_map(|_, _| [1.0, 0.0, 0.0, 1.0]));
    let mut floor: Mesh = Plane3d::default()
        .mesh()
        .size(4.0, 4.0)
        .subdivisions(3)
        .into();
    let Some(VertexAttributeValues::Float32x3(positions)) =
        floor.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        panic!("a plane has positions");
    };
    let middle = positions
        .iter()
        .position(|p| Vec3::from(*p).length() < 1e-6)
        .expect("a vertex in the middle");
    let Some(VertexAttributeValues::Float32x3(normals)) =
        floor.attribute_mut(Mesh::ATTRIBUTE_NORMAL)
    else {
        panic!("a plane has normals");
    };
    normals[middle] = [0.0; 3];
    let mesh = world.resource_mut::<Assets<Mesh>>().add(floor);
    let material = world
        .resource_mut::<Assets<PhongMaterial>>()
        .add(PhongMaterial {
            base_color: Color::srgb(0.7, 0.7, 0.6),
            displacement_map: Some(map),
            displacement_scale: LIFT,
            ..default()
        });
    world.spawn((
        Mesh3d(mesh),
        MeshMaterial3d(material),
        Transform::from_xyz(0.0, -1.0, 0.0),
    ));
    harness.settle();
    let rendered = harness.render_next_frame();
    let inputs = harness.capture_inputs();
    assert_eq!(rendered.non_finite_pixels(), 0, "NaN or infinite pixels");
    let lifted = f64::from(LIFT) - 1.0;
    let (mut outside, mut dipping) = (0, 0);
    // The lowest pixel within 0.15 of the unmoved vertex (a few pixels across): a barycentric
    // weight falls by at most √2 per unit, so it lies below −1 + 0.3 · √2 · 0.15 = −0.936 (a
    // vertex lifted half-way, at −0.85, lies above).
    let mut lowest_near_it = f64::INFINITY;
    for position in &inputs.positions.pixels {
        if !inputs.materials.contains_key(&(position[3] as u32)) {
            continue;
        }
        let [x, y, z] = [0, 1, 2].map(|c| f64::from(position[c]));
        // Rounding of the captured position: a few 1e-7 at these coordinates.
        assert!(
            (-1.0 - 1e-5..=lifted + 1e-5).contains(&y),
            "a floor pixel at y = {y}, outside [−1, {lifted}]"
        );
        if x.abs().max(z.abs()) > 1.0 + 1e-3 {
            outside += 1;
            assert!(
                (y - lifted).abs() < 1e-5,
                "a pixel outside the middle vertex's cells at y = {y}, not {lifted}"
            );
        } else {
            dipping += usize::from(y < lifted - 0.01);
        }
        if x.hypot(z) < 0.15 {
            lowest_near_it = lowest_near_it.min(y);
        }
    }
    println!(
        "{outside} pixels lifted, {dipping} dipping toward the unmoved vertex, the lowest near \
         it at {lowest_near_it:.4}"
    );
    assert!(
        outside > 1000,
        "only {outside} pixels outside the middle cells"
    );
    assert!(
        dipping > 100,
        "only {dipping} pixels dip toward the unmoved vertex"
    );
    assert!(
        lowest_near_it < -0.936,
        "the unmoved vertex's neighbourhood lies at {lowest_near_it} at the lowest, not near −1"
    );
}
