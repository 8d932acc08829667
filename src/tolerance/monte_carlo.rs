//! Monte Carlo over a design's tolerances: sample `i` draws from its own random stream
//! (ChaCha8 seeded with the run's seed, stream `i`), as the multistart seeds its starts, so
//! that the thread count changes no result.

use rand::Rng;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;
use serde::Serialize;

use super::makeable::Rules;
use super::Outputs;
use crate::model::part_rules::broken;
use crate::problem::tolerances::{Distribution, Input, Tolerance};

/// How many samples, from which seed, on how many threads (0: every core).
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    pub samples: usize,
    pub seed: u64,
    pub threads: usize,
}

/// The probabilities of [`Spread::quantiles`].
pub const QUANTILES: [f64; 7] = [0.001, 0.01, 0.05, 0.5, 0.95, 0.99, 0.999];

/// The confidence of the yield's interval, and its normal quantile.
pub const CONFIDENCE: f64 = 0.95;
const Z95: f64 = 1.959_963_984_540_054;

/// One output over the samples.
#[derive(Debug, Clone, Serialize)]
pub struct Spread {
    pub mean: f64,
    pub std: f64,
    /// `[probability, value]` at each of [`QUANTILES`].
    pub quantiles: Vec<[f64; 2]>,
    pub min: f64,
    pub max: f64,
}

/// The samples' outputs and what they say.
#[derive(Debug, Clone, Serialize)]
pub struct MonteCarlo {
    pub samples: usize,
    pub seed: u64,
    /// The fraction of samples whose part can be made and that meet every constraint the
    /// yield counts.
    #[serde(rename = "yield")]
    pub yield_fraction: f64,
    /// Its Wilson score interval at [`CONFIDENCE`].
    pub yield_interval: [f64; 2],
    pub interval_method: &'static str,
    /// Per wanted output, in the order of [`Outputs::wanted`].
    pub outputs: Vec<Spread>,
    /// Per constraint, the fraction of samples that meet it (whether or not their part can
    /// be made: the performance alone).
    pub constraint_yields: Vec<f64>,
    /// The fraction of samples whose part breaks one of the part's rules or more: parts that
    /// cannot be made, which the yield counts as failed ([`super::makeable`]).
    pub unmakeable: f64,
    /// Per rule of the part, in its order, the fraction of samples that break it.
    pub rule_breaks: Vec<f64>,
    /// Every sample's wanted outputs, row-major (for the histograms; not written).
    #[serde(skip)]
    pub values: Vec<f64>,
    /// Whether each sample's part keeps every rule (not written).
    #[serde(skip)]
    pub makeable: Vec<bool>,
}

/// The deviation of one input, in standard deviations, from `rng`.
fn draw(rng: &mut ChaCha8Rng, distribution: Distribution) -> f64 {
    match distribution {
        Distribution::Normal => rng.sample(StandardNormal),
        // uniform on +-sqrt(3): unit variance
        Distribution::Uniform => (2.0 * rng.random::<f64>() - 1.0) * 3f64.sqrt(),
    }
}

/// Sample `i` of the tolerances around `x` from the seed `seed`: the design (every
/// parameter, SI) and the modulus's factor. Every analysis that samples a design (the
/// Monte Carlo here, the FE's few samples in [`crate::refine::spread`]) draws through this,
/// so that its sample `i` is the Monte Carlo's. A factor at or below zero is an error.
pub fn draw_sample(
    tolerances: &[Tolerance],
    x: &[f64],
    seed: u64,
    i: usize,
) -> Result<(Vec<f64>, f64), String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(i as u64);
    let mut xi = x.to_vec();
    let mut modulus = 1.0;
    for t in tolerances {
        let d = draw(&mut rng, t.distribution) * t.sigma;
        match t.input {
            Input::Parameter(j) => xi[j] += d,
            Input::Modulus => modulus += d,
        }
    }
    if modulus <= 0.0 {
        let why = format!("youngs_modulus's factor {modulus} is not positive");
        return Err(out_of_domain(tolerances, seed, i, &why));
    }
    Ok((xi, modulus))
}

