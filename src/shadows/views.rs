//! Where each shadow map looks from: the view and projection of a spot light's map, a point
//! light's six cube faces and a directional light's cascades. Depth is reversed (near 1,
//! far 0) and every projection maps a light's full reach into the map.

use super::gpu_types::GpuShadowView;
use crate::lights::PhongCascades;
use bevy::math::{Mat4, Vec3, Vec4};

/// Texels at each side of a cube face that its projection adds, so that a filter centred on
/// the face's edge still reads inside the face. It bounds the filter radius.
pub(crate) const MAX_FILTER_RADIUS_TEXELS: f32 = 16.0;

/// A shadow map's view, before it is given a layer of the shadow map array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ShadowLightView {
    /// World space to clip space.
    pub clip_from_world: Mat4,
    /// `ORTHOGRAPHIC` or `PERSPECTIVE`.
    pub projection: u32,
    /// World size of a texel: orthographic, everywhere; perspective, at distance 1.
    pub texel_size: f32,
    /// Orthographic: world units from depth 1 to depth 0.
    pub depth_range: f32,
    /// Perspective: the near distance.
    pub near: f32,
    /// Directional cascades: the camera's view depth as a plane (`dot(xyz, P) + w`).
    pub view_plane: Vec4,
    /// Directional cascades: the view depth where the cascade ends.
    pub cascade_far: f32,
    /// Directional cascades: where it starts blending into the next.
    pub cascade_blend_start: f32,
}

impl ShadowLightView {
    fn perspective(view_from_world: Mat4, fov: f32, near: f32, resolution: u32) -> Self {
        let clip_from_view =
            glam::camera::rh::proj::directx::perspective_infinite_reverse(fov, 1.0, near);
        Self {
            clip_from_world: clip_from_view * view_from_world,
            projection: GpuShadowView::PERSPECTIVE,
            texel_size: 2.0 * (fov / 2.0).tan() / resolution as f32,
            depth_range: 0.0,
            near,
            view_plane: Vec4::ZERO,
            cascade_far: 0.0,
            cascade_blend_start: 0.0,
        }
    }
}

/// A sphere that bounds a shadow caster.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bounds {
    /// World-space centre.
    pub center: Vec3,
    /// Radius, world units.
    pub radius: f32,
}

/// The directions of a point light's six cube faces, with an up vector each: +X, −X, +Y,
/// −Y, +Z, −Z, the order the shader picks them in by the major axis.
pub(crate) const CUBE_FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::NEG_Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::NEG_Z),
    (Vec3::Z, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_Y),
];

/// The field of view of a cube face: 90° widened by [`MAX_FILTER_RADIUS_TEXELS`] at each side.
fn cube_face_fov(resolution: u32) -> f32 {
    2.0 * (1.0 + 2.0 * MAX_FILTER_RADIUS_TEXELS / resolution as f32).atan()
}

/// The six views of a point light at `position` (or of a spot light too wide for one map).
pub(crate) fn cube_views(position: Vec3, near: f32, resolution: u32) -> [ShadowLightView; 6] {
    CUBE_FACES.map(|(forward, up)| {
        let view_from_world = glam::camera::rh::view::look_to_mat4(position, forward, up);
        ShadowLightView::perspective(view_from_world, cube_face_fov(resolution), near, resolution)
    })
}

/// Widest outer cone angle a spot light's single map covers; past it the light gets a cube.
pub(crate) const MAX_CONE_MAP_ANGLE: f32 = 60.0 * core::f32::consts::PI / 180.0;

/// The view of a spot light at `position` shining along `direction` with half-angle
/// `outer_angle` (at most [`MAX_CONE_MAP_ANGLE`]).
pub(crate) fn cone_view(
    position: Vec3,
    direction: Vec3,
    outer_angle: f32,
    near: f32,
    resolution: u32,
) -> ShadowLightView {
    let up = any_perpendicular(direction);
    let view_from_world = glam::camera::rh::view::look_to_mat4(position, direction, up);
    // The cone's edge plus the filter's margin.
    let half_tan = outer_angle.tan() * (1.0 + 2.0 * MAX_FILTER_RADIUS_TEXELS / resolution as f32);
    ShadowLightView::perspective(view_from_world, 2.0 * half_tan.atan(), near, resolution)
}

/// A unit vector not parallel to `direction`, as the up vector of a view along it.
fn any_perpendicular(direction: Vec3) -> Vec3 {
    if direction.y.abs() > 0.9 {
        Vec3::Z
    } else {
        Vec3::Y
    }
}

