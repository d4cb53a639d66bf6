//! The layering that lib.rs states under "## Layers", checked on the sources.
//!
//! [`LAYERS`] mirrors that list (a test compares the two). Each file of each top-level
//! module is read, its comments and literals blanked, and every path from the crate root
//! (`crate::x::..`, and each entry of a group `crate::{a::.., b::..}`) is read as a use of a
//! top-level module; a name that lib.rs re-exports at the root (`crate::PhongPlugin`)
//! counts as a use of the module it comes from. Each such use must lead to the module
//! itself or to a module of a lower layer.
//!
//! Exempt, as lib.rs says, is test code: the items under `#[cfg(test)]` (inline `mod tests`
//! blocks, and whole files declared as `#[cfg(test)] mod name;`, such as
//! `scene/hostile_file_tests.rs`), and the test-only top-level modules (`test_app`, this
//! one). `super::` paths cannot leave a top-level module (none climbs out of one), so only
//! paths from the crate root are followed.

use std::{
    collections::BTreeMap,
    fs,
    path::{Path, PathBuf},
};

/// The layers of lib.rs's "## Layers", from the bottom: a name for messages, and the
/// top-level modules in it.
const LAYERS: &[(&str, &[&str])] = &[
    (
        "foundations",
        &[
            "limits",
            "direction",
            "displacement",
            "quoting",
            "schedule",
            "scene_variants",
            "storage_buffer",
            "view_key",
        ],
    ),
    ("the data model", &["lights", "material", "culling"]),
    ("rules over the model", &["validation", "reference"]),
    ("shadow maps", &["shadows"]),
    ("light kinds", &["light_kind"]),
    ("gather and bindings", &["render"]),
    (
        "features",
        &[
            "scene",
            "interop",
            "from_three",
            "extension",
            "surface_inputs",
        ],
    ),
    ("the plugin", &["plugin"]),
    ("glTF", &["gltf"]),
    ("the testing feature", &["testing"]),
];

/// The layer of `module`: its index in [`LAYERS`] (1 for the bottom one, as lib.rs counts)
/// and its name.
fn layer_of(module: &str) -> Option<(usize, &'static str)> {
    LAYERS
        .iter()
        .enumerate()
        .find(|(_, (_, modules))| modules.contains(&module))
        .map(|(index, (name, _))| (index + 1, *name))
}

/// A word or a punctuation character of Rust source, with its line.
#[derive(Clone, Debug)]
pub(super) struct Token {
    pub text: String,
    pub line: usize,
}

fn is_ident_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// `source` with its comments, string literals and character literals replaced by spaces
/// (newlines kept, so lines keep their numbers).
fn blank_comments_and_literals(source: &str) -> String {
    let chars: Vec<char> = source.chars().collect();
    let mut out = String::with_capacity(source.len());
    let mut i = 0;
    while i < chars.len() {
        match comment_or_literal_end(&chars, i) {
            Some(end) => {
                let end = end.min(chars.len());
                out.extend(
                    chars[i..end]
                        .iter()
                        .map(|&c| if c == '\n' { c } else { ' ' }),
                );
                i = end;
            }
            None => {
                out.push(chars[i]);
                i += 1;
            }
        }
    }
    out
}

