//! The spread of the measured outputs (the FE's) under the tolerances, from a handful of
//! samples: where the analytic spread is not to be trusted, the part's own.
//!
//! An FE check costs a second or two, so the measured spread comes from few samples, `n`
//! of the Monte Carlo's own (sample `i` is the analytic Monte Carlo's sample `i`,
//! [`draw_sample`]). Their sample standard deviation alone is coarse (with 12 samples its
//! 95 % interval spans about 0.7 to 1.7 times it), but the analytic model, evaluated at the
//! same samples, moves with the FE: the measured deviations `d_F,i = F(p_i) - F(p_0)` are
//! regressed on the analytic ones `d_a,i = a(p_i) - a(p_0)` through the origin,
//!
//! ```text
//! beta = sum d_F d_a / sum d_a^2,    se(beta)^2 = sum (d_F - beta d_a)^2 / ((n - 1) sum d_a^2)
//! ```
//!
//! and the measured spread is `|beta|` times the analytic first-order one: the analytic
//! model as a control variate of the expensive one (multifidelity estimation: Ng and
//! Willcox, "Multifidelity approaches for optimization under uncertainty", Int. J. Numer.
//! Meth. Engng 100 (2014) 746-772, Sec. 3). `beta` over the correction's factor
//! `F(p_0) / a(p_0)` says whether the refinement's multiplicative correction, which scales
//! the spread by that factor, carries it (1: it does).
//!
//! The yield of the part is then the analytic Monte Carlo's samples with each measured
//! output mapped onto the measurement, `F(p_0) + beta (a - a(p_0))`: the fraction of them
//! that meet every constraint and whose part can be made.
//!
//! A sample whose part breaks one of the part's rules or fails its checks cannot be cut: it
//! is passed over for the next one ([`Unmade`], reported), and its Monte Carlo twin counts
//! as a failed part in the yield ([`crate::tolerance::makeable`]).

use rayon::prelude::*;
use serde::Serialize;

use super::HighFidelity;
use crate::problem::Problem;
use crate::tolerance::makeable::Rules;
use crate::tolerance::monte_carlo::{count_met, draw_sample, mean_and_std, out_of_domain, wilson};
use crate::tolerance::Analysis;

/// Why a measured spread could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum SpreadError {
    /// The settings or the tolerances: too few samples, a sample out of the model's domain,
    /// nothing measured.
    Input(String),
    /// The high fidelity could not measure a sample (its part cannot be made or checked).
    Measure(String),
}

impl std::fmt::Display for SpreadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SpreadError::Input(e) | SpreadError::Measure(e) => f.write_str(e),
        }
    }
}

/// How many samples, from which seed, on how many threads (0: every core).
#[derive(Debug, Clone, Copy)]
pub struct SpreadSettings {
    pub samples: usize,
    pub seed: u64,
    pub threads: usize,
}

/// The fewest samples a measured spread takes: two deviations leave one degree of freedom
/// for the regression's error.
pub const MIN_SAMPLES: usize = 3;

/// One measured output under the tolerances (SI).
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredSpread {
    pub output: String,
    /// At the design: the model's value, the measurement and its estimated relative error.
    pub analytic: f64,
    pub measured: f64,
    pub measured_error: Option<f64>,
    /// The measurement over the model at the design: the refinement's correction.
    pub factor: f64,
    /// The model's first-order standard deviation.
    pub analytic_std: f64,
    /// The measured deviations over the model's, on the samples, and its standard error.
    pub beta: f64,
    pub beta_error: f64,
    /// `beta / factor`: 1 where the correction's factor carries the spread.
    pub beta_over_factor: f64,
    /// The measured standard deviation: `|beta|` times the model's first-order one.
    pub std: f64,
    /// The samples' own standard deviation, and its 95 % interval (chi-square).
    pub sample_std: f64,
    pub sample_std_interval: [f64; 2],
}

