//! The one exception the package raises, carrying the command line's message and the file,
//! key and exit code it names.

use std::fmt::Display;

use flexopt::vocab::error::ProblemError;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

pyo3::create_exception!(
    _flexopt,
    FlexoptError,
    PyException,
    "A problem file, design or option flexopt refuses, or work it could not do. `str(e)` is the \
     command line's message; `e.file`, `e.key` and `e.code` (the command line's exit code) say \
     where and what."
);

/// What went wrong, before it becomes a Python exception.
#[derive(Debug, Clone)]
pub struct Error {
    pub message: String,
    pub file: Option<String>,
    pub key: Option<String>,
    /// The exit code of the command line for the same mistake: 2 bad input, 1 not written,
    /// 5 no part that can be made.
    pub code: u8,
}

impl Error {
    /// Bad input (exit code 2), said as the command line says it: `file: key `key`: what`.
    pub fn bad_input(file: &std::path::Path, key: &str, what: impl Display) -> Self {
        let message = if key.is_empty() {
            format!("{}: {what}", file.display())
        } else {
            format!("{}: key `{key}`: {what}", file.display())
        };
        Error {
            message,
            file: Some(file.display().to_string()),
            key: (!key.is_empty()).then(|| key.to_string()),
            code: 2,
        }
    }

    pub fn with_code(mut self, code: u8) -> Self {
        self.code = code;
        self
    }
}

impl From<ProblemError> for Error {
    fn from(e: ProblemError) -> Self {
        Error {
            message: e.to_string(),
            file: Some(e.file.display().to_string()),
            key: (!e.key.is_empty()).then(|| e.key.clone()),
            code: 2,
        }
    }
}

impl From<Error> for PyErr {
    fn from(e: Error) -> PyErr {
        Python::attach(|py| {
            let err = FlexoptError::new_err(e.message.clone());
            let value = err.value(py);
            // attributes of an exception instance; setting them cannot fail
            let _ = value.setattr("file", e.file);
            let _ = value.setattr("key", e.key);
            let _ = value.setattr("code", e.code);
            err
        })
    }
}
