//! Lighting `PhongMaterial` meshes with Bevy's own lights: [`PhongBevyLightsPlugin`] mirrors
//! Bevy's `PointLight`, `SpotLight`, `DirectionalLight` and `RectLight` into this crate's
//! lights, on the same entities, and lights each camera's view with its Bevy ambient light
//! (`AmbientLight`, `GlobalAmbientLight`), so an existing scene needs no new entities.
//!
//! # The conversion
//!
//! Bevy's lights are in photometric units, and its renderer multiplies what reaches the
//! camera by the camera's exposure `e = 2^-EV100 / 1.2` (EV100 9.7, Bevy's default
//! `Exposure::BLENDER`, gives `e = 6.4e-4`). A Phong light is given the color for which its
//! diffuse term on a white surface equals what Bevy's Lambertian diffuse term (`k_d / π`)
//! shows on screen:
//!
//! | Bevy | Phong |
//! |---|---|
//! | `DirectionalLight { illuminance: E lux, color }` | `color · e · E / π` |
//! | `PointLight { intensity: Φ lumens, color, range }` | `color · e · Φ / (4π²) · 10⁴`, `Decay::new(0, 0, 10⁴)`, `range` |
//! | `SpotLight` | as `PointLight`, with its `inner_angle` and `outer_angle` |
//! | `RectLight { intensity: Φ lumens, color, width, height, range }` | `PhongRectLight` of `color · e · Φ / π²`, the same `width`, `height` and `range`, one-sided |
//! | `GlobalAmbientLight { brightness: L cd/m², color }`, or a camera's `AmbientLight` | `color · e · L`, in that camera's view |
//!
//! Each camera's view is lit by its own Bevy ambient light, as Bevy lights it: the camera's
//! `AmbientLight` where it has one, else `GlobalAmbientLight`. The shader reads it from
//! Bevy's uniform of that view; [`PhongAmbientLight`] is set to none when the plugin is
//! added, and one a game sets adds to Bevy's.
//!
//! Under the mirrored ambient light, a material converted from a `StandardMaterial` shows
//! Bevy's ambient term: its `ambient_factor` 0.4524 is Bevy's weight on the diffuse color,
//! and its `ambient_specular` reflects the ambient light by its specular color as Bevy does
//! (SPEC.md, "Ambient specular"). Bevy's `EnvironmentMapLight` on a camera needs no mirror:
//! a converted material's `environment_light` reads it as `StandardMaterial` does (SPEC.md,
//! "Environment light").
//!
//! The point light's decay `1 / (10⁴ d²)` (and its color, ×10⁴) reproduce Bevy's
//! inverse-square fall-off `1 / max(d², 10⁻⁴)` exactly: the `min(1, …)` of SPEC.md's
//! attenuation clamps where Bevy's `max` does, at 1 cm.
//!
//! Bevy's rectangle is a Lambertian emitter of radiance `Φ / (π·A)` (`A` its area); its
//! diffuse light on a white surface is that radiance times the form factor `F` of the part
//! above the surface's horizon (linearly transformed cosines with the identity matrix:
//! `F = Σ Θᵢ (N·nᵢ) / 2π`, its arc function fitted within 1e-3). A `PhongRectLight`'s
//! diffuse term is `color / A · π·F` (SPEC.md, "Area lights"), hence `color = e · Φ / π²`.
//! Both face the entity's local −Z and light nothing behind it.
//!
//! What does not carry over: Bevy fades a light smoothly to zero toward its `range`, a Phong
//! light is cut off there (a rectangle's range is measured from its center in Bevy, from its
//! nearest point in Phong); Bevy stretches a rectangle by its transform's scale, a
//! `PhongRectLight` ignores scale (give the size in `width` and `height`); Bevy's spot edge is the square `t²` of the linear ramp `t`
//! across the edge, a mirrored spot's is `t` ([`ConeEdge::Linear`]): they differ by
//! `t − t² ≤ 1/4` of the light, the most at the middle of the edge, and Bevy's meets the dark
//! outside without a kink; Bevy's specular is a microfacet (GGX) lobe, while a mirrored light's
//! specular intensity is its diffuse color, shaped by the material's shininess (a mirrored
//! rectangle's highlight integrated over its area, [`AreaHighlight::Bounded`](crate::AreaHighlight));
//! Bevy's ambient light on a mesh with a `Lightmap` follows its `affects_lightmapped_meshes`,
//! a Phong material's ambient term lights every mesh.
//!
//! Shadows carry over as settings: a Bevy light's `shadow_maps_enabled`, `shadow_depth_bias`
//! and `shadow_normal_bias` (the same units) and, for point and spot lights,
//! `shadow_map_near_z` become the mirror's [`PhongShadows`]; the Phong light then renders
//! its own maps, which `PhongMaterial` meshes read (Bevy's maps serve its own materials). A
//! directional light's cascades are [`PhongCascades::default`], not Bevy's
//! `CascadeShadowConfig`; resolution and softness are the defaults.
//!
//! A `Lightmap` on a Phong mesh is read as Bevy reads it, weighed by the material's
//! `light_map_intensity`; [`BevyLightExposure::light_map_intensity`] gives the intensity that
//! shows it as a `StandardMaterial` with a `lightmap_exposure` does under the exposure.
//!
//! Bevy's light textures (`SpotLightTexture`, `PointLightTexture`,
//! `DirectionalLightTexture`) become a [`PhongLightCookie`] on the same entity, laid out the
//! same way and read, as Bevy reads them, by their red channel (`red_only`).
//!
//! A mirrored light is updated whenever its Bevy light changes, and removed with it. Do not
//! also put a Phong light of the same kind on a Bevy light's entity: the mirror owns it.

