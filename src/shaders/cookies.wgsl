// Light cookies (`PhongLightCookie`): the tint of a light where its rays reach a point, from
// the light's image in the cookie atlas, laid out as Bevy's light textures are (SPEC.md,
// "Light cookies"). Imported by `bevy_phong::shading` only in the PHONG_LIGHT_COOKIES
// variant. Where the scene data is in the data texture (WebGL2) there is no atlas: every
// light is untinted.
#define_import_path bevy_phong::cookies

#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
#import bevy_phong::bindings::cookie_atlas
#import bevy_phong::scene::record_word
#endif

// `GpuCookie::projection`: a spot light's cone, a directional light's plane, or a point
// light's cube map plus its layout (Bevy's CUBEMAP_TYPE_*: 0 cross vertical, 1 cross
// horizontal, 2 sequence vertical, 3 sequence horizontal).
const COOKIE_SPOT: u32 = 0u;
const COOKIE_DIRECTIONAL: u32 = 1u;
const COOKIE_POINT: u32 = 2u;
// `GpuCookie::flags`.
const COOKIE_RED_ONLY: u32 = 1u;
const COOKIE_TILED: u32 = 2u;

#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
// Texel `texel` of layer `layer` of a `side`-texel atlas, its coordinates wrapped (tiled)
// or clamped to the layer, decoded from the 8-bit sRGB values the atlas holds to linear
// (exactly: some devices' own sRGB decoding is approximate).
fn cookie_texel(layer: u32, texel: vec2<i32>, side: i32, tiled: bool) -> vec3<f32> {
    let wrapped = ((texel % side) + side) % side;
    let clamped = clamp(texel, vec2<i32>(0), vec2<i32>(side - 1));
    let srgb = textureLoad(cookie_atlas, select(clamped, wrapped, tiled), layer, 0).rgb;
    return select(pow((srgb + 0.055) / 1.055, vec3<f32>(2.4)), srgb / 12.92, srgb <= vec3<f32>(0.04045));
}

// Layer `layer` at `uv`, bilinear between the four nearest texel centers (with f32 weights:
// the reference model's filter, not the sampler's fixed-point one).
fn cookie_sample(layer: u32, uv: vec2<f32>, tiled: bool) -> vec3<f32> {
    let side = i32(textureDimensions(cookie_atlas).x);
    let at = uv * f32(side) - 0.5;
    let corner = floor(at);
    let weight = at - corner;
    let texel = vec2<i32>(corner);
    let top = mix(cookie_texel(layer, texel, side, tiled), cookie_texel(layer, texel + vec2<i32>(1, 0), side, tiled), weight.x);
    let bottom = mix(cookie_texel(layer, texel + vec2<i32>(0, 1), side, tiled), cookie_texel(layer, texel + vec2<i32>(1, 1), side, tiled), weight.x);
    return mix(top, bottom, weight.y);
}

// Where the direction `direction` (from a point light, in its frame) falls in a cube map
// packed in one image by `packing` (a layout index): Bevy's `cubemap_uv`, face for face.
fn cube_face_uv(direction: vec3<f32>, packing: u32) -> vec2<f32> {
    let a = abs(direction);
    let largest = max(a.x, max(a.y, a.z));
    // Faces in Bevy's order: +x, -x, +y, -y, -z, +z.
    var face: u32;
    var face_uv: vec2<f32>;
    var divisor: f32;
    if largest == a.x {
        face = select(0u, 1u, direction.x < 0.0);
        face_uv = vec2<f32>(select(direction.z, -direction.z, direction.x < 0.0), -direction.y);
        divisor = a.x;
    } else if largest == a.y {
        face = select(2u, 3u, direction.y < 0.0);
        face_uv = vec2<f32>(direction.x, select(-direction.z, direction.z, direction.y < 0.0));
        divisor = a.y;
    } else {
        face = select(5u, 4u, direction.z < 0.0);
        face_uv = vec2<f32>(direction.x, select(direction.y, -direction.y, direction.z < 0.0));
        divisor = a.z;
    }
    if !(divisor > 0.0) {
        // At the light itself: no direction, and no light either.
        return vec2<f32>(0.5);
    }
    face_uv = face_uv / divisor * 0.5 + 0.5;
    var corner = vec2<u32>(0u);
    var face_size = vec2<f32>(1.0);
    switch packing {
        case 0u: {
            face_size = vec2<f32>(1.0 / 3.0, 1.0 / 4.0);
            corner = vec2<u32>((0x111102u >> (4u * face)) & 0xfu, (0x132011u >> (4u * face)) & 0xfu);
        }
        case 1u: {
            face_size = vec2<f32>(1.0 / 4.0, 1.0 / 3.0);
            corner = vec2<u32>((0x131102u >> (4u * face)) & 0xfu, (0x112011u >> (4u * face)) & 0xfu);
        }
        case 2u: {
            face_size = vec2<f32>(1.0, 1.0 / 6.0);
            corner.y = face;
        }
        default: {
            face_size = vec2<f32>(1.0 / 6.0, 1.0);
            corner.x = face;
        }
    }
    return (vec2<f32>(corner) + face_uv) * face_size;
}
#endif

// The tint of the cookie whose record is at `index` in the light buffer (after the lights)
// at world position `position`:
// the image's color there, clamped to [0, 1], or its red channel alone; 1 where the image
// does not reach (behind a spot light, off an untiled directional light's tile).
fn light_cookie(index: u32, position: vec3<f32>) -> vec3<f32> {
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 8
    let at = vec4<f32>(position, 1.0);
    let local = vec3<f32>(
        dot(bitcast<vec4<f32>>(record_word(index, 0u)), at),
        dot(bitcast<vec4<f32>>(record_word(index, 1u)), at),
        dot(bitcast<vec4<f32>>(record_word(index, 2u)), at),
    );
    let terms = record_word(index, 3u);
    let layer = terms.x;
    let projection = terms.y;
    let tan_outer = bitcast<f32>(terms.z);
    let tiled = (terms.w & COOKIE_TILED) != 0u;
    var uv: vec2<f32>;
    if projection == COOKIE_SPOT {
        if !(local.z < 0.0) {
            return vec3<f32>(1.0);
        }
        uv = local.xy / (local.z * tan_outer) * vec2<f32>(-0.5, 0.5) + 0.5;
    } else if projection == COOKIE_DIRECTIONAL {
        uv = local.xy * vec2<f32>(-0.5, 0.5) + 0.5;
        if !tiled && any(uv != clamp(uv, vec2<f32>(0.0), vec2<f32>(1.0))) {
            return vec3<f32>(1.0);
        }
    } else {
        uv = cube_face_uv(local, projection - COOKIE_POINT);
    }
    let tint = saturate(cookie_sample(layer, uv, tiled));
    return select(tint, vec3<f32>(tint.r), (terms.w & COOKIE_RED_ONLY) != 0u);
#else
    return vec3<f32>(1.0);
#endif
}