/// A camera that a directional light's cascades are fitted to (each camera gets its own).
pub(crate) struct CascadeCamera {
    /// The camera's world transform.
    pub world_from_view: Mat4,
    /// The eight view-space corners of the camera's frustum between two view depths.
    pub slice_corners: Box<dyn Fn(f32, f32) -> [Vec3; 8] + Send + Sync>,
    /// View depth where the camera's frustum starts.
    pub near: f32,
}

/// The cascades of a directional light shining along `direction`, fitted to `camera`, each
/// an orthographic map of `resolution`² whose depth range reaches back to every caster in
/// `casters` that could shade the slice.
///
/// Each cascade's map covers the bounding sphere of its slice of the camera's view, and its
/// centre moves in whole texels: a moving camera does not make shadow edges shimmer.
pub(crate) fn cascade_views(
    direction: Vec3,
    camera: &CascadeCamera,
    cascades: &PhongCascades,
    resolution: u32,
    casters: &[Bounds],
) -> Vec<ShadowLightView> {
    let up = any_perpendicular(direction);
    let light_from_world = glam::camera::rh::view::look_to_mat4(Vec3::ZERO, direction, up);
    let forward = camera
        .world_from_view
        .transform_vector3(Vec3::NEG_Z)
        .normalize();
    let eye = camera.world_from_view.transform_point3(Vec3::ZERO);
    let view_plane = forward.extend(-forward.dot(eye));
    let overlap = cascades.overlap.clamp(0.0, 0.95);

    let far_bounds = cascades.far_bounds();
    let mut start = camera.near;
    let mut views = Vec::with_capacity(far_bounds.len());
    for (index, &far) in far_bounds.iter().enumerate() {
        let previous_far = if index == 0 {
            camera.near
        } else {
            far_bounds[index - 1]
        };
        let blend_start = far - overlap * (far - previous_far);
        let corners = (camera.slice_corners)(start, far)
            .map(|corner| camera.world_from_view.transform_point3(corner));
        let view = cascade_view(&light_from_world, &corners, resolution, casters);
        views.push(ShadowLightView {
            view_plane,
            cascade_far: far,
            cascade_blend_start: blend_start,
            ..view
        });
        start = blend_start;
    }
    views
}

/// The orthographic map around the slice with world-space `corners`.
fn cascade_view(
    light_from_world: &Mat4,
    corners: &[Vec3; 8],
    resolution: u32,
    casters: &[Bounds],
) -> ShadowLightView {
    let center_world = corners.iter().copied().sum::<Vec3>() / 8.0;
    let radius = corners
        .iter()
        .map(|corner| corner.distance(center_world))
        .fold(0.0, f32::max);
    // Quantized so that the texel size, and with it the snapping grid, holds still while
    // the camera turns.
    let radius = (radius * 16.0).ceil() / 16.0;
    let texel_size = 2.0 * radius / resolution as f32;
    let mut center = light_from_world.transform_point3(center_world);
    center.x = (center.x / texel_size).round() * texel_size;
    center.y = (center.y / texel_size).round() * texel_size;

    // Depth along the light (−z in light space): the slice's sphere, reaching back to the
    // casters whose shadow can fall on it.
    let far_depth = -center.z + radius;
    let near_depth = casters
        .iter()
        .filter_map(|caster| {
            let c = light_from_world.transform_point3(caster.center);
            let reach = radius + caster.radius;
            let inside = (c.x - center.x).abs() <= reach
                && (c.y - center.y).abs() <= reach
                && -c.z - caster.radius <= far_depth;
            inside.then_some(-c.z - caster.radius)
        })
        .fold(-center.z - radius, f32::min);
    // Reversed depth: `orthographic_rh(…, far, near)` puts the near plane at 1.
    let clip_from_light = glam::camera::rh::proj::directx::orthographic(
        center.x - radius,
        center.x + radius,
        center.y - radius,
        center.y + radius,
        far_depth,
        near_depth,
    );
    ShadowLightView {
        clip_from_world: clip_from_light * *light_from_world,
        projection: GpuShadowView::ORTHOGRAPHIC,
        texel_size,
        depth_range: far_depth - near_depth,
        near: 0.0,
        view_plane: Vec4::ZERO,
        cascade_far: 0.0,
        cascade_blend_start: 0.0,
    }
}

