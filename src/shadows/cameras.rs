//! The cameras that shadow maps serve: every active 3D camera that draws a Phong-lit mesh,
//! one per distinct view. Each gets directional cascades fitted to its own view; point and
//! spot lights whose reach meets none of their views get no maps.

use super::views::CascadeCamera;
use crate::view_key::view_key;
use bevy::{
    camera::{Camera, Camera3d, Projection, primitives::Frustum, visibility::VisibleEntities},
    ecs::{
        change_detection::DetectChanges, component::Component, entity::Entity, query::With,
        system::Query, world::Ref,
    },
    math::Vec3,
    mesh::Mesh3d,
    transform::components::GlobalTransform,
};
use core::any::TypeId;

/// Marks a mesh drawn with a material that Phong lights light: `PhongMaterial`, or any
/// material added with [`add_phong_material`](crate::PhongMaterialAppExt::add_phong_material),
/// whose `MeshMaterial3d` brings this marker along (a required component). A camera whose
/// view holds none of these gets no shadow maps of its own.
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct PhongLit;

/// What the shadow gather reads of each 3D camera.
pub(crate) type ShadowCameraQuery<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static Camera,
        &'static GlobalTransform,
        &'static Projection,
        &'static Frustum,
        Ref<'static, VisibleEntities>,
    ),
    With<Camera3d>,
>;

/// A camera whose view the shadow maps serve.
pub(crate) struct ShadowCamera {
    /// Its view's key ([`view_key`]), by which the shader finds the cascades fitted to it.
    pub key: u32,
    /// Where it is, world space.
    pub eye: Vec3,
    /// What it sees.
    pub frustum: Frustum,
    /// Its shape, for fitting cascades to it.
    pub cascades: CascadeCamera,
}

/// The active 3D cameras that draw a Phong-lit mesh ([`draws_phong_lit`]), by
/// `Camera::order` (then entity), one per distinct view: cameras with the same frustum see
/// the same volume and share cascades.
pub(crate) fn shadow_cameras(
    cameras: &ShadowCameraQuery,
    phong_lit: &Query<(), With<PhongLit>>,
) -> Vec<ShadowCamera> {
    let mut active: Vec<_> = cameras
        .iter()
        .filter(|(_, camera, .., visible)| camera.is_active && draws_phong_lit(visible, phong_lit))
        .collect();
    active.sort_by_key(|(entity, camera, ..)| (camera.order, *entity));
    let mut keys = Vec::with_capacity(active.len());
    active
        .into_iter()
        .filter_map(|(_, _, transform, projection, frustum, _)| {
            let key = view_key(frustum);
            (!keys.contains(&key)).then(|| {
                keys.push(key);
                ShadowCamera {
                    key,
                    eye: transform.translation(),
                    frustum: *frustum,
                    cascades: cascade_camera(transform, projection),
                }
            })
        })
        .collect()
}

/// Whether a camera draws a Phong-lit mesh: one is among the meshes Bevy found visible to
/// it (in the last frame: the gather runs before this frame's visibility check). A camera
/// whose visible list Bevy has not written yet (a camera in its first frame, or an app
/// without Bevy's visibility systems) counts as drawing one.
fn draws_phong_lit(visible: &Ref<VisibleEntities>, phong_lit: &Query<(), With<PhongLit>>) -> bool {
    let never_checked = visible.last_changed() == visible.added();
    never_checked
        || visible
            .iter(TypeId::of::<Mesh3d>())
            .any(|&entity| phong_lit.contains(entity))
}

