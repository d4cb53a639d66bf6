//! Area lights on the time-against-error plot: 1, 16 or 256 `PhongRectLight` panels over the
//! field, facing down, their highlight integrated (`AreaHighlight::Exact`) or taken at a
//! representative point, beside the point-light variants. Each panel fades as
//! `1 / (1 + 0.2 d²)` from its nearest point on top of its own inverse square, and is cut off
//! 4 units from it, as the field's point lights are.

use crate::scene::scatter;
use bevy::prelude::*;
use bevy_phong::prelude::*;

/// The panels of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panels {
    pub count: usize,
    pub highlight: AreaHighlight,
}

impl Panels {
    /// The counts the plot measures, and the one the smoke run (`--quick`) does.
    pub const COUNTS: [usize; 3] = [1, 16, 256];
    pub const QUICK_COUNT: usize = 16;

    pub fn name(self) -> String {
        let highlight = match self.highlight {
            AreaHighlight::Exact => "integrated",
            AreaHighlight::RepresentativePoint => "representative point",
        };
        format!(
            "field, {} rect light{} ({highlight})",
            self.count,
            if self.count == 1 { "" } else { "s" }
        )
    }
}

/// Spawns the panels: 1.2 × 0.6 units, 1.6 to 2.6 units above the field (the first at its
/// middle), each of its own hue and turned about the vertical.
pub fn spawn_panels(world: &mut World, panels: Panels) {
    for i in 0..panels.count {
        let (u, v, w) = if panels.count == 1 {
            (0.5, 0.5, 0.0)
        } else {
            scatter(i)
        };
        let position = Vec3::new(u * 24.0 - 12.0, 1.6 + w, v * 24.0 - 12.0);
        world.spawn((
            PhongRectLight {
                color: Color::hsl(w * 360.0, 1.0, 0.5),
                width: 1.2,
                height: 0.6,
                decay: Decay::quadratic(0.2),
                range: Some(4.0),
                highlight: panels.highlight,
                ..default()
            },
            Transform::from_translation(position).looking_to(
                Vec3::NEG_Y,
                Quat::from_rotation_y(w * std::f32::consts::TAU) * Vec3::Z,
            ),
        ));
    }
}
