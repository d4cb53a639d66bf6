//! The meshes of the asset, in glTF's frame (+Y up, metres), their floats quantized.

use crate::builder::quantize;
use core::f64::consts::{PI, TAU};

/// A triangle list with what the asset's meshes carry.
#[derive(Default)]
pub struct Shape {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uvs: Vec<[f32; 2]>,
    pub tangents: Vec<[f32; 4]>,
    pub joints: Vec<[u8; 4]>,
    pub weights: Vec<[f32; 4]>,
    /// Position displacements of the one morph target (empty: none).
    pub morph_positions: Vec<[f32; 3]>,
    /// Counter-clockwise seen from the side the normals point to.
    pub indices: Vec<u16>,
}

fn vec3(v: [f64; 3]) -> [f32; 3] {
    v.map(quantize)
}

/// Indices of a grid of `columns × rows` quads over vertices laid out row by row
/// (`columns + 1` per row), counter-clockwise seen from where `u × v` points (`u` the
/// direction of growing column, `v` of growing row).
pub(crate) fn grid_indices(columns: usize, rows: usize) -> Vec<u16> {
    let stride = columns + 1;
    let mut indices = Vec::new();
    for row in 0..rows {
        for column in 0..columns {
            let a = (row * stride + column) as u16;
            let b = a + 1;
            let c = a + stride as u16;
            let d = c + 1;
            indices.extend_from_slice(&[a, b, c, b, d, c]);
        }
    }
    indices
}

/// `Ground`: a 10 × 10 square at y = 0 facing +Y, UVs 0..1 (u along +X, v along +Z, so the
/// image's top is at −Z), tangent +X with w = 1 (the bitangent `w · N × T` = −Z points to
/// the image's top, as glTF's +Y-up normal maps expect).
pub fn ground() -> Shape {
    let corners = [[-5.0, -5.0], [5.0, -5.0], [-5.0, 5.0], [5.0, 5.0]];
    Shape {
        positions: corners.iter().map(|[x, z]| vec3([*x, 0.0, *z])).collect(),
        normals: vec![[0.0, 1.0, 0.0]; 4],
        uvs: corners
            .iter()
            .map(|[x, z]| [quantize(x / 10.0 + 0.5), quantize(z / 10.0 + 0.5)])
            .collect(),
        tangents: vec![[1.0, 0.0, 0.0, 1.0]; 4],
        // Counter-clockwise seen from above.
        indices: vec![0, 2, 1, 1, 2, 3],
        ..Shape::default()
    }
}

/// The arm's segments around and along its length.
pub const ARM_SIDES: usize = 12;
pub const ARM_RINGS: usize = 16;
/// The arm's radius and length, and where the elbow joint sits (m, from the shoulder).
pub const ARM_RADIUS: f64 = 0.25;
pub const ARM_LENGTH: f64 = 2.0;
pub const ELBOW: f64 = 1.0;
/// Half the length over which the weights blend from shoulder to elbow, around the elbow.
pub const BLEND_HALF_WIDTH: f64 = 0.25;

/// `Arm`: an open tube along +Y from `shoulder` (its bind pose position), `ARM_SIDES`
/// segments around and `ARM_RINGS` along. Joint 0 (shoulder) moves the lower part, joint 1
/// (elbow, `ELBOW` above) the upper part; in between the weights blend linearly.
pub fn arm(shoulder: [f64; 3]) -> Shape {
    let mut shape = Shape::default();
    for ring in 0..=ARM_RINGS {
        let y = ARM_LENGTH * ring as f64 / ARM_RINGS as f64;
        let upper = ((y - (ELBOW - BLEND_HALF_WIDTH)) / (2.0 * BLEND_HALF_WIDTH)).clamp(0.0, 1.0);
        let upper = quantize(upper);
        for side in 0..=ARM_SIDES {
            let angle = TAU * side as f64 / ARM_SIDES as f64;
            let (sin, cos) = angle.sin_cos();
            shape.positions.push(vec3([
                shoulder[0] + ARM_RADIUS * cos,
                shoulder[1] + y,
                shoulder[2] - ARM_RADIUS * sin,
            ]));
            shape.normals.push(vec3([cos, 0.0, -sin]));
            shape.uvs.push([
                quantize(side as f64 / ARM_SIDES as f64),
                quantize(1.0 - y / ARM_LENGTH),
            ]);
            shape.joints.push([0, 1, 0, 0]);
            shape.weights.push([1.0 - upper, upper, 0.0, 0.0]);
        }
    }
    // Around (angle grows from +X toward −Z) × up = outward.
    shape.indices = grid_indices(ARM_SIDES, ARM_RINGS);
    shape
}

