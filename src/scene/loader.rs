//! The `*.phong_scene.ron` loader: a [`PhongSceneDescription`] made into meshes, materials
//! and light components, ready to spawn.

use super::{
    LightDescription, MaterialSource, MeshDescription, PhongSceneDescription, SceneFileError,
    read_ron, relative_path, scene_color,
};
use crate::{
    lights::{PhongAmbientLight, PhongDirectionalLight, PhongPointLight, PhongSpotLight},
    material::PhongMaterial,
};
use bevy::{
    asset::{Asset, AssetLoader, Handle, LoadContext, io::Reader},
    math::{Vec3, primitives::*},
    mesh::{Mesh, Meshable},
    reflect::TypePath,
    transform::components::Transform,
};

/// A loaded scene file: what [`PhongSceneRoot`](super::PhongSceneRoot) spawns.
#[derive(Asset, TypePath, Clone, Debug)]
pub struct PhongScene {
    /// The camera's transform and vertical field of view (radians), if the file has one.
    pub camera: Option<(Transform, f32)>,
    /// The ambient light, if the file sets one.
    pub ambient: Option<PhongAmbientLight>,
    /// Each light with where it is.
    pub lights: Vec<(SceneLight, Transform)>,
    /// Each object's mesh, material and transform.
    pub objects: Vec<(Handle<Mesh>, Handle<PhongMaterial>, Transform)>,
}

/// A light component of a [`PhongScene`].
#[derive(Clone, Debug)]
pub enum SceneLight {
    /// A directional light.
    Directional(PhongDirectionalLight),
    /// A point light.
    Point(PhongPointLight),
    /// A spot light.
    Spot(PhongSpotLight),
}

/// Loads a [`PhongScene`] from a `*.phong_scene.ron` file ([`PhongSceneDescription`]).
/// Meshes and inline materials become labeled sub-assets (`object3/mesh`,
/// `object3/material`); material files and textures are loaded relative to the scene file.
#[derive(Default, TypePath)]
pub struct PhongSceneLoader;

impl AssetLoader for PhongSceneLoader {
    type Asset = PhongScene;
    type Settings = ();
    type Error = SceneFileError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<PhongScene, SceneFileError> {
        let description: PhongSceneDescription = read_ron(reader, load_context).await?;
        build_scene(&description, load_context)
    }

    fn extensions(&self) -> &[&str] {
        &["phong_scene.ron"]
    }
}

fn build_scene(
    description: &PhongSceneDescription,
    load_context: &mut LoadContext,
) -> Result<PhongScene, SceneFileError> {
    let camera = match &description.camera {
        None => None,
        Some(camera) => {
            let field = "camera.fov_degrees";
            if !(camera.fov_degrees > 0.0 && camera.fov_degrees < 180.0) {
                return Err(SceneFileError::invalid(
                    load_context,
                    field,
                    format!("must be between 0 and 180, got {}", camera.fov_degrees),
                ));
            }
            let transform =
                Transform::from_translation(camera.position).looking_at(camera.looking_at, Vec3::Y);
            Some((transform, camera.fov_degrees.to_radians()))
        }
    };
    let ambient = match &description.ambient {
        None => None,
        Some(color) => Some(PhongAmbientLight {
            color: scene_color(load_context, color, "ambient")?,
        }),
    };
    let lights = description
        .lights
        .iter()
        .enumerate()
        .map(|(index, light)| scene_light(light, &format!("lights[{index}]"), load_context))
        .collect::<Result<_, _>>()?;
    let mut objects = Vec::new();
    for (index, object) in description.objects.iter().enumerate() {
        let field = format!("objects[{index}]");
        let mesh = mesh(&object.mesh).map_err(|message| {
            SceneFileError::invalid(load_context, format!("{field}.mesh"), message)
        })?;
        let mesh = load_context.add_labeled_asset(format!("object{index}/mesh"), mesh);
        let material = match &object.material {
            MaterialSource::Inline(material) => {
                let material = material.to_material(&format!("{field}.material"), load_context)?;
                load_context.add_labeled_asset(format!("object{index}/material"), material)
            }
            MaterialSource::File(path) => {
                let resolved = relative_path(load_context, path, format!("{field}.material"))?;
                load_context.load(resolved)
            }
        };
        objects.push((mesh, material, Transform::from(&object.transform)));
    }
    Ok(PhongScene {
        camera,
        ambient,
        lights,
        objects,
    })
}

