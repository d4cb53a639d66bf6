//! The normal a fragment is lit with in the reference model (SPEC.md, "Texture maps", "Bump
//! map" and "Flat shading"): the face normal, the normal map and the bump map, each in the
//! interpolated tangent frame. Every result may have any length; the lighting normalizes it.

use glam::{DVec2, DVec3, DVec4};

/// The normal a normal map gives: `n.x·T + n.y·B + n.z·N`, with `n = 2·texel − 1` (its `y`
/// negated when `flip_y`, then its `x` and `y` times `scale`), `T = tangent.xyz`,
/// `B = tangent.w · N × T`, from the interpolated, unnormalized `normal` and `tangent`
/// (MikkTSpace's frame).
pub fn mapped_normal(
    normal: DVec3,
    tangent: DVec4,
    texel: DVec3,
    flip_y: bool,
    scale: DVec2,
) -> DVec3 {
    let mut n = texel * 2.0 - 1.0;
    if flip_y {
        n.y = -n.y;
    }
    let n = (n.truncate() * scale).extend(n.z);
    n.x * tangent.truncate() + n.y * bitangent(normal, tangent) + n.z * normal
}

/// `B = tangent.w · frame_normal × tangent.xyz`.
fn bitangent(frame_normal: DVec3, tangent: DVec4) -> DVec3 {
    tangent.w * frame_normal.cross(tangent.truncate())
}

/// The normal a bump map gives: `normal − scale · (slope.x·T + slope.y·B)`, where `slope` is
/// the height's change one texel along u and along v, `normal` the normal so far (after the
/// normal map) and `T`, `B` the tangent frame of [`mapped_normal`] around `frame_normal`.
pub fn bumped_normal(
    normal: DVec3,
    frame_normal: DVec3,
    tangent: DVec4,
    slope: DVec2,
    scale: f64,
) -> DVec3 {
    normal - scale * (slope.x * tangent.truncate() + slope.y * bitangent(frame_normal, tangent))
}

/// The flat-shading normal: the unit normal `face` of the triangle's plane (either sign),
/// turned to the side of `side`, the interpolated normal as it faces the viewer.
pub fn face_normal(face: DVec3, side: DVec3) -> DVec3 {
    let unit = crate::reference::normalize_or_zero(face);
    if unit.dot(side) < 0.0 { -unit } else { unit }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flat_texel_keeps_the_normal_and_the_others_tilt_it_in_the_tangent_frame() {
        let normal = DVec3::Z * 2.0;
        let tangent = DVec4::new(1.0, 0.0, 0.0, 1.0);
        let flat = DVec3::new(0.5, 0.5, 1.0);
        assert_eq!(
            mapped_normal(normal, tangent, flat, false, DVec2::ONE),
            normal
        );
        // Green up: toward B = N × T = +Y (times |N| = 2); flipped: toward -Y.
        let up = DVec3::new(0.5, 1.0, 0.5);
        assert_eq!(
            mapped_normal(normal, tangent, up, false, DVec2::ONE),
            DVec3::Y * 2.0
        );
        assert_eq!(
            mapped_normal(normal, tangent, up, true, DVec2::ONE),
            -DVec3::Y * 2.0
        );
        // A left-handed tangent (w = -1) mirrors the bitangent.
        let mirrored = DVec4::new(1.0, 0.0, 0.0, -1.0);
        assert_eq!(
            mapped_normal(normal, mirrored, up, false, DVec2::ONE),
            -DVec3::Y * 2.0
        );
        let right = DVec3::new(1.0, 0.5, 0.5);
        assert_eq!(
            mapped_normal(normal, tangent, right, false, DVec2::ONE),
            DVec3::X
        );
        // Scaled: n.x and n.y times the scale, n.z as it is (three.js's `normalScale`): n is
        // (1, 0.5, 0), flipped (1, −0.5, 0), scaled (0.5, −1, 0); B is 2·Y (|N| = 2).
        let tilted = DVec3::new(1.0, 0.75, 0.5);
        let scaled = mapped_normal(normal, tangent, tilted, true, DVec2::new(0.5, 2.0));
        assert_eq!(scaled, DVec3::new(0.5, -2.0, 0.0));
    }

    #[test]
    fn a_rising_height_tilts_the_normal_away_from_the_rise() {
        let normal = DVec3::Z;
        let tangent = DVec4::new(1.0, 0.0, 0.0, 1.0);
        // Flat height: no tilt, whatever the scale.
        assert_eq!(
            bumped_normal(normal, normal, tangent, DVec2::ZERO, 5.0),
            normal
        );
        // Rising along u (T = +X) by 1 at scale 1: 45° toward -X.
        let rise_u = bumped_normal(normal, normal, tangent, DVec2::X, 1.0);
        assert_eq!(rise_u, DVec3::new(-1.0, 0.0, 1.0));
        // Rising along v (B = +Y): toward -Y; a negative scale dents instead.
        let rise_v = bumped_normal(normal, normal, tangent, DVec2::Y, 0.5);
        assert_eq!(rise_v, DVec3::new(0.0, -0.5, 1.0));
        let dent = bumped_normal(normal, normal, tangent, DVec2::Y, -0.5);
        assert_eq!(dent, DVec3::new(0.0, 0.5, 1.0));
        // The frame's bitangent comes from the frame normal, not the normal map's.
        let mapped = DVec3::new(0.3, 0.0, 1.0);
        let tilted = bumped_normal(mapped, normal, tangent, DVec2::Y, 1.0);
        assert_eq!(tilted, DVec3::new(0.3, -1.0, 1.0));
    }

    #[test]
    fn the_face_normal_is_a_unit_vector_on_the_side_of_the_interpolated_normal() {
        let face = DVec3::new(0.0, 0.0, -3.0);
        assert_eq!(face_normal(face, DVec3::new(0.2, 0.1, 0.9)), DVec3::Z);
        assert_eq!(face_normal(face, DVec3::new(0.2, 0.1, -0.9)), -DVec3::Z);
        assert_eq!(face_normal(DVec3::ZERO, DVec3::Z), DVec3::ZERO);
        // A side in the face's plane keeps the face's own sign, as the shader's
        // `select(face, -face, dot(face, side) < 0.0)` does.
        assert_eq!(face_normal(face, DVec3::X), -DVec3::Z);
        assert_eq!(face_normal(-face, DVec3::X), DVec3::Z);
    }
}
