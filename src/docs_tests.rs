//! The field tables of the docs against the types: every field of a light, of its settings
//! and of [`PhongMaterial`](crate::PhongMaterial) is a row of the table under the heading that
//! names its type (docs/lights.md, docs/material.md). A field added to a type without a row
//! fails here, naming the type, the field and the file. Every built-in light kind (a folder
//! of `src/light_kind/`) is named by `PhongLightKind`'s docs and by docs/lights.md.

use bevy::reflect::{TypeInfo, Typed};
use std::{collections::BTreeSet, fs, path::Path};

/// The names in the first column of the first table after the heading that names
/// `type_name` in backticks (`## \`PhongSpotLight\``): every name written in backticks
/// there (a row may name several fields).
fn documented_fields(markdown: &str, type_name: &str) -> Option<BTreeSet<String>> {
    let heading = format!("`{type_name}`");
    let mut lines = markdown.lines();
    lines.find(|line| line.starts_with('#') && line.contains(&heading))?;
    let rows = lines
        .skip_while(|line| !line.starts_with('|'))
        .take_while(|line| line.starts_with('|'));
    Some(
        rows.filter_map(|row| row.split('|').nth(1))
            .flat_map(|cell| cell.split('`').skip(1).step_by(2).map(str::to_string))
            .collect(),
    )
}

/// The reflected fields of `T` (every field a user sets; `#[reflect(ignore)]` ones left out).
fn fields_of<T: Typed>() -> Vec<&'static str> {
    match T::type_info() {
        TypeInfo::Struct(info) => info.iter().map(|field| field.name()).collect(),
        other => panic!("{} is not a struct", other.type_path()),
    }
}

/// Fails naming each field of `T` without a row in `file`'s table for it.
fn assert_documented<T: Typed>(file: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let markdown = fs::read_to_string(&path).unwrap_or_else(|error| panic!("{file}: {error}"));
    let type_name = T::type_info().type_path_table().short_path();
    let documented = documented_fields(&markdown, type_name)
        .unwrap_or_else(|| panic!("{file} has no heading naming `{type_name}`"));
    let missing: Vec<_> = fields_of::<T>()
        .into_iter()
        .filter(|field| !documented.contains(*field))
        .collect();
    assert!(
        missing.is_empty(),
        "{file}: the table under `{type_name}` lacks {missing:?}"
    );
}

#[test]
fn every_field_of_every_light_and_its_settings_has_a_row_in_the_lights_page() {
    use crate::light_kind::{PhongDirectionalLight, PhongPointLight, PhongSpotLight};
    use crate::lights::*;
    assert_documented::<PhongAmbientLight>("docs/lights.md");
    assert_documented::<PhongHemisphereLight>("docs/lights.md");
    assert_documented::<PhongDirectionalLight>("docs/lights.md");
    assert_documented::<PhongPointLight>("docs/lights.md");
    assert_documented::<PhongSpotLight>("docs/lights.md");
    assert_documented::<Decay>("docs/lights.md");
    assert_documented::<PhongLightCookie>("docs/lights.md");
    assert_documented::<PhongShadows>("docs/lights.md");
    assert_documented::<PhongCascades>("docs/lights.md");
    assert_documented::<crate::PhongLightCulling>("docs/lights.md");
    assert_documented::<crate::PhongViewClusters>("docs/lights.md");
}

#[test]
fn every_field_of_the_material_has_a_row_in_the_material_page() {
    assert_documented::<crate::PhongMaterial>("docs/material.md");
}

#[test]
fn a_table_is_read_from_its_heading_to_its_last_row() {
    let markdown = "# Page\n## `Other`\n| field |\n|---|\n| `x` |\n## `Light`\ntext\n\n\
                    | field | meaning |\n|---|---|\n| `color` | c |\n| `range` (world units), `reach` | r |\n\n\
                    | `later` | not this table |\n";
    let fields = documented_fields(markdown, "Light").unwrap();
    assert_eq!(
        fields,
        BTreeSet::from(["color", "range", "reach"].map(String::from))
    );
    assert_eq!(documented_fields(markdown, "Missing"), None);
}

#[test]
fn the_readme_shows_the_minimal_example_whole() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let example = fs::read_to_string(root.join("examples/minimal.rs")).expect("the example");
    let readme = fs::read_to_string(root.join("README.md")).expect("the README");
    let code = &example[example.find("use bevy::").expect("the example's code")..];
    assert!(
        readme.contains(code),
        "README.md's \"Use it\" block is no longer examples/minimal.rs: copy the example there"
    );
}