mod ambient;
mod standard_material;

pub use standard_material::PhongStandardMaterialPlugin;

use crate::light_kind::{PhongDirectionalLight, PhongPointLight, PhongRectLight, PhongSpotLight};
use crate::{
    lights::{
        BevyAmbientPerView, ConeEdge, Decay, PhongAmbientLight, PhongCascades, PhongLightCookie,
        PhongShadows,
    },
    schedule::PhongSystems,
};
use bevy::{
    app::{App, Plugin, PostUpdate},
    camera::Exposure,
    color::{Color, ColorToComponents, LinearRgba},
    ecs::{
        change_detection::DetectChanges,
        component::Component,
        entity::Entity,
        lifecycle::RemovedComponents,
        query::Changed,
        resource::Resource,
        schedule::IntoScheduleConfigs,
        system::{Commands, Query, Res},
    },
    light::{
        DirectionalLight, DirectionalLightTexture, GlobalAmbientLight, PointLight,
        PointLightTexture, RectLight, SpotLight, SpotLightTexture,
    },
    prelude::{ReflectDefault, ReflectResource},
    reflect::Reflect,
};
use core::f32::consts::PI;

/// The quadratic decay coefficient (and color factor) that gives Bevy's
/// `1 / max(d², 10⁻⁴)` fall-off.
pub(crate) const BEVY_FALL_OFF: f32 = 1e4;

/// Mirrors Bevy's lights into this crate's lights (see the [module docs](self)). Opt-in: add
/// it beside [`PhongPlugin`](crate::PhongPlugin).
#[derive(Clone, Copy, Debug, Default)]
pub struct PhongBevyLightsPlugin;

/// The exposure the conversion assumes. A resource; change it to match your camera's
/// [`Exposure`]. Every mirrored light is converted again when it changes.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Resource, Default, Debug, PartialEq, Clone)]
pub struct BevyLightExposure {
    /// Exposure value at ISO 100. Default Bevy's default camera exposure,
    /// [`Exposure::EV100_BLENDER`] (9.7).
    pub ev100: f32,
}

impl Default for BevyLightExposure {
    fn default() -> Self {
        Self {
            ev100: Exposure::EV100_BLENDER,
        }
    }
}

impl BevyLightExposure {
    /// The factor Bevy multiplies scene light by, `2^-EV100 / 1.2`.
    pub fn factor(&self) -> f32 {
        Exposure { ev100: self.ev100 }.exposure()
    }

    /// The [`light_map_intensity`](crate::PhongMaterial::light_map_intensity) under which
    /// Bevy's `Lightmap` on a Phong mesh shows as it does on a `StandardMaterial` with
    /// `lightmap_exposure`: Bevy weighs a lightmap's light by the material's
    /// `lightmap_exposure` and the camera's exposure and, unlike a light's, does not divide
    /// it by π, so the intensity is `lightmap_exposure · factor()` (Bevy's `lightmaps`
    /// example, 250 at EV100 9.7: 0.25). An AO map still darkens it, as three.js's `aoMap`
    /// darkens its `lightMap` (Bevy's occlusion texture leaves a lightmap alone).
    pub fn light_map_intensity(&self, lightmap_exposure: f32) -> f32 {
        lightmap_exposure * self.factor()
    }

