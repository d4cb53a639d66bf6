//! Street lamps (`--lamps`): 16 ranged spot lights over the field, and lamps in far towns
//! that reach no visible pixel, with cookies (a window image), with shadows, or both. The
//! table sets each scene with 2,000 far lamps beside the same scene without them, Phong and
//! `StandardMaterial` (lit by the equivalent Bevy spot lights, without cookies), so that what
//! a light costs where it does not shine shows as the ratio.

use crate::scene::{SHADOW_MAP_SIZE, Scene, Shading, scatter};
use crate::timing::{Frames, median_frame_time};
use crate::{alternating_medians_of, ms, write};
use bevy::{
    asset::RenderAssetUsages,
    prelude::*,
    render::render_resource::{Extent3d, TextureDimension, TextureFormat},
};
use bevy_phong::prelude::*;
use std::{fmt::Write as _, path::Path};

/// The lamps near the camera, on a 4 × 4 grid over the field.
const NEAR_LAMPS: usize = 16;
/// The lamps in far towns, in the table's scenes with far lamps.
const FAR_LAMPS: usize = 2_000;

/// Which lamps cast shadows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LampShadows {
    /// None.
    Off,
    /// Every other near lamp (8).
    HalfNear,
    /// Every near lamp and the first 16 far ones.
    NearAndFar,
}

/// A street-lamp scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lamps {
    /// Lamps in far towns, each at least 40 units from the field's middle along x or z.
    pub far: usize,
    /// Every lamp has the same cookie: a 64² window image.
    pub cookies: bool,
    pub shadows: LampShadows,
}

impl Lamps {
    /// The scene a `--scene` name picks: `lamps`, then any of `-cookies`, `-shadows` (8 near
    /// lamps casting them) and `-far` (2,000 far lamps), in that order.
    pub fn from_name(name: &str) -> Option<Self> {
        let rest = name.strip_prefix("lamps")?;
        let (cookies, rest) = match rest.strip_prefix("-cookies") {
            Some(rest) => (true, rest),
            None => (false, rest),
        };
        let (shadows, rest) = match rest.strip_prefix("-shadows") {
            Some(rest) => (LampShadows::HalfNear, rest),
            None => (LampShadows::Off, rest),
        };
        let (far, rest) = match rest.strip_prefix("-far") {
            Some(rest) => (FAR_LAMPS, rest),
            None => (0, rest),
        };
        rest.is_empty().then_some(Self {
            far,
            cookies,
            shadows,
        })
    }

    /// How many lamps the scene has.
    pub fn light_count(self) -> usize {
        NEAR_LAMPS + self.far
    }

    pub fn name(self) -> String {
        let shadows = match self.shadows {
            LampShadows::Off => "",
            LampShadows::HalfNear => ", 8 near casting shadows",
            LampShadows::NearAndFar => ", 16 near and 16 far casting shadows",
        };
        format!(
            "lamps: {NEAR_LAMPS} near + {} far{}{shadows}",
            self.far,
            if self.cookies { ", cookies" } else { "" }
        )
    }
}

/// One lamp: where it hangs and whether it casts shadows.
struct Lamp {
    position: Vec3,
    shadows: bool,
}

/// The lamps of `lamps`: the near grid, then the far ones.
fn lamp_places(lamps: Lamps) -> Vec<Lamp> {
    let near = (0..NEAR_LAMPS).map(|i| Lamp {
        position: Vec3::new((i % 4) as f32 * 6.0 - 9.0, 3.0, (i / 4) as f32 * 6.0 - 9.0),
        shadows: match lamps.shadows {
            LampShadows::Off => false,
            LampShadows::HalfNear => i % 2 == 0,
            LampShadows::NearAndFar => true,
        },
    });
    let far = (0..)
        .map(|i| {
            let (u, v, _) = scatter(i + 2_000_003);
            Vec3::new(u * 1000.0 - 500.0, 3.0, v * 1000.0 - 500.0)
        })
        .filter(|position| position.x.abs().max(position.z.abs()) >= 40.0)
        .take(lamps.far)
        .enumerate()
        .map(|(i, position)| Lamp {
            position,
            shadows: lamps.shadows == LampShadows::NearAndFar && i < 16,
        });
    near.chain(far).collect()
}

