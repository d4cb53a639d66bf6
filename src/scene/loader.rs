//! The `*.phong_scene.ron` loader: a [`PhongSceneDescription`] made into meshes, materials
//! and light components, ready to spawn.

use super::{
    CameraDescription, LightDescription, MaterialSource, MeshDescription, PhongSceneDescription,
    SceneFileError, TransformDescription, material_file::load_texture, read_ron, relative_path,
    scene_color,
};
use crate::light_kind::{
    PhongDirectionalLight, PhongDiskLight, PhongPointLight, PhongRectLight, PhongSpotLight,
};
use crate::{
    direction,
    lights::{PhongAmbientLight, PhongHemisphereLight, PhongLightCookie},
    material::PhongMaterial,
};
use bevy::{
    asset::{Asset, AssetLoader, Handle, LoadContext, io::Reader},
    math::Vec3,
    mesh::{Mesh, Meshable},
    reflect::TypePath,
    shape::*,
    transform::components::Transform,
};

/// A loaded scene file: what [`PhongSceneRoot`](super::PhongSceneRoot) spawns.
#[derive(Asset, TypePath, Clone, Debug)]
pub struct PhongScene {
    /// The camera's transform and vertical field of view (radians), if the file has one.
    pub camera: Option<(Transform, f32)>,
    /// The ambient light, if the file sets one.
    pub ambient: Option<PhongAmbientLight>,
    /// The hemisphere light, if the file has one.
    pub hemisphere: Option<PhongHemisphereLight>,
    /// Each light with where it is, and its cookie if it has one.
    pub lights: Vec<(SceneLight, Transform, Option<PhongLightCookie>)>,
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
    /// A rectangle light.
    Rect(PhongRectLight),
    /// A disk light.
    Disk(PhongDiskLight),
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
        Some(camera) => Some(scene_camera(camera, load_context)?),
    };
    let ambient = match &description.ambient {
        None => None,
        Some(color) => Some(PhongAmbientLight {
            color: scene_color(load_context, color, "ambient")?,
        }),
    };
    let hemisphere = match &description.hemisphere {
        None => None,
        Some(hemisphere) => Some(PhongHemisphereLight {
            sky_color: scene_color(load_context, &hemisphere.sky_color, "hemisphere.sky_color")?,
            ground_color: scene_color(
                load_context,
                &hemisphere.ground_color,
                "hemisphere.ground_color",
            )?,
            up: hemisphere.up,
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
        let transform = object_transform(
            &object.transform,
            &format!("{field}.transform"),
            load_context,
        )?;
        objects.push((mesh, material, transform));
    }
    Ok(PhongScene {
        camera,
        ambient,
        hemisphere,
        lights,
        objects,
    })
}

fn scene_light(
    light: &LightDescription,
    field: &str,
    load_context: &mut LoadContext,
) -> Result<(SceneLight, Transform, Option<PhongLightCookie>), SceneFileError> {
    let cookie = match light {
        LightDescription::Directional { cookie, .. }
        | LightDescription::Point { cookie, .. }
        | LightDescription::Spot { cookie, .. } => cookie,
        LightDescription::Rect { .. } | LightDescription::Disk { .. } => &None,
    };
    let cookie = match cookie {
        None => None,
        Some(cookie) => {
            let field = format!("{field}.cookie.image");
            let image = load_texture(load_context, Some(&cookie.image), &field, true)?
                .expect("a path was given");
            Some(PhongLightCookie {
                image,
                cubemap_layout: cookie.cubemap_layout.to_layout(),
                tiled: cookie.tiled,
                red_only: cookie.red_only,
                dark_outside: cookie.dark_outside,
            })
        }
    };
    let (light, transform) = scene_light_alone(light, field, load_context)?;
    Ok((light, transform, cookie))
}

/// Reads the fields of the light described at `field`, each error naming its field.
struct LightFields<'a, 'c> {
    field: &'a str,
    load_context: &'a LoadContext<'c>,
}

impl LightFields<'_, '_> {
    /// The color of field `name`.
    fn color(
        &self,
        name: &str,
        color: &super::SceneColor,
    ) -> Result<bevy::color::Color, SceneFileError> {
        scene_color(self.load_context, color, format!("{}.{name}", self.field))
    }

    /// The specular color, if the light has its own.
    fn specular(
        &self,
        color: &Option<super::SceneColor>,
    ) -> Result<Option<bevy::color::Color>, SceneFileError> {
        color
            .as_ref()
            .map(|specular| self.color("specular", specular))
            .transpose()
    }

    /// A light at `position`, which must be finite.
    fn placed(&self, position: Vec3) -> Result<Transform, SceneFileError> {
        if position.is_finite() {
            Ok(Transform::from_translation(position))
        } else {
            Err(SceneFileError::invalid(
                self.load_context,
                format!("{}.position", self.field),
                format!("must be finite, got {position}"),
            ))
        }
    }

    /// A light at `position` pointing along `direction`, which must be finite and not zero.
    fn aimed(&self, position: Vec3, direction: Vec3) -> Result<Transform, SceneFileError> {
        let position = self.placed(position)?;
        // Normalized by its largest component first: huge and tiny directions keep theirs.
        let unit = direction::normalize_or_zero(direction);
        if unit == Vec3::ZERO {
            return Err(SceneFileError::invalid(
                self.load_context,
                format!("{}.direction", self.field),
                format!(
                    "must be finite and non-zero (its largest component at least {:e}), got {direction}",
                    direction::MIN_COMPONENT
                ),
            ));
        }
        Ok(position.looking_to(unit, any_up(unit)))
    }

    /// A light at `position` facing `direction` (as [`Self::aimed`]), its local Y along
    /// `up` turned square to `direction`; [`any_up`] where `up` is `None`, along
    /// `direction` or not finite.
    fn aimed_up(
        &self,
        position: Vec3,
        direction: Vec3,
        up: Option<Vec3>,
    ) -> Result<Transform, SceneFileError> {
        let aimed = self.aimed(position, direction)?;
        let facing = direction::normalize_or_zero(direction);
        let up = direction::normalize_or_zero(up.unwrap_or(Vec3::ZERO));
        if up.cross(facing).length_squared() < 1e-12 {
            return Ok(aimed);
        }
        Ok(aimed.looking_to(facing, up))
    }
}

/// The light component of `light` and where it is.
fn scene_light_alone(
    light: &LightDescription,
    field: &str,
    load_context: &LoadContext,
) -> Result<(SceneLight, Transform), SceneFileError> {
    let fields = LightFields {
        field,
        load_context,
    };
    let color = |name: &str, color: &super::SceneColor| fields.color(name, color);
    let specular = |color: &Option<super::SceneColor>| fields.specular(color);
    let placed = |position: Vec3| fields.placed(position);
    let aimed = |position: Vec3, direction: Vec3| fields.aimed(position, direction);
    Ok(match light {
        LightDescription::Directional {
            color: diffuse,
            specular: specular_color,
            direction,
            shadows,
            cascades,
            ..
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
            ..
        } => (
            SceneLight::Point(PhongPointLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                decay: *decay,
                range: *range,
                shadows: *shadows,
            }),
            placed(*position)?,
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
            cone_edge,
            shadows,
            ..
        } => (
            SceneLight::Spot(PhongSpotLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                decay: *decay,
                range: *range,
                inner_angle: inner_angle_degrees.to_radians(),
                outer_angle: outer_angle_degrees.to_radians(),
                exponent: *exponent,
                cone_edge: *cone_edge,
                shadows: *shadows,
            }),
            aimed(*position, *direction)?,
        ),
        LightDescription::Rect {
            color: diffuse,
            specular: specular_color,
            position,
            direction,
            up,
            width,
            height,
            two_sided,
            decay,
            range,
            highlight,
            shadows,
        } => (
            SceneLight::Rect(PhongRectLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                width: *width,
                height: *height,
                two_sided: *two_sided,
                decay: *decay,
                range: *range,
                highlight: *highlight,
                shadows: *shadows,
            }),
            fields.aimed_up(*position, *direction, *up)?,
        ),
        LightDescription::Disk {
            color: diffuse,
            specular: specular_color,
            position,
            direction,
            radius,
            two_sided,
            decay,
            range,
            highlight,
            shadows,
        } => (
            SceneLight::Disk(PhongDiskLight {
                color: color("color", diffuse)?,
                specular: specular(specular_color)?,
                radius: *radius,
                two_sided: *two_sided,
                decay: *decay,
                range: *range,
                highlight: *highlight,
                shadows: *shadows,
            }),
            fields.aimed(*position, *direction)?,
        ),
    })
}