    /// The Phong directional light that shows like `light`.
    pub fn directional(&self, light: &DirectionalLight) -> PhongDirectionalLight {
        PhongDirectionalLight {
            color: scaled(light.color, self.factor() * light.illuminance / PI),
            specular: None,
            shadows: PhongShadows {
                enabled: light.shadow_maps_enabled,
                depth_bias: light.shadow_depth_bias,
                normal_bias: light.shadow_normal_bias,
                ..PhongShadows::default()
            },
            cascades: PhongCascades::default(),
        }
    }

    /// The Phong point light that shows like `light`.
    pub fn point(&self, light: &PointLight) -> PhongPointLight {
        PhongPointLight {
            color: self.point_color(light.color, light.intensity),
            specular: None,
            decay: Decay::new(0.0, 0.0, BEVY_FALL_OFF),
            range: Some(light.range),
            shadows: point_shadows(
                light.shadow_maps_enabled,
                light.shadow_depth_bias,
                light.shadow_normal_bias,
                light.shadow_map_near_z,
            ),
        }
    }

    /// The Phong spot light that shows like `light` (its edge linear, not squared).
    pub fn spot(&self, light: &SpotLight) -> PhongSpotLight {
        PhongSpotLight {
            color: self.point_color(light.color, light.intensity),
            specular: None,
            decay: Decay::new(0.0, 0.0, BEVY_FALL_OFF),
            range: Some(light.range),
            inner_angle: light.inner_angle,
            outer_angle: light.outer_angle,
            exponent: 0.0,
            cone_edge: ConeEdge::Linear,
            shadows: point_shadows(
                light.shadow_maps_enabled,
                light.shadow_depth_bias,
                light.shadow_normal_bias,
                light.shadow_map_near_z,
            ),
        }
    }

    /// The Phong rectangle light that shows like `light`: its radiance `Φ / (π·A)`
    /// through the form factor, times the exposure (see the [module docs](self)).
    pub fn rect(&self, light: &RectLight) -> PhongRectLight {
        PhongRectLight {
            color: scaled(light.color, self.factor() * light.intensity / (PI * PI)),
            width: light.width,
            height: light.height,
            range: Some(light.range),
            ..PhongRectLight::default()
        }
    }

    /// The Phong ambient light that shows like `light` (the mirror itself lights each view by
    /// its camera's Bevy ambient light: see the [module docs](self)).
    pub fn ambient(&self, light: &GlobalAmbientLight) -> PhongAmbientLight {
        PhongAmbientLight {
            color: scaled(light.color, self.factor() * light.brightness),
        }
    }

    /// `Φ` lumens over the sphere (`Φ / 4π` candela), through a Lambertian `1 / π`, times
    /// the exposure, times the decay's `10⁴`.
    fn point_color(&self, color: Color, lumens: f32) -> Color {
        scaled(
            color,
            self.factor() * lumens / (4.0 * PI * PI) * BEVY_FALL_OFF,
        )
    }
}

/// The shadow settings of a Bevy point or spot light: on and off, both biases (Bevy's have
/// the same units) and the near plane.
fn point_shadows(enabled: bool, depth_bias: f32, normal_bias: f32, near_z: f32) -> PhongShadows {
    PhongShadows {
        enabled,
        depth_bias,
        normal_bias,
        near_distance: near_z,
        ..PhongShadows::default()
    }
}

/// `color`'s linear RGB times `factor`.
fn scaled(color: Color, factor: f32) -> Color {
    let linear = color.to_linear().to_vec3() * factor;
    LinearRgba::rgb(linear.x, linear.y, linear.z).into()
}

