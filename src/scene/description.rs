//! A scene as written in a `*.phong_scene.ron` file.

use super::{PhongMaterialDescription, SceneColor};
use crate::lights::{AreaHighlight, ConeEdge, Decay, PhongCascades, PhongShadows};
use bevy::math::{EulerRot, Quat, Vec2, Vec3};
use bevy::transform::components::Transform;
use serde::{Deserialize, Serialize};

/// A whole scene: a camera, the ambient light, lights, and objects made of Bevy's mesh
/// primitives. Every field is optional.
///
/// ```ron
/// (
///     camera: Some((position: (0.0, 2.5, 7.0), looking_at: (0.0, 0.0, 0.0))),
///     ambient: Linear(0.1, 0.1, 0.1),
///     lights: [
///         Directional(direction: (-1.0, -1.0, -1.0)),
///         Point(position: (0.0, 3.0, 0.0), color: Srgb(1.0, 0.5, 0.2),
///               decay: (constant: 1.0, linear: 0.09, quadratic: 0.032)),
///     ],
///     objects: [
///         (mesh: Sphere(radius: 1.0), material: Inline((shininess: 50.0))),
///         (mesh: Cuboid(size: (1.0, 1.0, 1.0)),
///          transform: (translation: (2.0, 0.0, 0.0), rotation: (0.0, 30.0, 0.0)),
///          material: File("crate.phong.ron")),
///     ],
/// )
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhongSceneDescription {
    /// Where the scene is seen from; none spawns no camera.
    pub camera: Option<CameraDescription>,
    /// The ambient light (the `PhongAmbientLight` resource is set to it when the scene is
    /// spawned). Default linear gray `0.1`, as `PhongAmbientLight::default()`.
    pub ambient: Option<SceneColor>,
    /// A hemisphere light (the `PhongHemisphereLight` resource is inserted when the scene is
    /// spawned). Default none.
    pub hemisphere: Option<HemisphereDescription>,
    /// The lights.
    pub lights: Vec<LightDescription>,
    /// The objects.
    pub objects: Vec<ObjectDescription>,
}

/// A hemisphere light: `(sky_color: Linear(0.3, 0.35, 0.4), ground_color: Srgb(0.2, 0.15,
/// 0.1))`, `up` optional.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HemisphereDescription {
    /// The light from above.
    pub sky_color: SceneColor,
    /// The light from below.
    pub ground_color: SceneColor,
    /// The direction of the sky. Default `(0.0, 1.0, 0.0)`.
    #[serde(default = "default_up")]
    pub up: Vec3,
}

fn default_up() -> Vec3 {
    Vec3::Y
}

/// A perspective camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDescription {
    /// Camera position, world units.
    pub position: Vec3,
    /// The point it looks at, with +Y up. Default the origin.
    #[serde(default)]
    pub looking_at: Vec3,
    /// Vertical field of view, degrees. Default 45.
    #[serde(default = "default_fov_degrees")]
    pub fov_degrees: f32,
}

fn default_fov_degrees() -> f32 {
    45.0
}

