//! Writes the crate's glTF assets (see the library's documentation).

use std::path::{Path, PathBuf};

fn write(relative: &str, text: String) -> std::io::Result<()> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(relative);
    std::fs::create_dir_all(path.parent().unwrap_or(Path::new(".")))?;
    std::fs::write(&path, text)?;
    println!("wrote {}", path.display());
    Ok(())
}

fn main() -> std::io::Result<()> {
    write(
        phong_gltf_asset::ASSET_PATH,
        phong_gltf_asset::phong_test_gltf(),
    )?;
    write(
        phong_gltf_asset::baked_room::ASSET_PATH,
        phong_gltf_asset::baked_room::baked_room_gltf(),
    )
}