/// The message of sample `i` (seed `seed`) leaving the model's domain for `why`.
pub fn out_of_domain(tolerances: &[Tolerance], seed: u64, i: usize, why: &str) -> String {
    format!(
        "Monte Carlo sample {i} (seed {seed}) leaves the model's domain: {why}; the \
         tolerances ({}) are too wide for this design",
        tolerances
            .iter()
            .map(|t| t.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// The samples one task of [`run`] takes: the rules' counts are summed per block, so that
/// the thread count changes no count.
const BLOCK: usize = 256;

/// Samples the tolerances around `x` and evaluates the wanted outputs and the part's rules
/// at each sample; an error names the first sample (by index) whose design leaves the
/// model's domain.
pub fn run(
    outputs: &Outputs,
    tolerances: &[Tolerance],
    x: &[f64],
    settings: Settings,
) -> Result<MonteCarlo, String> {
    let m = outputs.wanted.len();
    let model = outputs.problem.model();
    let rules = Rules::of(outputs.problem);
    let r = rules.len();
    let mut values = vec![0.0; settings.samples * m];
    let mut makeable = vec![true; settings.samples];
    // one block of samples from `first`: their outputs, whether each can be made, and how
    // many break each rule
    let block = |first: usize, rows: &mut [f64], made: &mut [bool]| {
        let mut breaks = vec![0usize; r];
        let mut margins = vec![0.0; r];
        for (k, (row, made)) in rows.chunks_mut(m).zip(made.iter_mut()).enumerate() {
            let i = first + k;
            let (xi, modulus) = draw_sample(tolerances, x, settings.seed, i).map_err(|e| (i, e))?;
            if let Some(why) = model.domain_error(&xi) {
                return Err((i, out_of_domain(tolerances, settings.seed, i, &why)));
            }
            outputs.values(&xi, modulus, row);
            *made = rules.keeps_all(&xi, &mut margins);
            if !*made {
                for (count, &margin) in breaks.iter_mut().zip(&margins) {
                    *count += usize::from(broken(margin));
                }
            }
        }
        Ok(breaks)
    };
    let mut work = || {
        values
            .par_chunks_mut(m * BLOCK)
            .zip(makeable.par_chunks_mut(BLOCK))
            .enumerate()
            .map(|(b, (rows, made))| block(b * BLOCK, rows, made))
            .collect::<Vec<_>>()
    };
    let blocks = match rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
    {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    };
    let mut breaks = vec![0usize; r];
    for block in blocks {
        // blocks in order, and the first sample of a block that failed stops it: the first
        // error is the first failing sample's
        for (total, count) in breaks.iter_mut().zip(block.map_err(|(_, e)| e)?) {
            *total += count;
        }
    }
    Ok(summarize(outputs, values, makeable, &breaks, settings))
}

/// How many rows of `values` (the wanted outputs of each sample, row-major) meet each
/// constraint, and how many of those whose part can be made (`makeable`, one per row) meet
/// every one the yield counts ([`crate::problem::Constraint::in_yield`]).
pub fn count_met(outputs: &Outputs, values: &[f64], makeable: &[bool]) -> (Vec<usize>, usize) {
    let m = outputs.wanted.len();
    let constraints = &outputs.problem.constraints;
    let columns: Vec<usize> = constraints
        .iter()
        .map(|c| {
            outputs
                .wanted
                .iter()
                .position(|&w| w == c.index)
                .unwrap_or(0)
        })
        .collect();
    let meets = |row: &[f64], k: usize| {
        let (c, y) = (&constraints[k], row[columns[k]]);
        c.lower.is_none_or(|l| y >= l) && c.upper.is_none_or(|u| y <= u)
    };
    let mut met = vec![0usize; constraints.len()];
    let mut all = 0usize;
    for (row, &made) in values.chunks(m).zip(makeable) {
        let mut every = made;
        for (k, count) in met.iter_mut().enumerate() {
            if meets(row, k) {
                *count += 1;
            } else if constraints[k].in_yield {
                every = false;
            }
        }
        all += usize::from(every);
    }
    (met, all)
}

/// The mean of `v` and its sample standard deviation (`n - 1` in the denominator).
pub fn mean_and_std(v: &[f64]) -> (f64, f64) {
    let n = v.len();
    let mean = v.iter().sum::<f64>() / n as f64;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1).max(1) as f64;
    (mean, var.sqrt())
}

fn summarize(
    outputs: &Outputs,
    values: Vec<f64>,
    makeable: Vec<bool>,
    breaks: &[usize],
    settings: Settings,
) -> MonteCarlo {
    let (n, m) = (settings.samples, outputs.wanted.len());
    let (met, all) = count_met(outputs, &values, &makeable);
    let unmade = makeable.iter().filter(|&&made| !made).count();
    let spreads = (0..m)
        .map(|j| {
            let mut column: Vec<f64> = values.iter().skip(j).step_by(m).copied().collect();
            let (mean, std) = mean_and_std(&column);
            column.sort_by(f64::total_cmp);
            Spread {
                mean,
                std,
                quantiles: QUANTILES.map(|q| [q, quantile(&column, q)]).to_vec(),
                min: column[0],
                max: column[n - 1],
            }
        })
        .collect();
    let fraction = all as f64 / n as f64;
    MonteCarlo {
        samples: n,
        seed: settings.seed,
        yield_fraction: fraction,
        yield_interval: wilson(all, n),
        interval_method: "Wilson score, 95 %",
        outputs: spreads,
        constraint_yields: met.iter().map(|&c| c as f64 / n as f64).collect(),
        unmakeable: unmade as f64 / n as f64,
        rule_breaks: breaks.iter().map(|&c| c as f64 / n as f64).collect(),
        values,
        makeable,
    }
}

/// The `q` quantile of the sorted `v`, interpolated linearly between order statistics
/// (Hyndman and Fan's definition 7, the default of R and NumPy).
pub fn quantile(v: &[f64], q: f64) -> f64 {
    let h = (v.len() - 1) as f64 * q;
    let (lo, frac) = (h.floor() as usize, h - h.floor());
    let hi = (lo + 1).min(v.len() - 1);
    v[lo] + (v[hi] - v[lo]) * frac
}

/// The Wilson score interval of a proportion of `k` in `n` at 95 % (E. B. Wilson, J. Am.
/// Stat. Assoc. 22 (1927) 209-212; Brown, Cai and DasGupta, Stat. Sci. 16 (2001) 101-133,
/// recommend it over the normal interval, which collapses at a yield of 0 or 1).
pub fn wilson(k: usize, n: usize) -> [f64; 2] {
    let (n, p) = (n as f64, k as f64 / n as f64);
    let z2 = Z95 * Z95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}
