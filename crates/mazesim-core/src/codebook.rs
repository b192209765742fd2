//! Barcode code books (report section 4.2): each checkpoint gets a code that is not a palindrome
//! and whose reverse is no checkpoint's code, so one reading tells both the checkpoint and the
//! direction it was crossed in.

use crate::error::{Error, Result};

/// The default five-bit book: one code of each of the 12 pairs of non-palindromic codes and their
/// reverses, in a fixed order (checkpoint k gets the k-th code). The lower of each pair is kept.
pub fn default_codes() -> Vec<String> {
    let mut out = Vec::new();
    for v in 0u32..32 {
        let code = format!("{v:05b}");
        let rev: String = code.chars().rev().collect();
        if code != rev && code < rev {
            out.push(code);
        }
    }
    out
}

/// Most codes in a book (a book of 12-bit codes has fewer than 2,048 usable ones).
pub const MAX_CODES: usize = 4096;

/// Checks a code book (at most [`MAX_CODES`] codes): codes of 0/1 of one length, no palindrome, no duplicate, and no code whose
/// reverse is another code of the book.
pub fn validate(codes: &[String]) -> Result<()> {
    let bad = |msg: String| Err(Error::InvalidArgument(msg));
    if codes.len() > MAX_CODES {
        return bad(format!(
            "expected a book of at most {MAX_CODES} codes, found {}",
            codes.len()
        ));
    }
    for (i, c) in codes.iter().enumerate() {
        if c.is_empty() || !c.chars().all(|b| b == '0' || b == '1') {
            return bad(format!(
                "code {i}: expected a string of 0 and 1, found {c:?}"
            ));
        }
        if c.len() != codes[0].len() {
            return bad(format!(
                "code {i}: expected {} bits like the first code, found {c:?}",
                codes[0].len()
            ));
        }
        let rev: String = c.chars().rev().collect();
        if rev == *c {
            return bad(format!(
                "code {i}: {c:?} is a palindrome, so its reading cannot tell the direction"
            ));
        }
        for (j, d) in codes.iter().enumerate().take(i) {
            if d == c {
                return bad(format!("code {i}: {c:?} is a duplicate of code {j}"));
            }
            if *d == rev {
                return bad(format!(
                    "code {i}: {c:?} read backwards is code {j} ({d:?}), so the two would be confused"
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_book_has_twelve_valid_codes() {
        let book = default_codes();
        assert_eq!(book.len(), 12);
        validate(&book).unwrap();
    }

    #[test]
    fn rejects_palindromes_duplicates_and_reverse_clashes() {
        let s = |v: &[&str]| v.iter().map(|c| c.to_string()).collect::<Vec<_>>();
        assert!(validate(&s(&["10101"]))
            .unwrap_err()
            .to_string()
            .contains("palindrome"));
        assert!(validate(&s(&["10110", "10110"]))
            .unwrap_err()
            .to_string()
            .contains("duplicate"));
        assert!(validate(&s(&["10110", "01101"]))
            .unwrap_err()
            .to_string()
            .contains("backwards"));
        assert!(validate(&s(&["10110", "1011"])).is_err());
        assert!(validate(&s(&["10x10"])).is_err());
    }
}
