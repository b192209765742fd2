//! Turning a byte offset in a TOML text into a line, a column and the field that sits there.

use crate::error::Error;

/// `offset` within `text`, moved back to the start of the character it falls in (a parser may
/// point inside a character of several bytes, such as the replacement of an invalid byte).
fn char_start(text: &str, offset: usize) -> usize {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// 1-based line and column of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = char_start(text, offset);
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

/// The dotted field path at `offset`: the enclosing `[table]` / `[[array]]` (with its index, and
/// its parent array's: `robots[0].carried[1]`), the key whose value holds `offset`, and the
/// place in that value's arrays (`table[2][0]` for an item of a multi-line array of rows), e.g.
/// `walls[2].size`. A line of a multi-line value that starts with `[` is part of the value,
/// not a table header.
pub fn field_at(text: &str, offset: usize) -> String {
    let offset = char_start(text, offset);
    let mut scan = FieldScan::default();
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    for line in text[..line_start].lines() {
        scan.line(line);
    }
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let header = text[line_start..line_end].trim();
    if scan.levels.is_empty() && header.starts_with('[') {
        // The error points at a table header itself (a missing field of that table).
        return scan.header_name(header, false);
    }
    if scan.levels.is_empty() {
        // The key is the line's, wherever on it the offset is; the value is read up to it.
        let line = &text[line_start..line_end];
        if let Some(equals) = line.find('=') {
            let key = line[..equals].trim().trim_matches('"');
            scan.key = (!key.is_empty() && !key.contains(' ')).then(|| key.to_string());
            let value_start = line_start + equals + 1;
            if offset > value_start {
                scan.value(&text[value_start..offset]);
            }
        } else {
            scan.key = None;
        }
    } else {
        scan.value(&text[line_start..offset]);
    }
    let mut field = match (scan.table.clone(), scan.key.clone()) {
        (Some(t), Some(k)) => format!("{t}.{k}"),
        (Some(t), None) => t,
        (None, Some(k)) => k,
        (None, None) => "(top level)".to_string(),
    };
    for index in scan.levels.iter().flatten() {
        field.push_str(&format!("[{index}]"));
    }
    field
}

/// What [`field_at`] knows of the text before the offset, line by line.
#[derive(Default)]
struct FieldScan {
    /// The table the lines are in (`walls[2]`, `goal`), None at the top level.
    table: Option<String>,
    /// `[[name]]` arrays seen, by their full path, with how many entries each has so far.
    counts: std::collections::HashMap<String, usize>,
    /// The key whose value is being read (or the last key of the table).
    key: Option<String>,
    /// The open brackets of that value: the index of the item an array is at, None for an
    /// inline table.
    levels: Vec<Option<usize>>,
}

impl FieldScan {
    fn line(&mut self, line: &str) {
        let trimmed = line.trim();
        let mut value = line;
        if self.levels.is_empty() {
            if trimmed.starts_with('[') {
                self.table = Some(self.header_name(trimmed, true));
                self.key = None;
                return;
            }
            match line.split_once('=') {
                Some((key, rest)) => {
                    let key = key.trim().trim_matches('"');
                    self.key = (!key.is_empty() && !key.contains(' ')).then(|| key.to_string());
                    value = rest;
                }
                None => return,
            }
        }
        self.value(value);
    }

    /// The brackets of (part of) a value: strings and comments skipped.
    fn value(&mut self, text: &str) {
        let mut quote: Option<char> = None;
        let mut escaped = false;
        for c in text.chars() {
            if let Some(q) = quote {
                if escaped {
                    escaped = false;
                } else if c == '\\' && q == '"' {
                    escaped = true;
                } else if c == q {
                    quote = None;
                }
                continue;
            }
            match c {
                '"' | '\'' => quote = Some(c),
                '#' => return,
                '[' => self.levels.push(Some(0)),
                '{' => self.levels.push(None),
                ']' | '}' => {
                    self.levels.pop();
                }
                ',' => {
                    if let Some(Some(index)) = self.levels.last_mut() {
                        *index += 1;
                    }
                }
                _ => {}
            }
        }
    }

    /// The path of a `[table]` or `[[array]]` header (`robots[0].carried[1]`), counting an
    /// array's entry when `count`.
    fn header_name(&mut self, header: &str, count: bool) -> String {
        let array = header.starts_with("[[");
        let name = header
            .trim_start_matches('[')
            .split(']')
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        // A table under an array of tables is under its last entry.
        let mut path = String::new();
        for part in name.split('.') {
            if !path.is_empty() {
                path.push('.');
            }
            path.push_str(part.trim());
            if let Some(&n) = self.counts.get(&path) {
                if path.len() < name.len() || !array {
                    path = format!("{path}[{}]", n.saturating_sub(1));
                }
            }
        }
        if !array {
            return path;
        }
        let n = self.counts.get(&path).copied().unwrap_or(0);
        if count {
            self.counts.insert(path.clone(), n + 1);
        }
        format!("{path}[{n}]")
    }
}

/// A format error at byte `offset` of `text` read from `source`.
pub fn format_error(
    source: &str,
    text: &str,
    offset: usize,
    field: Option<&str>,
    message: impl Into<String>,
) -> Error {
    let (line, column) = line_column(text, offset);
    let field = field.map_or_else(|| field_at(text, offset), str::to_string);
    Error::format_at(source, line, column, field, message)
}

/// Converts a TOML reader error into a located format error.
///
/// An error about the document as a whole (a missing top-level field, whose span is empty at
/// the start or the whole text) is placed at the top level, not in the table that happens to stand first; a missing
/// `format` or `version` says which lines a world file starts with.
pub fn from_toml_error(source: &str, text: &str, err: &toml::de::Error) -> Error {
    let span = err.span();
    let offset = span.as_ref().map_or(0, |s| s.start);
    let mut message = in_plain_words(err.message().trim());
    if let Some(written) = span.as_ref().and_then(|s| text.get(s.clone())) {
        message = date_time_named(message, written.trim());
    }
    let whole = span
        .as_ref()
        .is_none_or(|s| s.start == 0 && (s.end == 0 || s.end >= text.trim_end().len()));
    if !whole {
        return format_error(source, text, offset, None, message);
    }
    if message.contains("`format`") || message.contains("`version`") {
        message.push_str(&format!(
            "; a world file starts with the two lines `format = \"{}\"` and `version = {}`",
            super::values::WORLD_FORMAT_TAG,
            super::values::WORLD_FORMAT_VERSION
        ));
    }
    format_error(source, text, offset, Some("(top level)"), message)
}

/// The reader's names of Rust's number types, and what a world file's author calls them.
const TYPE_WORDS: [(&str, &str); 12] = [
    ("f64", "a number"),
    ("f32", "a number"),
    ("i64", "a whole number"),
    ("i32", "a whole number"),
    ("i16", "a whole number"),
    ("i8", "a whole number"),
    ("u64", "a whole number, 0 or more"),
    ("u32", "a whole number, 0 or more"),
    ("u16", "a whole number, 0 or more"),
    ("u8", "a whole number, 0 or more"),
    ("usize", "a whole number, 0 or more"),
    ("isize", "a whole number"),
];

/// A TOML reader's message in the words of the package's others: a number type by what it
/// takes ("expected f64" is "expected a number"), and "invalid type: X, expected Y" as
/// "expected Y, found X", the order every message of mazesim has.
fn in_plain_words(message: &str) -> String {
    let mut text = message.to_string();
    for (rust, words) in TYPE_WORDS {
        let named = format!("expected {rust}");
        let mut from = 0;
        while let Some(found) = text[from..].find(&named) {
            let start = from + found;
            let end = start + named.len();
            let boundary = text[end..]
                .chars()
                .next()
                .is_none_or(|c| !c.is_alphanumeric() && c != '_');
            if boundary {
                text.replace_range(start..end, &format!("expected {words}"));
            }
            from = start + 1;
        }
    }
    for opening in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = text.strip_prefix(opening) {
            if let Some((found, expected)) = rest.rsplit_once(", expected ") {
                return format!("expected {expected}, found {found}");
            }
        }
    }
    text
}