/// One sample: its index in the Monte Carlo's streams, the modulus's factor, and the
/// measured outputs' values by the model and measured, in the order of
/// [`FeSpread::outputs`].
#[derive(Debug, Clone, Serialize)]
pub struct Sample {
    pub index: usize,
    /// Every parameter (SI).
    pub design: Vec<f64>,
    pub modulus: f64,
    pub analytic: Vec<f64>,
    pub measured: Vec<f64>,
    pub errors: Vec<Option<f64>>,
}

/// A sample the high fidelity did not measure: its part cannot be made.
#[derive(Debug, Clone, Serialize)]
pub struct Unmade {
    pub index: usize,
    /// Every parameter (SI).
    pub design: Vec<f64>,
    pub modulus: f64,
    /// The rules it breaks, or what the part's checks found.
    pub why: String,
}

/// The measured spread of a design.
#[derive(Debug, Clone, Serialize)]
pub struct FeSpread {
    pub fidelity: String,
    pub samples: usize,
    pub seed: u64,
    /// Each output the high fidelity measures among those the problem uses.
    pub outputs: Vec<MeasuredSpread>,
    /// The fraction of the analytic Monte Carlo's samples, mapped onto the measurements,
    /// that meet every constraint; its Wilson interval (of the Monte Carlo's count alone:
    /// `beta`'s own error is not in it); and per constraint.
    #[serde(rename = "yield")]
    pub yield_fraction: f64,
    pub yield_interval: [f64; 2],
    pub constraint_yields: Vec<f64>,
    pub sample_records: Vec<Sample>,
    /// The samples among the first drawn whose part cannot be made, passed over for the
    /// next ones: failed parts, which the yield counts as such.
    pub unmade: Vec<Unmade>,
    pub seconds: f64,
}

/// The measured spread of the design `x` (SI, every parameter) of `problem`, whose analytic
/// analysis (first order and Monte Carlo) is `analysis`, measured by `high` at `settings`'
/// samples, the first whose part can be made. The error names a sample that leaves the
/// model's domain or that the high fidelity cannot measure, or says that too few samples
/// can be made.
pub fn measure_spread(
    problem: &Problem,
    x: &[f64],
    analysis: &Analysis,
    high: &dyn HighFidelity,
    settings: SpreadSettings,
) -> Result<FeSpread, SpreadError> {
    use SpreadError::{Input, Measure};
    let begin = std::time::Instant::now();
    if settings.samples < MIN_SAMPLES {
        return Err(Input(format!(
            "a measured spread takes at least {MIN_SAMPLES} samples, got {}",
            settings.samples
        )));
    }
    let model = problem.model();
    let wanted = &analysis.outputs.wanted;
    let slots: Vec<usize> = (0..wanted.len())
        .filter(|&j| high.measures(x, wanted[j]))
        .collect();
    if slots.is_empty() {
        return Err(Input(format!(
            "{} measures none of the outputs the problem uses",
            high.describe()
        )));
    }
    let asked: Vec<usize> = slots.iter().map(|&j| wanted[j]).collect();
    let nominal = high
        .measure(x, &asked)
        .map_err(|e| Measure(format!("the design itself: {e}")))?;
    let one = |(i, xi, modulus): &(usize, Vec<f64>, f64)| -> Result<Sample, SpreadError> {
        let mut all = vec![0.0; wanted.len()];
        analysis.outputs.values(xi, *modulus, &mut all);
        let m = high
            .measure_at_modulus(xi, *modulus, &asked)
            .map_err(|e| Measure(format!("sample {i} (seed {}): {e}", settings.seed)))?;
        Ok(Sample {
            index: *i,
            design: xi.clone(),
            modulus: *modulus,
            analytic: slots.iter().map(|&j| all[j]).collect(),
            measured: m.values,
            errors: m.errors,
        })
    };
    let work = || {
        let (chosen, unmade) = makeable_samples(problem, x, settings)?;
        let samples = chosen.par_iter().map(one).collect::<Result<Vec<_>, _>>()?;
        Ok::<_, SpreadError>((samples, unmade))
    };
    let (samples, unmade) = match rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
    {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    }?;
    let outputs: Vec<MeasuredSpread> = slots
        .iter()
        .enumerate()
        .map(|(k, &j)| {
            let f = &analysis.first_order[j];
            let a0 = f.nominal;
            let m0 = nominal.values[k];
            let da: Vec<f64> = samples.iter().map(|s| s.analytic[k] - a0).collect();
            let dm: Vec<f64> = samples.iter().map(|s| s.measured[k] - m0).collect();
            let factor = m0 / a0;
            let (beta, beta_error) = regression(&da, &dm).unwrap_or((factor, 0.0));
            let measured: Vec<f64> = samples.iter().map(|s| s.measured[k]).collect();
            let sample_std = mean_and_std(&measured).1;
            MeasuredSpread {
                output: model.outputs()[wanted[j]].name.to_string(),
                analytic: a0,
                measured: m0,
                measured_error: nominal.errors[k],
                factor,
                analytic_std: f.std,
                beta,
                beta_error,
                beta_over_factor: beta / factor,
                std: beta.abs() * f.std,
                sample_std,
                sample_std_interval: std_interval(sample_std, samples.len() - 1),
            }
        })
        .collect();
    // the analytic Monte Carlo's samples mapped onto the measurements
    let m = wanted.len();
    let mut mapped = analysis.monte_carlo.values.clone();
    for row in mapped.chunks_mut(m) {
        for (k, &j) in slots.iter().enumerate() {
            let o = &outputs[k];
            row[j] = o.measured + o.beta * (row[j] - o.analytic);
        }
    }
    let (met, all) = count_met(&analysis.outputs, &mapped, &analysis.monte_carlo.makeable);
    let n = analysis.monte_carlo.samples;
    Ok(FeSpread {
        fidelity: high.describe(),
        samples: samples.len(),
        seed: settings.seed,
        outputs,
        yield_fraction: all as f64 / n as f64,
        yield_interval: wilson(all, n),
        constraint_yields: met.iter().map(|&c| c as f64 / n as f64).collect(),
        sample_records: samples,
        unmade,
        seconds: begin.elapsed().as_secs_f64(),
    })
}

