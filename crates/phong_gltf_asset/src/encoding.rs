//! How the asset embeds its textures and buffer: PNG files, in base64 `data:` URIs.
//!
//! The PNGs are written uncompressed (stored deflate blocks, no row filter), so that a file
//! depends on its pixels alone: a change in a compression library's choices never changes the
//! committed asset.

use base64::{Engine as _, engine::general_purpose::STANDARD};

/// A PNG of `width × height` pixels with `channels` (3: RGB, 4: RGBA) bytes each, rows top
/// to bottom, 8 bits per channel.
pub fn png(width: u32, height: u32, channels: u8, pixels: &[u8]) -> Vec<u8> {
    let color = match channels {
        3 => ::png::ColorType::Rgb,
        4 => ::png::ColorType::Rgba,
        _ => panic!("{channels} channels: RGB or RGBA only"),
    };
    let mut file = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut file, width, height);
    encoder.set_color(color);
    encoder.set_depth(::png::BitDepth::Eight);
    encoder.set_compression(::png::Compression::NoCompression);
    encoder.set_filter(::png::Filter::NoFilter);
    // Writing to memory fails only on a pixel count that does not fit the size: a bug here.
    let mut writer = encoder.write_header().expect("PNG header");
    writer.write_image_data(pixels).expect("pixel count");
    writer.finish().expect("PNG end");
    file
}

/// A `data:` URI holding `bytes`: standard base64 (RFC 4648), with padding.
pub fn data_uri(mime: &str, bytes: &[u8]) -> String {
    format!("data:{mime};base64,{}", STANDARD.encode(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_png_decodes_to_its_pixels() {
        let pixels = [1, 2, 3, 4, 5, 6, 7, 8];
        let file = png(2, 1, 4, &pixels);
        let mut reader = ::png::Decoder::new(std::io::Cursor::new(file))
            .read_info()
            .expect("a PNG");
        let mut decoded = vec![0; reader.output_buffer_size().expect("a size")];
        let info = reader.next_frame(&mut decoded).expect("a frame");
        assert_eq!((info.width, info.height), (2, 1));
        assert_eq!(info.color_type, ::png::ColorType::Rgba);
        assert_eq!(&decoded[..info.buffer_size()], &pixels);
    }

    #[test]
    fn a_data_uri_is_padded_base64() {
        assert_eq!(data_uri("image/png", b"fo"), "data:image/png;base64,Zm8=");
    }
}
