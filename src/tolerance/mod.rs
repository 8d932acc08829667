//! A design under its tolerances ([`crate::problem::tolerances`]): the spread of every output
//! the problem uses, to first order from the model's exact gradients ([`first_order`]) and
//! by Monte Carlo ([`monte_carlo`]), and the yield, the fraction of parts cut to the
//! tolerances that can be made ([`makeable`]) and meet every constraint.
//!
//! First order (the first-order second-moment method, FOSM: Parkinson, Sorensen and
//! Pourhassan, J. Mech. Des. 115 (1993) 74-80): with independent inputs `p_j` of standard
//! deviations `s_j`, an output `y` has `var y = sum_j (dy/dp_j s_j)^2`; each term over the
//! sum is the input's share of the variance, and `y +- sum_j |dy/dp_j| b_j`, with `b_j` the
//! inputs' bands, is the worst case of the linearized output.

pub mod makeable;
pub mod monte_carlo;
pub mod robust;

use serde::Serialize;

use crate::problem::tolerances::{Input, Tolerance};
use crate::problem::Problem;

/// The outputs a problem uses (its objective's, then each constraint's), and the inputs its
/// tolerances vary: how the analysis evaluates a design.
pub struct Outputs<'a> {
    pub problem: &'a Problem,
    /// Indices among the model's outputs, each once.
    pub wanted: Vec<usize>,
    /// Whether a tolerance varies the material's modulus.
    pub modulus: bool,
}

impl<'a> Outputs<'a> {
    pub fn new(problem: &'a Problem) -> Self {
        let mut wanted = vec![problem.objective.index];
        for c in &problem.constraints {
            if !wanted.contains(&c.index) {
                wanted.push(c.index);
            }
        }
        let modulus = problem.tolerances.iter().any(|t| t.input == Input::Modulus);
        Outputs {
            problem,
            wanted,
            modulus,
        }
    }

    /// The inputs: the model's parameters, and the modulus's factor where it varies.
    pub fn inputs(&self) -> usize {
        self.problem.model().parameters().len() + usize::from(self.modulus)
    }

    /// The wanted outputs at design `x` and the moduli `modulus` times the nominal ones.
    pub fn values(&self, x: &[f64], modulus: f64, out: &mut [f64]) {
        match (&self.problem.mechanism.modulus, self.modulus) {
            (Some(m), true) => m.evaluate_scaled(x, modulus, &self.wanted, out),
            _ => self.problem.model().evaluate(x, &self.wanted, out),
        }
    }

    /// The wanted outputs at `x` and the nominal moduli, and their gradients by every input
    /// ([`Outputs::inputs`] columns, row-major).
    pub fn gradients(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        match (&self.problem.mechanism.modulus, self.modulus) {
            (Some(m), true) => m.evaluate_scaled_with_gradient(x, 1.0, &self.wanted, out, jacobian),
            _ => self
                .problem
                .model()
                .evaluate_with_gradient(x, &self.wanted, out, jacobian),
        }
    }
}

/// The column of an input among [`Outputs::gradients`]'.
pub fn column(input: Input, parameters: usize) -> usize {
    match input {
        Input::Parameter(i) => i,
        Input::Modulus => parameters,
    }
}

/// An output's spread to first order.
#[derive(Debug, Clone, Serialize)]
pub struct FirstOrder {
    pub nominal: f64,
    pub std: f64,
    /// The linearized output's extremes over every input's band.
    pub worst_case: [f64; 2],
    /// Each tolerance's share of the variance, in the order of the tolerances (they sum to
    /// one; all zero for an output no tolerance moves).
    pub shares: Vec<f64>,
}

/// The first-order spread of each wanted output at `x`, in the order of `outputs.wanted`.
pub fn first_order(outputs: &Outputs, tolerances: &[Tolerance], x: &[f64]) -> Vec<FirstOrder> {
    let (m, n) = (outputs.wanted.len(), outputs.inputs());
    let parameters = outputs.problem.model().parameters().len();
    let mut values = vec![0.0; m];
    let mut jacobian = vec![0.0; m * n];
    outputs.gradients(x, &mut values, &mut jacobian);
    (0..m)
        .map(|i| {
            let row = &jacobian[i * n..(i + 1) * n];
            let terms: Vec<f64> = tolerances
                .iter()
                .map(|t| {
                    let d = row[column(t.input, parameters)] * t.sigma;
                    d * d
                })
                .collect();
            let var: f64 = terms.iter().sum();
            let reach: f64 = tolerances
                .iter()
                .map(|t| (row[column(t.input, parameters)] * t.band()).abs())
                .sum();
            FirstOrder {
                nominal: values[i],
                std: var.sqrt(),
                worst_case: [values[i] - reach, values[i] + reach],
                shares: terms
                    .iter()
                    .map(|&t| if var > 0.0 { t / var } else { 0.0 })
                    .collect(),
            }
        })
        .collect()
}

/// The probability that a normal output of mean `mean` and deviation `std` lies within
/// `lower..upper` (either may be absent): a constraint's first-order yield.
pub fn normal_within(mean: f64, std: f64, lower: Option<f64>, upper: Option<f64>) -> f64 {
    use crate::problem::tolerances::normal_cdf;
    // without spread, the nominal value meets a limit it equals
    let below = |limit: f64, at: bool| {
        if std > 0.0 {
            normal_cdf((limit - mean) / std)
        } else {
            f64::from(u8::from(mean < limit || (at && mean == limit)))
        }
    };
    upper.map_or(1.0, |u| below(u, true)) - lower.map_or(0.0, |l| below(l, false))
}

/// A design's tolerance analysis: first order and Monte Carlo.
pub struct Analysis<'a> {
    pub outputs: Outputs<'a>,
    /// Per wanted output.
    pub first_order: Vec<FirstOrder>,
    pub monte_carlo: monte_carlo::MonteCarlo,
}

/// Analyses the design `x` (SI, every parameter) of `problem` under its tolerances; the
/// error says why it cannot (no tolerance, a sample out of the model's domain).
pub fn analyze<'a>(
    problem: &'a Problem,
    x: &[f64],
    settings: monte_carlo::Settings,
) -> Result<Analysis<'a>, String> {
    if problem.tolerances.is_empty() {
        return Err(
            "no tolerances: the file has no [tolerances] section and the model has no part \
             whose process would give the defaults"
                .into(),
        );
    }
    let outputs = Outputs::new(problem);
    if outputs.modulus && problem.mechanism.modulus.is_none() {
        return Err(format!(
            "the {} model cannot vary its material's modulus (a refined model's corrections \
             hold at the nominal one): remove the tolerance on youngs_modulus",
            problem.model().name()
        ));
    }
    let first_order = first_order(&outputs, &problem.tolerances, x);
    let monte_carlo = monte_carlo::run(&outputs, &problem.tolerances, x, settings)?;
    Ok(Analysis {
        outputs,
        first_order,
        monte_carlo,
    })
}
