//! `flexopt hinge --format table`: one hinge's figures as a designer reads them, each with
//! its unit (the JSON is the calculator's report as it is, SI unless a key says otherwise).

use std::fmt::{self, Display};

use crate::model::hinge::calculator::HingeReport;

/// The table of a hinge's report.
pub struct HingeTable<'a>(pub &'a HingeReport);

/// `v` with `digits` significant digits.
fn sig(v: f64, digits: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if !(-3..6).contains(&magnitude) {
        return format!("{:.*e}", digits - 1, v);
    }
    let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
    format!("{v:.decimals$}")
}

/// A dimension as a designer gives it: six significant digits, no trailing zeros.
fn dimension(v: f64) -> String {
    let s = sig(v, 6);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl Display for HingeTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = self.0;
        let dims: Vec<String> = r
            .dimensions_mm
            .iter()
            .map(|(k, v)| format!("{k} = {} mm", dimension(*v)))
            .collect();
        writeln!(
            f,
            "{} hinge, {}, {} mm wide, {}",
            r.kind.name(),
            dims.join(", "),
            dimension(r.width_mm),
            r.material.name
        )?;
        let c = &r.compliance;
        let k = &r.stiffness;
        let rows: [(&str, String, &str); 14] = [
            ("length", dimension(r.length_mm), "mm"),
            ("least thickness", dimension(r.least_thickness_mm), "mm"),
            ("root thickness", dimension(r.root_thickness_mm), "mm"),
            ("c11 (axial)", sig(c.c11 * 1e6, 5), "um/N"),
            ("c22 (transverse)", sig(c.c22 * 1e6, 5), "um/N"),
            ("c23 (slope per force)", sig(c.c23 * 1e3, 5), "mrad/N"),
            ("c33 (slope per moment)", sig(c.c33, 5), "rad/(N m)"),
            ("k11 (axial)", sig(k.k11 * 1e-6, 5), "N/um"),
            ("k22 (transverse)", sig(k.k22 * 1e-6, 5), "N/um"),
            ("k33 (rotational)", sig(k.k33, 5), "N m/rad"),
            ("stress limit", sig(r.stress_limit * 1e-6, 5), "MPa"),
            (
                "stress concentration K_t",
                sig(r.stress_concentration, 5),
                "",
            ),
            ("largest moment", sig(r.max_moment * 1e3, 5), "N mm"),
            ("largest rotation", sig(r.max_rotation_deg, 5), "deg"),
        ];
        for (name, value, unit) in rows {
            let line = format!("  {name:<26} {value:>12} {unit}");
            writeln!(f, "{}", line.trim_end())?;
        }
        writeln!(
            f,
            "  (the stress limit is {}; the largest moment and rotation reach it at the \
             thinnest section, K_t included)",
            r.stress_limit_from
        )?;
        for check in &r.fit_ranges {
            let range = match (check.lower, check.upper) {
                (Some(lo), Some(hi)) => format!("{lo} .. {hi}"),
                (Some(lo), None) => format!("{lo} .."),
                (None, Some(hi)) => format!(".. {hi}"),
                (None, None) => "any".into(),
            };
            writeln!(
                f,
                "  {} = {} (fitted for {range}): {}",
                check.ratio,
                sig(check.value, 4),
                if check.inside {
                    "inside"
                } else {
                    "OUTSIDE: the figures above are not to be trusted"
                }
            )?;
        }
        Ok(())
    }
}
