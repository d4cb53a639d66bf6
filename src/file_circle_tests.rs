//! No two files of src/ use each other: within a module, as between the layers
//! (`layering_tests`), each file's imports point one way, so that a reader can read the
//! files from the bottom up.
//!
//! Each file that is not test code is read with the layering test's scanner; every path from
//! the crate root or up from the file (`crate::a::b`, `super::b`, `self::c`, each entry of
//! a group) is a use of the file of the longest module path it names (a name that lib.rs
//! re-exports at the root, `crate::PhongPlugin`, a use of its top-level module). A file and
//! the files of its own submodules are exempt: a module declares its children and they may
//! use what it holds.

use super::layering_tests::{
    Root, Scanned, Token, closing_brace, lib_source, next_entry, read_lib, reads, scan, scan_file,
    src,
};
use std::{
    collections::{BTreeMap, BTreeSet},
    path::PathBuf,
};

/// A module's path from the crate root (`["render", "batching", "classes"]`).
type ModulePath = Vec<String>;

/// Every file of the crate that is not test code, by its module path, with its scan.
fn crate_files() -> BTreeMap<ModulePath, (PathBuf, Scanned)> {
    let mut files = BTreeMap::new();
    let mut pending = vec![(ModulePath::new(), src().join("lib.rs"))];
    while let Some((path, file)) = pending.pop() {
        let (scanned, children) = scan_file(&file);
        for (child, child_file) in children {
            let mut child_path = path.clone();
            child_path.push(child);
            pending.push((child_path, child_file));
        }
        files.insert(path, (file, scanned));
    }
    files
}

/// Pushes each path that starts at `tokens[k]`, after `prefix`: a word and `::` and what
/// follows, or a group `{a, b::c}` of paths.
fn paths_from(tokens: &[Token], k: usize, prefix: &[String], out: &mut Vec<ModulePath>) {
    let Some(token) = tokens.get(k) else {
        out.push(prefix.to_vec());
        return;
    };
    if token.text == "{" {
        let close = closing_brace(tokens, k);
        let mut entry = k + 1;
        while entry < close {
            paths_from(tokens, entry, prefix, out);
            entry = next_entry(tokens, entry, close);
        }
        return;
    }
    let mut path = prefix.to_vec();
    if token
        .text
        .starts_with(|c: char| c.is_alphanumeric() || c == '_')
    {
        path.push(token.text.clone());
        if reads(tokens, k + 1, &[":", ":"]) {
            paths_from(tokens, k + 3, &path, out);
            return;
        }
    }
    out.push(path);
}

/// The module paths that the code of the file of module `module` names (test code left
/// out): each path from the crate root, `super::` or `self::`, made absolute.
fn named_paths(module: &[String], scanned: &Scanned, root: &Root) -> Vec<ModulePath> {
    let tokens = &scanned.tokens;
    let mut out = Vec::new();
    for k in 0..tokens.len() {
        if scanned.test[k] || !reads(tokens, k + 1, &[":", ":"]) {
            continue;
        }
        // A path's first word: not the middle of another path.
        if k >= 2 && reads(tokens, k - 2, &[":", ":"]) {
            continue;
        }
        let mut start: ModulePath = match tokens[k].text.as_str() {
            "crate" => ModulePath::new(),
            "self" => module.to_vec(),
            "super" => module[..module.len().saturating_sub(1)].to_vec(),
            _ => continue,
        };
        let mut next = k + 3;
        // `super::super::`.
        while reads(tokens, next, &["super", ":", ":"]) {
            start.pop();
            next += 3;
        }
        let mut found = Vec::new();
        paths_from(tokens, next, &start, &mut found);
        for mut path in found {
            // A name that lib.rs re-exports at the root stands for its top-level module.
            if path.len() == 1
                && let Some(top) = root.names.get(&path[0])
            {
                path = vec![top.clone()];
            }
            out.push(path);
        }
    }
    out
}

/// The longest module of `files` that `path` names (the crate root at least).
fn file_of(path: &[String], files: &BTreeMap<ModulePath, (PathBuf, Scanned)>) -> ModulePath {
    (0..=path.len())
        .rev()
        .map(|length| path[..length].to_vec())
        .find(|prefix| files.contains_key(prefix))
        .unwrap_or_default()
}

/// The pairs of files that use each other, neither a submodule of the other, each pair
/// named once by its files.
fn circles() -> BTreeSet<(String, String)> {
    let files = crate_files();
    let (_, root) = read_lib(&lib_source());
    let uses: BTreeMap<&ModulePath, BTreeSet<ModulePath>> = files
        .iter()
        .map(|(module, (_, scanned))| {
            let used = named_paths(module, scanned, &root)
                .iter()
                .map(|path| file_of(path, &files))
                .filter(|used| used != module)
                .collect();
            (module, used)
        })
        .collect();
    let shown = |module: &ModulePath| {
        let file = &files[module].0;
        let src = src();
        file.strip_prefix(src.parent().unwrap_or(&src))
            .unwrap_or(file)
            .display()
            .to_string()
    };
    let mut pairs = BTreeSet::new();
    for (&module, used) in &uses {
        for other in used {
            let nested = module.starts_with(other) || other.starts_with(module);
            if !nested && uses.get(other).is_some_and(|back| back.contains(module)) {
                let (a, b) = (shown(module), shown(other));
                pairs.insert(if a < b { (a, b) } else { (b, a) });
            }
        }
    }
    pairs
}

#[test]
fn no_two_files_use_each_other() {
    let pairs = circles();
    assert!(
        pairs.is_empty(),
        "files that use each other (split each pair by what it owns):\n{}",
        pairs
            .iter()
            .map(|(a, b)| format!("{a} <-> {b}"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The scanner reads groups, `super::` and `self::` paths, and skips test code. (The paths
/// are put together at run time, so that tools that grep the sources find none here.)
#[test]
fn the_paths_of_a_file_are_read_from_the_root_and_up_from_it() {
    let (up, root) = ("super", "crate");
    let source = format!(
        "use {up}::{{records::{{A, B}}, slots}};\n\
         use {root}::render::gather::X;\n\
         fn f() {{ self::inner::g(); {up}::{up}::lights::h(); }}\n\
         #[cfg(test)]\n\
         mod tests {{ use {up}::classes::Q; }}\n"
    );
    let scanned = scan(&source);
    let module: ModulePath = ["render", "batching", "classes"].map(String::from).to_vec();
    let names = Root {
        names: BTreeMap::new(),
    };
    let path = |words: &[&str]| words.iter().map(|w| w.to_string()).collect::<ModulePath>();
    assert_eq!(
        named_paths(&module, &scanned, &names),
        [
            path(&["render", "batching", "records", "A"]),
            path(&["render", "batching", "records", "B"]),
            path(&["render", "batching", "slots"]),
            path(&["render", "gather", "X"]),
            path(&["render", "batching", "classes", "inner", "g"]),
            path(&["render", "lights", "h"]),
        ]
    );
}