/// One light; colors default to white, `specular` to `color`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum LightDescription {
    /// Parallel light travelling along `direction`.
    Directional {
        /// Diffuse intensity.
        #[serde(default = "SceneColor::white")]
        color: SceneColor,
        /// Specular intensity.
        #[serde(default)]
        specular: Option<SceneColor>,
        /// Direction the light travels (any length).
        direction: Vec3,
        /// Shadow settings, as `PhongShadows`. Default off.
        #[serde(default)]
        shadows: PhongShadows,
        /// Shadow cascades, as `PhongCascades`.
        #[serde(default)]
        cascades: PhongCascades,
        /// A cookie on the light's plane (one tile over `[−1, 1]²` across the light). Default
        /// none.
        #[serde(default)]
        cookie: Option<CookieDescription>,
    },
    /// Light from a point in all directions.
    Point {
        /// Diffuse intensity.
        #[serde(default = "SceneColor::white")]
        color: SceneColor,
        /// Specular intensity.
        #[serde(default)]
        specular: Option<SceneColor>,
        /// Position, world units.
        position: Vec3,
        /// Distance fall-off. Default none.
        #[serde(default)]
        decay: Decay,
        /// Distance past which it gives no light. Default unlimited.
        #[serde(default)]
        range: Option<f32>,
        /// Shadow settings, as `PhongShadows`. Default off.
        #[serde(default)]
        shadows: PhongShadows,
        /// A cookie around the light (a cube map packed in one image). Default none.
        #[serde(default)]
        cookie: Option<CookieDescription>,
    },
    /// Light from a point in a cone around `direction`.
    Spot {
        /// Diffuse intensity.
        #[serde(default = "SceneColor::white")]
        color: SceneColor,
        /// Specular intensity.
        #[serde(default)]
        specular: Option<SceneColor>,
        /// Position, world units.
        position: Vec3,
        /// The cone's axis (any length).
        direction: Vec3,
        /// Distance fall-off. Default none.
        #[serde(default)]
        decay: Decay,
        /// Distance past which it gives no light. Default unlimited.
        #[serde(default)]
        range: Option<f32>,
        /// Half-angle of the fully lit core, degrees. Default 12.5.
        #[serde(default = "default_inner_angle_degrees")]
        inner_angle_degrees: f32,
        /// Half-angle where the light reaches zero, degrees. Default 17.5.
        #[serde(default = "default_outer_angle_degrees")]
        outer_angle_degrees: f32,
        /// Rim darkening exponent. Default 0.
        #[serde(default)]
        exponent: f32,
        /// How the light fades between the cones, as `ConeEdge`. Default `Linear`.
        #[serde(default)]
        cone_edge: ConeEdge,
        /// Shadow settings, as `PhongShadows`. Default off.
        #[serde(default)]
        shadows: PhongShadows,
        /// A cookie across the cone. Default none.
        #[serde(default)]
        cookie: Option<CookieDescription>,
    },
    /// A rectangle that emits from its area (`PhongRectLight`), centered on `position` and
    /// facing `direction`.
    Rect {
        /// The whole rectangle's diffuse intensity.
        #[serde(default = "SceneColor::white")]
        color: SceneColor,
        /// Its specular intensity.
        #[serde(default)]
        specular: Option<SceneColor>,
        /// Its center, world units.
        position: Vec3,
        /// The direction it faces (any length).
        direction: Vec3,
        /// The direction its height runs along, turned square to `direction` (any length).
        /// Default +Y (+Z for a rectangle facing straight up or down).
        #[serde(default)]
        up: Option<Vec3>,
        /// Its size across `up`, world units. Default 1.
        #[serde(default = "default_size")]
        width: f32,
        /// Its size along `up`, world units. Default 1.
        #[serde(default = "default_size")]
        height: f32,
        /// Whether it emits from its back face too. Default `false`.
        #[serde(default)]
        two_sided: bool,
        /// Fall-off with the distance to its nearest point. Default none.
        #[serde(default)]
        decay: Decay,
        /// Distance from its nearest point past which it gives no light. Default unlimited.
        #[serde(default)]
        range: Option<f32>,
        /// How its highlight is computed, as `AreaHighlight`. Default `Bounded`.
        #[serde(default)]
        highlight: AreaHighlight,
        /// Shadow settings, as `PhongShadows` (soft as the light's size). Default off.
        #[serde(default)]
        shadows: PhongShadows,
    },
    /// A disk that emits from its area (`PhongDiskLight`), centered on `position` and facing
    /// `direction`.
    Disk {
        /// The whole disk's diffuse intensity.
        #[serde(default = "SceneColor::white")]
        color: SceneColor,
        /// Its specular intensity.
        #[serde(default)]
        specular: Option<SceneColor>,
        /// Its center, world units.
        position: Vec3,
        /// The direction it faces (any length).
        direction: Vec3,
        /// World units. Default 0.5.
        #[serde(default = "default_radius")]
        radius: f32,
        /// Whether it emits from its back face too. Default `false`.
        #[serde(default)]
        two_sided: bool,
        /// Fall-off with the distance to its nearest point. Default none.
        #[serde(default)]
        decay: Decay,
        /// Distance from its nearest point past which it gives no light. Default unlimited.
        #[serde(default)]
        range: Option<f32>,
        /// How its highlight is computed, as `AreaHighlight`. Default `Bounded`.
        #[serde(default)]
        highlight: AreaHighlight,
        /// Shadow settings, as `PhongShadows` (soft as the light's size). Default off.
        #[serde(default)]
        shadows: PhongShadows,
    },
}