/// How many candidates [`makeable_samples`] draws at most, per sample asked.
const CANDIDATES_PER_SAMPLE: usize = 10;

/// The first `settings.samples` of the Monte Carlo's samples whose part can be made (each
/// `(index, design, modulus)`), and those passed over before them because their part breaks
/// a rule or fails its checks. With fewer makeable among the first
/// [`CANDIDATES_PER_SAMPLE`] times as many, those found, if at least [`MIN_SAMPLES`].
#[allow(clippy::type_complexity)]
fn makeable_samples(
    problem: &Problem,
    x: &[f64],
    settings: SpreadSettings,
) -> Result<(Vec<(usize, Vec<f64>, f64)>, Vec<Unmade>), SpreadError> {
    let (model, tolerances) = (problem.model(), &problem.tolerances);
    let rules = Rules::of(problem);
    // a candidate: its draw, and why its part cannot be made where it cannot
    let candidate = |i: usize| -> Result<(usize, Vec<f64>, f64, Option<String>), SpreadError> {
        let (xi, modulus) =
            draw_sample(tolerances, x, settings.seed, i).map_err(SpreadError::Input)?;
        if let Some(why) = model.domain_error(&xi) {
            return Err(SpreadError::Input(out_of_domain(
                tolerances,
                settings.seed,
                i,
                &why,
            )));
        }
        let mut why = rules.broken_at(&xi);
        if why.is_empty() {
            if let Some(Err(e)) = problem.mechanism().part(&xi) {
                why = e.problems.join("; ");
            }
        } else {
            why = format!("it breaks {why}");
        }
        Ok((i, xi, modulus, (!why.is_empty()).then_some(why)))
    };
    let (wanted, most) = (settings.samples, settings.samples * CANDIDATES_PER_SAMPLE);
    let (mut chosen, mut unmade) = (Vec::new(), Vec::new());
    let mut next = 0;
    while chosen.len() < wanted && next < most {
        // a batch as large as the samples still wanted, checked in parallel, taken in order
        let batch = (wanted - chosen.len()).min(most - next);
        let checked: Vec<_> = (next..next + batch)
            .into_par_iter()
            .map(candidate)
            .collect::<Result<_, _>>()?;
        next += batch;
        for (index, design, modulus, why) in checked {
            match why {
                Some(why) => unmade.push(Unmade {
                    index,
                    design,
                    modulus,
                    why,
                }),
                None => chosen.push((index, design, modulus)),
            }
        }
    }
    if chosen.len() < MIN_SAMPLES {
        return Err(SpreadError::Input(format!(
            "only {} of the first {next} samples can be made (at least {MIN_SAMPLES} are \
             needed): {}",
            chosen.len(),
            unmade.first().map_or("", |u| u.why.as_str())
        )));
    }
    Ok((chosen, unmade))
}

