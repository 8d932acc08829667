//! Errors in problem files: each names the file, the key path, where it is and what is wrong.

use std::fmt;
use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// A rejected problem file, or a rejected design or option given with it.
#[derive(Debug, Clone, PartialEq)]
pub struct ProblemError {
    pub file: PathBuf,
    /// The key path, as `variables[2].lower`; empty for the file as a whole.
    pub key: String,
    /// 1-based line and column, when the key is in the file.
    pub position: Option<(usize, usize)>,
    pub message: String,
}

impl fmt::Display for ProblemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, col)) = self.position {
            write!(f, ":{line}:{col}")?;
        }
        if !self.key.is_empty() {
            write!(f, ": key `{}`", printable(&self.key))?;
        }
        write!(f, ": {}", printable(&self.message))
    }
}

/// The most characters of a key or value from the input that a message repeats.
pub const ECHO_CHARS: usize = 60;

/// `text` as a terminal may show it: each control character escaped (a NUL byte reads
/// `\0`), and each quoted stretch (between `"` or backticks) and each unquoted word longer
/// than [`ECHO_CHARS`] characters cut there, with an ellipsis. Messages repeat the input's
/// keys and values, and a 900 kB key or a raw escape sequence is no help to anyone.
pub fn printable(text: &str) -> String {
    let mut out = String::with_capacity(text.len().min(4 * ECHO_CHARS));
    let mut open: Option<char> = None;
    let mut run = 0;
    for c in text.chars() {
        let quote = c == '"' || c == '`';
        let boundary = match open {
            Some(q) => c == q,
            None => quote || c.is_whitespace(),
        };
        if boundary {
            open = match open {
                Some(_) => None,
                None if quote => Some(c),
                None => None,
            };
            run = 0;
            out.push(c);
            continue;
        }
        run += 1;
        if run > ECHO_CHARS {
            if run == ECHO_CHARS + 1 {
                out.push('…');
            }
        } else if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    out
}

impl std::error::Error for ProblemError {}

/// A segment of a key path.
#[derive(Debug, Clone, PartialEq)]
pub enum Segment {
    Key(String),
    Index(usize),
}

/// Formats a key path as TOML readers write it: `variables[2].lower`.
pub fn format_path(path: &[Segment]) -> String {
    let mut s = String::new();
    for seg in path {
        match seg {
            Segment::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Segment::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Builds errors for one file and finds where its keys are.
pub struct Locator<'a> {
    file: PathBuf,
    text: &'a str,
    root: Option<Spanned<DeTable<'a>>>,
}

impl<'a> Locator<'a> {
    pub fn new(file: &Path, text: &'a str) -> Self {
        Locator {
            file: file.to_path_buf(),
            text,
            root: DeTable::parse(text).ok(),
        }
    }

    pub fn file(&self) -> &Path {
        &self.file
    }

    /// An error at `path` with `message`, positioned at the key's value when it is in the
    /// file, or at the nearest enclosing table otherwise.
    pub fn error(&self, path: &[Segment], message: impl Into<String>) -> ProblemError {
        ProblemError {
            file: self.file.clone(),
            key: format_path(path),
            position: self.span_of(path).map(|s| self.line_col(s)),
            message: message.into(),
        }
    }

    /// An error at a byte offset the parser gave.
    pub fn error_at(
        &self,
        key: String,
        span: Option<std::ops::Range<usize>>,
        message: String,
    ) -> ProblemError {
        ProblemError {
            file: self.file.clone(),
            key,
            position: span.map(|s| self.line_col(s.start)),
            message,
        }
    }

    fn span_of(&self, path: &[Segment]) -> Option<usize> {
        let root = self.root.as_ref()?;
        let mut best = None;
        let mut value: Option<&DeValue> = None;
        let mut table: Option<&DeTable> = Some(root.get_ref());
        for seg in path {
            let next = match (seg, table, value) {
                (Segment::Key(k), Some(t), _) => t
                    .iter()
                    .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                    .map(|(_, v)| v),
                (Segment::Index(i), _, Some(DeValue::Array(items))) => items.get(*i),
                _ => None,
            };
            let Some(next) = next else { break };
            best = Some(next.span().start);
            value = Some(next.get_ref());
            table = match next.get_ref() {
                DeValue::Table(t) => Some(t),
                _ => None,
            };
        }
        best
    }

    fn line_col(&self, offset: usize) -> (usize, usize) {
        let before = &self.text[..offset.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let col = before
            .rfind('\n')
            .map_or(before.len(), |nl| before.len() - nl - 1)
            + 1;
        (line, col)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_and_control_characters_are_not_echoed_raw() {
        let long = "k".repeat(900_000);
        let shown = printable(&format!("unknown field `{long}`, expected one of `name`"));
        assert_eq!(
            shown,
            format!(
                "unknown field `{}…`, expected one of `name`",
                "k".repeat(60)
            )
        );
        assert_eq!(
            printable("\"a\0b\u{1b}[31m\" cannot name a results folder"),
            "\"a\\0b\\u{1b}[31m\" cannot name a results folder"
        );
        let spaced = format!("\"{}\" is not a number", "a b ".repeat(100));
        assert_eq!(printable(&spaced).chars().count(), 60 + 2 + 1 + 16);
        // what is short passes unchanged
        let plain =
            "lower bound 25 is not below upper bound 20 (for a fixed variable write `value`)";
        assert_eq!(printable(plain), plain);
    }
}
