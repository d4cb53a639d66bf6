//! The searchlight: a beam of parallel light with a radius and a circular, triangular,
//! diamond or square cross-section (seed 000's closing exercise), added to Phong lighting
//! through `bevy_phong`'s public extension API only.
//!
//! Shared by the `searchlight` example and the render test that checks it against its f64
//! reference (`reference.rs`).

use bevy::{
    pbr::{ExtendedMaterial, MaterialExtension},
    prelude::*,
    render::render_resource::AsBindGroup,
    shader::ShaderRef,
};
use bevy_phong::reference::ReferenceLight;
use bevy_phong::{
    Decay, PhongMaterial, PhongShadows,
    extension::{
        BoundingSphere, Checker, PhongLightKind, PhongLightKindBuffer, PhongLightKindPlugin,
        PhongShadowProjection, PhongShadowRequest, influence_radius, light_direction, linear_rgb,
    },
    prelude::PhongMaterialAppExt,
};
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;

#[path = "reference.rs"]
pub mod reference;
use serde::{Deserialize, Serialize};

/// The material of meshes that searchlights light: every `PhongMaterial` field, plus the
/// searchlight buffer.
pub type SearchlitMaterial = ExtendedMaterial<PhongMaterial, SearchlightExtension>;

/// Adds searchlights: their gather system and [`SearchlitMaterial`].
pub struct SearchlightPlugin;

impl Plugin for SearchlightPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(PhongLightKindPlugin::<Searchlight>::default())
            .add_phong_material::<SearchlitMaterial>()
            .register_type::<Searchlight>();
    }
}

/// The cross-section of a beam, inscribed in its radius and oriented by the light's +Y.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect, Serialize, Deserialize)]
pub enum BeamShape {
    /// A disc of the beam's radius.
    #[default]
    Circle,
    /// An equilateral triangle with a corner toward +Y.
    Triangle,
    /// A square standing on a corner, corners toward ±X and ±Y.
    Diamond,
    /// A square with sides parallel to X and Y.
    Square,
}

impl BeamShape {
    /// Every shape, in the order the example cycles through them.
    pub const ALL: [BeamShape; 4] = [
        BeamShape::Circle,
        BeamShape::Triangle,
        BeamShape::Diamond,
        BeamShape::Square,
    ];

    /// The number the shader switches on.
    pub fn shader_index(self) -> u32 {
        match self {
            BeamShape::Circle => 0,
            BeamShape::Triangle => 1,
            BeamShape::Diamond => 2,
            BeamShape::Square => 3,
        }
    }
}

/// A beam of parallel light along the entity's -Z, filling the prism of `shape` and `radius`
/// around the axis through its position, and only in front of it.
#[derive(Component, Clone, Debug, PartialEq, Reflect, Serialize, Deserialize)]
#[reflect(Component, Default)]
#[require(Transform, Visibility)]
pub struct Searchlight {
    /// Diffuse intensity, linear RGB. Default white.
    pub color: Color,
    /// Specular intensity; `None` uses `color`.
    pub specular: Option<Color>,
    /// Radius of the circle the cross-section is inscribed in, world units. Default 1.
    pub radius: f32,
    /// Cross-section. Default circle.
    pub shape: BeamShape,
    /// Width of the soft boundary outside the shape, world units; 0 (the default) is a hard
    /// boundary.
    pub edge: f32,
    /// Fall-off with the distance along the beam. Default none.
    pub decay: Decay,
    /// How far along the beam it lights, world units; `None` (the default) without end.
    /// With a range, or a `decay` and the plugin's ε (`PhongLightCulling`), the beam is
    /// listed only in the light clusters it reaches.
    pub range: Option<f32>,
    /// Shadow settings: the beam's parallel rays get one orthographic shadow map over the
    /// square around every cross-section's soft edge (`radius + 2·edge` from the axis),
    /// `shadow_distance` deep; a `softness` is an angle in degrees, as a directional
    /// light's. Default off.
    pub shadows: PhongShadows,
    /// How far along the beam its shadow map reaches, world units. Default 50.
    pub shadow_distance: f32,
}

impl Default for Searchlight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            specular: None,
            radius: 1.0,
            shape: BeamShape::Circle,
            edge: 0.0,
            decay: Decay::NONE,
            range: None,
            shadows: PhongShadows::default(),
            shadow_distance: 50.0,
        }
    }
}

/// One searchlight as `searchlight.wesl` reads it (96 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSearchlight {
    pub position: [f32; 3],
    pub radius: f32,
    pub direction: [f32; 3],
    pub edge: f32,
    pub up: [f32; 3],
    pub shape: u32,
    pub color: [f32; 3],
    /// The shadow slot (`PhongLightKind::set_shadow`).
    pub shadow: u32,
    pub specular: [f32; 3],
    /// How far along the beam it lights (`PhongLightKind::set_reach`).
    pub reach: f32,
    pub decay: [f32; 3],
    pub padding2: f32,
}

