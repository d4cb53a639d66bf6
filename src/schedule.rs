//! [`PhongSystems`]: the system sets the crate's main-world systems run in, and their order.
//!
//! The sets sit below every module that adds systems to them (the shadows, the gather, the
//! extensions, the mirror of Bevy's lights), so that none of those needs the plugin that
//! wires them together.

use bevy::{
    app::{App, PostUpdate},
    asset::AssetEventSystems,
    camera::visibility::VisibilitySystems,
    ecs::schedule::{IntoScheduleConfigs, SystemSet},
    transform::TransformSystems,
};

/// The crate's systems in `PostUpdate`, in this order, after transform and visibility
/// propagation and before Bevy sends the frame's asset events.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PhongSystems {
    /// After this set, every light component, the ambient light and every material changed
    /// this frame holds only valid values (see `crate::validation`).
    Validate,
    /// Each light kind asks for the shadows its lights cast this frame.
    RequestShadows,
    /// After this set, the shadow maps of this frame are laid out: each shadow-casting light
    /// has its views, and each view its casters.
    GatherShadows,
    /// After this set, the light buffer holds every visible light of this frame, and the
    /// cluster buffer every active 3D camera's clusters.
    GatherLights,
    /// After this set, every material whose light buffer was reallocated this frame is
    /// marked modified, so its bind group is rebuilt before it is drawn.
    RefreshMaterials,
}

/// Orders the [`PhongSystems`] sets in `PostUpdate`: one after the other, after transform
/// and visibility propagation, before Bevy's asset events.
pub(crate) fn configure_phong_systems(app: &mut App) {
    app.configure_sets(
        PostUpdate,
        (
            PhongSystems::Validate,
            PhongSystems::RequestShadows,
            PhongSystems::GatherShadows,
            PhongSystems::GatherLights,
            PhongSystems::RefreshMaterials,
        )
            .chain()
            .after(TransformSystems::Propagate)
            .after(VisibilitySystems::VisibilityPropagate)
            .before(AssetEventSystems),
    );
}
