//! Mutations of a scene or material file's text: blind byte edits, and edits that know the
//! format (numbers, variant names, nesting, strings, encodings, paths).

use crate::random::Random;

/// Numbers that stress every float and integer a file holds.
const HOSTILE_NUMBERS: &[&str] = &[
    "NaN",
    "inf",
    "-inf",
    "0.0",
    "-0.0",
    "1e38",
    "-1e38",
    "3.4028235e38",
    "2e38",
    "1e-45",
    "-1e-45",
    "1e-30",
    "1e30",
    "1e400",
    "-1e400",
    "1e9",
    "180.0",
    "-1.0",
    "99999999999999999999999999999999999999999",
    "18446744073709551616",
    "0",
    "1",
];

/// Variant and keyword names of the formats, swapped for one another.
const NAMES: &[&str] = &[
    "Sphere",
    "Cuboid",
    "Plane",
    "Torus",
    "Cylinder",
    "Capsule",
    "Cone",
    "Directional",
    "Point",
    "Spot",
    "Srgb",
    "Srgba",
    "Linear",
    "Hex",
    "Inline",
    "File",
    "Some",
    "None",
    "Phong",
    "BlinnPhong",
    "Opaque",
    "Mask",
    "Blend",
    "true",
    "false",
];

/// Paths that climb out of the asset folder, are absolute, name another source, a folder,
/// nothing or the file itself (`{self}`), or are merely odd.
pub const HOSTILE_PATHS: &[&str] = &[
    "../../canary.phong.ron",
    "../canary.phong.ron",
    "../../../../../../etc/passwd",
    "../scenes/../../canary.phong.ron",
    "..\\..\\canary.phong.ron",
    "/etc/passwd",
    "{absolute canary}",
    "other://canary.phong.ron",
    "embedded://bevy_phong/shaders/types.wesl",
    "file:///etc/passwd",
    "C:\\Windows\\win.ini",
    "",
    ".",
    "..",
    "./",
    "../",
    "../materials/",
    "../materials",
    "{self}",
    "#object0/material",
    "#",
    "a#b#c",
    "x\u{0}y.png",
    "~/canary.phong.ron",
    "%2e%2e/%2e%2e/canary.phong.ron",
    "brass.phong.ron",
    "../materials/brass.phong.ron",
    "missing.png",
    "../materials/brass.phong.ron.png",
    "{long}",
];

/// A few blind edits of random bytes: flips, overwrites, insertions of format characters,
/// deletions, duplications, truncation.
pub fn bytes(random: &mut Random, seed: &[u8]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..1 + random.below(8) {
        if bytes.is_empty() {
            bytes.push(b'(');
        }
        let at = random.below(bytes.len());
        match random.below(6) {
            0 => bytes[at] ^= 1 << random.below(8),
            1 => bytes[at] = random.next_u64() as u8,
            2 => {
                let inserted = *random.pick(b"()[],:.\"#-+0123456789eE \n\\/");
                bytes.insert(at, inserted);
            }
            3 => {
                let end = (at + 1 + random.below(16)).min(bytes.len());
                bytes.drain(at..end);
            }
            4 => {
                let end = (at + 1 + random.below(64)).min(bytes.len());
                let copy = bytes[at..end].to_vec();
                let to = random.below(bytes.len());
                bytes.splice(to..to, copy);
            }
            _ => bytes.truncate(at),
        }
    }
    bytes
}

/// The byte ranges of the numbers in `text`.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut index = 0;
    while index < bytes.len() {
        let starts = bytes[index].is_ascii_digit()
            || (bytes[index] == b'-' && bytes.get(index + 1).is_some_and(u8::is_ascii_digit));
        let after_word = index > 0 && (bytes[index - 1].is_ascii_alphanumeric());
        if starts && !after_word {
            let start = index;
            index += 1;
            while index < bytes.len()
                && (bytes[index].is_ascii_digit()
                    || matches!(bytes[index], b'.' | b'e' | b'E')
                    || (matches!(bytes[index], b'-' | b'+')
                        && matches!(bytes[index - 1], b'e' | b'E')))
            {
                index += 1;
            }
            spans.push((start, index));
        } else {
            index += 1;
        }
    }
    spans
}

/// Replaces `spans` of `text` (sorted, not overlapping) by what `with` gives for each.
fn replace_spans(text: &str, spans: &[(usize, usize)], mut with: impl FnMut() -> String) -> String {
    let mut out = String::with_capacity(text.len());
    let mut last = 0;
    for &(start, end) in spans {
        out.push_str(&text[last..start]);
        out.push_str(&with());
        last = end;
    }
    out.push_str(&text[last..]);
    out
}

/// Replaces one, a few or all numbers by NaN, ±∞, ±0, 1e38, 1e-45, huge integers and the
/// like.
pub fn numbers_replaced(random: &mut Random, text: &str) -> String {
    let spans = numbers(text);
    if spans.is_empty() {
        return text.to_owned();
    }
    let chosen: Vec<_> = if random.one_in(6) {
        spans
    } else {
        let mut chosen: Vec<_> = (0..1 + random.below(3))
            .map(|_| spans[random.below(spans.len())])
            .collect();
        chosen.sort();
        chosen.dedup();
        chosen
    };
    replace_spans(text, &chosen, || random.pick(HOSTILE_NUMBERS).to_string())
}

