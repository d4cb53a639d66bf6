//! Values quoted in warnings and errors, cut to a readable length: a 50 MB string in a file
//! gives an error of one line, not one as large as the file.

/// The most characters of a value a message quotes; a longer value is cut there and
/// followed by its full length.
pub(crate) const MAX_QUOTED_CHARS: usize = 80;

/// `value` itself, or its first [`MAX_QUOTED_CHARS`] characters, `…` and its full length:
/// `#fffff…ff… (52,428,800 characters)`.
pub(crate) fn bounded(value: &str) -> String {
    match cut(value) {
        None => value.to_owned(),
        Some(head) => format!("{head}… ({} characters)", thousands(value.chars().count())),
    }
}

/// `value` in double quotes (escaped as Rust's `{:?}` does), cut as [`bounded`] cuts it:
/// `"#fffff…ff…" (52,428,800 characters)`.
#[cfg(feature = "scene")]
pub(crate) fn quoted(value: &str) -> String {
    match cut(value) {
        None => format!("{value:?}"),
        Some(head) => format!(
            "{:?} ({} characters)",
            format!("{head}…"),
            thousands(value.chars().count())
        ),
    }
}

/// `message` with every span between backticks or double quotes that is longer than
/// [`MAX_QUOTED_CHARS`] cut, its length named after it. RON's and serde's messages repeat
/// the offending text there (an unknown field's name, a string where a number belongs); a
/// quote that is never closed runs to the end of the message.
#[cfg(feature = "scene")]
pub(crate) fn shorten_quoted_spans(message: &str) -> String {
    let mut shortened = String::with_capacity(message.len().min(4 * 1024));
    let mut rest = message;
    while let Some(start) = rest.find(['`', '"']) {
        let delimiter = rest.as_bytes()[start] as char;
        shortened.push_str(&rest[..=start]);
        let after = &rest[start + 1..];
        let end = closing_delimiter(after, delimiter);
        let span = &after[..end.unwrap_or(after.len())];
        let head = cut(span);
        shortened.push_str(head.unwrap_or(span));
        if head.is_some() {
            shortened.push('…');
        }
        if end.is_some() {
            shortened.push(delimiter);
        }
        if head.is_some() {
            let length = thousands(span.chars().count());
            shortened.push_str(&format!(" ({length} characters)"));
        }
        let Some(end) = end else {
            return shortened;
        };
        rest = &after[end + 1..];
    }
    shortened.push_str(rest);
    shortened
}

/// The byte index of the `delimiter` that closes a span starting at `text`; inside double
/// quotes a backslash escapes the next character.
#[cfg(feature = "scene")]
fn closing_delimiter(text: &str, delimiter: char) -> Option<usize> {
    let mut escaped = false;
    for (index, character) in text.char_indices() {
        if escaped {
            escaped = false;
        } else if character == '\\' && delimiter == '"' {
            escaped = true;
        } else if character == delimiter {
            return Some(index);
        }
    }
    None
}

/// The first [`MAX_QUOTED_CHARS`] characters of `value`, or `None` if it is no longer.
fn cut(value: &str) -> Option<&str> {
    let (end, _) = value.char_indices().nth(MAX_QUOTED_CHARS)?;
    Some(&value[..end])
}

/// `52428800` as `52,428,800`.
fn thousands(count: usize) -> String {
    let digits = count.to_string();
    let mut grouped = String::with_capacity(digits.len() + digits.len() / 3);
    for (index, digit) in digits.chars().enumerate() {
        if index > 0 && (digits.len() - index).is_multiple_of(3) {
            grouped.push(',');
        }
        grouped.push(digit);
    }
    grouped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_value_is_quoted_whole() {
        assert_eq!(bounded("#ffcc00"), "#ffcc00");
        assert_eq!(quoted("#ffcc00"), "\"#ffcc00\"");
        assert_eq!(
            shorten_quoted_spans("named `x` in \"y\""),
            "named `x` in \"y\""
        );
    }

    #[test]
    fn a_long_value_is_cut_to_80_characters_and_names_its_length() {
        let long = "é".repeat(52_428_800 / 64);
        let quoted = quoted(&long);
        assert_eq!(
            quoted,
            format!("\"{}…\" (819,200 characters)", "é".repeat(80))
        );
        assert_eq!(thousands(52_428_800), "52,428,800");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1_000), "1,000");
    }

    #[test]
    fn long_spans_in_a_message_are_cut_and_the_rest_is_kept() {
        let name = "a".repeat(1_000);
        let message =
            format!("Unexpected field named `{name}` in `Scene`, invalid type: string \"{name}\"");
        let expected = format!(
            "Unexpected field named `{0}…` (1,000 characters) in `Scene`, invalid type: string \"{0}…\" (1,000 characters)",
            "a".repeat(80)
        );
        assert_eq!(shorten_quoted_spans(&message), expected);
        // An escaped quote does not end a span; an unclosed span runs to the end.
        assert_eq!(
            shorten_quoted_spans(&format!("string \"\\\"{name}")),
            format!("string \"\\\"{}… (1,002 characters)", "a".repeat(78))
        );
    }
}