/// The unit vector of the light's +Y, made perpendicular to its beam.
pub fn beam_up(transform: &GlobalTransform, direction: Vec3) -> Vec3 {
    let up = transform.affine().matrix3 * Vec3::Y;
    (up - direction * up.dot(direction)).normalize_or_zero()
}

/// How far from the axis any cross-section's soft edge reaches: `radius + 2·edge` (a
/// triangle's corner; a circle's `radius + edge`, a square's or diamond's `radius + √2·edge`).
fn widest_reach(radius: f32, edge: f32) -> f32 {
    radius + 2.0 * edge
}

impl PhongLightKind for Searchlight {
    type Gpu = GpuSearchlight;
    // A beam that fades takes its share of ε, as the crate's point and spot lights do.
    const SHARES_EPSILON: bool = true;

    fn to_gpu(&self, transform: &GlobalTransform) -> GpuSearchlight {
        let direction = light_direction(transform);
        GpuSearchlight {
            position: transform.translation().to_array(),
            radius: self.radius,
            direction: direction.to_array(),
            edge: self.edge,
            up: beam_up(transform, direction).to_array(),
            shape: self.shape.shader_index(),
            color: linear_rgb(self.color),
            specular: linear_rgb(self.specular.unwrap_or(self.color)),
            decay: self.decay.to_array(),
            reach: f32::MAX,
            ..default()
        }
    }

    /// The range, shortened to where the beam has faded below `epsilon` (its largest
    /// channel times its decay).
    fn reach(&self, record: &GpuSearchlight, epsilon: f32) -> f32 {
        let intensity = record
            .color
            .into_iter()
            .chain(record.specular)
            .fold(0.0, f32::max);
        self.range
            .unwrap_or(f32::INFINITY)
            .min(influence_radius(record.decay, intensity, epsilon))
    }

    /// The one place the record's reach is written.
    fn set_reach(record: &mut GpuSearchlight, reach: f32) {
        record.reach = reach.min(f32::MAX);
    }

    /// The prism of the beam's cross-section, `reach` long, its soft edge at most
    /// [`widest_reach`] from the axis.
    fn bounding_sphere(record: &GpuSearchlight, reach: f32) -> Option<BoundingSphere> {
        let half_length = 0.5 * reach;
        let center = Vec3::from(record.position) + Vec3::from(record.direction) * half_length;
        let radius = half_length.hypot(widest_reach(record.radius, record.edge));
        Some(BoundingSphere::new(center, radius))
    }

    /// Non-negative sizes, a positive range and shadow distance, and the crate's rules for
    /// colors, decay and shadow settings.
    fn validate(&mut self, checker: &mut Checker) {
        checker.color("color", &mut self.color);
        checker.optional_color("specular", &mut self.specular);
        checker.number("radius", &mut self.radius, 0.0..=f32::MAX, 0.0);
        checker.number("edge", &mut self.edge, 0.0..=f32::MAX, 0.0);
        checker.decay(&mut self.decay);
        checker.range(&mut self.range);
        checker.shadows(&mut self.shadows);
        checker.number(
            "shadow_distance",
            &mut self.shadow_distance,
            1e-3..=f32::MAX,
            50.0,
        );
    }

    fn casts_shadows(&self) -> bool {
        self.shadows.enabled
    }

    fn shadow(&self, transform: &GlobalTransform) -> Option<PhongShadowRequest> {
        let direction = light_direction(transform);
        let up = beam_up(transform, direction);
        let half_size = widest_reach(self.radius, self.edge);
        Some(PhongShadowRequest {
            projection: PhongShadowProjection::Beam {
                origin: transform.translation(),
                direction,
                right: direction.cross(up),
                half_size: Vec2::splat(half_size),
                length: self.shadow_distance,
            },
            settings: self.shadows,
            reach: self.shadow_distance,
        })
    }

    fn reference_light(&self, transform: &GlobalTransform) -> Option<Arc<dyn ReferenceLight>> {
        Some(Arc::new(reference::ReferenceSearchlight::new(
            self, transform,
        )))
    }

    fn set_shadow(record: &mut GpuSearchlight, shadow: u32) {
        record.shadow = shadow;
    }
}

/// The searchlight binding that [`SearchlitMaterial`] adds to `PhongMaterial`: the data
/// texture of [`PhongLightKindBuffer<Searchlight>`], which every device binds, WebGL2
/// included (a native-only extension could bind its storage buffer instead).
#[derive(Asset, AsBindGroup, Reflect, Clone, Debug)]
pub struct SearchlightExtension {
    /// The data texture of [`PhongLightKindBuffer<Searchlight>`].
    #[texture(100, sample_type = "u_int")]
    pub searchlights: Handle<Image>,
}

impl SearchlightExtension {
    /// The extension bound to the app's searchlights.
    pub fn new(buffer: &PhongLightKindBuffer<Searchlight>) -> Self {
        Self {
            searchlights: buffer.texture().clone(),
        }
    }
}

impl MaterialExtension for SearchlightExtension {
    fn fragment_shader() -> ShaderRef {
        "shaders/searchlight.wesl".into()
    }
}