fn scene_light(
    light: &LightDescription,
    field: &str,
    load_context: &LoadContext,
) -> Result<(SceneLight, Transform), SceneFileError> {
    let color = |name: &str, color: &super::SceneColor| {
        scene_color(load_context, color, format!("{field}.{name}"))
    };
    let specular = |color_of: &Option<super::SceneColor>| match color_of {
        None => Ok(None),
        Some(specular) => color("specular", specular).map(Some),
    };
    let aimed = |position: Vec3, direction: Vec3| {
        if direction.length_squared() > 0.0 && direction.is_finite() {
            Ok(Transform::from_translation(position).looking_to(direction, any_up(direction)))
        } else {
            Err(SceneFileError::invalid(
                load_context,
                format!("{field}.direction"),
                format!("must be a finite, non-zero vector, got {direction}"),
            ))
        }
    };
    Ok(match light {
        LightDescription::Directional {
            color: diffuse,
            specular: specular_color,
            direction,
            shadows,
            cascades,
        } => (
            SceneLight::Directional(PhongDirectionalLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                shadows: *shadows,
                cascades: *cascades,
            }),
            aimed(Vec3::ZERO, *direction)?,
        ),
        LightDescription::Point {
            color: diffuse,
            specular: specular_color,
            position,
            decay,
            range,
            shadows,
        } => (
            SceneLight::Point(PhongPointLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                decay: *decay,
                range: *range,
                shadows: *shadows,
            }),
            Transform::from_translation(*position),
        ),
        LightDescription::Spot {
            color: diffuse,
            specular: specular_color,
            position,
            direction,
            decay,
            range,
            inner_angle_degrees,
            outer_angle_degrees,
            exponent,
            shadows,
        } => (
            SceneLight::Spot(PhongSpotLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                decay: *decay,
                range: *range,
                inner_angle: inner_angle_degrees.to_radians(),
                outer_angle: outer_angle_degrees.to_radians(),
                exponent: *exponent,
                shadows: *shadows,
            }),
            aimed(*position, *direction)?,
        ),
    })
}

/// An up vector not parallel to `direction`.
fn any_up(direction: Vec3) -> Vec3 {
    if direction.normalize().y.abs() > 0.99 {
        Vec3::Z
    } else {
        Vec3::Y
    }
}

/// `value` if it is positive and finite, else a message naming `name`.
fn positive(name: &str, value: f32) -> Result<f32, String> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!("{name} must be positive and finite, got {value}"))
    }
}

/// The mesh of `description`, with UVs and (where they can be generated) tangents.
fn mesh(description: &MeshDescription) -> Result<Mesh, String> {
    let mesh: Mesh = match *description {
        MeshDescription::Sphere { radius } => {
            Sphere::new(positive("radius", radius)?).mesh().uv(64, 32)
        }
        MeshDescription::Cuboid { size } => {
            for (axis, value) in ["size.x", "size.y", "size.z"]
                .into_iter()
                .zip(size.to_array())
            {
                positive(axis, value)?;
            }
            Cuboid::from_size(size).into()
        }
        MeshDescription::Plane { size } => {
            positive("size.x", size.x)?;
            positive("size.y", size.y)?;
            Plane3d::default().mesh().size(size.x, size.y).into()
        }
        MeshDescription::Torus {
            minor_radius,
            major_radius,
        } => {
            positive("minor_radius", minor_radius)?;
            if !(major_radius.is_finite() && major_radius > minor_radius) {
                return Err(format!(
                    "major_radius must be finite and larger than minor_radius ({minor_radius}), got {major_radius}"
                ));
            }
            Torus {
                minor_radius,
                major_radius,
            }
            .into()
        }
        MeshDescription::Cylinder { radius, height } => {
            Cylinder::new(positive("radius", radius)?, positive("height", height)?).into()
        }
        MeshDescription::Capsule { radius, length } => {
            Capsule3d::new(positive("radius", radius)?, positive("length", length)?).into()
        }
        MeshDescription::Cone { radius, height } => Cone {
            radius: positive("radius", radius)?,
            height: positive("height", height)?,
        }
        .into(),
    };
    // Every primitive has UVs, normals and indices, which is all tangents need.
    mesh.with_generated_tangents()
        .map_err(|error| format!("could not generate tangents: {error}"))
}
