//! The gather system: every frame in which a light changed, it writes all visible lights
//! into the light buffer.

use super::{
    PHONG_LIGHT_BUFFER,
    gpu_types::{GpuLight, GpuLightsHeader},
    light_buffer::{LightBuffer, LightBufferResized},
    light_records::linear_rgb,
};
use crate::lights::{PhongAmbientLight, PhongDirectionalLight, PhongPointLight, PhongSpotLight};
use crate::validation::is_finite_transform;
use bevy::{
    asset::Assets,
    camera::visibility::InheritedVisibility,
    ecs::{
        change_detection::DetectChanges,
        component::Component,
        lifecycle::RemovedComponents,
        message::MessageWriter,
        query::{Changed, Or, With},
        resource::Resource,
        system::{Query, Res, ResMut, SystemParam},
    },
    render::storage::ShaderBuffer,
    transform::components::GlobalTransform,
};

/// The built-in lights' buffer and the scratch space the gather system fills it from.
#[derive(Resource, Debug)]
pub struct PhongLightBuffer {
    buffer: LightBuffer,
    records: Vec<GpuLight>,
    header: GpuLightsHeader,
}

impl Default for PhongLightBuffer {
    fn default() -> Self {
        Self {
            buffer: LightBuffer::new(PHONG_LIGHT_BUFFER),
            records: Vec::new(),
            header: GpuLightsHeader::default(),
        }
    }
}

impl PhongLightBuffer {
    /// What was last written: the ambient light and the count of each kind.
    pub fn header(&self) -> &GpuLightsHeader {
        &self.header
    }

    /// The records last written, directional then point then spot lights.
    pub fn records(&self) -> &[GpuLight] {
        &self.records
    }

    /// How many lights the GPU buffer has room for.
    pub fn capacity(&self) -> usize {
        self.buffer.capacity()
    }
}

/// Matches the lights of kind `L` whose component, transform or visibility changed.
pub type LightChanged<L> = (
    With<L>,
    Or<(
        Changed<L>,
        Changed<GlobalTransform>,
        Changed<InheritedVisibility>,
    )>,
);

/// Whether any light of kind `L` was added, changed, moved, shown, hidden or removed since
/// the last run of the system that holds this parameter.
#[derive(SystemParam)]
pub struct LightChanges<'w, 's, L: Component> {
    changed: Query<'w, 's, (), LightChanged<L>>,
    removed: RemovedComponents<'w, 's, L>,
}

impl<L: Component> LightChanges<'_, '_, L> {
    /// `true` if any light of kind `L` changed. Call it once per run: it consumes the
    /// removals it has seen.
    pub fn any(&mut self) -> bool {
        let removed = self.removed.read().count() > 0;
        removed || !self.changed.is_empty()
    }
}

/// The lights of kind `L` with the transform and visibility their record is made from.
pub type LightQuery<'w, 's, L> = Query<
    'w,
    's,
    (
        &'static L,
        &'static GlobalTransform,
        &'static InheritedVisibility,
    ),
>;

/// Appends the record of every visible light in `lights` to `records`, skipping lights with
/// a non-finite transform; returns how many.
pub fn push_visible<L: Component, R>(
    lights: &LightQuery<L>,
    records: &mut Vec<R>,
    to_gpu: impl Fn(&L, &GlobalTransform) -> R,
) -> u32 {
    let start = records.len();
    records.extend(
        lights
            .iter()
            .filter(|(_, transform, visibility)| visibility.get() && is_finite_transform(transform))
            .map(|(light, transform, _)| to_gpu(light, transform)),
    );
    (records.len() - start) as u32
}