impl Plugin for PhongBevyLightsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<BevyLightExposure>()
            .register_type::<BevyLightExposure>()
            .insert_resource(BevyAmbientPerView { scale: 0.0 })
            .insert_resource(PhongAmbientLight::NONE)
            .add_systems(
                PostUpdate,
                (
                    mirror::<DirectionalLight, PhongDirectionalLight>(
                        BevyLightExposure::directional,
                    ),
                    mirror::<PointLight, PhongPointLight>(BevyLightExposure::point),
                    mirror::<SpotLight, PhongSpotLight>(BevyLightExposure::spot),
                    mirror::<RectLight, PhongRectLight>(BevyLightExposure::rect),
                    mirror::<SpotLightTexture, PhongLightCookie>(spot_cookie),
                    mirror::<PointLightTexture, PhongLightCookie>(point_cookie),
                    mirror::<DirectionalLightTexture, PhongLightCookie>(directional_cookie),
                    ambient::mirror_ambient_scale,
                    ambient::validate_bevy_ambient_lights,
                )
                    .before(PhongSystems::Validate),
            );
    }
}

/// The cookie of a Bevy `SpotLightTexture`: its image across the cone, its red channel.
fn spot_cookie(_: &BevyLightExposure, texture: &SpotLightTexture) -> PhongLightCookie {
    PhongLightCookie {
        image: texture.image.clone(),
        red_only: true,
        ..Default::default()
    }
}

/// The cookie of a Bevy `PointLightTexture`: its packed cube map, its red channel.
fn point_cookie(_: &BevyLightExposure, texture: &PointLightTexture) -> PhongLightCookie {
    PhongLightCookie {
        image: texture.image.clone(),
        cubemap_layout: texture.cubemap_layout,
        red_only: true,
        ..Default::default()
    }
}

/// The cookie of a Bevy `DirectionalLightTexture`: its image on the light's plane, tiled or
/// not, its red channel, the light dark outside an untiled image (`pbr_lighting.wesl`'s
/// `texture_sample = 0`).
fn directional_cookie(
    _: &BevyLightExposure,
    texture: &DirectionalLightTexture,
) -> PhongLightCookie {
    PhongLightCookie {
        image: texture.image.clone(),
        tiled: texture.tiled,
        red_only: true,
        dark_outside: true,
        ..Default::default()
    }
}

