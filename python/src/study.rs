//! `flexopt.Study`: a multistart study or a shard of one, its reports as the files of
//! `flexopt run` hold them, and its copy into another process (pickle) as its runs.

use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

use flexopt::optim::{Solution, Status};
use flexopt::problem::{Solver, SOLVERS};
use flexopt::report::study::{optimum_report, start_records, zones_report};
use flexopt::study::{self, Overrides, Run, Study as Inner, StudyOptions};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::error::Error;
use crate::json::to_python;
use crate::problem::Problem;

/// A multistart study's result, or a shard's (`start_range`) until `flexopt.merge` joins them.
#[pyclass(module = "flexopt._flexopt", frozen)]
pub struct Study {
    problem: Py<Problem>,
    inner: Inner,
}

/// The study options of `problem` with the caller's overrides, checked as `flexopt run`
/// checks its options (the keys named without its `--`).
pub fn options(
    problem: &Problem,
    starts: Option<i64>,
    seed: Option<i64>,
    threads: Option<i64>,
    solver: Option<&str>,
) -> Result<StudyOptions, Error> {
    let overrides = Overrides {
        starts: starts.map(i128::from),
        seed: seed.map(i128::from),
        threads: threads.map(i128::from),
        solver,
    };
    StudyOptions::with_overrides(&problem.inner, &overrides, "").map_err(|e| Error {
        message: e.message,
        file: Some(problem.file().display().to_string()),
        key: e.key,
        code: 2,
    })
}

/// Runs the study of `problem` (its starts in `range`, else all), the GIL released.
pub fn run(
    py: Python<'_>,
    problem: &Bound<'_, Problem>,
    options: StudyOptions,
    range: Option<(usize, usize)>,
) -> PyResult<Study> {
    let p = problem.get();
    let inner = py.detach(|| match range {
        None => Ok(study::run(&p.inner, &options)),
        Some((a, b)) => study::run_range(&p.inner, &options, a..b)
            .map_err(|e| Error::bad_input(p.file(), "start_range", e)),
    })?;
    Ok(Study {
        problem: problem.clone().unbind(),
        inner,
    })
}

/// The study of `problem` from its shards.
pub fn merge(
    py: Python<'_>,
    problem: &Bound<'_, Problem>,
    shards: Vec<Bound<'_, Study>>,
) -> PyResult<Study> {
    let p = problem.get();
    let inner: Vec<Inner> = shards.iter().map(|s| s.get().inner.clone()).collect();
    let merged = py
        .detach(|| study::merge(&p.inner, inner))
        .map_err(|e| Error::bad_input(p.file(), "shards", e))?;
    Ok(Study {
        problem: problem.clone().unbind(),
        inner: merged,
    })
}

pub fn solver_name(s: Solver) -> &'static str {
    SOLVERS
        .0
        .iter()
        .find(|(_, v)| *v == s)
        .map_or("sqp", |(n, _)| n)
}

/// A run as plain values, to be sent to another process and read back there by [`run_from`].
type RunState = (
    usize,
    Vec<f64>,
    Vec<f64>,
    f64,
    bool,
    (String, Option<String>),
    Vec<f64>,
    (f64, Vec<f64>, f64, Option<f64>, usize, usize),
);

fn run_state(r: &Run) -> RunState {
    let s = &r.solution;
    let status = match &s.status {
        Status::Converged => ("converged".to_string(), None),
        Status::IterationLimit => ("iteration_limit".to_string(), None),
        Status::Infeasible => ("infeasible".to_string(), None),
        Status::Failed(why) => ("failed".to_string(), Some(why.clone())),
    };
    (
        r.start,
        r.x_start.clone(),
        r.x_end.clone(),
        r.objective,
        r.feasible,
        status,
        s.x.clone(),
        (
            s.objective,
            s.constraints.clone(),
            s.max_violation,
            s.kkt_residual,
            s.iterations,
            s.evaluations,
        ),
    )
}

fn run_from(state: RunState) -> Result<Run, String> {
    let (start, x_start, x_end, objective, feasible, (status, why), x, rest) = state;
    let (sol_objective, constraints, max_violation, kkt_residual, iterations, evaluations) = rest;
    let status = match (status.as_str(), why) {
        ("converged", _) => Status::Converged,
        ("iteration_limit", _) => Status::IterationLimit,
        ("infeasible", _) => Status::Infeasible,
        ("failed", Some(why)) => Status::Failed(why),
        (other, _) => return Err(format!("a run of status \"{other}\"")),
    };
    Ok(Run {
        start,
        x_start,
        x_end,
        objective,
        feasible,
        solution: Solution {
            status,
            x,
            objective: sol_objective,
            constraints,
            max_violation,
            kkt_residual,
            iterations,
            evaluations,
        },
        optimum: None,
        zone: None,
    })
}

type StudyState = (u64, u64, String, usize, (usize, usize), bool, f64);