/// Swaps one variant or keyword name for another.
pub fn variant_swapped(random: &mut Random, text: &str) -> String {
    let found: Vec<(usize, usize)> = NAMES
        .iter()
        .flat_map(|name| {
            text.match_indices(name).filter_map(|(at, _)| {
                let before = text[..at].chars().next_back();
                let after = text[at + name.len()..].chars().next();
                let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
                (!word(before) && !word(after)).then_some((at, at + name.len()))
            })
        })
        .collect();
    if found.is_empty() {
        return text.to_owned();
    }
    let span = found[random.below(found.len())];
    replace_spans(text, &[span], || random.pick(NAMES).to_string())
}

/// Opens (and sometimes closes) many brackets at a bracket of the text.
pub fn nested(random: &mut Random, text: &str) -> Vec<u8> {
    let depth = *random.pick(&[64, 200, 10_000, 100_000, 1_000_000]);
    let (open, close) = *random.pick(&[("(", ")"), ("[", "]"), ("Some(", ")"), ("((", "))")]);
    let positions: Vec<usize> = text.match_indices(['(', '[']).map(|(at, _)| at).collect();
    let at = positions
        .get(random.below(positions.len().max(1)))
        .copied()
        .unwrap_or(0);
    let mut out = text[..at].to_owned();
    out.push_str(&open.repeat(depth));
    if random.one_in(2) {
        out.push_str("1.0");
        out.push_str(&close.repeat(depth));
    }
    out.push_str(&text[at..]);
    out.into_bytes()
}

/// The byte ranges of the string literals' contents in `text`.
fn strings(text: &str) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut chars = text.char_indices();
    while let Some((index, c)) = chars.next() {
        if c != '"' {
            continue;
        }
        let start = index + 1;
        let mut escaped = false;
        for (end, c) in chars.by_ref() {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                spans.push((start, end));
                break;
            }
        }
    }
    spans
}

/// Makes a string (or, where there is none, a hex color) very long.
pub fn long_string(random: &mut Random, text: &str) -> String {
    let length = *random.pick(&[1_000, 100_000, 1_000_000]);
    let long = match random.below(3) {
        0 => format!("#{}", "f".repeat(length)),
        1 => "é".repeat(length),
        _ => "../".repeat(length / 3),
    };
    let spans = strings(text);
    if spans.is_empty() || random.one_in(3) {
        let colors: Vec<usize> = text.match_indices("Srgb(").map(|(at, _)| at).collect();
        if let Some(&at) = colors.get(random.below(colors.len().max(1))) {
            let end = at + text[at..].find(')').unwrap_or(0) + 1;
            return format!("{}Hex({long:?}){}", &text[..at], &text[end..]);
        }
        return text.to_owned();
    }
    let span = spans[random.below(spans.len())];
    replace_spans(text, &[span], || long.clone())
}

/// Puts bytes that are not UTF-8 into the text, most often inside a string.
pub fn not_utf8(random: &mut Random, text: &str) -> Vec<u8> {
    let invalid: &[&[u8]] = &[
        b"\xff",
        b"\xfe\xff",
        b"\xc3",
        b"\xed\xa0\x80",
        b"\xf8\x88\x80\x80\x80",
        b"\x80",
    ];
    let spans = strings(text);
    let at = if !spans.is_empty() && random.one_in(2) {
        spans[random.below(spans.len())].0
    } else {
        random.below(text.len().max(1)).min(text.len())
    };
    let mut bytes = text.as_bytes().to_vec();
    bytes.splice(at..at, random.pick(invalid).iter().copied());
    bytes
}

/// Replaces a path (a material `File` or a texture) by a hostile one; where the file has
/// no path, adds a texture or material file that names one. `self_name` is the file's own
/// name, `canary` the absolute path of the canary outside the asset folder.
pub fn path_replaced(random: &mut Random, text: &str, self_name: &str, canary: &str) -> String {
    let path = match *random.pick(HOSTILE_PATHS) {
        "{self}" => self_name.to_owned(),
        "{absolute canary}" => canary.to_owned(),
        "{long}" => "a/".repeat(600),
        path => path.to_owned(),
    };
    let quoted = format!("{path:?}");
    let holders: Vec<usize> = ["File(", "_texture: Some("]
        .iter()
        .flat_map(|holder| text.match_indices(holder).map(|(at, h)| at + h.len()))
        .collect();
    if let Some(&at) = holders.get(random.below(holders.len().max(1))) {
        let end = at + text[at..].find(')').unwrap_or(0);
        return format!("{}{quoted}{}", &text[..at], &text[end..]);
    }
    // No path yet: name one at the start of the outermost parentheses.
    let field = if text.contains("objects") {
        format!("objects: [(mesh: Sphere(radius: 1.0), material: File({quoted}))], ")
    } else {
        format!("base_color_texture: Some({quoted}), ")
    };
    match text.find('(') {
        Some(at) if !text.contains("objects") => {
            format!("{}{field}{}", &text[..=at], &text[at + 1..])
        }
        _ => format!("({field})"),
    }
}
