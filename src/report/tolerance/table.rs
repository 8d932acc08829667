//! The terminal's tables of `flexopt tolerance` and of a robust study: the tolerances,
//! each output's spread and yield, the part's yield by the FE, and the nominal optimum beside
//! the robust one.

use std::fmt::{self, Display};

use super::{FeReport, ToleranceReport};
use crate::problem::display::{human, significant};
use crate::problem::tolerances::{Distribution, Origin};
use crate::problem::Problem;
use crate::tolerance::robust::{Comparison, Side};

/// A fraction as a percentage with its sign, four significant digits.
pub(super) fn pc(fraction: f64) -> String {
    format!("{} %", significant(100.0 * fraction, 4))
}

/// The terminal's table: the tolerances, then each output's spread and yield.
pub struct ToleranceTable<'a>(pub &'a ToleranceReport);

impl Display for ToleranceTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = self.0;
        writeln!(s, "{} ({} model): tolerances", r.problem, r.model)?;
        for t in &r.tolerances {
            let unit = if t.unit == "1" { "" } else { &t.unit };
            let distribution = match t.distribution {
                Distribution::Normal => {
                    format!("normal, the band {} standard deviations", human(t.coverage))
                }
                Distribution::Uniform => "uniform".into(),
            };
            let origin = match t.origin {
                Origin::File => "",
                Origin::Default => " (wire EDM's default)",
            };
            writeln!(
                s,
                "  {:<16} +-{:<10} {:<4} {distribution}{origin}",
                t.name,
                human(t.plus_minus),
                unit,
            )?;
        }
        writeln!(
            s,
            "{:<18} {:>12} {:>11} {:>11} {:>11} {:>9} {:>9}  unit; largest share",
            "output", "nominal", "std (1st)", "std (MC)", "mean (MC)", "meet 1st", "meet MC"
        )?;
        for o in &r.outputs {
            let (top, share) = o
                .shares
                .iter()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .map_or(("-", 0.0), |(n, &v)| (n.as_str(), v));
            let unit = if o.unit == "1" { "" } else { &o.unit };
            writeln!(
                s,
                "{:<18} {:>12} {:>11} {:>11} {:>11} {:>9} {:>9}  {unit}; {top} {}",
                o.name,
                human(o.nominal),
                human(o.std),
                human(o.monte_carlo.std),
                human(o.monte_carlo.mean),
                o.first_order_yield.map_or("-".into(), pc),
                o.monte_carlo_yield.map_or("-".into(), pc),
                pc(share),
            )?;
        }
        writeln!(
            s,
            "yield: {} of {} samples can be made and meet {} ({} {} interval {} .. {})",
            pc(r.yield_fraction),
            r.samples,
            if r.yield_of.len()
                == r.outputs
                    .iter()
                    .filter(|o| o.monte_carlo_yield.is_some())
                    .count()
            {
                "every constraint".to_string()
            } else {
                r.yield_of.join(", ")
            },
            pc(r.yield_confidence),
            r.interval_method.split(',').next().unwrap_or(""),
            pc(r.yield_interval[0]),
            pc(r.yield_interval[1]),
        )?;
        if !r.rules_broken.is_empty() {
            let broken: Vec<String> = r
                .rules_broken
                .iter()
                .filter(|(_, &f)| f > 0.0)
                .map(|(rule, &f)| format!("{rule} {}", pc(f)))
                .collect();
            writeln!(
                s,
                "cannot be made: {} of the samples break the part's rules{}",
                pc(r.unmakeable),
                if broken.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", broken.join(", "))
                }
            )?;
        }
        if let Some(fe) = &r.fe {
            write!(s, "{}", FeTable(fe))?;
        }
        Ok(())
    }
}

/// The measured spread's lines of the terminal's table.
struct FeTable<'a>(&'a FeReport);

impl Display for FeTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let fe = self.0;
        writeln!(
            s,
            "by FE ({}), {} of the Monte Carlo's samples, {} s:",
            fe.fidelity,
            fe.samples,
            significant(fe.seconds, 3)
        )?;
        if !fe.unmade.is_empty() {
            let indices: Vec<String> = fe.unmade.iter().map(|u| u.index.to_string()).collect();
            writeln!(
                s,
                "  passed over, their part cannot be made: samples {} (the first: {})",
                indices.join(", "),
                fe.unmade[0].why
            )?;
        }
        writeln!(
            s,
            "{:<18} {:>11} {:>11} {:>8} {:>15} {:>11} {:>11} {:>25}  unit",
            "output",
            "FE",
            "model",
            "FE/model",
            "beta/factor",
            "std (FE)",
            "std (model)",
            "samples' std [95 %]"
        )?;
        for o in &fe.outputs {
            let unit = if o.unit == "1" { "" } else { &o.unit };
            writeln!(
                s,
                "{:<18} {:>11} {:>11} {:>8} {:>15} {:>11} {:>11} {:>25}  {unit}",
                o.name,
                human(o.fe),
                human(o.model),
                significant(o.factor, 4),
                format!(
                    "{} +-{}",
                    significant(o.beta_over_factor, 3),
                    significant(o.beta_error / o.factor.abs(), 2)
                ),
                human(o.std),
                human(o.model_std),
                format!(
                    "{} [{} .. {}]",
                    human(o.sample_std),
                    human(o.sample_std_interval[0]),
                    human(o.sample_std_interval[1])
                ),
            )?;
        }
        writeln!(
            s,
            "yield of the part (the Monte Carlo mapped onto the FE): {} ({} .. {})",
            pc(fe.yield_fraction),
            pc(fe.yield_interval[0]),
            pc(fe.yield_interval[1]),
        )
    }
}

/// The nominal and the robust optimum side by side.
pub struct RobustTable<'a>(pub &'a Comparison, pub &'a Problem);

impl Display for RobustTable<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (c, p) = (self.0, self.1);
        let target = c
            .target_yield
            .map_or(String::new(), |y| format!(" for a yield of {}", pc(y)));
        writeln!(
            s,
            "robust study: every constraint and rule of the part kept {} first-order standard \
             deviations inside its limits{target}; yields by {} Monte Carlo samples",
            significant(c.k_sigma, 4),
            c.samples
        )?;
        let sides = [("nominal", c.nominal.as_ref()), ("robust", Some(&c.robust))];
        writeln!(s, "  {:<22} {:>16} {:>16}", "", "nominal", "robust")?;
        let cell = |f: &dyn Fn(&Side) -> String, side: Option<&Side>| side.map_or("-".into(), f);
        writeln!(
            s,
            "  {:<22} {:>16} {:>16}",
            p.objective.output,
            cell(&|x| human(x.objective), sides[0].1),
            cell(&|x| human(x.objective), sides[1].1)
        )?;
        writeln!(
            s,
            "  {:<22} {:>16} {:>16}",
            "yield (Monte Carlo)",
            cell(&|x| pc(x.yield_fraction), sides[0].1),
            cell(&|x| pc(x.yield_fraction), sides[1].1)
        )?;
        writeln!(
            s,
            "  {:<22} {:>16} {:>16}",
            "cannot be made",
            cell(&|x| pc(x.unmakeable), sides[0].1),
            cell(&|x| pc(x.unmakeable), sides[1].1)
        )?;
        for k in c.robust.margins_in_sigma.keys() {
            let m = |x: &Side| format!("{} sigma", significant(x.margins_in_sigma[k], 3));
            writeln!(
                s,
                "  {:<22} {:>16} {:>16}",
                format!("margin of {k}"),
                cell(&m, sides[0].1),
                cell(&m, sides[1].1)
            )?;
        }
        Ok(())
    }
}
