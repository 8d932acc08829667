//! What a verification's outputs are compared with, and what its table says they are
//! measured under.

use crate::fe::verify::Verification;
use crate::part::analysis::{Comparison, FeCounterpart, Quantity};
use crate::problem::Problem;

/// The analytic value each FE output (by its place in the part's analysis) is compared
/// with: that of the model's output whose counterpart it is
/// ([`crate::model::PartMaker::fe_counterpart`]), else the comparison the analysis states for it
/// (a displacement from a stiffness at the test force, or another output).
pub(super) fn analytic(problem: &Problem, x: &[f64], v: &Verification) -> Vec<Option<f64>> {
    let model = problem.model();
    let mut out = vec![None; v.analysis.outputs.len()];
    for i in 0..model.outputs().len() {
        if let (Some(FeCounterpart::Output(id)), Some(value)) =
            (problem.mechanism().fe_counterpart(i), value(model, x, i))
        {
            if let Some(slot) = out.get_mut(id.0) {
                *slot = Some(value);
            }
        }
    }
    for (slot, o) in out.iter_mut().zip(&v.analysis.outputs) {
        if slot.is_some() {
            continue;
        }
        *slot = match o.analytic {
            None => None,
            Some(Comparison::Output(i)) => value(model, x, i),
            Some(Comparison::PerTestForce { stiffness, times }) => value(model, x, stiffness)
                .and_then(|k| match times {
                    None => Some(v.test_force / k),
                    Some(t) => value(model, x, t).map(|a| a * v.test_force / k),
                }),
        };
    }
    out
}

/// The model's output `i` at `x`, where the model can compute it: not a stand-in for what
/// only the FE measures, which has no analytic value to compare with.
pub(super) fn value(model: &dyn crate::model::Model, x: &[f64], i: usize) -> Option<f64> {
    let own = model.unavailable(i).is_none() && model.outputs()[i].stand_in.is_none();
    own.then(|| {
        let mut v = [0.0];
        model.evaluate(x, &[i], &mut v);
        v[0]
    })
}

/// The displacement outputs and the load case they are measured under, as `"fe_a, fe_b at
/// 10 N on the faces"`.
pub(super) fn displacements_at(v: &Verification) -> String {
    let an = &v.analysis;
    let shown: Vec<(&str, usize)> = an
        .outputs
        .iter()
        .filter_map(|o| match o.quantity {
            Quantity::Displacement(m) => Some((o.name, an.measures.get(m)?.case)),
            _ => None,
        })
        .collect();
    let Some(&(_, case)) = shown.first() else {
        return String::new();
    };
    let names: Vec<&str> = shown.iter().map(|s| s.0).collect();
    let case = an.cases.get(case).map_or("", |c| c.name.as_str());
    format!("{} at {} N {case}; ", names.join(", "), v.test_force)
}