/// The light kinds built in: each folder of `src/light_kind/` whose `mod.rs` declares a
/// `pub struct Phong…Light`, by that name.
fn built_in_kinds() -> Vec<String> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/light_kind");
    let mut kinds: Vec<String> = fs::read_dir(&folder)
        .expect("src/light_kind is readable")
        .filter_map(|entry| fs::read_to_string(entry.ok()?.path().join("mod.rs")).ok())
        .flat_map(|source| {
            source
                .lines()
                .filter_map(|line| line.strip_prefix("pub struct Phong"))
                .filter_map(|rest| rest.split([' ', '{', '<']).next())
                .filter(|name| name.ends_with("Light"))
                .map(|name| format!("Phong{name}"))
                .collect::<Vec<_>>()
        })
        .collect();
    kinds.sort();
    kinds
}

#[test]
fn every_built_in_light_kind_is_named_by_the_trait_docs_and_the_lights_page() {
    let kinds = built_in_kinds();
    assert!(kinds.len() >= 5, "found {kinds:?}");
    for file in ["src/light_kind.rs", "docs/lights.md"] {
        let text = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file))
            .unwrap_or_else(|error| panic!("{file}: {error}"));
        let missing: Vec<&String> = kinds
            .iter()
            .filter(|kind| !text.contains(&format!("{kind}`")))
            .collect();
        assert!(missing.is_empty(), "{file} does not name {missing:?}");
    }
}

/// The `.rs` files under `folder`, recursively.
fn rust_files(folder: &Path) -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    let entries =
        fs::read_dir(folder).unwrap_or_else(|error| panic!("{}: {error}", folder.display()));
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|extension| extension == "rs") {
            files.push(path);
        }
    }
    files
}

#[test]
fn nothing_public_is_hidden_from_the_docs() {
    // A public item or field hidden from the docs is still a game's to use and to see in
    // `Debug`, without being told what it is: what the crate keeps to itself is
    // `pub(crate)`, and what the render world needs of a material lives there.
    let attribute = concat!("#[doc", "(hidden)]");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let hidden: Vec<String> = rust_files(&src)
        .iter()
        .flat_map(|path| {
            let source = fs::read_to_string(path).unwrap_or_default();
            source
                .lines()
                .enumerate()
                .filter(|(_, line)| line.trim() == attribute)
                .map(|(index, _)| format!("{}:{}", path.display(), index + 1))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(hidden.is_empty(), "hidden from the docs: {hidden:?}");
}

/// The items a kind's macro of `file` (`macro_rules! name { … }`) writes: the names of its
/// `fn`s, `const`s and `type`s.
fn items_of_macro(file: &str, name: &str) -> Vec<String> {
    let source = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file))
        .unwrap_or_else(|error| panic!("{file}: {error}"));
    let start = source
        .find(&format!("macro_rules! {name} {{"))
        .unwrap_or_else(|| panic!("{file} has no macro {name}"));
    let body = &source[start..];
    let body = &body[..body.find("\n}").expect("the macro's closing brace")];
    body.split_whitespace()
        .collect::<Vec<_>>()
        .windows(2)
        .filter(|pair| ["fn", "const", "type"].contains(&pair[0]))
        .map(|pair| {
            let name = pair[1]
                .split(['(', ':', '<', ' '])
                .next()
                .unwrap_or_default();
            name.to_owned()
        })
        .collect()
}

#[test]
fn a_kinds_generated_trait_items_are_named_where_the_kind_is() {
    let macros = [
        ("src/light_kind/built_in.rs", "built_in_record"),
        ("src/light_kind/built_in.rs", "fading_reach_kind"),
        ("src/light_kind/gpu_area_light.rs", "area_light_kind"),
    ];
    let kinds = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/light_kind");
    let mut calls = 0;
    for entry in fs::read_dir(&kinds)
        .expect("src/light_kind is readable")
        .flatten()
    {
        let Ok(source) = fs::read_to_string(entry.path().join("kind.rs")) else {
            continue;
        };
        let lines: Vec<&str> = source.lines().collect();
        for (file, name) in macros {
            let Some(call) = lines
                .iter()
                .position(|line| line.trim() == format!("{name}!();"))
            else {
                continue;
            };
            calls += 1;
            // The comment lines right above the call.
            let comment: String = lines[..call]
                .iter()
                .rev()
                .take_while(|line| line.trim_start().starts_with("//"))
                .copied()
                .collect::<Vec<_>>()
                .join(" ");
            let words: BTreeSet<&str> = comment
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .collect();
            let unnamed: Vec<String> = items_of_macro(file, name)
                .into_iter()
                .filter(|item| !words.contains(item.as_str()))
                .collect();
            assert!(
                unnamed.is_empty(),
                "{}/kind.rs: the comment above {name}!() does not name {unnamed:?}",
                entry.file_name().display()
            );
        }
    }
    assert!(calls >= 7, "found {calls} calls of the kinds' macros");
}
