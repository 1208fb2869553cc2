//! Spec errors: what is wrong, which key, and where.

use super::value::Span;
use std::fmt;

/// A problem with a spec: the message names the texture and key; `span` points at the offending
/// value (TOML byte range, or the macro's token) when known.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError {
    /// What is wrong, naming the key.
    pub message: String,
    /// The offending key (`dims`, `groups[1].sigma`, …), if any.
    pub key: Option<String>,
    /// Where the offending value is.
    pub span: Option<Span>,
}

impl SpecError {
    /// An error about `key` at `span`.
    pub fn at(key: impl Into<String>, span: Option<Span>, message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            key: Some(key.into()),
            span,
        }
    }

    /// An error not tied to a key.
    pub fn msg(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            key: None,
            span: None,
        }
    }

    /// Renders the error against a TOML file: `file:line:col: message` plus the source line.
    pub fn render(&self, file: &str, source: &str) -> String {
        match self.span {
            Some(span) if span.start <= source.len() => {
                let before = &source[..span.start];
                let line = before.matches('\n').count() + 1;
                let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
                let text = source.lines().nth(line - 1).unwrap_or("");
                // A long line is shown around the column, not whole.
                let chars: Vec<char> = text.chars().collect();
                let text = if chars.len() <= 2 * SHOWN_CHARS {
                    text.to_string()
                } else {
                    let at = before[before.rfind('\n').map_or(0, |i| i + 1)..]
                        .chars()
                        .count();
                    let from = at.saturating_sub(SHOWN_CHARS / 2);
                    let to = (from + 2 * SHOWN_CHARS).min(chars.len());
                    let head = if from > 0 { "…" } else { "" };
                    let tail = if to < chars.len() { "…" } else { "" };
                    format!("{head}{}{tail}", chars[from..to].iter().collect::<String>())
                };
                format!("{file}:{line}:{col}: {}\n    | {text}", self.message)
            }
            _ => format!("{file}: {}", self.message),
        }
    }
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SpecError {}

/// A number as an error message shows it: the shortest decimal that reads back as the same
/// `f64` when that is short, else scientific notation (`1e308`, never 309 digits).
#[derive(Clone, Copy, Debug)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plain = self.0.to_string();
        if plain.len() <= 16 {
            f.write_str(&plain)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Longest text an error message quotes from the user's input; longer text is cut.
pub const SHOWN_CHARS: usize = 40;

/// A user's text as an error message quotes it: whole when short, else its first
/// [`SHOWN_CHARS`] characters, `…` and its length (a 10 000-character value is not echoed).
#[derive(Clone, Copy, Debug)]
pub struct Shown<'a>(pub &'a str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let chars = self.0.chars().count();
        if chars <= SHOWN_CHARS {
            f.write_str(self.0)
        } else {
            let head: String = self.0.chars().take(SHOWN_CHARS).collect();
            write!(f, "{head}… ({chars} characters)")
        }
    }
}

/// The closest of `candidates` to `word` (Levenshtein distance ≤ max(2, len/3)), for "did you
/// mean" hints.
pub fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let limit = (word.len() / 3).max(2);
    candidates
        .iter()
        .filter(|c| **c != word)
        .map(|c| (levenshtein(word, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_near_misses_only() {
        assert_eq!(closest("sigam", &["sigma", "seed", "dims"]), Some("sigma"));
        assert_eq!(closest("dim", &["sigma", "seed", "dims"]), Some("dims"));
        assert_eq!(closest("colour_space", &["sigma", "seed", "dims"]), None);
    }

    #[test]
    fn renders_line_and_column() {
        let src = "a = 1\nsigma = -2\n";
        let e = SpecError::at("sigma", Some(Span { start: 14, end: 16 }), "bad");
        assert_eq!(
            e.render("noise.toml", src),
            "noise.toml:2:9: bad\n    | sigma = -2"
        );
    }
}