/// One past the end of the comment or literal that starts at `chars[i]`, if one does.
fn comment_or_literal_end(chars: &[char], i: usize) -> Option<usize> {
    let at = |k: usize| chars.get(k).copied();
    let find_from = |from: usize, wanted: char| {
        (from..chars.len())
            .find(|&k| chars[k] == wanted)
            .unwrap_or(chars.len())
    };
    // `r"..."` and `br#"..."#`, but not the `r` that ends a word.
    let raw_prefix = i == 0
        || !is_ident_char(chars[i - 1])
        || (chars[i - 1] == 'b' && (i < 2 || !is_ident_char(chars[i - 2])));
    match (chars[i], at(i + 1)) {
        ('/', Some('/')) => Some(find_from(i, '\n')),
        ('/', Some('*')) => {
            let mut depth = 0;
            let mut k = i;
            while k < chars.len() {
                if chars[k] == '/' && at(k + 1) == Some('*') {
                    depth += 1;
                    k += 2;
                } else if chars[k] == '*' && at(k + 1) == Some('/') {
                    depth -= 1;
                    k += 2;
                    if depth == 0 {
                        return Some(k);
                    }
                } else {
                    k += 1;
                }
            }
            Some(chars.len())
        }
        ('"', _) => {
            let mut k = i + 1;
            while k < chars.len() && chars[k] != '"' {
                k += if chars[k] == '\\' { 2 } else { 1 };
            }
            Some(k + 1)
        }
        ('r', Some('#' | '"')) if raw_prefix => {
            let hashes = chars[i + 1..].iter().take_while(|&&c| c == '#').count();
            if at(i + 1 + hashes) != Some('"') {
                return None; // a raw identifier, `r#name`
            }
            let closing: Vec<char> = core::iter::once('"')
                .chain(core::iter::repeat_n('#', hashes))
                .collect();
            let end = (i + 2 + hashes..chars.len())
                .find(|&k| chars[k..].starts_with(&closing))
                .map_or(chars.len(), |k| k + closing.len());
            Some(end)
        }
        ('\'', Some('\\')) => Some(find_from(i + 3, '\'') + 1),
        ('\'', Some(_)) if at(i + 2) == Some('\'') => Some(i + 3),
        // A lifetime or a label: kept.
        _ => None,
    }
}

/// The words and punctuation of `source`, without its comments and literals.
fn tokens(source: &str) -> Vec<Token> {
    let code = blank_comments_and_literals(source);
    let mut tokens = Vec::new();
    let mut line = 1;
    let mut word = String::new();
    for c in code.chars() {
        if is_ident_char(c) {
            word.push(c);
            continue;
        }
        if !word.is_empty() {
            tokens.push(Token {
                text: core::mem::take(&mut word),
                line,
            });
        }
        if c == '\n' {
            line += 1;
        } else if !c.is_whitespace() {
            tokens.push(Token {
                text: c.to_string(),
                line,
            });
        }
    }
    if !word.is_empty() {
        tokens.push(Token { text: word, line });
    }
    tokens
}

/// Whether the tokens at `i` read `texts`.
pub(super) fn reads(tokens: &[Token], i: usize, texts: &[&str]) -> bool {
    tokens.len() >= i + texts.len()
        && texts
            .iter()
            .enumerate()
            .all(|(k, text)| tokens[i + k].text == *text)
}

/// Where the entry of a `{…}` group (closed at `close`) after the one at `entry` starts: past
/// its comma, or at `close`.
pub(super) fn next_entry(tokens: &[Token], mut entry: usize, close: usize) -> usize {
    let mut depth = 0;
    while entry < close {
        match tokens[entry].text.as_str() {
            "{" => depth += 1,
            "}" => depth -= 1,
            "," if depth == 0 => break,
            _ => {}
        }
        entry += 1;
    }
    entry + 1
}

