//! `flexopt.Problem`: a problem file loaded once, its model evaluated at designs given in the
//! file's units, and the commands of the library run on it.

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use flexopt::problem::design::parse_design;
use flexopt::problem::{Problem as Inner, Variable};
use flexopt::report::DesignReport;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString, PyTuple};

use crate::commands;
use crate::error::Error;
use crate::json::to_python;
use crate::study::{self, Study};

/// A problem file, read and checked: its model, variables, objective and constraints.
#[pyclass(module = "flexopt._flexopt", frozen)]
pub struct Problem {
    pub inner: Arc<Inner>,
    /// The file's text, from which a copy is rebuilt in another process (pickle).
    text: String,
    /// The free variables' indices among the variables (the model's parameters).
    free: Vec<usize>,
    /// The outputs `flexopt eval` reports: every one the model computes by its formulas.
    analytic: Vec<usize>,
    /// Their names as Python strings.
    output_names: PyOnceLock<Vec<Py<PyString>>>,
}

impl Problem {
    fn new(path: &Path, text: String) -> Result<Self, Error> {
        let inner = Inner::parse(path, &text)?;
        Ok(Self::wrap(inner, text))
    }

    fn wrap(inner: Inner, text: String) -> Self {
        let free = (0..inner.variables.len())
            .filter(|&i| !inner.variables[i].fixed)
            .collect();
        let analytic = inner.model().analytic_outputs();
        Problem {
            inner: Arc::new(inner),
            text,
            free,
            analytic,
            output_names: PyOnceLock::new(),
        }
    }

    pub fn file(&self) -> &Path {
        &self.inner.file
    }

    /// The model's parameters (SI) at the free variables' values `free` (the file's units),
    /// the fixed ones at their values; refused outside the model's domain as `flexopt eval`
    /// refuses a `--design` there.
    pub fn design_of_free(
        &self,
        free: &[f64],
        key: &dyn Fn() -> String,
    ) -> Result<Vec<f64>, Error> {
        if free.len() != self.free.len() {
            return Err(Error::bad_input(
                self.file(),
                &key(),
                format!(
                    "expected {} values (the free variables {}), got {}",
                    self.free.len(),
                    self.free_names().join(", "),
                    free.len()
                ),
            ));
        }
        let mut x: Vec<f64> = self.inner.variables.iter().map(|v| v.lower).collect();
        for (&i, &value) in self.free.iter().zip(free) {
            let v = &self.inner.variables[i];
            if !value.is_finite() {
                return Err(Error::bad_input(
                    self.file(),
                    &format!("{} {}", key(), v.name),
                    format!("{value} is not a finite number"),
                ));
            }
            x[i] = v.unit.to_si(value);
        }
        if let Some(why) = self.inner.model().domain_error(&x) {
            let what = format!("outside the model's domain: {why}");
            return Err(Error::bad_input(self.file(), &key(), what));
        }
        Ok(x)
    }

    fn in_domain(&self, x: &[f64], key: &str) -> Result<(), Error> {
        match self.inner.model().domain_error(x) {
            Some(why) => Err(Error::bad_input(
                self.file(),
                key,
                format!("outside the model's domain: {why}"),
            )),
            None => Ok(()),
        }
    }

    /// The analytic outputs at the full design `x` (SI), in the order of [`Self::analytic`].
    pub fn outputs_at(&self, x: &[f64], out: &mut [f64]) {
        self.inner.model().evaluate(x, &self.analytic, out);
    }

    fn free_names(&self) -> Vec<&str> {
        self.free
            .iter()
            .map(|&i| self.inner.variables[i].name.as_str())
            .collect()
    }