/// Writes every visible built-in light into [`PhongLightBuffer`] when any of them, or the
/// ambient light, changed (and on the first run); otherwise it touches nothing, so the GPU
/// buffer is not uploaded again.
#[allow(clippy::too_many_arguments)]
pub fn gather_lights(
    ambient: Res<PhongAmbientLight>,
    directional: LightQuery<PhongDirectionalLight>,
    point: LightQuery<PhongPointLight>,
    spot: LightQuery<PhongSpotLight>,
    mut directional_changes: LightChanges<PhongDirectionalLight>,
    mut point_changes: LightChanges<PhongPointLight>,
    mut spot_changes: LightChanges<PhongSpotLight>,
    mut state: ResMut<PhongLightBuffer>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut resized: MessageWriter<LightBufferResized>,
) {
    // Evaluate every detector: each one drains its removals.
    let changes = [
        directional_changes.any(),
        point_changes.any(),
        spot_changes.any(),
        ambient.is_changed(),
        state.capacity() == 0,
    ];
    if !changes.contains(&true) {
        return;
    }

    let state = &mut *state;
    state.records.clear();
    state.header = GpuLightsHeader {
        ambient: linear_rgb(ambient.color),
        directional_count: push_visible(
            &directional,
            &mut state.records,
            PhongDirectionalLight::to_gpu,
        ),
        point_count: push_visible(&point, &mut state.records, PhongPointLight::to_gpu),
        spot_count: push_visible(&spot, &mut state.records, PhongSpotLight::to_gpu),
        padding: [0; 2],
    };
    if state
        .buffer
        .write(&mut buffers, &state.header, &state.records)
    {
        resized.write(LightBufferResized {
            buffer: state.buffer.handle().clone(),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_app::{built_in_buffer_bytes, test_app, uploads_in_next_frame};
    use bevy::prelude::{Transform, Vec3, Visibility};

    #[test]
    fn lights_are_uploaded_only_in_frames_where_they_change() {
        let mut app = test_app(|_| {});
        let light = app
            .world_mut()
            .spawn((
                PhongPointLight::default(),
                Transform::from_xyz(1.0, 2.0, 3.0),
            ))
            .id();
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a new light is uploaded"
        );
        let state = app.world().resource::<PhongLightBuffer>();
        assert_eq!(state.header().point_count, 1);
        assert_eq!(state.records()[0].position, [1.0, 2.0, 3.0]);

        assert_eq!(
            uploads_in_next_frame(&mut app),
            0,
            "nothing changed: no upload"
        );
        assert_eq!(
            uploads_in_next_frame(&mut app),
            0,
            "nothing changed: no upload"
        );

        app.world_mut()
            .get_mut::<Transform>(light)
            .unwrap()
            .translation = Vec3::X;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a moved light is uploaded"
        );
        let state = app.world().resource::<PhongLightBuffer>();
        assert_eq!(state.records()[0].position, [1.0, 0.0, 0.0]);

        *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Hidden;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a hidden light is removed"
        );
        assert_eq!(
            app.world()
                .resource::<PhongLightBuffer>()
                .header()
                .light_count(),
            0
        );

        *app.world_mut().get_mut::<Visibility>(light).unwrap() = Visibility::Inherited;
        assert_eq!(uploads_in_next_frame(&mut app), 1, "a shown light is back");
        app.world_mut().despawn(light);
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a despawned light is removed"
        );
        assert_eq!(
            app.world()
                .resource::<PhongLightBuffer>()
                .header()
                .light_count(),
            0
        );

        app.world_mut().resource_mut::<PhongAmbientLight>().color = bevy::color::Color::BLACK;
        assert_eq!(
            uploads_in_next_frame(&mut app),
            1,
            "a changed ambient light is uploaded"
        );
        assert_eq!(
            app.world().resource::<PhongLightBuffer>().header().ambient,
            [0.0; 3]
        );
        assert!(!built_in_buffer_bytes(&app).is_empty());
    }

    #[test]
    fn lights_are_ordered_directional_point_spot() {
        let mut app = test_app(|_| {});
        let world = app.world_mut();
        world.spawn(PhongSpotLight::default());
        world.spawn(PhongPointLight::default());
        world.spawn(PhongDirectionalLight::default());
        world.spawn(PhongPointLight::default());
        app.update();
        let state = app.world().resource::<PhongLightBuffer>();
        let header = state.header();
        assert_eq!(
            (
                header.directional_count,
                header.point_count,
                header.spot_count
            ),
            (1, 2, 1)
        );
        // A directional light has no range; point and spot lights keep "unlimited".
        assert_eq!(state.records()[0].range, 0.0);
        assert_eq!(state.records()[1].range, f32::MAX);
        assert!(state.records()[3].cone_scale > 0.0);
    }
}
