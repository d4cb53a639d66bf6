//! three.js's `SphereGeometry`, `PlaneGeometry` and `BoxGeometry` built vertex for vertex as
//! three.js builds them (positions, normals, UVs and triangles in its order, computed in
//! `f64` and rounded once, as its `Float32Array`s hold them), so that a converted mesh is
//! rasterized and interpolated as three.js's is; an object's placement; the perspective
//! camera.

use bevy::{
    asset::RenderAssetUsages,
    camera::PerspectiveProjection,
    math::{EulerRot, Quat, Vec3},
    mesh::{Indices, Mesh, PrimitiveTopology},
    transform::components::Transform,
};
#[cfg(feature = "scene")]
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A three.js geometry, as its JSON's `type` names it, with its constructor's parameters
/// (those not listed keep three.js's defaults: full spheres, one segment per side).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "scene", derive(Serialize, Deserialize))]
#[cfg_attr(feature = "scene", serde(tag = "type"))]
pub enum ThreeGeometry {
    /// `SphereGeometry(radius, widthSegments, heightSegments)`.
    #[cfg_attr(feature = "scene", serde(rename_all = "camelCase"))]
    SphereGeometry {
        /// Radius.
        radius: f32,
        /// Segments around the y axis (at least 3).
        width_segments: u32,
        /// Segments from pole to pole (at least 2).
        height_segments: u32,
    },
    /// `PlaneGeometry(width, height)`: in the xy plane, facing +z.
    PlaneGeometry {
        /// Along x.
        width: f32,
        /// Along y.
        height: f32,
    },
    /// `BoxGeometry(width, height, depth)`.
    BoxGeometry {
        /// Along x.
        width: f32,
        /// Along y.
        height: f32,
        /// Along z.
        depth: f32,
    },
}

/// Vertices and triangles as three.js's `BufferGeometry` holds them.
#[derive(Default)]
struct Buffers {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

impl Buffers {
    fn vertex(&mut self, position: [f64; 3], normal: [f64; 3], uv: [f64; 2]) {
        self.positions.push(position.map(|c| c as f32));
        self.normals.push(normal.map(|c| c as f32));
        self.uvs.push(uv.map(|c| c as f32));
    }

    fn mesh(self) -> Mesh {
        Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, self.positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, self.normals)
        .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, self.uvs)
        .with_inserted_indices(Indices::U32(self.indices))
    }
}

impl ThreeGeometry {
    /// The mesh three.js builds (segment counts below three.js's minimum are raised to it).
    pub fn to_mesh(&self) -> Mesh {
        match *self {
            ThreeGeometry::SphereGeometry {
                radius,
                width_segments,
                height_segments,
            } => sphere(radius.into(), width_segments.max(3), height_segments.max(2)),
            ThreeGeometry::PlaneGeometry { width, height } => {
                let mut buffers = Buffers::default();
                plane_side(
                    &mut buffers,
                    Side::PLANE,
                    [width.into(), height.into(), 0.0],
                    1.0,
                );
                buffers.mesh()
            }
            ThreeGeometry::BoxGeometry {
                width,
                height,
                depth,
            } => {
                let (w, h, d): (f64, f64, f64) = (width.into(), height.into(), depth.into());
                let mut buffers = Buffers::default();
                // three.js's `buildPlane` calls, in its order: +x, −x, +y, −y, +z, −z.
                for (side, size) in [
                    (Side::new([2, 1, 0], -1.0, -1.0), [d, h, w]),
                    (Side::new([2, 1, 0], 1.0, -1.0), [d, h, -w]),
                    (Side::new([0, 2, 1], 1.0, 1.0), [w, d, h]),
                    (Side::new([0, 2, 1], 1.0, -1.0), [w, d, -h]),
                    (Side::new([0, 1, 2], 1.0, -1.0), [w, h, d]),
                    (Side::new([0, 1, 2], -1.0, -1.0), [w, h, -d]),
                ] {
                    let facing = if size[2] > 0.0 { 1.0 } else { -1.0 };
                    plane_side(&mut buffers, side, size, facing);
                }
                buffers.mesh()
            }
        }
    }
}

/// three.js's `SphereGeometry` over the full sphere.
fn sphere(radius: f64, width_segments: u32, height_segments: u32) -> Mesh {
    let mut buffers = Buffers::default();
    let (columns, rows) = (width_segments as usize + 1, height_segments as usize + 1);
    for iy in 0..rows {
        let v = iy as f64 / f64::from(height_segments);
        // (r187: the ring's radius from y, `sqrt(r² − y²)`.)
        // The poles' UVs are moved half a segment, as three.js moves them.
        let u_offset = if iy == 0 {
            0.5 / f64::from(width_segments)
        } else if iy == rows - 1 {
            -0.5 / f64::from(width_segments)
        } else {
            0.0
        };
        for ix in 0..columns {
            let u = ix as f64 / f64::from(width_segments);
            let phi = u * (2.0 * PI);
            let y = radius * (v * PI).cos();
            let ring_radius = (radius * radius - y * y).sqrt();
            let position = [-ring_radius * phi.cos(), y, ring_radius * phi.sin()];
            let length = position.iter().map(|c| c * c).sum::<f64>().sqrt();
            // three.js's `normalize`: times `1 / length`, and as it is without a length.
            let normal = if length > 0.0 {
                position.map(|c| c * (1.0 / length))
            } else {
                position
            };
            buffers.vertex(position, normal, [u + u_offset, 1.0 - v]);
        }
    }
    let at = |iy: usize, ix: usize| (iy * columns + ix) as u32;
    for iy in 0..rows - 1 {
        for ix in 0..columns - 1 {
            let (a, b, c, d) = (
                at(iy, ix + 1),
                at(iy, ix),
                at(iy + 1, ix),
                at(iy + 1, ix + 1),
            );
            if iy != 0 {
                buffers.indices.extend([a, b, d]);
            }
            if iy != rows - 2 {
                buffers.indices.extend([b, c, d]);
            }
        }
    }
    buffers.mesh()
}