/// The slope of `y` on `x` through the origin and its standard error; `None` where `x` does
/// not move.
fn regression(x: &[f64], y: &[f64]) -> Option<(f64, f64)> {
    let xx: f64 = x.iter().map(|v| v * v).sum();
    if xx <= 0.0 || x.len() < 2 {
        return None;
    }
    let beta = x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>() / xx;
    let residual: f64 = x.iter().zip(y).map(|(a, b)| (b - beta * a).powi(2)).sum();
    let se = (residual / (x.len() - 1) as f64 / xx).sqrt();
    Some((beta, se))
}

/// The 95 % interval of a normal population's standard deviation from a sample's `s` with
/// `nu` degrees of freedom: `s sqrt(nu / chi2_0.975)` to `s sqrt(nu / chi2_0.025)`.
fn std_interval(s: f64, nu: usize) -> [f64; 2] {
    let nu_f = nu as f64;
    [
        s * (nu_f / chi_square_quantile(0.975, nu)).sqrt(),
        s * (nu_f / chi_square_quantile(0.025, nu)).sqrt(),
    ]
}

/// The chi-square distribution's `p` quantile with `nu` degrees of freedom: bisection of
/// its distribution function, the regularized lower incomplete gamma function
/// `P(nu/2, q/2)`, summed as its series `P(a, x) = x^a e^-x / Gamma(a + 1) sum_k x^k /
/// ((a + 1) ... (a + k))` (Press, Teukolsky, Vetterling and Flannery, *Numerical Recipes*,
/// 3rd ed., 2007, Eq. 6.2.5), which converges for every `x`.
fn chi_square_quantile(p: f64, nu: usize) -> f64 {
    let a = nu as f64 / 2.0;
    let cdf = |q: f64| {
        let x = q / 2.0;
        let (mut term, mut sum, mut k) = (1.0 / a, 1.0 / a, 1.0);
        while term > sum * 1e-17 && k < 10_000.0 {
            term *= x / (a + k);
            sum += term;
            k += 1.0;
        }
        (a * x.ln() - x - libm::lgamma(a) + sum.ln()).exp()
    };
    let (mut lo, mut hi) = (0.0, 10.0 * (nu as f64 + 10.0));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi_square_quantiles_agree_with_the_tables() {
        // the exact quantiles (NIST/SEMATECH e-Handbook, Table 1.3.6.7.4)
        for (p, nu, exact) in [
            (0.975, 11, 21.920),
            (0.025, 11, 3.816),
            (0.975, 5, 12.833),
            (0.025, 5, 0.831),
            (0.975, 30, 46.979),
            (0.025, 30, 16.791),
        ] {
            let q = chi_square_quantile(p, nu);
            // to the table's three decimals
            assert!((q - exact).abs() <= 5e-4, "{p} {nu}: {q} vs {exact}");
        }
    }

    #[test]
    fn the_regression_recovers_an_exact_slope_with_no_error() {
        let x = [0.3, -1.2, 0.7, 2.0];
        let y: Vec<f64> = x.iter().map(|v| -1.7 * v).collect();
        let (beta, se) = regression(&x, &y).unwrap();
        assert!((beta + 1.7).abs() < 1e-15 && se < 1e-15);
        assert!(regression(&[0.0, 0.0], &[1.0, 2.0]).is_none());
    }
}