/// The blob's segments around and from pole to pole: 7 × 4 = 28 vertices. Bevy (0.19, 0.20) keeps a
/// mesh's morph targets in a 3D texture 9 texels tall per vertex, and WebGL2's limits allow
/// 256: 28 vertices is the most a morphed mesh can have there.
pub const BLOB_SIDES: usize = 6;
pub const BLOB_RINGS: usize = 3;
/// How far the morph target lifts the top pole (m); points above the equator rise in
/// proportion to their height.
pub const BLOB_LIFT: f64 = 0.6;

/// `Blob`: a sphere of radius `radius`, whose one morph target stretches its upper half up
/// (positions only).
pub fn blob(radius: f64) -> Shape {
    let mut shape = Shape::default();
    for ring in 0..=BLOB_RINGS {
        // From the top pole (polar angle 0) down.
        let polar = PI * ring as f64 / BLOB_RINGS as f64;
        let (sin_polar, cos_polar) = polar.sin_cos();
        for side in 0..=BLOB_SIDES {
            let angle = TAU * side as f64 / BLOB_SIDES as f64;
            let (sin, cos) = angle.sin_cos();
            let normal = [sin_polar * cos, cos_polar, -sin_polar * sin];
            shape.positions.push(vec3(normal.map(|n| n * radius)));
            shape.normals.push(vec3(normal));
            shape.uvs.push([
                quantize(side as f64 / BLOB_SIDES as f64),
                quantize(ring as f64 / BLOB_RINGS as f64),
            ]);
            shape
                .morph_positions
                .push(vec3([0.0, BLOB_LIFT * cos_polar.max(0.0), 0.0]));
        }
    }
    // Around × down = inward: flip each triangle.
    shape.indices = grid_indices(BLOB_SIDES, BLOB_RINGS)
        .chunks(3)
        .flat_map(|t| [t[0], t[2], t[1]])
        .collect();
    shape
}

/// `Fence`: a `width × height` quad standing on y = 0 in the XY plane, facing +Z, UVs
/// 0..1 (v down), tangent +X.
pub fn fence(width: f64, height: f64) -> Shape {
    let corners = [[0.0, 1.0], [1.0, 1.0], [0.0, 0.0], [1.0, 0.0]];
    Shape {
        positions: corners
            .iter()
            .map(|[u, v]| vec3([(u - 0.5) * width, (1.0 - v) * height, 0.0]))
            .collect(),
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: corners
            .iter()
            .map(|[u, v]| [*u as f32, *v as f32])
            .collect(),
        tangents: vec![[1.0, 0.0, 0.0, 1.0]; 4],
        // Counter-clockwise seen from +Z.
        indices: vec![0, 1, 2, 1, 3, 2],
        ..Shape::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle_normal(shape: &Shape, t: &[u16]) -> [f32; 3] {
        let p = |i: u16| shape.positions[usize::from(i)];
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    }

    /// Every triangle winds counter-clockwise seen from where its vertices' normals point:
    /// its geometric normal has a positive dot product with theirs.
    fn assert_front_faces_outward(shape: &Shape, name: &str) {
        for t in shape.indices.chunks(3) {
            let geometric = triangle_normal(shape, t);
            let area: f32 = geometric.iter().map(|x| x * x).sum();
            if area < 1e-12 {
                continue; // the sphere's poles: degenerate triangles
            }
            let mean: Vec<f32> = (0..3)
                .map(|k| t.iter().map(|&i| shape.normals[usize::from(i)][k]).sum())
                .collect();
            let dot: f32 = (0..3).map(|k| geometric[k] * mean[k]).sum();
            assert!(dot > 0.0, "{name}: triangle {t:?} faces inward");
        }
    }

    #[test]
    fn every_shape_faces_outward() {
        assert_front_faces_outward(&ground(), "Ground");
        assert_front_faces_outward(&arm([0.0; 3]), "Arm");
        assert_front_faces_outward(&blob(1.0), "Blob");
        assert_front_faces_outward(&fence(2.0, 1.0), "Fence");
    }

    #[test]
    fn the_arm_weights_sum_to_one_and_blend_only_near_the_elbow() {
        let arm = arm([0.0; 3]);
        for (position, weights) in arm.positions.iter().zip(&arm.weights) {
            let sum: f32 = weights.iter().sum();
            assert!((sum - 1.0).abs() < 1e-6, "{weights:?}");
            let y = f64::from(position[1]);
            let blended = weights[0] > 0.0 && weights[1] > 0.0;
            assert_eq!(blended, (y - ELBOW).abs() < BLEND_HALF_WIDTH, "y = {y}");
        }
    }
}