    /// A design given as a dict of variables (the file's units; the fixed ones may be left
    /// out), read as `flexopt eval --design` reads its text, with its messages and warnings;
    /// or as a sequence of the free variables' values.
    fn design(&self, py: Python<'_>, design: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        if let Ok(dict) = design.cast::<PyDict>() {
            if let Some(x) = self.plain_design(dict) {
                self.in_domain(&x, "--design")?;
                return Ok(x);
            }
            let mut text = String::new();
            for (k, v) in dict.iter() {
                let name: String = k.extract()?;
                let value: f64 = v.extract().map_err(|_| {
                    Error::bad_input(
                        self.file(),
                        &format!("--design {name}"),
                        format!("{} is not a finite number", shown(&v)),
                    )
                })?;
                // Rust's shortest decimal reads back as the same float
                text.push_str(&format!("{name}={value:?},"));
            }
            let parsed = parse_design(&self.inner, &text).map_err(Error::from)?;
            for w in &parsed.warnings {
                let message =
                    CString::new(format!("{}: {w}", self.file().display())).unwrap_or_default();
                PyErr::warn(py, &py.get_type::<PyUserWarning>(), &message, 2)?;
            }
            self.in_domain(&parsed.x, "--design")?;
            return Ok(parsed.x);
        }
        let free = free_values(py, self.file(), design)?;
        Ok(self.design_of_free(&free, &|| "design".into())?)
    }

    /// A bound of each free variable (SI, `side` picks it) in the file's units.
    fn bounds(&self, side: impl Fn(&Variable) -> f64) -> Vec<f64> {
        let v = &self.inner.variables;
        self.free
            .iter()
            .map(|&i| v[i].unit.from_si(side(&v[i])))
            .collect()
    }

    /// The design of a dict that `parse_design` would take without a message or a warning
    /// (every free variable given, each once, finite and within its bounds), read directly;
    /// `None` for any other, which the text's reading then refuses or warns of.
    fn plain_design(&self, dict: &Bound<'_, PyDict>) -> Option<Vec<f64>> {
        let vars = &self.inner.variables;
        let mut x = vec![f64::NAN; vars.len()];
        for (k, v) in dict.iter() {
            let name = k.cast::<PyString>().ok()?.to_cow().ok()?;
            let i = vars.iter().position(|v| v.name == *name)?;
            let value: f64 = v.extract().ok()?;
            if !value.is_finite() {
                return None;
            }
            x[i] = vars[i].unit.to_si(value);
        }
        for (xi, var) in x.iter_mut().zip(vars) {
            if xi.is_nan() {
                if !var.fixed {
                    return None;
                }
                *xi = var.lower;
            }
            // parse_design's tolerance of a bound
            let tol = 1e-12 * var.upper.abs().max(var.lower.abs());
            if *xi < var.lower - tol || *xi > var.upper + tol {
                return None;
            }
        }
        Some(x)
    }

    fn output_dict<'py>(&self, py: Python<'py>, values: &[f64]) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        // the names made once: a dict's keys are most of an evaluation's cost
        let names = self.output_names.get_or_init(py, || {
            let infos = self.inner.model().outputs();
            let names = self.analytic.iter().map(|&i| infos[i].name.as_ref());
            names.map(|n| PyString::new(py, n).unbind()).collect()
        });
        for (name, &v) in names.iter().zip(values) {
            d.set_item(name.bind(py), if v.is_finite() { v } else { f64::NAN })?;
        }
        Ok(d)
    }
}

/// A sequence or 1-D array of numbers, of any numeric type NumPy converts to `float64`.
fn free_values(py: Python<'_>, file: &Path, design: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(a) = design.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().to_vec());
    }
    let refuse = |what: String| Error::bad_input(file, "design", what);
    if design.is_instance_of::<PyString>() {
        return Err(refuse(
            "a string is no design: give a dict of the variables, {\"l2\": 1.96, ...}, or the \
             free variables' values in order (the command line's `l2=1.96,...` is not read here)"
                .into(),
        )
        .into());
    }
    let a = float_array(py, design).map_err(|_| {
        refuse(format!(
            "{} is no design: give a dict of the variables or the free variables' values in \
             order",
            shown(design)
        ))
    })?;
    let Ok(a) = a.extract::<PyReadonlyArray1<'_, f64>>() else {
        let ndim: usize = a.getattr("ndim")?.extract()?;
        return Err(refuse(format!(
            "a {ndim}-D array: a design is one row of the free variables' values (several \
             rows: `evaluate_many`)"
        ))
        .into());
    };
    Ok(a.as_array().to_vec())
}

