//! Light cookies in the reference model (SPEC.md, "Light cookies"): the tint a light's
//! image gives it at a point, from the atlas layer the crate made of the image.

use crate::lights::cookie_layer_texels;
use crate::lights::{PhongCookieProjection, PhongLightCookie};
use crate::limits::{CONE_ANGLE, WIDEST_COOKIE_CONE};
use bevy::{
    camera::primitives::CubemapLayout, image::Image, transform::components::GlobalTransform,
};
use glam::{DAffine3, DVec2, DVec3};

/// How a cookie's image is laid over its light.
#[derive(Clone, Copy, Debug)]
pub enum CookieProjection {
    /// Across a cone: `tan` of its half-angle (below 89.5°).
    Cone {
        /// `tan(half_angle)`.
        tan_half_angle: f64,
    },
    /// Around the light, as a cube map packed by the layout.
    Cube(CubemapLayout),
    /// On the light's local XY plane, once or repeated.
    Plane {
        /// Whether the image repeats.
        tiled: bool,
        /// Whether the light is dark outside an untiled image.
        dark_outside: bool,
    },
}

/// A light's cookie.
#[derive(Clone, Debug)]
pub struct Cookie {
    /// The atlas layer's texels, 8-bit sRGB RGBA, row by row, `side` square.
    pub texels: Vec<[u8; 4]>,
    /// The layer's side in texels.
    pub side: u32,
    /// How the image is laid over the light.
    pub projection: CookieProjection,
    /// The inverse of the light's transform.
    pub light_from_world: DAffine3,
    /// Whether the red channel tints all three.
    pub red_only: bool,
}

impl Cookie {
    /// The cookie `cookie`, whose image is `image`, on a light at `transform` that lays it
    /// over its rays by `projection` (its kind's `PhongLightKind::cookie_projection`).
    pub fn new(
        cookie: &PhongLightCookie,
        image: &Image,
        transform: &GlobalTransform,
        projection: PhongCookieProjection,
    ) -> Option<Self> {
        let texels = cookie_layer_texels(image)?;
        let side = (texels.len() as f64).sqrt() as u32;
        let affine = transform.affine();
        let light_to_world = DAffine3::from_cols(
            affine.matrix3.x_axis.as_dvec3(),
            affine.matrix3.y_axis.as_dvec3(),
            affine.matrix3.z_axis.as_dvec3(),
            affine.translation.as_dvec3(),
        );
        let projection = match projection {
            PhongCookieProjection::Cone { half_angle } => CookieProjection::Cone {
                tan_half_angle: f64::from(CONE_ANGLE.apply(half_angle).min(WIDEST_COOKIE_CONE))
                    .tan(),
            },
            PhongCookieProjection::Cube => CookieProjection::Cube(cookie.cubemap_layout),
            PhongCookieProjection::Plane => CookieProjection::Plane {
                tiled: cookie.tiled,
                dark_outside: cookie.dark_outside,
            },
        };
        Some(Self {
            texels,
            side,
            projection,
            light_from_world: light_to_world.inverse(),
            red_only: cookie.red_only,
        })
    }

    /// The tint at world position `position`: the image's linear color there (bilinear
    /// between texel centers, the coordinates clamped, or wrapped for a tiled image),
    /// clamped to `[0, 1]`, or its red channel thrice with `red_only`; 1 where the image
    /// does not reach (behind a cone's apex, off an untiled plane's tile), 0 off the tile
    /// of one that is dark outside it.
    pub fn tint(&self, position: DVec3) -> DVec3 {
        let local = self.light_from_world.transform_point3(position);
        let (uv, tiled) = match self.projection {
            CookieProjection::Cone { tan_half_angle } => {
                if local.z >= 0.0 {
                    return DVec3::ONE;
                }
                let plane = local.truncate() / (local.z * tan_half_angle);
                (plane * DVec2::new(-0.5, 0.5) + 0.5, false)
            }
            CookieProjection::Plane {
                tiled,
                dark_outside,
            } => {
                let uv = local.truncate() * DVec2::new(-0.5, 0.5) + 0.5;
                if !tiled && uv != uv.clamp(DVec2::ZERO, DVec2::ONE) {
                    return if dark_outside {
                        DVec3::ZERO
                    } else {
                        DVec3::ONE
                    };
                }
                (uv, tiled)
            }
            CookieProjection::Cube(layout) => (cube_face_uv(local, layout), false),
        };
        let tint = self.sample(uv, tiled).clamp(DVec3::ZERO, DVec3::ONE);
        if self.red_only {
            DVec3::splat(tint.x)
        } else {
            tint
        }
    }

    fn texel(&self, x: i64, y: i64, tiled: bool) -> DVec3 {
        let side = i64::from(self.side);
        let fit = |c: i64| {
            if tiled {
                c.rem_euclid(side)
            } else {
                c.clamp(0, side - 1)
            }
        };
        let [r, g, b, _] = self.texels[(fit(y) * side + fit(x)) as usize];
        DVec3::new(decode(r), decode(g), decode(b))
    }

