//! The extension module `flexopt._flexopt`: flexopt's problems, studies and commands for
//! Python. The package `flexopt` (beside this crate) re-exports it and adds the OpenMDAO
//! component and the Dask studies.

use pyo3::prelude::*;

mod commands;
mod error;
mod json;
mod problem;
mod study;

/// The study of `problem` from its shards (`Problem.run(start_range=...)`), in any order:
/// exactly the study one `run` of all the starts gives.
#[pyfunction]
fn merge(
    py: Python<'_>,
    problem: Bound<'_, problem::Problem>,
    shards: Vec<Bound<'_, study::Study>>,
) -> PyResult<study::Study> {
    study::merge(py, &problem, shards)
}

#[pymodule]
fn _flexopt(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<problem::Problem>()?;
    m.add_class::<study::Study>()?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add("FlexoptError", m.py().get_type::<error::FlexoptError>())?;
    Ok(())
}