/// The camera's shape, for fitting cascades to it.
fn cascade_camera(transform: &GlobalTransform, projection: &Projection) -> CascadeCamera {
    let near = match projection {
        Projection::Perspective(perspective) => perspective.near,
        Projection::Orthographic(orthographic) => orthographic.near.max(0.0),
        Projection::Custom(_) => 0.0,
    };
    let projection = projection.clone();
    CascadeCamera {
        world_from_view: transform.to_matrix(),
        slice_corners: Box::new(move |near, far| {
            projection.get_frustum_corners(-near, -far).map(Vec3::from)
        }),
        near,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        PhongDirectionalLight,
        lights::{PhongCascades, PhongShadows},
        shadows::PhongShadowViews,
        test_app::test_app,
    };
    use bevy::{
        app::App,
        prelude::{Transform, default},
    };

    /// A 3D camera at `position` looking at the origin, with the frustum Bevy would give it
    /// (the test app has no camera systems).
    fn camera(app: &mut App, position: Vec3, order: isize) -> Entity {
        let transform = Transform::from_translation(position).looking_at(Vec3::ZERO, Vec3::Y);
        let projection = Projection::default();
        let frustum = projection.compute_frustum(&GlobalTransform::from(transform));
        app.world_mut()
            .spawn((
                Camera3d::default(),
                Camera { order, ..default() },
                projection,
                frustum,
                transform,
                GlobalTransform::from(transform),
            ))
            .id()
    }

    /// Each set of the light's views: (camera key, views in the set).
    fn sets(app: &App) -> Vec<(u32, u32)> {
        let views = app.world().resource::<PhongShadowViews>().views();
        let Some(first) = views.first() else {
            return Vec::new();
        };
        (0..first.camera_count as usize)
            .map(|set| {
                let head = &views[set * first.view_count as usize];
                (head.camera_key, head.view_count)
            })
            .collect()
    }

    fn key(app: &App, camera: Entity) -> u32 {
        view_key(app.world().get::<Frustum>(camera).unwrap())
    }

    #[test]
    fn each_camera_that_draws_a_phong_lit_mesh_gets_cascades_of_its_own() {
        let mut app = test_app(|_| {});
        app.world_mut().spawn((
            PhongDirectionalLight {
                shadows: PhongShadows::ON,
                cascades: PhongCascades {
                    count: 2,
                    ..default()
                },
                ..default()
            },
            Transform::default().looking_to(Vec3::new(-0.5, -1.0, -0.3), Vec3::Y),
        ));
        let later = camera(&mut app, Vec3::new(6.0, 3.0, 0.0), 1);
        let first = camera(&mut app, Vec3::new(0.0, 3.0, 6.0), 0);
        // The same view as `first`: it shares its cascades.
        camera(&mut app, Vec3::new(0.0, 3.0, 6.0), 2);
        let inactive = camera(&mut app, Vec3::new(-6.0, 3.0, 0.0), 3);
        app.world_mut()
            .get_mut::<Camera>(inactive)
            .unwrap()
            .is_active = false;
        let elsewhere = camera(&mut app, Vec3::new(0.0, 3.0, -6.0), 4);
        app.update();
        let (first_key, later_key, elsewhere_key) =
            (key(&app, first), key(&app, later), key(&app, elsewhere));
        assert_eq!(
            sets(&app),
            [(first_key, 2), (later_key, 2), (elsewhere_key, 2)],
            "by order, one set per distinct view; before Bevy checked visibility, every \
             active camera counts as drawing a Phong-lit mesh"
        );

        // Bevy found only a mesh of another material in view of `elsewhere`: no set.
        let other_mesh = app.world_mut().spawn_empty().id();
        let lit_mesh = app.world_mut().spawn(PhongLit).id();
        let show = |app: &mut App, mesh: Entity| {
            let mut visible = app
                .world_mut()
                .get_mut::<VisibleEntities>(elsewhere)
                .unwrap();
            visible.clear_all();
            visible.get_mut(TypeId::of::<Mesh3d>()).push(mesh);
        };
        show(&mut app, other_mesh);
        app.update();
        assert_eq!(sets(&app), [(first_key, 2), (later_key, 2)]);
        show(&mut app, lit_mesh);
        app.update();
        assert_eq!(sets(&app).len(), 3, "a Phong-lit mesh came into its view");
    }
}