#[pymethods]
impl Study {
    /// Rebuilds a study (or shard) from `__reduce__`'s state.
    #[staticmethod]
    fn _from_state(
        py: Python<'_>,
        problem: Bound<'_, Problem>,
        state: StudyState,
        runs: Vec<RunState>,
    ) -> PyResult<Self> {
        let (starts, seed, solver, threads, (a, b), interrupted, elapsed) = state;
        let p = problem.get();
        let bad = |e: String| Error::bad_input(p.file(), "study", e);
        let mut options = options(p, None, None, None, Some(&solver))?;
        options.starts = starts as usize;
        options.seed = seed;
        options.threads = threads;
        options.stop = Arc::new(AtomicBool::new(false));
        let runs = runs
            .into_iter()
            .map(run_from)
            .collect::<Result<Vec<_>, _>>()
            .map_err(bad)?;
        let mut inner = py.detach(|| study::from_runs(&p.inner, &options, runs, interrupted, a..b));
        inner.elapsed = Duration::from_secs_f64(elapsed.max(0.0));
        Ok(Study {
            problem: problem.unbind(),
            inner,
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let s = &slf.get().inner;
        let o = &s.options;
        let state: StudyState = (
            o.starts as u64,
            o.seed,
            solver_name(o.solver).to_string(),
            o.threads,
            (s.range.start, s.range.end),
            s.interrupted,
            s.elapsed.as_secs_f64(),
        );
        let runs: Vec<RunState> = s.runs.iter().map(run_state).collect();
        let from = py.get_type::<Study>().getattr("_from_state")?;
        let args = (slf.get().problem.clone_ref(py), state, runs).into_pyobject(py)?;
        PyTuple::new(py, [from.into_any(), args.into_any()])
    }

    #[getter]
    fn problem(&self, py: Python<'_>) -> Py<Problem> {
        self.problem.clone_ref(py)
    }

    /// The objective at the reported design, as the problem states it (SI).
    #[getter]
    fn objective(&self) -> f64 {
        self.inner.reported_objective()
    }

    /// The reported design in the file's units.
    #[getter]
    fn design<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = self.problem.get();
        let d = PyDict::new(py);
        for (k, v) in p.inner.design_in_file_units(self.inner.reported_design()) {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// The reported design as the model's parameters in SI.
    #[getter]
    fn design_si(&self) -> Vec<f64> {
        self.inner.reported_design().to_vec()
    }

    /// Whether some start ended feasible.
    #[getter]
    fn feasible(&self) -> bool {
        self.inner.any_feasible
    }

    #[getter]
    fn converged(&self) -> bool {
        self.inner.best_converged
    }

    #[getter]
    fn interrupted(&self) -> bool {
        self.inner.interrupted
    }

    /// The starts solved, `(first, end)`: all of them, or a shard's.
    #[getter]
    fn start_range(&self) -> (usize, usize) {
        (self.inner.range.start, self.inner.range.end)
    }

    #[getter]
    fn starts(&self) -> usize {
        self.inner.options.starts
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.inner.options.seed
    }

    #[getter]
    fn solver(&self) -> &'static str {
        solver_name(self.inner.options.solver)
    }

    /// Wall time of the solves, seconds (for a merged study, the shards' summed).
    #[getter]
    fn elapsed(&self) -> f64 {
        self.inner.elapsed.as_secs_f64()
    }

    fn __len__(&self) -> usize {
        self.inner.runs.len()
    }

    /// `optimum.json` of `flexopt run` as a dict (without the part's problems, which the
    /// part decides).
    fn optimum(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let p = self.problem.get();
        to_python(py, &optimum_report(&p.inner, &self.inner, None))
    }

    /// `zones.json` of `flexopt run` as a dict.
    fn zones(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let p = self.problem.get();
        to_python(py, &zones_report(&p.inner, &self.inner))
    }

    /// `starts.json` of `flexopt run`: one dict a start.
    fn starts_report(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let p = self.problem.get();
        to_python(py, &start_records(&p.inner, &self.inner))
    }

    /// One flat dict a start, for `pandas.DataFrame(study.to_records())`: the columns of
    /// `starts.csv`, the status a word, the designs in the file's units as `start_<name>` and
    /// `end_<name>`.
    fn to_records<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let p = self.problem.get();
        let list = PyList::empty(py);
        for r in start_records(&p.inner, &self.inner) {
            let d = PyDict::new(py);
            d.set_item("start", r.start)?;
            d.set_item("zone", r.zone)?;
            d.set_item("optimum", r.optimum)?;
            d.set_item("objective", r.objective)?;
            d.set_item("feasible", r.feasible)?;
            let (status, reason) = match &r.status {
                Status::Converged => ("converged", None),
                Status::IterationLimit => ("iteration_limit", None),
                Status::Infeasible => ("infeasible", None),
                Status::Failed(why) => ("failed", Some(why.as_str())),
            };
            d.set_item("status", status)?;
            d.set_item("reason", reason)?;
            d.set_item("iterations", r.iterations)?;
            d.set_item("evaluations", r.evaluations)?;
            d.set_item("max_violation", r.max_violation)?;
            d.set_item("kkt_residual", r.kkt_residual)?;
            d.set_item("configuration", r.configuration)?;
            for (k, v) in &r.x_start {
                d.set_item(format!("start_{k}"), v)?;
            }
            for (k, v) in &r.x_end {
                d.set_item(format!("end_{k}"), v)?;
            }
            list.append(d)?;
        }
        Ok(list)
    }

    fn __repr__(&self) -> String {
        let s = &self.inner;
        format!(
            "Study(starts {}..{} of {}, objective {}, {} zones)",
            s.range.start,
            s.range.end,
            s.options.starts,
            s.reported_objective(),
            s.clustering.zones.len()
        )
    }
}