/// The orthographic view of a parallel beam: rays along `direction` through the rectangle
/// centred on `origin` with half-extents `half_size` across the beam (x along `right`,
/// y along `direction × right`), from `origin` to `length` along it. For extension light
/// kinds such as the searchlight.
pub(crate) fn beam_view(
    origin: Vec3,
    direction: Vec3,
    right: Vec3,
    half_size: [f32; 2],
    length: f32,
    resolution: u32,
) -> ShadowLightView {
    let up = direction.cross(right).normalize();
    let light_from_world = glam::camera::rh::view::look_to_mat4(origin, direction, up);
    let clip_from_light = glam::camera::rh::proj::directx::orthographic(
        -half_size[0],
        half_size[0],
        -half_size[1],
        half_size[1],
        length,
        0.0,
    );
    ShadowLightView {
        clip_from_world: clip_from_light * light_from_world,
        projection: GpuShadowView::ORTHOGRAPHIC,
        texel_size: 2.0 * half_size[0].max(half_size[1]) / resolution as f32,
        depth_range: length,
        near: 0.0,
        view_plane: Vec4::ZERO,
        cascade_far: 0.0,
        cascade_blend_start: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::math::Vec4Swizzles;

    fn project(view: &ShadowLightView, point: Vec3) -> Vec3 {
        let clip = view.clip_from_world * point.extend(1.0);
        clip.xyz() / clip.w
    }

    #[test]
    fn cube_faces_cover_every_direction_in_the_face_of_its_major_axis() {
        let position = Vec3::new(1.0, 2.0, 3.0);
        let views = cube_views(position, 0.1, 256);
        for (face, (forward, _)) in CUBE_FACES.iter().enumerate() {
            // A direction 44° off the face's axis, toward a neighbour, is still inside.
            let side = any_perpendicular(*forward);
            let direction = (*forward + 0.96 * side).normalize();
            let ndc = project(&views[face], position + 5.0 * direction);
            assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "face {face}: {ndc}");
            // Reversed depth: near / distance along the axis.
            let on_axis = project(&views[face], position + 2.0 * *forward);
            assert!(
                (on_axis.z - 0.05).abs() < 1e-6,
                "face {face}: {}",
                on_axis.z
            );
        }
    }

    #[test]
    fn a_cone_view_holds_its_cone() {
        let angle = 30f32.to_radians();
        let view = cone_view(Vec3::ZERO, Vec3::NEG_Y, angle, 0.1, 512);
        let edge = Vec3::new(angle.sin(), -angle.cos(), 0.0) * 3.0;
        let ndc = project(&view, edge);
        assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "{ndc}");
        assert!(
            ndc.x.abs().max(ndc.y.abs()) > 0.9,
            "the cone fills the map: {ndc}"
        );
    }

    #[test]
    fn cascades_cover_their_slices_and_reach_back_to_casters() {
        let camera = CascadeCamera {
            world_from_view: glam::camera::rh::view::look_at_mat4(
                Vec3::new(0.0, 2.0, 8.0),
                Vec3::ZERO,
                Vec3::Y,
            )
            .inverse(),
            slice_corners: Box::new(|near, far| {
                let corner = |z: f32, sx: f32, sy: f32| Vec3::new(sx * z * 0.5, sy * z * 0.4, -z);
                [
                    corner(near, 1.0, -1.0),
                    corner(near, 1.0, 1.0),
                    corner(near, -1.0, 1.0),
                    corner(near, -1.0, -1.0),
                    corner(far, 1.0, -1.0),
                    corner(far, 1.0, 1.0),
                    corner(far, -1.0, 1.0),
                    corner(far, -1.0, -1.0),
                ]
            }),
            near: 0.1,
        };
        let direction = Vec3::new(0.3, -1.0, 0.2).normalize();
        // A point on the ground 3 units in front of the camera, and a caster 50 units above
        // it toward the light.
        let ground = Vec3::new(0.0, 0.0, 5.0);
        let high_caster = Bounds {
            center: ground - 50.0 * direction,
            radius: 1.0,
        };
        let views = cascade_views(
            direction,
            &camera,
            &PhongCascades::default(),
            1024,
            &[high_caster],
        );
        assert_eq!(views.len(), 4);
        let ndc = project(&views[0], ground);
        assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0 && (0.0..=1.0).contains(&ndc.z));
        // The caster's near side is inside the first map's depth range: it shades the ground.
        let caster = project(
            &views[0],
            high_caster.center - direction * high_caster.radius,
        );
        assert!((0.0..=1.0).contains(&caster.z), "{}", caster.z);
        assert!(
            caster.z > ndc.z,
            "nearer the light than the ground (reversed depth)"
        );
        assert!(views[0].cascade_far < views[1].cascade_far);
        assert!(views[0].cascade_blend_start < views[0].cascade_far);
    }
}
