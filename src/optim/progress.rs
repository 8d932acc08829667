//! Progress of a multistart: a bar with the best objective so far and the time left on a
//! terminal; elsewhere (a log, CI), a line every few seconds once a run lasts that long.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

use super::problem::Solution;

/// The rank (smaller is better) and the text of a solution's objective, where it counts as
/// a result (a feasible end).
pub type Label<'a> = dyn Fn(&Solution) -> Option<(f64, String)> + Sync + 'a;

/// How often a progress line is written when stderr is no terminal.
const LINE_EVERY: Duration = Duration::from_secs(5);

/// Reports the progress of `total` local solves.
pub struct Progress<'a> {
    what: String,
    total: usize,
    bar: Option<ProgressBar>,
    /// Write lines (stderr is no terminal).
    lines: bool,
    label: &'a Label<'a>,
    state: Mutex<State>,
}

struct State {
    done: usize,
    best: Option<(f64, String)>,
    started: Instant,
    last_line: Instant,
}

impl<'a> Progress<'a> {
    /// Progress of `total` solves of `what` (`"local solves"`), labelled by `label`.
    pub fn new(what: &str, total: usize, label: &'a Label<'a>) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = terminal.then(|| {
            let bar = ProgressBar::new(total as u64);
            if let Ok(style) = ProgressStyle::with_template(
                "{bar:40} {pos}/{len} {prefix} {msg} ({elapsed}, about {eta} left)",
            ) {
                bar.set_style(style);
            }
            bar.set_prefix(what.to_string());
            bar
        });
        let now = Instant::now();
        Progress {
            what: what.to_string(),
            total,
            bar,
            lines: !terminal,
            label,
            state: Mutex::new(State {
                done: 0,
                best: None,
                started: now,
                last_line: now,
            }),
        }
    }

    /// One solve ended with `s`.
    pub fn record(&self, s: &Solution) {
        let label = (self.label)(s);
        let Ok(mut st) = self.state.lock() else {
            return;
        };
        st.done += 1;
        if let Some((rank, text)) = label {
            if st.best.as_ref().is_none_or(|(b, _)| rank < *b) {
                st.best = Some((rank, text));
                if let (Some(bar), Some((_, t))) = (&self.bar, &st.best) {
                    bar.set_message(format!(", best {t}"));
                }
            }
        }
        if let Some(bar) = &self.bar {
            bar.set_position(st.done as u64);
        } else if self.lines && st.last_line.elapsed() >= LINE_EVERY && st.done < self.total {
            st.last_line = Instant::now();
            let elapsed = st.started.elapsed().as_secs_f64();
            let left = elapsed / st.done as f64 * (self.total - st.done) as f64;
            let best = st
                .best
                .as_ref()
                .map_or("none feasible yet".to_string(), |(_, t)| {
                    format!("best {t}")
                });
            eprintln!(
                "{}/{} {}, {best}, {elapsed:.0} s, about {left:.0} s left",
                st.done, self.total, self.what
            );
        }
    }

    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
