//! Scenes from three.js: its `MeshPhongMaterial`, `MeshToonMaterial`, lights, geometries and
//! perspective camera turned into the crate's, so that a converted scene draws as three.js
//! (r187) draws it. docs/from-three.md lists every conversion and what does not carry over.
//!
//! The numbers are three.js's own, named as its constructors and its JSON (`toJSON`) name
//! them: colors as `0xRRGGBB` integers in sRGB (what `Color.getHex()` returns), angles in
//! radians, the camera's field of view in degrees. With the `scene` feature each type
//! deserializes from JSON of that shape (a `type` key, camelCase fields; for materials and
//! lights three.js's defaults for what is missing), with a toon material's `gradientMap` as
//! its texels rather than a texture's id. Only the fields each type lists are read: texture
//! maps, `side`, `opacity`, `vertexColors`, partial spheres and segment counts of planes and
//! boxes are not (docs/from-three.md).
//!
//! Where three.js's convention differs from the crate's, the conversion carries it:
//! three.js divides the diffuse light by π (`BRDF_Lambert`), which the converted diffuse
//! color folds in; its Phong highlight is [`SpecularModel::NormalizedBlinnPhong`]; its point
//! and spot lights fall off as `1 / max(d^decay, 0.01)`, which a [`Decay`] with the color
//! scaled by 100 reproduces exactly for `decay` 0, 1 and 2; its spot edge is
//! [`ConeEdge::Smooth`]; and its toon material without a `gradientMap` is a ramp of two
//! tones. A light's fall-off that cannot be converted is an error naming the field
//! ([`ThreeError`]).
//!
//! [`SpecularModel::NormalizedBlinnPhong`]: crate::SpecularModel::NormalizedBlinnPhong
//! [`Decay`]: crate::Decay
//! [`ConeEdge::Smooth`]: crate::ConeEdge::Smooth

mod geometry;
mod lights;
mod materials;

pub use geometry::{ThreeGeometry, object_transform, perspective_projection};
pub use lights::{ThreeLight, ThreeLightOf, aimed_transform};
pub use materials::{ThreeMaterial, ThreePhongMaterial, ThreeToonMaterial};

use bevy::color::LinearRgba;

/// What a three.js scene asks for that the crate cannot draw as three.js does.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ThreeError {
    /// A field whose value has no exact counterpart.
    #[error("three.js {object}: `{field}` = {value} cannot be converted: {reason}")]
    Unsupported {
        /// The three.js class, `PointLight` say.
        object: &'static str,
        /// Its field, as three.js names it.
        field: &'static str,
        /// The value given.
        value: f32,
        /// Why, and what converts.
        reason: &'static str,
    },
}

/// A three.js color `0xRRGGBB` (sRGB, as `Color.getHex()` gives it) in linear RGB, decoded
/// as three.js's `SRGBToLinear` decodes it, in `f64` and rounded once.
pub fn linear_color(hex: u32) -> LinearRgba {
    let channel = |shift: u32| {
        let c = f64::from((hex >> shift) & 0xff) / 255.0;
        let linear = if c < 0.04045 {
            c * 0.0773993808
        } else {
            (c * 0.9478672986 + 0.0521327014).powf(2.4)
        };
        linear as f32
    };
    LinearRgba::rgb(channel(16), channel(8), channel(0))
}

/// `color · factor`, in `f64` and rounded once.
fn scaled(color: LinearRgba, factor: f64) -> LinearRgba {
    let scale = |c: f32| (f64::from(c) * factor) as f32;
    LinearRgba::rgb(scale(color.red), scale(color.green), scale(color.blue))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// three.js's decoding, worked by hand: 0x11 = 17/255 = 0.0666…, past 0.04045, gives
    /// ((0.0666… + 0.055) / 1.055)^2.4 = 0.005605…; 0x08 = 0.0313… gives 0.0313… / 12.92.
    #[test]
    fn colors_decode_as_three_js_decodes_them() {
        let color = linear_color(0x11_08_ff);
        assert!((color.red - 0.005_605_39).abs() < 1e-8, "{color:?}");
        assert!(
            (color.green - 8.0 / 255.0 / 12.92).abs() < 1e-8,
            "{color:?}"
        );
        assert_eq!(color.blue, 1.0);
    }
}
