//! The command line's one error type, carrying the exit code, and its one way to print.

use std::fmt::Display;

/// Why the command stopped: the message to print and the exit code.
pub struct Failure {
    pub code: u8,
    pub message: String,
}

impl Failure {
    /// Exit code 2: a rejected problem file, design or option.
    pub fn bad_input(e: impl Display) -> Self {
        Failure {
            code: 2,
            message: e.to_string(),
        }
    }

    /// Exit code 1: results that could not be written or printed.
    pub fn write_failed(e: impl Display) -> Self {
        Failure {
            code: 1,
            message: e.to_string(),
        }
    }

    /// Exit code 130, the shell's for an interrupt: the run was stopped by Ctrl-C.
    pub fn interrupted(e: impl Display) -> Self {
        Failure {
            code: 130,
            message: e.to_string(),
        }
    }

    /// Exit code 5: a part that cannot be made with the problem's `[part]` sizes.
    pub fn cannot_be_made(e: impl Display) -> Self {
        Failure {
            code: 5,
            message: e.to_string(),
        }
    }

    /// Exit code 3: no feasible design; the results were written all the same. (Exit code
    /// 4, a feasible design that did not converge, is built where it arises.)
    pub fn no_feasible(e: impl Display) -> Self {
        Failure {
            code: 3,
            message: e.to_string(),
        }
    }
}

/// Writes `text` to standard output, whole, or says why it could not: a full disk, a closed
/// pipe or `/dev/full` end the command with exit code 1, never with 0 and never with a panic,
/// so that a script never takes a cut-off result for a whole one.
pub fn emit(text: &impl Display) -> Result<(), Failure> {
    write_stdout(text.to_string().as_bytes())
}

/// Writes `bytes` to standard output and flushes them, as [`emit`].
pub fn write_stdout(bytes: &[u8]) -> Result<(), Failure> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|()| out.flush())
        .map_err(|e| Failure::write_failed(format!("cannot write to standard output: {e}")))
}

pub fn print_json(value: &impl serde::Serialize) -> Result<(), Failure> {
    let s = serde_json::to_string_pretty(value)
        .map_err(|e| Failure::write_failed(format!("cannot format the result: {e}")))?;
    emit(&format!("{s}\n"))
}

impl From<flexopt::report::html::ReportError> for Failure {
    fn from(e: flexopt::report::html::ReportError) -> Self {
        match e {
            flexopt::report::html::ReportError::BadInput(m) => Failure::bad_input(m),
            flexopt::report::html::ReportError::Write(w) => Failure::write_failed(w),
        }
    }
}