/// A system that keeps a `P` beside every `B`, converted by `convert`.
#[allow(clippy::type_complexity)]
fn mirror<B: Component, P: Component>(
    convert: fn(&BevyLightExposure, &B) -> P,
) -> impl FnMut(
    Commands,
    Res<BevyLightExposure>,
    Query<(Entity, &B)>,
    Query<(Entity, &B), Changed<B>>,
    RemovedComponents<B>,
) {
    move |mut commands, exposure, all, changed, mut removed| {
        let mut insert = |entity: Entity, light: &B| {
            commands.entity(entity).insert(convert(&exposure, light));
        };
        if exposure.is_changed() {
            all.iter().for_each(|(entity, light)| insert(entity, light));
        } else {
            changed
                .iter()
                .for_each(|(entity, light)| insert(entity, light));
        }
        for entity in removed.read() {
            if let Ok(mut entity) = commands.get_entity(entity) {
                entity.try_remove::<P>();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{reference, test_app::test_app};
    use bevy::{
        math::{DVec3, Vec3},
        prelude::Transform,
        transform::components::GlobalTransform,
    };

    /// What Bevy's renderer shows for a white Lambertian surface facing the light: the
    /// radiance `E / π` times the exposure, with `E` the illuminance at `distance`.
    fn bevy_point_radiance(lumens: f32, distance: f64, exposure: f32) -> f64 {
        let candela = f64::from(lumens) / (4.0 * std::f64::consts::PI);
        let illuminance = candela / (distance * distance).max(1e-4);
        illuminance / std::f64::consts::PI * f64::from(exposure)
    }

    /// Bevy's `lightmaps` example (`lightmap_exposure` 250) at its default EV100 of 9.7:
    /// Bevy shows `2^-9.7 / 1.2 · 250 = 0.2505` of the texel times the base color
    /// (`pbr_functions.wesl`: `view.exposure · lightmap · lightmap_exposure · diffuse`),
    /// worked by hand; the Phong material's term is `texel · intensity · k_d`.
    #[test]
    fn a_lightmaps_intensity_carries_bevys_exposures() {
        let intensity = BevyLightExposure::default().light_map_intensity(250.0);
        assert!((intensity - 0.250_477).abs() < 1e-6, "{intensity}");
    }

    #[test]
    fn a_mirrored_point_light_shows_as_bright_as_bevy_shows_it() {
        let exposure = BevyLightExposure::default();
        let phong = exposure.point(&PointLight {
            intensity: 800_000.0,
            range: 50.0,
            ..PointLight::default()
        });
        let light = reference::Light::point(&phong, &GlobalTransform::IDENTITY);
        let reference::Light::Point { color, decay, .. } = light else {
            unreachable!()
        };
        for distance in [0.001, 0.01, 0.5, 1.0, 3.0, 20.0] {
            let phong = color.x * reference::attenuation(distance, decay, None);
            let bevy = bevy_point_radiance(800_000.0, distance, exposure.factor());
            assert!(
                (phong - bevy).abs() <= 1e-6 * bevy,
                "at {distance}: Phong {phong}, Bevy {bevy}"
            );
        }
    }

    /// What Bevy's renderer shows for a white Lambertian surface (`normal`, at `point`) lit by
    /// `light` at `transform`, written again from bevy_pbr 0.20.1 (`light.rs` extracts the
    /// radiance `Φ / (π·w·h)`; `pbr_lighting.wesl`'s `rect_light` multiplies it by
    /// `ltc_integrate_quad` with the identity: the form factor `Σ Θᵢ (N·nᵢ) / 2π` of the
    /// rectangle clipped to the horizon, here with the exact arc where Bevy fits it).
    fn bevy_rect_radiance(
        light: &RectLight,
        transform: &GlobalTransform,
        point: DVec3,
        normal: DVec3,
        exposure: f32,
    ) -> f64 {
        let affine = transform.affine();
        let (right, up) = (
            affine.matrix3.x_axis.as_dvec3(),
            affine.matrix3.y_axis.as_dvec3(),
        );
        let center = affine.translation.as_dvec3();
        let (hw, hh) = (
            right * f64::from(light.width) * 0.5,
            up * f64::from(light.height) * 0.5,
        );
        let corners = [
            center + hw - hh,
            center - hw - hh,
            center - hw + hh,
            center + hw + hh,
        ];
        // Bevy's back-face test: the light faces up × right.
        if up.cross(right).dot(point - corners[0]) <= 0.0 {
            return 0.0;
        }
        let mut clipped = Vec::new();
        for i in 0..4 {
            let (a, b) = (corners[i] - point, corners[(i + 1) % 4] - point);
            let (ha, hb) = (a.dot(normal), b.dot(normal));
            if ha >= 0.0 {
                clipped.push(a);
            }
            if (ha >= 0.0) != (hb >= 0.0) {
                clipped.push(a + (b - a) * (ha / (ha - hb)));
            }
        }
        let form_factor: f64 = (0..clipped.len())
            .map(|i| {
                let (a, b) = (
                    clipped[i].normalize(),
                    clipped[(i + 1) % clipped.len()].normalize(),
                );
                let plane = a.cross(b);
                plane.length().atan2(a.dot(b)) * plane.normalize().dot(normal)
            })
            .sum::<f64>()
            / std::f64::consts::TAU;
        let radiance = f64::from(light.intensity)
            / (f64::from(light.width) * f64::from(light.height) * std::f64::consts::PI);
        radiance * form_factor.abs() * f64::from(exposure)
    }

    #[test]
    fn a_mirrored_rect_light_shows_as_bright_as_bevy_shows_it() {
        let exposure = BevyLightExposure::default();
        let bevy = RectLight {
            intensity: 50_000.0,
            width: 2.0,
            height: 0.8,
            range: 100.0,
            ..RectLight::default()
        };
        // Overhead, facing down and tilted a little.
        let transform = GlobalTransform::from(
            Transform::from_xyz(0.3, 2.0, -0.2).looking_at(Vec3::new(0.6, 0.0, 0.4), Vec3::Z),
        );
        let phong = exposure.rect(&bevy);
        let light = reference::AreaLight::rect(&phong, &transform);
        let material = reference::Material {
            diffuse: DVec3::ONE,
            specular_strength: 0.0,
            ..reference::Material::from(&crate::PhongMaterial::default())
        };
        for (position, normal) in [
            (DVec3::ZERO, DVec3::Y),
            (DVec3::new(2.5, 0.0, 1.0), DVec3::Y),
            (
                DVec3::new(-1.5, 0.5, 0.5),
                DVec3::new(0.6, 1.0, 0.0).normalize(),
            ),
            // The panel partly below this point's horizon.
            (
                DVec3::new(0.3, 1.4, 0.0),
                DVec3::new(0.0, 0.2, 1.0).normalize(),
            ),
            // Behind the panel: nothing in either.
            (DVec3::new(0.3, 3.0, -0.2), DVec3::NEG_Y),
        ] {
            let surface = reference::SurfacePoint {
                position,
                normal,
                camera: DVec3::new(-1.0, 2.5, 3.0),
            };
            let phong = reference::area_light_contribution(&surface, &material, &light).x;
            let bevy = bevy_rect_radiance(&bevy, &transform, position, normal, exposure.factor());
            // The quadrature's 1e-9 and the color's rounding to f32.
            assert!(
                (phong - bevy).abs() <= 1e-6 * bevy.max(1e-3),
                "at {position}: Phong {phong}, Bevy {bevy}"
            );
        }
    }

    #[test]
    fn directional_and_ambient_lights_convert_by_exposure_over_pi() {
        let exposure = BevyLightExposure { ev100: 0.0 };
        let factor = 1.0 / 1.2;
        let sun = exposure.directional(&DirectionalLight {
            illuminance: 10.0,
            ..DirectionalLight::default()
        });
        let red = sun.color.to_linear().red;
        assert!((red - factor * 10.0 / PI).abs() < 1e-6);
        let ambient = exposure.ambient(&GlobalAmbientLight {
            brightness: 3.0,
            color: Color::linear_rgb(1.0, 0.5, 0.0),
            ..GlobalAmbientLight::default()
        });
        let linear = ambient.color.to_linear();
        assert!((linear.red - factor * 3.0).abs() < 1e-6);
        assert!((linear.green - factor * 1.5).abs() < 1e-6);
    }

    #[test]
    fn bevy_lights_are_mirrored_updated_and_removed() {
        let mut app = test_app(|app| {
            app.add_plugins(PhongBevyLightsPlugin)
                .insert_resource(GlobalAmbientLight::default());
        });
        let point = app
            .world_mut()
            .spawn((PointLight::default(), Transform::default()))
            .id();
        let spot = app
            .world_mut()
            .spawn((SpotLight::default(), Transform::default()))
            .id();
        let sun = app
            .world_mut()
            .spawn((DirectionalLight::default(), Transform::default()))
            .id();
        let panel = app
            .world_mut()
            .spawn((RectLight::default(), Transform::default()))
            .id();
        app.update();
        let world = app.world();
        let exposure = *world.resource::<BevyLightExposure>();
        assert_eq!(
            world.get::<PhongPointLight>(point),
            Some(&exposure.point(&PointLight::default()))
        );
        assert!(world.get::<PhongSpotLight>(spot).is_some());
        assert!(world.get::<PhongDirectionalLight>(sun).is_some());
        assert_eq!(
            world.get::<PhongRectLight>(panel),
            Some(&exposure.rect(&RectLight::default()))
        );
        // Bevy's ambient light is read per view, from Bevy's uniform, times the factor.
        assert_eq!(
            *world.resource::<PhongAmbientLight>(),
            PhongAmbientLight::NONE
        );
        let header = *world.resource::<crate::render::PhongLightBuffer>().header();
        assert_eq!(header.ambient, [0.0; 3]);
        assert_eq!(header.bevy_ambient_scale, exposure.factor());
        assert_eq!(header.directional_count, 1);
        assert_eq!(header.light_count(), 4);
        assert_eq!(header.area_count + header.clustered_area_count, 1);

        app.world_mut().entity_mut(spot).insert(SpotLightTexture {
            image: Default::default(),
        });
        app.world_mut()
            .entity_mut(sun)
            .insert(DirectionalLightTexture {
                image: Default::default(),
                tiled: true,
            });
        app.update();
        let cookie = app.world().get::<PhongLightCookie>(sun).unwrap();
        // Read as Bevy reads it: its red channel, dark outside an untiled image.
        assert!(cookie.tiled && cookie.red_only && cookie.dark_outside);
        assert!(app.world().get::<PhongLightCookie>(spot).unwrap().red_only);

        app.world_mut().get_mut::<PointLight>(point).unwrap().range = 7.0;
        app.update();
        let mirrored = app.world().get::<PhongPointLight>(point).unwrap();
        assert_eq!(mirrored.range, Some(7.0));

        app.world_mut().entity_mut(point).remove::<PointLight>();
        app.world_mut().despawn(spot);
        app.update();
        assert!(app.world().get::<PhongPointLight>(point).is_none());
    }
}
