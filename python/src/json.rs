//! The library's reports, which it serializes for its JSON files, as Python objects: the
//! same JSON, read back by Python's `json` module, so that a value is the file's to the bit.

use pyo3::prelude::*;
use serde::Serialize;

pub fn to_python(py: Python<'_>, value: &impl Serialize) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    Ok(py
        .import("json")?
        .getattr("loads")?
        .call1((text,))?
        .unbind())
}
