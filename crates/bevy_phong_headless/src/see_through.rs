//! What a pixel shows where a mesh lets what is behind it through: an alpha mask that
//! discards, or a blended material (`AlphaMode::Blend`, its color weighed by its alpha over
//! what is behind). The captured inputs hold the nearest surface whatever its alpha, so what
//! is behind is captured again with the see-through meshes hidden ([`Behind`]), and each
//! pixel is followed through the layers it shows ([`expected_through`]).
//!
//! One masked and one blended layer are followed, in either order; a pixel with two meshes
//! of the same kind in front of each other, or on an edge of what shows through (where the
//! device's rasterization and the capture may take different neighbours), is unjudged.

use bevy::{
    asset::{AssetId, Assets},
    image::Image,
    math::DVec3,
    pbr::Material,
    prelude::AlphaMode,
};
use bevy_phong::{PhongMaterial, PhongSceneMaterial};
use std::collections::HashMap;

use crate::{Expected, SurfaceInputs, pixel_model};

/// The inputs captured with see-through meshes hidden.
pub struct Behind<M: Material = PhongMaterial> {
    /// With the blended meshes hidden.
    pub without_blended: SurfaceInputs<M>,
    /// With the alpha-masked meshes hidden.
    pub without_masked: SurfaceInputs<M>,
    /// With both hidden.
    pub without_either: SurfaceInputs<M>,
}

/// Which capture a pixel is read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Layer {
    Front,
    WithoutBlended,
    WithoutMasked,
    WithoutEither,
}

impl Layer {
    /// The layer that shows where a mask discards on this one.
    fn past_mask(self) -> Option<Layer> {
        match self {
            Layer::Front => Some(Layer::WithoutMasked),
            Layer::WithoutBlended => Some(Layer::WithoutEither),
            Layer::WithoutMasked | Layer::WithoutEither => None,
        }
    }

    /// The layer that shows through a blended surface on this one.
    fn past_blend(self) -> Option<Layer> {
        match self {
            Layer::Front => Some(Layer::WithoutBlended),
            Layer::WithoutMasked => Some(Layer::WithoutEither),
            Layer::WithoutBlended | Layer::WithoutEither => None,
        }
    }
}

/// Whether `material` may let what is behind it through.
pub fn lets_through(material: &PhongMaterial) -> Option<SeeThrough> {
    match material.alpha_mode {
        AlphaMode::Mask(_) => Some(SeeThrough::Masked),
        AlphaMode::Blend => Some(SeeThrough::Blended),
        _ => None,
    }
}

/// How a mesh lets what is behind it through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeeThrough {
    /// Where its alpha mask discards.
    Masked,
    /// Weighed by one minus its alpha.
    Blended,
}

/// What pixel `pixel` should show, followed from `front` through the layers of `behind`:
/// `expected_on(inputs, pixel)` gives a surface's own color on one capture.
pub fn expected_through<M: PhongSceneMaterial>(
    pixel: usize,
    front: &SurfaceInputs<M>,
    behind: &Behind<M>,
    materials: &Assets<M>,
    images: &HashMap<AssetId<Image>, Image>,
    expected_on: &dyn Fn(&SurfaceInputs<M>, usize) -> Expected,
) -> Expected {
    let inputs_of = |layer| match layer {
        Layer::Front => front,
        Layer::WithoutBlended => &behind.without_blended,
        Layer::WithoutMasked => &behind.without_masked,
        Layer::WithoutEither => &behind.without_either,
    };
    let (mut low, mut high) = (DVec3::ZERO, DVec3::ZERO);
    let mut weight = 1.0;
    let mut layer = Layer::Front;
    loop {
        let inputs = inputs_of(layer);
        let tag = inputs.positions.pixels[pixel][3] as u32;
        let Some(handle) = inputs.materials.get(&tag) else {
            // Nothing behind: the clear color, black and transparent.
            return Expected::Between(low, high);
        };
        if layer != Layer::Front && !same_object_around(inputs, pixel) {
            return Expected::Unjudged;
        }
        let Some(material) = materials.get(handle).and_then(M::phong_material) else {
            return Expected::Unjudged;
        };
        let Some(share) = pixel_model::see_through(material, pixel, inputs, images) else {
            return Expected::Unjudged;
        };
        let next = match lets_through(material) {
            Some(SeeThrough::Masked) if share == 1.0 => layer.past_mask(),
            Some(SeeThrough::Blended) => layer.past_blend(),
            _ => {
                // Opaque here: what this surface shows ends the walk.
                return match expected_on(inputs, pixel) {
                    Expected::Between(own_low, own_high) => {
                        Expected::Between(low + weight * own_low, high + weight * own_high)
                    }
                    _ => Expected::Unjudged,
                };
            }
        };
        if share < 1.0 {
            let Expected::Between(own_low, own_high) = expected_on(inputs, pixel) else {
                return Expected::Unjudged;
            };
            low += weight * (1.0 - share) * own_low;
            high += weight * (1.0 - share) * own_high;
            weight *= share;
        }
        let Some(next) = next else {
            return Expected::Unjudged;
        };
        layer = next;
    }
}

/// Whether pixel `index` of `inputs` and its eight neighbours show the same object (or all
/// nothing).
fn same_object_around<M: Material>(inputs: &SurfaceInputs<M>, index: usize) -> bool {
    let (width, height) = (
        i64::from(inputs.positions.width),
        i64::from(inputs.positions.height),
    );
    let (x, y) = (index as i64 % width, index as i64 / width);
    let object = |x: i64, y: i64| inputs.positions.pixels[(y * width + x) as usize][3];
    let here = object(x, y);
    (-1..=1).all(|dy| {
        (-1..=1).all(|dx| {
            let (nx, ny) = (x + dx, y + dy);
            !(0..width).contains(&nx) || !(0..height).contains(&ny) || object(nx, ny) == here
        })
    })
}
