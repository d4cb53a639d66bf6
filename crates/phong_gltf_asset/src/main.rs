//! Writes `assets/gltf/phong_test.gltf` (see the library's documentation).

use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(phong_gltf_asset::ASSET_PATH);
    std::fs::create_dir_all(path.parent().expect("the asset path has a folder"))?;
    std::fs::write(&path, phong_gltf_asset::phong_test_gltf())?;
    println!("wrote {}", path.display());
    Ok(())
}