/// The axes and directions of one of three.js's `buildPlane` calls: the components `u`, `v`
/// and `w` of a vertex take `x · udir`, `y · vdir` and `depth / 2`.
#[derive(Clone, Copy)]
struct Side {
    axes: [usize; 3],
    u_direction: f64,
    v_direction: f64,
}

impl Side {
    /// `PlaneGeometry`'s: `(x, −y, 0)`.
    const PLANE: Self = Self::new([0, 1, 2], 1.0, -1.0);

    const fn new(axes: [usize; 3], u_direction: f64, v_direction: f64) -> Self {
        Self {
            axes,
            u_direction,
            v_direction,
        }
    }
}

/// One segment by one of three.js's `buildPlane` (`PlaneGeometry`'s vertices too), `size`
/// its width, height and depth, its normal `facing` (±1) along the third axis.
fn plane_side(buffers: &mut Buffers, side: Side, [width, height, depth]: [f64; 3], facing: f64) {
    let start = buffers.positions.len() as u32;
    let [u, v, w] = side.axes;
    for iy in 0..2 {
        let y = f64::from(iy) * height - height / 2.0;
        for ix in 0..2 {
            let x = f64::from(ix) * width - width / 2.0;
            let mut position = [0.0; 3];
            position[u] = x * side.u_direction;
            position[v] = y * side.v_direction;
            position[w] = depth / 2.0;
            let mut normal = [0.0; 3];
            normal[w] = facing;
            buffers.vertex(position, normal, [f64::from(ix), 1.0 - f64::from(iy)]);
        }
    }
    let (a, b, c, d) = (start, start + 2, start + 3, start + 1);
    buffers.indices.extend([a, b, d, b, c, d]);
}

/// The transform of a three.js object at `position` turned by `rotation`, Euler angles in
/// radians in three.js's default order `XYZ` (`R = Rx · Ry · Rz`).
pub fn object_transform(position: Vec3, rotation: Vec3) -> Transform {
    Transform::from_translation(position).with_rotation(Quat::from_euler(
        EulerRot::XYZ,
        rotation.x,
        rotation.y,
        rotation.z,
    ))
}

/// three.js's `PerspectiveCamera(fov, aspect, near, far)`, `fov` the vertical field of view
/// in degrees. Bevy's projection reaches to infinity with a reversed depth: `far` only culls
/// whole objects beyond it, where three.js clips at it.
pub fn perspective_projection(fov: f32, aspect: f32, near: f32, far: f32) -> PerspectiveProjection {
    PerspectiveProjection {
        fov: fov.to_radians(),
        aspect_ratio: aspect,
        near,
        far,
        ..PerspectiveProjection::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::mesh::VertexAttributeValues;

    fn positions(mesh: &Mesh) -> Vec<[f32; 3]> {
        match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
            Some(VertexAttributeValues::Float32x3(values)) => values.clone(),
            _ => panic!("positions"),
        }
    }

    /// three.js's `new SphereGeometry(1, 4, 2)`: 15 vertices, 8 triangles, the first
    /// vertex at the north pole, the sixth on the equator at `(−1, 0, 0)`.
    #[test]
    fn a_sphere_is_built_as_three_js_builds_it() {
        let mesh = ThreeGeometry::SphereGeometry {
            radius: 1.0,
            width_segments: 4,
            height_segments: 2,
        }
        .to_mesh();
        let positions = positions(&mesh);
        assert_eq!(positions.len(), 15);
        assert_eq!(mesh.indices().unwrap().len(), 3 * 8);
        assert_eq!(positions[0][1], 1.0);
        assert!((positions[5][0] + 1.0).abs() < 1e-7 && positions[5][1].abs() < 1e-7);
    }

    /// three.js's `new BoxGeometry(1, 2, 3)`: 24 vertices, 12 triangles, each side's normal
    /// facing out of it (its vertices' component along it is half the size that way).
    #[test]
    fn a_box_faces_out_on_every_side() {
        let mesh = ThreeGeometry::BoxGeometry {
            width: 1.0,
            height: 2.0,
            depth: 3.0,
        }
        .to_mesh();
        let positions = positions(&mesh);
        let Some(VertexAttributeValues::Float32x3(normals)) =
            mesh.attribute(Mesh::ATTRIBUTE_NORMAL)
        else {
            panic!("normals");
        };
        assert_eq!(positions.len(), 24);
        for (position, normal) in positions.iter().zip(normals) {
            let along = Vec3::from(*position).dot(Vec3::from(*normal));
            let half = Vec3::new(0.5, 1.0, 1.5).dot(Vec3::from(*normal).abs());
            assert!((along - half).abs() < 1e-6, "{position:?} {normal:?}");
        }
        // Counter-clockwise seen from outside: the triangle's normal is the side's.
        let indices: Vec<usize> = mesh.indices().unwrap().iter().collect();
        for triangle in indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|i| Vec3::from(positions[triangle[i]]));
            let facing = (b - a).cross(c - a).normalize();
            assert!(facing.dot(Vec3::from(normals[triangle[0]])) > 0.99);
        }
    }
}
