//! Which view a fragment is drawn for: the key by which the shader finds its view's light
//! clusters ([`crate::render`]) and shadow cascades ([`crate::shadows`]). Both use it, so it
//! sits below both.
//!
//! Every Phong material binds the same cluster data for every camera (the material bind
//! group is not per view), so the data holds each view's clusters side by side and the
//! fragment shader looks its own up by a key that it can compute from Bevy's view uniform:
//! a hash of the bits of the view's six frustum half-spaces (`view.frustum`). Bevy copies
//! those from the camera's [`Frustum`] component unchanged, so the key computed here from
//! the same component is bit for bit the shader's (`view_key` in `bevy_phong::view_key`).
//!
//! Two views with the same frustum see the same volume and get the same clusters. Two
//! different frusta whose keys collide (about one chance in four billion per pair) are
//! both left out of the cluster data: their fragments then find no entry and loop over
//! every light of finite reach, which is exact, only slower.

use bevy::camera::primitives::Frustum;

/// FNV-1a's offset basis.
const OFFSET_BASIS: u32 = 2_166_136_261;
/// FNV-1a's prime.
const PRIME: u32 = 16_777_619;

/// The key of a view with frustum `frustum`: FNV-1a over the bits of its half-spaces (each
/// `normal.xyz, d`, in Bevy's order), word by word, as the shader computes it.
pub fn view_key(frustum: &Frustum) -> u32 {
    frustum
        .half_spaces
        .iter()
        .flat_map(|half_space| half_space.normal_d().to_array())
        .fold(OFFSET_BASIS, |key, value| {
            (key ^ value.to_bits()).wrapping_mul(PRIME)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::math::Vec4;
    use bevy::shape::HalfSpace;

    fn frustum(offset: f32) -> Frustum {
        let mut frustum = Frustum::default();
        for (index, half_space) in frustum.half_spaces.iter_mut().enumerate() {
            *half_space = HalfSpace::new(Vec4::new(1.0, 0.0, 0.0, index as f32 + offset));
        }
        frustum
    }

    #[test]
    fn the_same_frustum_gives_the_same_key_and_a_moved_one_another() {
        assert_eq!(view_key(&frustum(0.0)), view_key(&frustum(0.0)));
        assert_ne!(view_key(&frustum(0.0)), view_key(&frustum(1e-3)));
        // One bit of one plane's distance changes the key.
        let mut nudged = frustum(0.0);
        let d = nudged.half_spaces[5].d();
        nudged.half_spaces[5] = HalfSpace::new(nudged.half_spaces[5].normal().extend(d.next_up()));
        assert_ne!(view_key(&frustum(0.0)), view_key(&nudged));
    }

    #[test]
    fn the_key_of_a_zero_frustum_is_fnv_1a_of_24_zero_words() {
        // A default frustum's half-spaces are all zero (no normalization).
        let zero = Frustum::default();
        assert!(zero.half_spaces.iter().all(|h| h.normal_d() == Vec4::ZERO));
        let expected = (0..24).fold(OFFSET_BASIS, |key, _| key.wrapping_mul(PRIME));
        assert_eq!(view_key(&zero), expected);
    }
}