/// The index of the `}` that closes the `{` at `open`.
pub(super) fn closing_brace(tokens: &[Token], open: usize) -> usize {
    let mut depth = 0;
    for (k, token) in tokens.iter().enumerate().skip(open) {
        match token.text.as_str() {
            "{" => depth += 1,
            "}" => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    tokens.len()
}

/// One past the end of the item, field or statement that starts at `start`: its `;` or
/// `,`, or the `}` of its body, or the `}` of the block around it.
fn item_end(tokens: &[Token], start: usize) -> usize {
    let mut depth = 0;
    let mut k = start;
    while k < tokens.len() {
        match tokens[k].text.as_str() {
            "(" | "[" => depth += 1,
            ")" | "]" => depth -= 1,
            ";" | "," if depth == 0 => return k + 1,
            "{" if depth == 0 => return closing_brace(tokens, k) + 1,
            "}" => return k,
            _ => {}
        }
        k += 1;
    }
    tokens.len()
}

/// A file's tokens, which of them are test code, and the modules it declares in files of
/// their own (`mod name;`), each with whether it is test code.
pub(super) struct Scanned {
    pub tokens: Vec<Token>,
    pub test: Vec<bool>,
    pub children: Vec<(String, bool)>,
}

pub(super) fn scan(source: &str) -> Scanned {
    let tokens = tokens(source);
    let mut test = vec![false; tokens.len()];
    let mut i = 0;
    while i < tokens.len() {
        if reads(&tokens, i, &["#", "!", "[", "cfg", "(", "test", ")", "]"]) {
            test.fill(true);
            break;
        }
        if reads(&tokens, i, &["#", "[", "cfg", "(", "test", ")", "]"]) {
            let end = item_end(&tokens, i + 7);
            test[i..end].fill(true);
            i = end;
        } else {
            i += 1;
        }
    }
    let children = (0..tokens.len())
        .filter(|&k| reads(&tokens, k, &["mod"]) && reads(&tokens, k + 2, &[";"]))
        .map(|k| (tokens[k + 1].text.clone(), test[k]))
        .collect();
    Scanned {
        tokens,
        test,
        children,
    }
}

/// Where a path from the crate root leads.
#[derive(Debug, PartialEq)]
enum Target {
    /// A top-level module.
    Module(String),
    /// A name neither a top-level module nor re-exported at the root.
    Unknown(String),
}

/// What a path from the crate root can start with: the top-level modules (each leading to
/// itself) and the names lib.rs re-exports (each leading to its module).
pub(super) struct Root {
    pub names: BTreeMap<String, String>,
}

impl Root {
    /// Resolves the path that starts at `tokens[k]` (just past `crate::`), pushing where
    /// each of its branches leads, with its line.
    fn resolve(&self, tokens: &[Token], k: usize, out: &mut Vec<(usize, Target)>) {
        let Some(token) = tokens.get(k) else {
            return;
        };
        let line = token.line;
        match token.text.as_str() {
            "{" => {
                let close = closing_brace(tokens, k);
                let mut entry = k + 1;
                while entry < close {
                    if tokens[entry].text != "self" {
                        self.resolve(tokens, entry, out);
                    }
                    entry = next_entry(tokens, entry, close);
                }
            }
            "prelude" if reads(tokens, k + 1, &[":", ":"]) => self.resolve(tokens, k + 3, out),
            name => match self.names.get(name) {
                Some(module) => out.push((line, Target::Module(module.clone()))),
                None => out.push((line, Target::Unknown(name.to_string()))),
            },
        }
    }

    /// Where each path from the crate root in the code of `scanned` (test code left out)
    /// leads, with its line.
    fn uses(&self, scanned: &Scanned) -> Vec<(usize, Target)> {
        let mut out = Vec::new();
        let tokens = &scanned.tokens;
        for (k, &test) in scanned.test.iter().enumerate() {
            if !test && reads(tokens, k, &["crate", ":", ":"]) {
                self.resolve(tokens, k + 3, &mut out);
            }
        }
        out
    }
}

/// The top-level modules lib.rs declares (each with whether it is test code), and the root
/// that its re-exports make.
pub(super) fn read_lib(lib: &str) -> (Vec<(String, bool)>, Root) {
    let scanned = scan(lib);
    let modules = scanned.children.clone();
    let mut names: BTreeMap<String, String> = modules
        .iter()
        .map(|(module, _)| (module.clone(), module.clone()))
        .collect();
    let tokens = &scanned.tokens;
    let mut depth = 0;
    for (k, token) in tokens.iter().enumerate() {
        match token.text.as_str() {
            "{" => depth += 1,
            "}" => depth -= 1,
            _ => {}
        }
        if depth != 0 || scanned.test[k] || !reads(tokens, k, &["pub", "use"]) {
            continue;
        }
        let module = tokens[k + 2].text.clone();
        if !modules.iter().any(|(name, _)| *name == module) {
            continue;
        }
        // The last word of each path in the re-export (`a as b` names `b`).
        let end = (k..tokens.len())
            .find(|&e| tokens[e].text == ";")
            .unwrap_or(tokens.len());
        for e in k + 3..end {
            let next = tokens.get(e + 1).map_or("", |t| t.text.as_str());
            let word = &tokens[e].text;
            if matches!(next, "," | "}" | ";") && word.starts_with(is_ident_char) && word != "self"
            {
                names.insert(word.clone(), module.clone());
            }
        }
    }
    (modules, Root { names })
}

/// The folder that the modules `file` declares live in.
pub(super) fn children_folder(file: &Path) -> PathBuf {
    let parent = file.parent().expect("a file in src/");
    match file.file_stem().and_then(|stem| stem.to_str()) {
        Some("mod" | "lib") => parent.to_path_buf(),
        Some(stem) => parent.join(stem),
        None => unreachable!("{} has a name", file.display()),
    }
}

/// The file of module `name` declared in `folder`.
pub(super) fn module_file(folder: &Path, name: &str) -> PathBuf {
    let flat = folder.join(format!("{name}.rs"));
    let nested = folder.join(name).join("mod.rs");
    if flat.exists() {
        flat
    } else {
        assert!(
            nested.exists(),
            "no file for module {name} in {}",
            folder.display()
        );
        nested
    }
}

/// The files of a top-level module that are not test code, from its own file down, each
/// with its scan.
fn module_files(src: &Path, module: &str) -> Vec<(PathBuf, Scanned)> {
    let mut files = Vec::new();
    let mut pending = vec![module_file(src, module)];
    while let Some(file) = pending.pop() {
        let (scanned, children) = scan_file(&file);
        pending.extend(children.into_iter().map(|(_, child)| child));
        files.push((file, scanned));
    }
    files
}

/// `file`'s scan, and each of its child modules that is not test code: its name and file.
pub(super) fn scan_file(file: &Path) -> (Scanned, Vec<(String, PathBuf)>) {
    let source = fs::read_to_string(file)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", file.display()));
    let scanned = scan(&source);
    let folder = children_folder(file);
    let children = scanned
        .children
        .iter()
        .filter(|(_, test)| !test)
        .map(|(child, _)| (child.clone(), module_file(&folder, child)))
        .collect();
    (scanned, children)
}

/// The message for a use of `target` by `module` in `file` at `line`, if it breaks the
/// layering.
fn violation(file: &str, line: usize, module: &str, target: &str) -> Option<String> {
    let (layer, layer_name) = layer_of(module)?;
    let (target_layer, target_layer_name) = layer_of(target)?;
    (module != target && target_layer >= layer).then(|| {
        format!(
            "{file}:{line}: `{module}` (layer {layer}, {layer_name}) uses `{target}` (layer \
             {target_layer}, {target_layer_name}), which is not below it; see \"## Layers\" in \
             src/lib.rs"
        )
    })
}

pub(super) fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

pub(super) fn lib_source() -> String {
    fs::read_to_string(src().join("lib.rs")).expect("src/lib.rs")
}

#[test]
fn every_module_uses_only_modules_of_lower_layers() {
    let src = src();
    let (modules, root) = read_lib(&lib_source());
    let mut problems = Vec::new();
    for (module, test) in &modules {
        if *test {
            continue;
        }
        for (file, scanned) in module_files(&src, module) {
            let shown = file.strip_prefix(src.parent().unwrap()).unwrap_or(&file);
            let shown = shown.display().to_string();
            for (line, target) in root.uses(&scanned) {
                match target {
                    Target::Module(target) => {
                        problems.extend(violation(&shown, line, module, &target));
                    }
                    Target::Unknown(name) => problems.push(format!(
                        "{shown}:{line}: the path from the crate root through `{name}` leads to \
                         no module that lib.rs declares or re-exports from"
                    )),
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "imports that break the layering:\n{}",
        problems.join("\n")
    );
}

#[test]
fn every_module_has_one_layer() {
    let (modules, _) = read_lib(&lib_source());
    let declared: Vec<&str> = modules
        .iter()
        .filter(|(_, test)| !test)
        .map(|(module, _)| module.as_str())
        .collect();
    for module in &declared {
        let layers = LAYERS
            .iter()
            .filter(|(_, modules)| modules.contains(module))
            .count();
        assert_eq!(
            layers, 1,
            "`{module}` is in {layers} layers of LAYERS, not one"
        );
    }
    for (_, layer) in LAYERS {
        for module in *layer {
            assert!(
                declared.contains(module),
                "LAYERS names `{module}`, which lib.rs does not declare (outside tests)"
            );
        }
    }
}

#[test]
fn the_layers_are_those_lib_rs_states() {
    let lib = lib_source();
    let (modules, _) = read_lib(&lib);
    let section: Vec<&str> = lib
        .lines()
        .map_while(|line| line.strip_prefix("//!"))
        .skip_while(|line| line.trim() != "## Layers")
        .skip(1)
        .take_while(|line| !line.trim_start().starts_with("## "))
        .collect();
    // The numbered items, each with its continuation lines.
    let mut items: Vec<String> = Vec::new();
    for line in section {
        let line = line.trim();
        let numbered = line
            .split_once(". ")
            .is_some_and(|(number, _)| number.parse::<usize>().is_ok());
        if numbered {
            items.push(line.to_string());
        } else if line.is_empty() {
            // Past the last item, only prose.
            if !items.is_empty() {
                break;
            }
        } else if let Some(item) = items.last_mut() {
            item.push(' ');
            item.push_str(line);
        }
    }
    assert_eq!(
        items.len(),
        LAYERS.len(),
        "lib.rs lists {} layers, LAYERS {}",
        items.len(),
        LAYERS.len()
    );
    for (item, (name, layer)) in items.iter().zip(LAYERS) {
        let named: Vec<&str> = item
            .split('`')
            .skip(1)
            .step_by(2)
            .filter(|word| modules.iter().any(|(module, _)| module == word))
            .collect();
        let mut expected = layer.to_vec();
        let mut named_sorted = named.clone();
        expected.sort_unstable();
        named_sorted.sort_unstable();
        named_sorted.dedup();
        assert_eq!(
            named_sorted, expected,
            "lib.rs's layer \"{item}\" names other modules than LAYERS' \"{name}\""
        );
    }
}

/// The scanner reads groups, root names and spacing, and skips comments, literals and test
/// code. (The paths are put together at run time, so that tools that grep the sources for
/// paths from the crate root find none here.)
#[test]
fn the_scanner_finds_paths_and_skips_comments_literals_and_tests() {
    let root = "crate";
    let source = format!(
        "use {root}::{{lights::{{A, B}}, limits, prelude::Decay, PhongPlugin as P}};\n\
         // use {root}::render::X;\n\
         /* use {root}::shadows::X; */\n\
         const S: &str = \"{root}::scene\";\n\
         const R: &str = r#\"{root}::\"gltf\"#;\n\
         const C: char = '\\'';\n\
         fn f<'a>(x: &'a u8) -> &'a u8 {{ {root} :: material :: g(x) }}\n\
         pub({root}) fn h() {{}}\n\
         #[cfg(test)]\n\
         mod tests {{ use {root}::plugin::Q; }}\n\
         #[cfg(test)]\n\
         mod range_tests;\n\
         mod gather;\n\
         fn k() {{ {root}::nowhere::f() }}\n"
    );
    let root_names = Root {
        names: [
            ("lights", "lights"),
            ("limits", "limits"),
            ("material", "material"),
            ("Decay", "lights"),
            ("PhongPlugin", "plugin"),
        ]
        .into_iter()
        .map(|(name, module)| (name.to_string(), module.to_string()))
        .collect(),
    };
    let scanned = scan(&source);
    let module = |name: &str| Target::Module(name.to_string());
    assert_eq!(
        root_names.uses(&scanned),
        [
            (1, module("lights")),
            (1, module("limits")),
            (1, module("lights")),
            (1, module("plugin")),
            (7, module("material")),
            (14, Target::Unknown("nowhere".to_string())),
        ]
    );
    // `mod tests { .. }` is inline: no file of its own.
    assert_eq!(
        scanned.children,
        [
            ("range_tests".to_string(), true),
            ("gather".to_string(), false),
        ]
    );
}

#[test]
fn an_import_of_an_equal_or_higher_layer_is_reported_with_both_layers() {
    assert_eq!(
        violation("src/lights/lit.rs", 3, "lights", "render").as_deref(),
        Some(
            "src/lights/lit.rs:3: `lights` (layer 2, the data model) uses `render` (layer 6, \
             gather and bindings), which is not below it; see \"## Layers\" in src/lib.rs"
        )
    );
    assert!(violation("x.rs", 1, "validation", "reference").is_some());
    assert_eq!(violation("x.rs", 1, "render", "shadows"), None);
    assert_eq!(violation("x.rs", 1, "render", "render"), None);
}