/// A light's cookie (`PhongLightCookie`): `(image: "window.png")`, and for a point light
/// `cubemap_layout: SequenceHorizontal`, for a directional one `tiled: true`. The image is
/// loaded as sRGB color data, relative to the scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CookieDescription {
    /// Path of the image.
    pub image: String,
    /// How a point light's image packs the cube's faces. Default `CrossVertical`.
    #[serde(default)]
    pub cubemap_layout: CubemapLayoutDescription,
    /// Whether a directional light's image repeats. Default `false`.
    #[serde(default)]
    pub tiled: bool,
    /// Whether the red channel alone tints the light. Default `false`.
    #[serde(default)]
    pub red_only: bool,
    /// Whether a directional light is dark outside its untiled image. Default `false`.
    #[serde(default)]
    pub dark_outside: bool,
}

/// Bevy's `CubemapLayout`, by name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum CubemapLayoutDescription {
    /// `+y` above `−x −z +x`, then `−y`, then `+z`, in a column of crosses.
    #[default]
    CrossVertical,
    /// `+y` above `−x −z +x +z`, then `−y`.
    CrossHorizontal,
    /// `+x −x +y −y −z +z` from top to bottom.
    SequenceVertical,
    /// `+x −x +y −y −z +z` from left to right.
    SequenceHorizontal,
}

impl CubemapLayoutDescription {
    /// Bevy's layout.
    pub fn to_layout(self) -> bevy::camera::primitives::CubemapLayout {
        use bevy::camera::primitives::CubemapLayout;
        match self {
            Self::CrossVertical => CubemapLayout::CrossVertical,
            Self::CrossHorizontal => CubemapLayout::CrossHorizontal,
            Self::SequenceVertical => CubemapLayout::SequenceVertical,
            Self::SequenceHorizontal => CubemapLayout::SequenceHorizontal,
        }
    }
}

fn default_size() -> f32 {
    1.0
}

fn default_radius() -> f32 {
    0.5
}

fn default_inner_angle_degrees() -> f32 {
    12.5
}

fn default_outer_angle_degrees() -> f32 {
    17.5
}

/// A mesh with a transform and a material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDescription {
    /// The shape.
    pub mesh: MeshDescription,
    /// Where it is. Default identity.
    #[serde(default)]
    pub transform: TransformDescription,
    /// What it is made of. Default `Inline(())`, the default material.
    #[serde(default)]
    pub material: MaterialSource,
}

/// A material written in place or in its own `*.phong.ron` file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MaterialSource {
    /// Written in the scene file.
    Inline(Box<PhongMaterialDescription>),
    /// A `*.phong.ron` file, relative to the scene file.
    File(String),
}

impl Default for MaterialSource {
    fn default() -> Self {
        MaterialSource::Inline(Box::default())
    }
}

/// Translation, rotation (Euler angles in degrees, applied Y, then X, then Z) and scale.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TransformDescription {
    /// World units. Default zero.
    pub translation: Vec3,
    /// Degrees about X, Y, Z. Default zero.
    pub rotation: Vec3,
    /// Default one.
    pub scale: Vec3,
}

impl Default for TransformDescription {
    fn default() -> Self {
        Self {
            translation: Vec3::ZERO,
            rotation: Vec3::ZERO,
            scale: Vec3::ONE,
        }
    }
}

impl From<&TransformDescription> for Transform {
    fn from(description: &TransformDescription) -> Self {
        let radians = description.rotation * (std::f32::consts::PI / 180.0);
        Transform {
            translation: description.translation,
            rotation: Quat::from_euler(EulerRot::YXZ, radians.y, radians.x, radians.z),
            scale: description.scale,
        }
    }
}

/// One of Bevy's mesh primitives, with UVs and tangents (for texture and normal maps).
/// Sizes are world units and must be positive.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MeshDescription {
    /// A UV sphere (64 × 32 segments).
    Sphere {
        /// Radius.
        radius: f32,
    },
    /// A box centred on the origin.
    Cuboid {
        /// Edge lengths along X, Y, Z.
        size: Vec3,
    },
    /// A plane through the origin facing +Y.
    Plane {
        /// Extent along X and Z.
        size: Vec2,
    },
    /// A torus around the Y axis.
    Torus {
        /// Radius of the tube.
        minor_radius: f32,
        /// Distance from the centre to the middle of the tube.
        major_radius: f32,
    },
    /// A cylinder along Y.
    Cylinder {
        /// Radius.
        radius: f32,
        /// Height.
        height: f32,
    },
    /// A capsule along Y.
    Capsule {
        /// Radius of the caps and the body.
        radius: f32,
        /// Length of the body between the caps.
        length: f32,
    },
    /// A cone along Y, tip up.
    Cone {
        /// Radius of the base.
        radius: f32,
        /// Height.
        height: f32,
    },
}