    fn sample(&self, uv: DVec2, tiled: bool) -> DVec3 {
        let at = uv * f64::from(self.side) - 0.5;
        let corner = at.floor();
        let weight = at - corner;
        let (x, y) = (corner.x as i64, corner.y as i64);
        let top = self
            .texel(x, y, tiled)
            .lerp(self.texel(x + 1, y, tiled), weight.x);
        let bottom = self
            .texel(x, y + 1, tiled)
            .lerp(self.texel(x + 1, y + 1, tiled), weight.x);
        top.lerp(bottom, weight.y)
    }
}

/// An 8-bit sRGB value as linear.
fn decode(value: u8) -> f64 {
    let c = f64::from(value) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Where `direction` falls in a cube map packed by `layout` (Bevy's `cubemap_uv`): the face
/// of its largest component (x, then y, then z on ties), the face's coordinates, placed in
/// the layout's grid.
pub fn cube_face_uv(direction: DVec3, layout: CubemapLayout) -> DVec2 {
    let a = direction.abs();
    let largest = a.max_element();
    // Faces in Bevy's order: +x, -x, +y, -y, -z, +z.
    let (face, face_uv, divisor) = if largest == a.x {
        if direction.x < 0.0 {
            (1, DVec2::new(-direction.z, -direction.y), a.x)
        } else {
            (0, DVec2::new(direction.z, -direction.y), a.x)
        }
    } else if largest == a.y {
        if direction.y < 0.0 {
            (3, DVec2::new(direction.x, direction.z), a.y)
        } else {
            (2, DVec2::new(direction.x, -direction.z), a.y)
        }
    } else if direction.z < 0.0 {
        (4, DVec2::new(direction.x, -direction.y), a.z)
    } else {
        (5, DVec2::new(direction.x, direction.y), a.z)
    };
    if divisor <= 0.0 {
        return DVec2::splat(0.5);
    }
    let face_uv = face_uv / divisor * 0.5 + 0.5;
    let nibble = |table: u32| f64::from((table >> (4 * face)) & 0xf);
    let (corner, size) = match layout {
        CubemapLayout::CrossVertical => (
            DVec2::new(nibble(0x111102), nibble(0x132011)),
            DVec2::new(1.0 / 3.0, 1.0 / 4.0),
        ),
        CubemapLayout::CrossHorizontal => (
            DVec2::new(nibble(0x131102), nibble(0x112011)),
            DVec2::new(1.0 / 4.0, 1.0 / 3.0),
        ),
        CubemapLayout::SequenceVertical => {
            (DVec2::new(0.0, f64::from(face)), DVec2::new(1.0, 1.0 / 6.0))
        }
        CubemapLayout::SequenceHorizontal => {
            (DVec2::new(f64::from(face), 0.0), DVec2::new(1.0 / 6.0, 1.0))
        }
    };
    (corner + face_uv) * size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_face_of_a_vertical_cross_lands_in_its_cell() {
        // As Bevy's `cubemap_uv` places them (its code, which a mirrored light texture
        // must match): +y top middle, -x +z +x across the second row, -y third, -z fourth.
        let cells = [
            (DVec3::X, (2.0, 1.0)),
            (-DVec3::X, (0.0, 1.0)),
            (DVec3::Y, (1.0, 0.0)),
            (-DVec3::Y, (1.0, 2.0)),
            (DVec3::Z, (1.0, 1.0)),
            (-DVec3::Z, (1.0, 3.0)),
        ];
        for (direction, (column, row)) in cells {
            let uv = cube_face_uv(direction, CubemapLayout::CrossVertical);
            let expected = DVec2::new((column + 0.5) / 3.0, (row + 0.5) / 4.0);
            assert!(
                (uv - expected).length() < 1e-12,
                "{direction}: {uv} vs {expected}"
            );
        }
    }

    #[test]
    fn each_face_of_the_other_layouts_lands_in_its_cell() {
        // Bevy's `cubemap_uv` again: the horizontal cross has +y on top, -x +z +x -z across
        // the middle row and -y below; the sequences run +x -x +y -y -z +z (its face order).
        let faces = [
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            -DVec3::Z,
            DVec3::Z,
        ];
        let horizontal_cross = [
            (2.0, 1.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (1.0, 2.0),
            (3.0, 1.0),
            (1.0, 1.0),
        ];
        for (index, direction) in faces.into_iter().enumerate() {
            let (column, row) = horizontal_cross[index];
            let cells = [
                (
                    CubemapLayout::CrossHorizontal,
                    DVec2::new((column + 0.5) / 4.0, (row + 0.5) / 3.0),
                ),
                (
                    CubemapLayout::SequenceVertical,
                    DVec2::new(0.5, (index as f64 + 0.5) / 6.0),
                ),
                (
                    CubemapLayout::SequenceHorizontal,
                    DVec2::new((index as f64 + 0.5) / 6.0, 0.5),
                ),
            ];
            for (layout, expected) in cells {
                let uv = cube_face_uv(direction, layout);
                assert!(
                    (uv - expected).length() < 1e-12,
                    "{layout:?}, {direction}: {uv} vs {expected}"
                );
            }
        }
    }
}