/// The camera's transform and vertical field of view (radians); a non-finite position, a
/// target at the camera or a field of view outside (0°, 180°) is an error naming its field.
fn scene_camera(
    camera: &CameraDescription,
    load_context: &LoadContext,
) -> Result<(Transform, f32), SceneFileError> {
    let invalid = |field: &str, message: String| {
        Err(SceneFileError::invalid(
            load_context,
            format!("camera.{field}"),
            message,
        ))
    };
    if !(camera.fov_degrees > 0.0 && camera.fov_degrees < 180.0) {
        let message = format!("must be between 0 and 180, got {}", camera.fov_degrees);
        return invalid("fov_degrees", message);
    }
    for (field, point) in [
        ("position", camera.position),
        ("looking_at", camera.looking_at),
    ] {
        if !point.is_finite() {
            return invalid(field, format!("must be finite, got {point}"));
        }
    }
    // In f64, where the difference of two finite f32 points cannot overflow.
    let offset = camera.looking_at.as_dvec3() - camera.position.as_dvec3();
    let forward = direction::normalize_or_zero_f64(offset).as_vec3();
    if forward == Vec3::ZERO {
        let message = format!("must differ from position, got {}", camera.looking_at);
        return invalid("looking_at", message);
    }
    let transform = Transform::from_translation(camera.position).looking_to(forward, Vec3::Y);
    Ok((transform, camera.fov_degrees.to_radians()))
}

/// An object's transform; a non-finite translation, rotation or scale is an error at
/// `field` (as `objects[2].transform.scale`).
fn object_transform(
    description: &TransformDescription,
    field: &str,
    load_context: &LoadContext,
) -> Result<Transform, SceneFileError> {
    for (name, value) in [
        ("translation", description.translation),
        ("rotation", description.rotation),
        ("scale", description.scale),
    ] {
        if !value.is_finite() {
            return Err(SceneFileError::invalid(
                load_context,
                format!("{field}.{name}"),
                format!("must be finite, got {value}"),
            ));
        }
    }
    Ok(Transform::from(description))
}

/// An up vector not parallel to the unit vector `direction`.
fn any_up(direction: Vec3) -> Vec3 {
    if direction.y.abs() > 0.99 {
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
