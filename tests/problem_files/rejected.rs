//! Every problem file the reader's tests refuse, in one table (issue 27, item 8),
//! `refused.toml`: the reader must refuse each with its key and words
//! (`problem_errors.rs`), and the JSON Schema of `flexopt schema` must refuse each too
//! (`designer.rs`), but for the few whose `schema_cannot` says why it cannot.

use serde::Deserialize;

/// A problem file the reader refuses: a shipped file with some edits.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Refused {
    pub id: String,
    /// The shipped file the edits start from; empty for an empty text.
    pub file: String,
    /// In order: `from` replaced by `to` once (`from` must occur), or `to` appended where
    /// `from` is empty.
    pub edits: Vec<(String, String)>,
    /// The key the reader names, and words its message holds.
    pub key: String,
    pub words: Vec<String>,
    /// Why the JSON Schema cannot refuse it, where it cannot.
    pub schema_cannot: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    case: Vec<Refused>,
}

/// The table.
pub fn refused() -> Vec<Refused> {
    toml::from_str::<Table>(include_str!("refused.toml"))
        .expect("refused.toml reads")
        .case
}

impl Refused {
    /// The file's text with the edits made.
    pub fn text(&self) -> String {
        let mut text = if self.file.is_empty() {
            String::new()
        } else {
            std::fs::read_to_string(&self.file).unwrap()
        };
        for (from, to) in &self.edits {
            if from.is_empty() {
                text.push_str(to);
            } else {
                assert!(
                    text.contains(from.as_str()),
                    "{}: {from:?} not in {}",
                    self.id,
                    self.file
                );
                text = text.replacen(from.as_str(), to, 1);
            }
        }
        text
    }
}
