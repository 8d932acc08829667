//! Hock-Schittkowski test problems (W. Hock, K. Schittkowski, Test Examples for Nonlinear
//! Programming Codes, Springer 1981), written once over `Scalar` so that `Jet` gives their
//! exact gradients.

use flexopt::model::scalar::{Jet, Scalar};
use flexopt::optim::Problem;

pub struct Hs<const N: usize> {
    pub name: &'static str,
    pub lower: [f64; N],
    pub upper: [f64; N],
    pub start: [f64; N],
    pub equalities: usize,
    pub constraints: usize,
    pub f: fn(&[Jet<N>; N]) -> Jet<N>,
    pub c: fn(&[Jet<N>; N], &mut [Jet<N>]),
    /// The known optimum.
    pub x_opt: [f64; N],
    pub f_opt: f64,
}

impl<const N: usize> Problem for Hs<N> {
    fn dimension(&self) -> usize {
        N
    }
    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }
    fn equality_count(&self) -> usize {
        self.equalities
    }
    fn constraint_count(&self) -> usize {
        self.constraints
    }
    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64 {
        let mut g = vec![0.0; N];
        let mut j = vec![0.0; N * self.constraints];
        self.evaluate_with_gradient(x, c, &mut g, &mut j)
    }
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        g: &mut [f64],
        jac: &mut [f64],
    ) -> f64 {
        let xs: [Jet<N>; N] = std::array::from_fn(|i| Jet::variable(x[i], i));
        let mut cs = vec![Jet::from(0.0); self.constraints];
        (self.c)(&xs, &mut cs);
        for (i, ci) in cs.iter().enumerate() {
            c[i] = ci.re;
            jac[i * N..(i + 1) * N].copy_from_slice(&ci.grad);
        }
        let f = (self.f)(&xs);
        g.copy_from_slice(&f.grad);
        f.re
    }
}

const INF: f64 = f64::INFINITY;

fn sq<D: Scalar>(x: D) -> D {
    x * x
}

pub fn hs6() -> Hs<2> {
    Hs {
        name: "HS6",
        lower: [-INF; 2],
        upper: [INF; 2],
        start: [-1.2, 1.0],
        equalities: 1,
        constraints: 1,
        f: |x| sq(-x[0] + 1.0),
        c: |x, c| c[0] = (x[1] - x[0] * x[0]) * 10.0,
        x_opt: [1.0, 1.0],
        f_opt: 0.0,
    }
}

pub fn hs7() -> Hs<2> {
    Hs {
        name: "HS7",
        lower: [-INF; 2],
        upper: [INF; 2],
        start: [2.0, 2.0],
        equalities: 1,
        constraints: 1,
        // ln(1 + x1^2) - x2, through a series-free form: Jet has no ln, so use the identity
        // d/dx ln(u) = u'/u by building the value and gradient by hand
        f: |x| {
            let u = x[0] * x[0] + 1.0;
            let mut v = Jet::from(u.re.ln());
            v.grad = u.grad.map(|g| g / u.re);
            v - x[1]
        },
        c: |x, c| c[0] = sq(x[0] * x[0] + 1.0) + x[1] * x[1] - 4.0,
        x_opt: [0.0, 1.7320508075688772],
        f_opt: -1.7320508075688772,
    }
}

pub fn hs10() -> Hs<2> {
    Hs {
        name: "HS10",
        lower: [-INF; 2],
        upper: [INF; 2],
        start: [-10.0, 10.0],
        equalities: 0,
        constraints: 1,
        f: |x| x[0] - x[1],
        c: |x, c| c[0] = -(x[0] * x[0] * 3.0) + x[0] * x[1] * 2.0 - x[1] * x[1] + 1.0,
        x_opt: [0.0, 1.0],
        f_opt: -1.0,
    }
}

pub fn hs14() -> Hs<2> {
    let s7 = 7f64.sqrt();
    Hs {
        name: "HS14",
        lower: [-INF; 2],
        upper: [INF; 2],
        start: [2.0, 2.0],
        equalities: 1,
        constraints: 2,
        f: |x| sq(x[0] - 2.0) + sq(x[1] - 1.0),
        c: |x, c| {
            c[0] = x[0] - x[1] * 2.0 + 1.0;
            c[1] = -(x[0] * x[0] * 0.25) - x[1] * x[1] + 1.0;
        },
        x_opt: [0.5 * (s7 - 1.0), 0.25 * (s7 + 1.0)],
        f_opt: 9.0 - 23.0 * s7 / 8.0,
    }
}

pub fn hs15() -> Hs<2> {
    Hs {
        name: "HS15",
        lower: [-INF, -INF],
        upper: [0.5, INF],
        start: [-2.0, 1.0],
        equalities: 0,
        constraints: 2,
        f: |x| sq(x[1] - x[0] * x[0]) * 100.0 + sq(-x[0] + 1.0),
        c: |x, c| {
            c[0] = x[0] * x[1] - 1.0;
            c[1] = x[0] + x[1] * x[1];
        },
        x_opt: [0.5, 2.0],
        f_opt: 306.5,
    }
}

pub fn hs21() -> Hs<2> {
    Hs {
        name: "HS21",
        lower: [2.0, -50.0],
        upper: [50.0, 50.0],
        start: [-1.0, -1.0],
        equalities: 0,
        constraints: 1,
        f: |x| x[0] * x[0] * 0.01 + x[1] * x[1] - 100.0,
        c: |x, c| c[0] = x[0] * 10.0 - x[1] - 10.0,
        x_opt: [2.0, 0.0],
        f_opt: -99.96,
    }
}

pub fn hs35() -> Hs<3> {
    Hs {
        name: "HS35",
        lower: [0.0; 3],
        upper: [INF; 3],
        start: [0.5; 3],
        equalities: 0,
        constraints: 1,
        f: |x| {
            -(x[0] * 8.0) - x[1] * 6.0 - x[2] * 4.0
                + 9.0
                + x[0] * x[0] * 2.0
                + x[1] * x[1] * 2.0
                + x[2] * x[2]
                + x[0] * x[1] * 2.0
                + x[0] * x[2] * 2.0
        },
        c: |x, c| c[0] = -x[0] - x[1] - x[2] * 2.0 + 3.0,
        x_opt: [4.0 / 3.0, 7.0 / 9.0, 4.0 / 9.0],
        f_opt: 1.0 / 9.0,
    }
}

pub fn hs71() -> Hs<4> {
    Hs {
        name: "HS71",
        lower: [1.0; 4],
        upper: [5.0; 4],
        start: [1.0, 5.0, 5.0, 1.0],
        equalities: 1,
        constraints: 2,
        f: |x| x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2],
        c: |x, c| {
            c[0] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3] - 40.0;
            c[1] = x[0] * x[1] * x[2] * x[3] - 25.0;
        },
        x_opt: [1.0, 4.742999643, 3.821149978, 1.379408293],
        f_opt: 17.0140172891,
    }
}
