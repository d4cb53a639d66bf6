//! What the scene holds that changes every Phong material's shader: whether it casts shadows
//! this frame, whether soft ones, and whether it has a hemisphere light. Process-wide flags
//! that the gathers ([`crate::shadows`], [`crate::render`]) set in the main world and that
//! [`PhongMaterialKey`](crate::PhongMaterialKey) reads when a material is specialized. They
//! sit below both, so that the material needs nothing of the shadows or the lights.

use core::sync::atomic::AtomicBool;

/// Whether any light casts shadows this frame. Phong materials compile the shadow code only
/// in the variant for scenes where one does (shader def `PHONG_SHADOWS`): on some devices
/// (lavapipe) the mere presence of that code makes every fragment several times slower.
/// The shadow gather sets it in the main world and, when it flips, marks every Phong
/// material modified in the same frame, so that each is prepared again with the new key.
pub(crate) static SCENE_CASTS_SHADOWS: AtomicBool = AtomicBool::new(false);

/// Whether some shadow-casting light has a size (`softness > 0`) this frame: only then is
/// the soft-shadow filter compiled in (shader def `PHONG_SOFT_SHADOWS`), as
/// [`SCENE_CASTS_SHADOWS`] and set beside it. Hard shadows are one bilinear comparison per
/// light.
pub(crate) static SCENE_HAS_SOFT_SHADOWS: AtomicBool = AtomicBool::new(false);

/// Whether the scene has a [`PhongHemisphereLight`](crate::PhongHemisphereLight) this frame:
/// only then is its term compiled in (shader def `PHONG_HEMISPHERE`), as
/// [`SCENE_CASTS_SHADOWS`]. The light gather sets it and, when it flips, marks every Phong
/// material modified in the same frame.
pub(crate) static SCENE_HAS_HEMISPHERE_LIGHT: AtomicBool = AtomicBool::new(false);

/// Whether some light of the scene has a [`PhongLightCookie`](crate::PhongLightCookie) this
/// frame: only then is the cookie code compiled in (shader def `PHONG_LIGHT_COOKIES`), as
/// [`SCENE_CASTS_SHADOWS`]. The cookie gather sets it.
pub(crate) static SCENE_HAS_LIGHT_COOKIES: AtomicBool = AtomicBool::new(false);