/// `value` as a NumPy array of `float64` (ints, `float32` and sequences converted).
fn float_array<'py>(py: Python<'py>, value: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    py.import("numpy")?
        .getattr("asarray")?
        .call1((value, "float64"))
}

/// A Python value for a message: its `repr`, cut short (an int of 400 digits is one).
pub fn shown(value: &Bound<'_, PyAny>) -> String {
    const MOST: usize = 40;
    let text = value
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "the value".into());
    match text.char_indices().nth(MOST) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text,
    }
}

#[pymethods]
impl Problem {
    /// Reads the problem file at `path`.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let inner = py.detach(|| Inner::load(&path)).map_err(Error::from)?;
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        Ok(Self::wrap(inner, text))
    }

    /// Reads a problem file's text; `path` is the name its messages give it.
    #[staticmethod]
    #[pyo3(signature = (text, path = "<string>"))]
    fn from_toml(text: String, path: &str) -> PyResult<Self> {
        let most = flexopt::problem::MAX_FILE_BYTES;
        if text.len() as u64 > most {
            let what = format!(
                "the text has {} bytes; a problem file may have at most {most} (1 MiB)",
                text.len()
            );
            return Err(Error::bad_input(Path::new(path), "", what).into());
        }
        Ok(Self::new(Path::new(path), text)?)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.get();
        let from_toml = py.get_type::<Problem>().getattr("from_toml")?;
        let args = (this.text.clone(), this.file().display().to_string());
        PyTuple::new(
            py,
            [from_toml.into_any(), args.into_pyobject(py)?.into_any()],
        )
    }

    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    #[getter]
    fn model(&self) -> &'static str {
        self.inner.model().name()
    }

    #[getter]
    fn file_name(&self) -> String {
        self.file().display().to_string()
    }

    /// Every variable, as the file names them, in the model's order.
    #[getter]
    fn variables(&self) -> Vec<String> {
        self.inner
            .variables
            .iter()
            .map(|v| v.name.clone())
            .collect()
    }

    /// The free variables: the order of a design given as an array.
    #[getter]
    fn free_variables(&self) -> Vec<String> {
        self.free_names().into_iter().map(str::to_string).collect()
    }

    /// Variable -> the file's unit.
    #[getter]
    fn variable_units(&self) -> Vec<(String, String)> {
        let v = &self.inner.variables;
        v.iter()
            .map(|v| (v.name.clone(), v.unit.name.clone()))
            .collect()
    }

    /// The free variables' lower bounds, in the file's units.
    #[getter]
    fn lower<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.bounds(|v| v.lower).into_pyarray(py)
    }

    /// The free variables' upper bounds, in the file's units.
    #[getter]
    fn upper<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.bounds(|v| v.upper).into_pyarray(py)
    }

    /// The outputs `evaluate` gives, in the order of its arrays.
    #[getter]
    fn outputs(&self) -> Vec<String> {
        let infos = self.inner.model().outputs();
        self.analytic
            .iter()
            .map(|&i| infos[i].name.to_string())
            .collect()
    }

    /// Output -> its SI unit.
    #[getter]
    fn output_units(&self) -> Vec<(String, &'static str)> {
        let infos = self.inner.model().outputs();
        self.analytic
            .iter()
            .map(|&i| (infos[i].name.to_string(), infos[i].dimension.si_unit()))
            .collect()
    }

    /// The output the objective names.
    #[getter]
    fn objective(&self) -> String {
        self.inner.objective.output.clone()
    }

    /// The file's `[search]`: `starts`, `seed`, `solver`, `threads`, the defaults of `run`.
    #[getter]
    fn search<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.inner.search;
        let d = PyDict::new(py);
        d.set_item("starts", s.starts)?;
        d.set_item("seed", s.seed)?;
        d.set_item("solver", study::solver_name(s.solver))?;
        d.set_item("threads", s.threads)?;
        Ok(d)
    }

    /// "maximize" or "minimize".
    #[getter]
    fn sense(&self) -> &'static str {
        match self.inner.objective.sense {
            flexopt::problem::Sense::Maximize => "maximize",
            flexopt::problem::Sense::Minimize => "minimize",
        }
    }

    /// Whether the objective is the output's absolute value.
    #[getter]
    fn absolute(&self) -> bool {
        self.inner.objective.absolute
    }

    /// The file's constraints: `(output, lower, upper)` in SI, `None` where a side is open.
    #[getter]
    fn constraints(&self) -> Vec<(String, Option<f64>, Option<f64>)> {
        let c = &self.inner.constraints;
        c.iter()
            .map(|c| (c.output.clone(), c.lower, c.upper))
            .collect()
    }

    /// The outputs at `design` in SI: a dict, or an array in the order of `outputs`. NaN where
    /// the model gives no finite number.
    #[pyo3(signature = (design, as_array = false))]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        design: &Bound<'py, PyAny>,
        as_array: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = self.design(py, design)?;
        let mut out = vec![0.0; self.analytic.len()];
        self.outputs_at(&x, &mut out);
        if as_array {
            for v in &mut out {
                if !v.is_finite() {
                    *v = f64::NAN;
                }
            }
            return Ok(out.into_pyarray(py).into_any());
        }
        Ok(self.output_dict(py, &out)?.into_any())
    }

    /// The outputs at each row of `designs` (free variables, the file's units): a 2-D array,
    /// one row a design, one column an output.
    fn evaluate_many<'py>(
        &self,
        py: Python<'py>,
        designs: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let refuse = |what: String| Error::bad_input(self.file(), "designs", what);
        let converted = float_array(py, designs).map_err(|_| {
            refuse(format!(
                "{} is no array of designs: give a 2-D array, one row a design",
                shown(designs)
            ))
        })?;
        let Ok(designs) = converted.extract::<PyReadonlyArray2<'py, f64>>() else {
            let ndim: usize = converted.getattr("ndim")?.extract()?;
            return Err(refuse(format!(
                "a {ndim}-D array: give a 2-D array, one row a design (one design: `evaluate`)"
            ))
            .into());
        };
        let a = designs.as_array();
        let m = self.analytic.len();
        let rows = a.nrows();
        let out = py.detach(|| -> Result<Vec<f64>, Error> {
            let mut out = vec![0.0; rows * m];
            let mut row = Vec::with_capacity(a.ncols());
            for (k, (r, o)) in a.outer_iter().zip(out.chunks_mut(m.max(1))).enumerate() {
                row.clear();
                row.extend(r.iter());
                let x = self.design_of_free(&row, &|| format!("designs row {k}"))?;
                self.outputs_at(&x, o);
            }
            Ok(out)
        })?;
        let out = out
            .into_iter()
            .map(|v| if v.is_finite() { v } else { f64::NAN });
        let a = Array2::from_shape_vec((rows, m), out.collect())
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
        Ok(a.into_pyarray(py))
    }

    /// The exact derivatives of the outputs (SI) by the free variables (the file's units):
    /// one row an output (the order of `outputs`), one column a free variable.
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        design: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = self.design(py, design)?;
        let n = x.len();
        let m = self.analytic.len();
        let mut out = vec![0.0; m];
        let mut full = vec![0.0; m * n];
        let model = self.inner.model();
        model.evaluate_with_gradient(&x, &self.analytic, &mut out, &mut full);
        let vars = &self.inner.variables;
        let j = Array2::from_shape_fn((m, self.free.len()), |(i, k)| {
            let p = self.free[k];
            full[i * n + p] * vars[p].unit.to_si(1.0)
        });
        Ok(j.into_pyarray(py))
    }

    /// Everything `flexopt eval` prints as JSON at `design`, as a dict.
    fn report<'py>(&self, py: Python<'py>, design: &Bound<'py, PyAny>) -> PyResult<Py<PyAny>> {
        let x = self.design(py, design)?;
        to_python(py, &DesignReport::new(&self.inner, &x))
    }

    /// The multistart study (the file's `[search]`, with these overrides), or the shard of
    /// it whose starts lie in `start_range = (first, end)`; the GIL is released meanwhile.
    #[pyo3(signature = (starts = None, seed = None, threads = None, solver = None, start_range = None))]
    fn run(
        slf: &Bound<'_, Self>,
        starts: Option<i64>,
        seed: Option<i64>,
        threads: Option<i64>,
        solver: Option<&str>,
        start_range: Option<(usize, usize)>,
    ) -> PyResult<Study> {
        let options = study::options(slf.get(), starts, seed, threads, solver)?;
        study::run(slf.py(), slf, options, start_range)
    }

    /// `tolerance.json` of `flexopt tolerance` at `design`, as a dict.
    #[pyo3(signature = (design, samples = 100_000, seed = None, threads = None))]
    fn tolerance<'py>(
        &self,
        py: Python<'py>,
        design: &Bound<'py, PyAny>,
        samples: i64,
        seed: Option<u64>,
        threads: Option<usize>,
    ) -> PyResult<Py<PyAny>> {
        let samples = commands::samples(self, samples)?;
        let x = self.design(py, design)?;
        let report = py.detach(|| commands::tolerance(self, &x, samples, seed, threads))?;
        to_python(py, &report)
    }

    /// Writes the part's files of `flexopt export` at `design` into the folder `out` as one
    /// set; their paths.
    fn export(
        &self,
        py: Python<'_>,
        design: &Bound<'_, PyAny>,
        out: PathBuf,
    ) -> PyResult<Vec<String>> {
        let x = self.design(py, design)?;
        Ok(py.detach(|| commands::export(self, &x, &out))?)
    }

    /// `verify.json` of `flexopt verify` at `design` (the finite-element check of its part),
    /// as a dict.
    #[pyo3(signature = (design, tolerance = None, max_dofs = None))]
    fn verify<'py>(
        &self,
        py: Python<'py>,
        design: &Bound<'py, PyAny>,
        tolerance: Option<f64>,
        max_dofs: Option<usize>,
    ) -> PyResult<Py<PyAny>> {
        let x = self.design(py, design)?;
        let report = py.detach(|| commands::verify(self, &x, tolerance, max_dofs))?;
        to_python(py, &report)
    }

    /// `refined.json` of `run --refine fe` for `design` refined against the finite elements
    /// of its part (at most `max_fe` FE checks; `[refine] max_fe` by default), as a dict.
    #[pyo3(signature = (design, max_fe = None))]
    fn refine<'py>(
        &self,
        py: Python<'py>,
        design: &Bound<'py, PyAny>,
        max_fe: Option<i64>,
    ) -> PyResult<Py<PyAny>> {
        let x = self.design(py, design)?;
        let report = py.detach(|| commands::refine(self, &x, max_fe))?;
        to_python(py, &report)
    }

    /// Time of `n` evaluations by Rust alone at `design` (free variables, the file's units),
    /// seconds per evaluation: the yardstick of the Python call's overhead.
    fn _bench_evaluate(&self, py: Python<'_>, design: Vec<f64>, n: usize) -> PyResult<f64> {
        let seconds = py.detach(|| -> Result<f64, Error> {
            let mut out = vec![0.0; self.analytic.len()];
            let begin = std::time::Instant::now();
            for _ in 0..n {
                let x = self.design_of_free(std::hint::black_box(&design), &|| "design".into())?;
                self.outputs_at(&x, &mut out);
                std::hint::black_box(&out);
            }
            Ok(begin.elapsed().as_secs_f64() / n.max(1) as f64)
        })?;
        Ok(seconds)
    }
}
