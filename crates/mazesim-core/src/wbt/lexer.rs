//! The tokens of a `.wbt` text (VRML97 syntax as Webots writes it): braces, brackets, numbers,
//! double-quoted strings and words. `#` starts a comment outside strings; commas are white space.
//! Lines end with `\n`, `\r\n` or a lone `\r`.

use crate::error::{Error, Result};

/// What a token is.
#[derive(Debug, Clone, PartialEq)]
pub enum TokenKind {
    /// `{`
    OpenBrace,
    /// `}`
    CloseBrace,
    /// `[`
    OpenBracket,
    /// `]`
    CloseBracket,
    /// A finite number (decimal, exponent or `0x` hexadecimal).
    Number(f64),
    /// A string with its escapes resolved.
    Str(String),
    /// A node type, field name, DEF name or keyword.
    Word(String),
    /// Text that starts as a number does but is no finite one (`1e400`, `1.2.3`): the parser
    /// refuses it, naming the field it stands in.
    NotANumber(String),
}

/// A token and where it starts (1-based line and column, columns counted in characters).
#[derive(Debug, Clone, PartialEq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Its line.
    pub line: usize,
    /// Its column.
    pub column: usize,
}

fn is_delimiter(c: char) -> bool {
    c.is_whitespace() || matches!(c, ',' | '"' | '#' | '{' | '}' | '[' | ']')
}

fn parse_number(text: &str) -> Option<f64> {
    let (negative, digits) = match text.as_bytes().first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    let hex = digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"));
    let value = match hex {
        Some(h) => i64::from_str_radix(h, 16).ok()? as f64,
        // Rust's parser also takes "inf" and "nan", which cannot start a number token here.
        None => digits.parse::<f64>().ok()?,
    };
    value
        .is_finite()
        .then_some(if negative { -value } else { value })
}

/// Splits `text` into tokens, skipping white space, commas and comments.
pub fn tokenize(text: &str, source: &str) -> Result<Vec<Token>> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let (mut i, mut line, mut column) = (0usize, 1usize, 1usize);
    while i < chars.len() {
        let c = chars[i];
        let (start_line, start_column) = (line, column);
        // `\n`, `\r\n` and a lone `\r` (old-Mac files) each end a line.
        if c == '\n' || (c == '\r' && chars.get(i + 1) != Some(&'\n')) {
            i += 1;
            line += 1;
            column = 1;
            continue;
        }
        if c.is_whitespace() || c == ',' || c == '\u{feff}' {
            i += 1;
            column += 1;
            continue;
        }
        if c == '#' {
            while i < chars.len() && chars[i] != '\n' && chars[i] != '\r' {
                i += 1;
                column += 1;
            }
            continue;
        }
        let single = match c {
            '{' => Some(TokenKind::OpenBrace),
            '}' => Some(TokenKind::CloseBrace),
            '[' => Some(TokenKind::OpenBracket),
            ']' => Some(TokenKind::CloseBracket),
            _ => None,
        };
        if let Some(kind) = single {
            tokens.push(Token { kind, line, column });
            i += 1;
            column += 1;
            continue;
        }
        if c == '"' {
            let mut value = String::new();
            i += 1;
            column += 1;
            loop {
                let Some(&d) = chars.get(i) else {
                    return Err(Error::format_at(
                        source,
                        start_line,
                        start_column,
                        "(string)",
                        "expected a closing `\"` for this string, found the end of the file",
                    ));
                };
                i += 1;
                column += 1;
                match d {
                    '"' => break,
                    '\\' if i < chars.len() => {
                        let escaped = chars[i];
                        i += 1;
                        column += 1;
                        if escaped == '\n' {
                            line += 1;
                            column = 1;
                        }
                        value.push(escaped);
                    }
                    '\n' => {
                        line += 1;
                        column = 1;
                        value.push('\n');
                    }
                    _ => value.push(d),
                }
            }
            tokens.push(Token {
                kind: TokenKind::Str(value),
                line: start_line,
                column: start_column,
            });
            continue;
        }
        if c.is_control() {
            return Err(Error::format_at(
                source,
                line,
                column,
                "(text)",
                format!(
                    "expected text, found the control character U+{:04X}",
                    c as u32
                ),
            ));
        }
        let begin = i;
        while i < chars.len() && !is_delimiter(chars[i]) && !chars[i].is_control() {
            i += 1;
            column += 1;
        }
        let word: String = chars[begin..i].iter().collect();
        let next = chars.get(begin + 1).copied().unwrap_or(' ');
        let numeric = c.is_ascii_digit()
            || (c == '.' && next.is_ascii_digit())
            || ((c == '-' || c == '+') && (next.is_ascii_digit() || next == '.'));
        let kind = if numeric {
            parse_number(&word).map_or(TokenKind::NotANumber(word), TokenKind::Number)
        } else {
            TokenKind::Word(word)
        };
        tokens.push(Token {
            kind,
            line: start_line,
            column: start_column,
        });
    }
    Ok(tokens)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<TokenKind> {
        tokenize(text, "t")
            .unwrap()
            .into_iter()
            .map(|t| t.kind)
            .collect()
    }

    #[test]
    fn reads_numbers_strings_words_and_skips_comments_and_commas() {
        use TokenKind::*;
        assert_eq!(
            kinds("Box { size 1, -.5 2e-3 0x1F } # note\n\"a \\\"b\\\"\" E-puck"),
            vec![
                Word("Box".into()),
                OpenBrace,
                Word("size".into()),
                Number(1.0),
                Number(-0.5),
                Number(0.002),
                Number(31.0),
                CloseBrace,
                Str("a \"b\"".into()),
                Word("E-puck".into()),
            ]
        );
    }

    #[test]
    fn positions_are_lines_and_columns() {
        let tokens = tokenize("a\n  \"x\ny\" b", "t").unwrap();
        assert_eq!((tokens[1].line, tokens[1].column), (2, 3));
        assert_eq!((tokens[2].line, tokens[2].column), (3, 4));
    }

    #[test]
    fn bad_numbers_are_tokens_and_open_strings_are_located() {
        let tokens = tokenize("size 1.2.3", "f.wbt").unwrap();
        assert_eq!(tokens[1].kind, TokenKind::NotANumber("1.2.3".into()));
        assert_eq!((tokens[1].line, tokens[1].column), (1, 6));
        let err = tokenize("x\n  \"open", "f.wbt").unwrap_err().to_string();
        assert!(err.starts_with("f.wbt:2:3:"), "{err}");
        let kind = &tokenize("1e999", "f").unwrap()[0].kind;
        assert_eq!(*kind, TokenKind::NotANumber("1e999".into()));
    }
}
