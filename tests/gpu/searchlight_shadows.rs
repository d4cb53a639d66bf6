//! Shadows of a light kind added from outside the crate: the searchlight example's beam
//! (`examples/searchlight/`) requests one orthographic map along its parallel rays
//! (`PhongShadowProjection::Beam`), and its shader reads it through
//! `bevy_phong::shaders::shadows::shadow_factors`. The shadow judge (`shadows.rs`) casts
//! each pixel's exact ray against the beam's rays (`L = −direction`); nothing of the scene
//! lies behind the beam's origin, where its map does not reach, so the unbounded ray is
//! exact. The searchlight's term is its own reference's (`ReferenceSearchlight`), scaled by
//! `f + (1 − f)·V`.

use crate::{
    light::{Searchlight, SearchlitMaterial},
    searchlight::searchlit_harness,
    shadow_band::MapCover,
    shadows::{CaseLight, EVERYONE, SIZE, Scene, SpawnLights, Toward, judge, on, spot},
};
use bevy::prelude::*;
use bevy_phong::{
    extension::{PhongLightKind, PhongShadowProjection},
    prelude::*,
};
use bevy_phong_headless::Harness;
/// The share of the covered pixels the beam's shadows must darken outside the band: the
/// sphere's and the box's shadows on the floor inside the beam, 2.0 % (the soft beam, whose
/// band is wider) to 5.4 % of them measured; a missing map would leave none.
const SHADOWED_SHARE: f64 = 0.015;
/// Where the beam starts, above and to the left of everything, and where its axis meets the
/// floor: slanted, so that the sphere's and the box's shadows fall beside them in view.
const BEAM_ORIGIN: Vec3 = Vec3::new(-5.0, 5.0, -1.0);
const BEAM_TARGET: Vec3 = Vec3::new(0.5, 0.0, 0.3);
/// The beam's radius and soft edge, world units: the prism holds the sphere and the box and
/// their shadows on the floor.
const RADIUS: f32 = 2.2;
const EDGE: f32 = 0.4;

/// The shadow scene's floor, sphere and box, searchlit, under a little ambient light.
fn searchlit_shadow_scene() -> (Harness, Scene<SearchlitMaterial>) {
    let (mut harness, extension) = searchlit_harness(SIZE);
    let scene = Scene::spawn_with(&mut harness, |base| SearchlitMaterial {
        base,
        extension: extension.clone(),
    });
    (harness, scene)
}

/// Spawns the beam with `shadows` and returns what the judge needs of it.
fn beam(harness: &mut Harness, shadows: PhongShadows) -> CaseLight {
    let direction = (BEAM_TARGET - BEAM_ORIGIN).normalize();
    let searchlight = Searchlight {
        color: Color::linear_rgb(1.2, 1.1, 0.9),
        radius: RADIUS,
        edge: EDGE,
        shadows,
        shadow_distance: 12.0,
        ..default()
    };
    let at = Transform::from_translation(BEAM_ORIGIN).looking_to(direction, Vec3::Z);
    // The rectangle the kind requests for its map.
    let Some(PhongShadowProjection::Beam { half_size, .. }) = searchlight
        .shadow(&GlobalTransform::from(at))
        .map(|request| request.projection)
    else {
        panic!("a searchlight requests a beam's map");
    };
    harness.world_mut().spawn((searchlight, at));
    CaseLight {
        toward: Toward::Direction(direction.as_dvec3()),
        settings: shadows,
        cover: MapCover::Beam {
            half_size: f64::from(half_size.max_element()),
        },
        of_other_kind: true,
    }
}

#[test]
fn a_searchlight_beam_shadows_where_its_parallel_rays_are_blocked() {
    let cases: [(&str, &SpawnLights); 3] = [
        ("beam", &|h| vec![beam(h, on())]),
        // Percentage-closer soft shadows: the beam's maps are orthographic, its softness an
        // angle as a directional light's. The band widens by the widest filter (32 texels),
        // so the map is finer, for the shadows' cores to show outside it.
        ("soft beam", &|h| {
            vec![beam(
                h,
                PhongShadows {
                    softness: 5.0,
                    resolution: 1024,
                    ..on()
                },
            )]
        }),
        // Light left in the shadows, and a built-in kind's shadows beside the beam's.
        ("beam and spot, light left in the shadows", &|h| {
            let beam_dimmed = PhongShadows {
                diffuse_in_shadow: 0.3,
                specular_in_shadow: 0.3,
                ..on()
            };
            let spot_dimmed = PhongShadows {
                diffuse_in_shadow: 0.6,
                specular_in_shadow: 0.1,
                ..on()
            };
            vec![
                beam(h, beam_dimmed),
                spot(h, Vec3::new(1.5, 4.0, 2.0), Vec3::ZERO, spot_dimmed),
            ]
        }),
    ];
    for (case, lights) in cases {
        let (mut harness, scene) = searchlit_shadow_scene();
        let lights = lights(&mut harness);
        harness.settle();
        let inputs = harness.capture_inputs_of::<SearchlitMaterial>();
        judge(&mut harness, &scene, &lights, &EVERYONE, &inputs)
            .assert_holds_with_shadows_on(case, SHADOWED_SHARE);
    }
}