/// A TOML date-time is read as a map: "found map" for one written where another type is
/// expected says "found the date-time `...`" instead.
fn date_time_named(message: String, written: &str) -> String {
    let date_like = written.chars().next().is_some_and(|c| c.is_ascii_digit())
        && written.len() <= 40
        && (written.contains('-') || written.contains(':'))
        && !written.contains(['{', '[', '"', '\'', '\n']);
    match message.strip_suffix("found map") {
        Some(before) if date_like => format!("{before}found the date-time `{written}`"),
        _ => message,
    }
}

/// Refuses a world text of more tables than a world within the limits has
/// (`MAX_WORLD_TABLES`), by counting its `{` and `[[` bytes before anything parses it: the
/// parser's time grows with the tables it reads, so a text of too many would be refused by the
/// count limits only after seconds of parsing. The error points at the first table past the
/// bound.
pub fn check_table_count(text: &str, source: &str) -> Result<(), Error> {
    let most = crate::limits::MAX_WORLD_TABLES;
    let bytes = text.as_bytes();
    let opens =
        |i: usize| bytes[i] == b'{' || (bytes[i] == b'[' && bytes.get(i + 1) == Some(&b'['));
    let mut found = 0usize;
    let mut first_past = None;
    for i in 0..bytes.len() {
        if opens(i) {
            found += 1;
            if found == most + 1 {
                first_past = Some(i);
            }
        }
    }
    let Some(offset) = first_past else {
        return Ok(());
    };
    Err(format_error(
        source,
        text,
        offset,
        Some("(file)"),
        format!(
            "expected a world text of at most {most} tables (`[[walls]]` headers and `{{ }}` \
             inline tables together: the walls, paint regions, checkpoints, bodies and robots a \
             world may have), found {found}"
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_item_of_a_multi_line_array_and_a_nested_array_of_tables_are_named_by_index() {
        // A row of a lookup table written one per line was named by its own text, taken for
        // a table header; `[[robots.carried]]` lost its robot's index.
        let text = "[models.ir]\nkind = \"ir\"\ntable = [\n  [0.0, 4095.0, 0.002],\n  \
                    [nan, 4095.0, 0.002], # \"a [b\"\n  [0.1, \"x\", 0.0],\n]\nnext = 1\n\
                    [[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\n[[robots.carried]]\n\
                    shape = \"disc\"\n";
        let cases = [
            ("nan", "models.ir.table[1][0]"),
            ("\"x\"", "models.ir.table[2][1]"),
            ("next", "models.ir.next"),
            ("shape", "robots[1].carried[0].shape"),
            ("name = \"b\"", "robots[1].name"),
        ];
        for (at, field) in cases {
            assert_eq!(field_at(text, text.find(at).unwrap()), field, "{at}");
        }
    }

    #[test]
    fn a_readers_type_names_are_said_in_words_expected_first() {
        let cases = [
            (
                "invalid type: string \"0.25\", expected f64",
                "expected a number, found string \"0.25\"",
            ),
            (
                "invalid type: floating point `1.0`, expected i64",
                "expected a whole number, found floating point `1.0`",
            ),
            (
                "invalid value: integer `-1`, expected u32",
                "expected a whole number, 0 or more, found integer `-1`",
            ),
            (
                "invalid type: integer `5`, expected a string",
                "expected a string, found integer `5`",
            ),
            (
                "unknown field `f64x`, expected f64x",
                "unknown field `f64x`, expected f64x",
            ),
        ];
        for (reader, said) in cases {
            assert_eq!(in_plain_words(reader), said);
        }
    }

    #[test]
    fn a_date_time_where_another_type_is_expected_is_named_as_written() {
        let text = "format = \"mazesim-world\"\nversion = 1\nname = 1979-05-27T07:32:00Z\n";
        let err = toml::from_str::<toml::Table>(text)
            .and_then(|_| toml::from_str::<NameOnly>(text))
            .unwrap_err();
        let said = from_toml_error("w.toml", text, &err).to_string();
        assert!(
            said.contains("found the date-time `1979-05-27T07:32:00Z`"),
            "{said}"
        );
        assert_eq!(
            date_time_named("expected a string, found map".into(), "{ a = 1 }"),
            "expected a string, found map"
        );
    }

    #[derive(serde::Deserialize, Debug)]
    #[allow(dead_code)]
    struct NameOnly {
        name: String,
    }

    #[test]
    fn a_text_of_more_tables_than_a_world_may_have_is_refused_before_parsing() {
        let most = crate::limits::MAX_WORLD_TABLES;
        let walls = "{ center = [0.0, 0.0], size = [0.1, 0.1] },\n".repeat(most);
        let at_bound = format!("walls = [\n{walls}]\n");
        assert!(check_table_count(&at_bound, "w.toml").is_ok());
        let past = format!("walls = [\n{walls}{{ }},\n[[x]]\n]\n");
        let Err(Error::Format {
            location, message, ..
        }) = check_table_count(&past, "w.toml")
        else {
            panic!("refused")
        };
        assert_eq!(location.line, most + 2, "{message}");
        assert!(
            message.contains(&format!("at most {most} tables")),
            "{message}"
        );
        assert!(
            message.contains(&format!("found {}", most + 2)),
            "{message}"
        );
    }

    #[test]
    fn finds_lines_columns_and_fields() {
        let text = "a = 1\n[[walls]]\nsize = 2\n[[walls]]\ncenter = 3\n[goal]\nradius = 4\n";
        assert_eq!(line_column(text, 0), (1, 1));
        let off = text.find("center").unwrap();
        assert_eq!(line_column(text, off + 2), (5, 3));
        assert_eq!(field_at(text, off), "walls[1].center");
        assert_eq!(field_at(text, text.find("size").unwrap()), "walls[0].size");
        assert_eq!(field_at(text, text.find("radius").unwrap()), "goal.radius");
        assert_eq!(field_at(text, 0), "a");
    }

    #[test]
    fn issue_35_an_offset_inside_a_character_points_at_its_start() {
        // The reader's error span may start inside the replacement of an invalid byte.
        let text = "[goal]\nname = \"\u{FFFD}x\"\n";
        let inside = text.find('\u{FFFD}').unwrap() + 2;
        assert_eq!(line_column(text, inside), (2, 9));
        assert_eq!(field_at(text, inside), "goal.name");
    }
}