/// A 64² window: four bright panes in a dark frame, 8-bit sRGB.
fn window_image() -> Image {
    const SIDE: u32 = 64;
    let texel = |x: u32, y: u32| {
        let frame =
            |t: u32| !(6..SIDE - 6).contains(&t) || (SIDE / 2 - 3..SIDE / 2 + 3).contains(&t);
        let value = if frame(x) || frame(y) { 20 } else { 235 };
        [value, value, (value as f32 * 0.85) as u8, 255]
    };
    let data = (0..SIDE * SIDE)
        .flat_map(|i| texel(i % SIDE, i / SIDE))
        .collect();
    Image::new(
        Extent3d {
            width: SIDE,
            height: SIDE,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    )
}

/// Spawns the lamps of `lamps` for `shading` (the meshes are the field's).
pub fn spawn_lamps(world: &mut World, lamps: Lamps, shading: Shading) {
    let cookie = lamps.cookies.then(|| PhongLightCookie {
        image: world.resource_mut::<Assets<Image>>().add(window_image()),
        ..default()
    });
    let color = Color::srgb(1.0, 0.85, 0.6);
    let (outer_angle, inner_angle, range) = (40f32.to_radians(), 30f32.to_radians(), 6.0);
    for lamp in lamp_places(lamps) {
        let transform =
            Transform::from_translation(lamp.position).looking_at(lamp.position - Vec3::Y, Vec3::Z);
        match shading {
            Shading::Phong(_) | Shading::PhongPerVertex { .. } => {
                let mut entity = world.spawn((
                    PhongSpotLight {
                        color,
                        decay: Decay::quadratic(0.2),
                        range: Some(range),
                        outer_angle,
                        inner_angle,
                        shadows: PhongShadows {
                            enabled: lamp.shadows,
                            resolution: SHADOW_MAP_SIZE,
                            ..default()
                        },
                        ..default()
                    },
                    transform,
                ));
                if let Some(cookie) = &cookie {
                    entity.insert(cookie.clone());
                }
            }
            Shading::Standard => {
                world.spawn((
                    SpotLight {
                        color,
                        range,
                        outer_angle,
                        inner_angle,
                        shadow_maps_enabled: lamp.shadows,
                        ..default()
                    },
                    transform,
                ));
            }
            Shading::Constant => {}
        }
    }
}

/// The lamps' scenes, each by its cookies and shadows: the table's rows.
pub const KINDS: [(bool, LampShadows); 5] = [
    (false, LampShadows::Off),
    (true, LampShadows::Off),
    (false, LampShadows::HalfNear),
    (true, LampShadows::HalfNear),
    (false, LampShadows::NearAndFar),
];

/// The row `--quick` measures: cookies and shadows both.
pub const QUICK_KINDS: [(bool, LampShadows); 1] = [(true, LampShadows::HalfNear)];

/// The columns of each kind's row: Phong without far lamps, Phong with them, Standard with
/// them.
const COLUMNS: usize = 3;

/// How many measurements [`table`] makes: Phong without far lamps, with them, and Standard
/// with them, for each kind in each round.
pub fn measurements(kinds: &[(bool, LampShadows)], rounds: usize) -> usize {
    kinds.len() * COLUMNS * rounds
}

/// The lamps' table: each scene of `kinds` with [`FAR_LAMPS`] far lamps beside the same
/// without them, Phong, and `StandardMaterial` beside it; the rows take turns over `rounds`
/// rounds.
pub fn table(
    size: u32,
    rounds: usize,
    frames: Frames,
    culling: PhongLightCulling,
    kinds: &[(bool, LampShadows)],
    directory: &Path,
) {
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    // Per kind: Phong without far lamps, Phong with them, Standard with them.
    let columns: [_; COLUMNS] = [
        (phong, 0),
        (phong, FAR_LAMPS),
        (Shading::Standard, FAR_LAMPS),
    ];
    let mut csv = String::from("scene,size,shading,round,median_ms\n");
    let times = alternating_medians_of(kinds.len() * COLUMNS, rounds, |row, round| {
        let ((cookies, shadows), (shading, far)) = (kinds[row / COLUMNS], columns[row % COLUMNS]);
        let lamps = Lamps {
            far,
            cookies,
            shadows,
        };
        let median = ms(median_frame_time(
            Scene::Lamps(lamps),
            size,
            shading,
            culling,
            frames,
        ));
        let shading_name = if shading == phong {
            "Phong"
        } else {
            "Standard"
        };
        let _ = writeln!(
            csv,
            "{},{size},{shading_name},{round},{median:.3}",
            lamps.name()
        );
        crate::measured!(
            "{} {size}² {shading_name}, round {round}: {median:.1} ms",
            lamps.name()
        );
        median
    });
    let mut table = format!(
        "| lamps | Phong, no far lamps ms | Phong, + {FAR_LAMPS} far ms | far / no far | Standard, + {FAR_LAMPS} far ms (no cookies) |\n|---|---|---|---|---|\n"
    );
    for ((cookies, shadows), row) in kinds.iter().zip(times.chunks(COLUMNS)) {
        let name = Lamps {
            far: 0,
            cookies: *cookies,
            shadows: *shadows,
        }
        .name();
        let name = name.trim_start_matches("lamps: ").replace(" + 0 far", "");
        let _ = writeln!(
            table,
            "| {name} | {:.1} | {:.1} | {:.2} | {:.1} |",
            row[0],
            row[1],
            row[1] / row[0],
            row[2]
        );
    }
    println!("\nStreet lamps at {size}², median ms (the median of {rounds} rounds):\n\n{table}");
    write(&directory.join("lamps.csv"), &csv);
}
