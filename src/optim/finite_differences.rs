//! Gradients by central differences, for problems without exact ones (and to measure what
//! exact gradients are worth).

use super::problem::Problem;

/// `problem` with its gradients replaced by central differences of its values, with step
/// `step * max(1, |x_j|)`, one-sided where a bound is closer than the step.
pub struct CentralDifferences<'a> {
    pub problem: &'a dyn Problem,
    pub step: f64,
}

impl<'a> CentralDifferences<'a> {
    /// The step `eps^(1/3)`, which balances truncation and rounding errors.
    pub fn new(problem: &'a dyn Problem) -> Self {
        CentralDifferences {
            problem,
            step: f64::EPSILON.cbrt(),
        }
    }
}

impl Problem for CentralDifferences<'_> {
    fn dimension(&self) -> usize {
        self.problem.dimension()
    }
    fn bounds(&self) -> (&[f64], &[f64]) {
        self.problem.bounds()
    }
    fn equality_count(&self) -> usize {
        self.problem.equality_count()
    }
    fn constraint_count(&self) -> usize {
        self.problem.constraint_count()
    }
    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64 {
        self.problem.evaluate(x, c)
    }
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let n = x.len();
        let m = c.len();
        let f = self.problem.evaluate(x, c);
        let (lower, upper) = self.problem.bounds();
        let mut xs = x.to_vec();
        let (mut cp, mut cm) = (vec![0.0; m], vec![0.0; m]);
        for j in 0..n {
            let h = self.step * x[j].abs().max(1.0);
            let (up, down) = ((x[j] + h).min(upper[j]), (x[j] - h).max(lower[j]));
            xs[j] = up;
            let fp = self.problem.evaluate(&xs, &mut cp);
            xs[j] = down;
            let fm = self.problem.evaluate(&xs, &mut cm);
            xs[j] = x[j];
            let width = up - down;
            gradient[j] = (fp - fm) / width;
            for i in 0..m {
                jacobian[i * n + j] = (cp[i] - cm[i]) / width;
            }
        }
        f
    }
}
