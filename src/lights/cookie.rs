//! Light cookies: an image that tints a light by where its rays go.

use crate::limits::COOKIE_RESOLUTION;
use bevy::{
    asset::Handle,
    camera::primitives::CubemapLayout,
    color::{ColorToComponents, ColorToPacked, LinearRgba, Srgba},
    ecs::component::Component,
    image::Image,
    prelude::{ReflectComponent, ReflectDefault},
    reflect::Reflect,
    render::render_resource::TextureFormat,
};

/// A texture that tints a light by the direction or place of its rays (a "cookie", or gobo),
/// laid out as Bevy's light textures are: put it on the entity of a
/// [`PhongSpotLight`](crate::PhongSpotLight), a [`PhongPointLight`](crate::PhongPointLight) or
/// a [`PhongDirectionalLight`](crate::PhongDirectionalLight). With `P` the lit point in the
/// light's local frame (its `GlobalTransform` inverted, scale included):
///
/// - **spot**: the image spans the cone, `uv = P.xy / (P.z · tan(outer_angle)) · (−½, ½) + ½`
///   (Bevy's `SpotLightTexture`); keep its border black to end the light at the cone;
/// - **point**: the image is a cube map packed in one image by
///   [`cubemap_layout`](Self::cubemap_layout), looked up along `P` (Bevy's
///   `PointLightTexture`);
/// - **directional**: the image lies on the light's local XY plane, one copy over
///   `[−1, 1]²` (the transform's scale sizes it), `uv = P.xy · (−½, ½) + ½`; outside it the
///   light is untouched, or dark with [`dark_outside`](Self::dark_outside), unless
///   [`tiled`](Self::tiled) repeats it (Bevy's `DirectionalLightTexture`).
///
/// The light's diffuse and specular colors are multiplied by the image's color there
/// (bilinear between texels, clamped to `[0, 1]`: a cookie only takes light away), or by its
/// red channel alone with [`red_only`](Self::red_only). The image is copied into the crate's
/// cookie atlas, each layer `COOKIE_RESOLUTION` texels
/// square, as 8-bit sRGB (see SPEC.md, "Light cookies").
///
/// A cookied light of finite reach is clustered as any other: a fragment looks its cookie
/// up only where the light can reach it. Cookies are left out under WebGL2
/// (`crate::render::binds_every_map`), with a warning: the light is drawn without its
/// cookie there. An image that is not loaded yet, or whose format cannot be read on the
/// CPU (compressed formats), leaves the light untinted (with a warning for the latter).
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug, Clone)]
pub struct PhongLightCookie {
    /// The image: any size (resampled to the atlas's layers), any uncompressed format.
    pub image: Handle<Image>,
    /// How a point light's image holds the six faces. Default
    /// [`CubemapLayout::CrossVertical`] (Bevy's default). Ignored by other lights.
    pub cubemap_layout: CubemapLayout,
    /// Repeats a directional light's image over its whole plane. Default `false`. Ignored by
    /// other lights.
    pub tiled: bool,
    /// Multiplies the light by the image's red channel only, as Bevy's light textures do
    /// (the interop plugin sets it). Default `false`: by its RGB.
    pub red_only: bool,
    /// Leaves a directional light dark outside its untiled image, as Bevy's
    /// `DirectionalLightTexture` does (the interop plugin sets it): the light shines only
    /// through the image, a window's shape. Default `false`: the light is untouched outside
    /// it (a cloud's shadow over one place). Ignored by other lights and by tiled images.
    pub dark_outside: bool,
}

/// How a light's [`PhongLightCookie`] lays its image over the light's rays: what a kind of
/// light answers in
/// [`PhongLightKind::cookie_projection`](crate::extension::PhongLightKind::cookie_projection).
/// A cone for a light that shines within one (the spot light), a cube for one that shines
/// all around (the point light), a plane for parallel rays (the directional light); see
/// [`PhongLightCookie`] for each one's mapping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhongCookieProjection {
    /// Over a cone of half-angle `half_angle` (radians) along the light's `-Z` axis.
    Cone {
        /// The cone's half-angle, radians; clamped to `[0, π]` and then to the widest cone a
        /// cookie spans.
        half_angle: f32,
    },
    /// A cube map around the light, packed by the cookie's `cubemap_layout`.
    Cube,
    /// A plane: the light's local XY plane, repeated where the cookie is `tiled`.
    Plane,
}

/// The format of the cookie images copied into the atlas unchanged: 8-bit sRGB, which keeps
/// the precision of sRGB in the dark.
const FORMAT: TextureFormat = TextureFormat::Rgba8UnormSrgb;

/// The texels of a layer made from `image`, row by row, as 8-bit sRGB RGBA: the image's own
/// bytes where it is already [`COOKIE_RESOLUTION`] square in `Rgba8UnormSrgb`; otherwise its
/// texels decoded to linear color, resampled bilinearly (texel centers, clamped at the
/// edges) at the layer's texel centers, clamped to `[0, 1]` and encoded again. `None` for
/// an image whose texels cannot be read on the CPU (compressed formats) or that is empty.
pub fn cookie_layer_texels(image: &Image) -> Option<Vec<[u8; 4]>> {
    let (width, height) = (image.width(), image.height());
    if width == 0 || height == 0 {
        return None;
    }
    let side = COOKIE_RESOLUTION;
    if (width, height) == (side, side) && image.texture_descriptor.format == FORMAT {
        let data = image.data.as_ref()?;
        return Some(
            data.chunks_exact(4)
                .map(|t| [t[0], t[1], t[2], t[3]])
                .collect(),
        );
    }
    image.get_color_at(0, 0).ok()?;
    let texel = |x: u32, y: u32| -> LinearRgba {
        image
            .get_color_at(x.min(width - 1), y.min(height - 1))
            .map_or(LinearRgba::NONE, |color| color.to_linear())
    };
    let sample = |u: f32, v: f32| -> LinearRgba {
        let (x, y) = (u * width as f32 - 0.5, v * height as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |dx: f32, dy: f32| texel((x0 + dx).max(0.0) as u32, (y0 + dy).max(0.0) as u32);
        let top = at(0.0, 0.0) * (1.0 - fx) + at(1.0, 0.0) * fx;
        let bottom = at(0.0, 1.0) * (1.0 - fx) + at(1.0, 1.0) * fx;
        top * (1.0 - fy) + bottom * fy
    };
    Some(
        (0..side * side)
            .map(|index| {
                let (x, y) = (index % side, index / side);
                let color = sample(
                    (x as f32 + 0.5) / side as f32,
                    (y as f32 + 0.5) / side as f32,
                );
                let clamped = LinearRgba::from_f32_array(
                    color
                        .to_f32_array()
                        .map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) }),
                );
                Srgba::from(clamped).to_u8_array()
            })
            .collect(),
    )
}
