//! How numbers and quantities read where a person reads them: in the unit the problem file
//! used for each (a variable's, a constraint's) or a designer's usual one, with the digits
//! that matter. JSON keeps SI and full precision; these are for terminals, plots and CSV.

use super::design::default_design;
use super::Problem;
use crate::model::Dimension;
use crate::vocab::units::Unit;

/// A number as a person reads it: exactly as written when it has few digits (a value from
/// the file: `1.96`, `-15`, `0.333`), else to six significant digits (`1.98403`), plain
/// between 1e-4 and 1e9 and in short scientific form outside (`6.19e-11`).
pub fn human(v: f64) -> String {
    if !v.is_finite() {
        return "-".to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let shortest = format!("{v:e}");
    let digits = shortest
        .split('e')
        .next()
        .map_or(17, |m| m.chars().filter(char::is_ascii_digit).count());
    let value = if digits <= 9 {
        v
    } else {
        format!("{v:.5e}").parse().unwrap_or(v)
    };
    plain_or_scientific(value)
}

/// `v` to `digits` significant digits, trailing zeros dropped.
pub fn significant(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return "-".to_string();
    }
    let rounded: f64 = format!("{v:.*e}", digits.max(1) - 1).parse().unwrap_or(v);
    plain_or_scientific(rounded)
}

/// A fraction as a percentage, to six significant digits: a tolerance of `1e-6` reads
/// `0.0001` (%), not the `0.00009999999999999999` of its product by 100.
pub fn percent(fraction: f64) -> String {
    significant(100.0 * fraction, 6)
}

fn plain_or_scientific(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-4..1e9).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A number in a CSV file: plain decimal between 1e-4 and 1e7, else short scientific form
/// (`6.189952040375121e-11`, never `1.2897935500824541e1`); every digit kept.
pub fn csv(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if !v.is_finite() || (1e-4..1e7).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The unit the output `output` of `problem`'s model is shown in, wherever a person reads
/// it (the terminal's summaries and tables, the report, plots' axes, CSV headers): its
/// constraint's unit when the file constrains it, else the model's choice for it, else the
/// designer's usual one for its dimension and size ([`usual_unit`]) at the middle of the
/// design space ([`default_design`]), so that one problem shows an output in one unit
/// whatever design it reports.
pub fn output_unit(problem: &Problem, output: usize) -> Unit {
    if let Some(c) = problem.constraints.iter().find(|c| c.index == output) {
        return c.unit.clone();
    }
    let model = problem.model();
    let info = &model.outputs()[output];
    if let Some(unit) = info
        .display
        .and_then(|name| Unit::parse(name, info.dimension).ok())
    {
        return unit;
    }
    let mut typical = [f64::NAN];
    if info.stand_in.is_none() && info.dimension == Dimension::Length {
        model.evaluate(&default_design(problem), &[output], &mut typical);
    }
    usual_unit(info.dimension, typical[0])
}

/// The unit a designer reads a quantity of `dimension` and size `si` in: a length under a
/// millimetre (a stroke, a displacement) in micrometres, any other in [`Unit::display`]'s
/// (mm, N/um, MPa, Hz, ...). A size that is zero or not finite says nothing: the
/// dimension's usual unit.
pub fn usual_unit(dimension: Dimension, si: f64) -> Unit {
    let small = si.is_finite() && si != 0.0 && si.abs() < 1e-3;
    match dimension {
        Dimension::Length if small => Unit::shown(dimension, Some("um")),
        _ => Unit::display(dimension),
    }
}

/// `value unit`, the unit left out for a dimensionless one.
pub fn with_unit(si: f64, unit: &Unit) -> String {
    let v = human(unit.from_si(si));
    if unit.name == "1" || unit.name.is_empty() {
        v
    } else {
        format!("{v} {}", unit.name)
    }
}

/// The design `x` (SI) in the file's units: `l2 = 1.98403 mm, delta2 = 4.05061 deg, ...`.
pub fn design_line(problem: &Problem, x: &[f64]) -> String {
    problem
        .variables
        .iter()
        .zip(x)
        .map(|(v, &xi)| format!("{} = {}", v.name, with_unit(xi, &v.unit)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The same as `name=value` pairs, as `--design` takes them (values in the file's units).
pub fn design_arg(problem: &Problem, x: &[f64]) -> String {
    problem
        .design_in_file_units(x)
        .iter()
        .map(|(name, &v)| format!("{name}={}", human(v)))
        .collect::<Vec<_>>()
        .join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentages_carry_no_rounding_noise() {
        assert_eq!(percent(1e-6), "0.0001");
        assert_eq!(percent(0.005), "0.5");
        assert_eq!(percent(0.1), "10");
        assert_eq!(percent(1e-9), "1e-7");
    }

    #[test]
    fn lengths_under_a_millimetre_read_in_micrometres() {
        let name = |d: Dimension, si: f64| usual_unit(d, si).name;
        assert_eq!(name(Dimension::Length, 82.19e-6), "um");
        assert_eq!(name(Dimension::Length, -150.4e-6), "um");
        assert_eq!(name(Dimension::Length, 1e-3), "mm");
        assert_eq!(name(Dimension::Length, 12e-3), "mm");
        assert_eq!(name(Dimension::Length, 0.0), "mm");
        assert_eq!(name(Dimension::Length, f64::NAN), "mm");
        assert_eq!(name(Dimension::Stiffness, 1e3), "N/um");
        assert_eq!(name(Dimension::Stress, 1e6), "MPa");
        assert_eq!(name(Dimension::Frequency, 500.0), "Hz");
    }

    #[test]
    fn numbers_read_as_a_designer_writes_them() {
        assert_eq!(human(1.96), "1.96");
        assert_eq!(human(-15.0), "-15");
        assert_eq!(human(1.9840321707657047), "1.98403");
        assert_eq!(human(12.897935500824541), "12.8979");
        assert_eq!(human(7e6), "7000000");
        assert_eq!(human(6.189952040375121e-11), "6.18995e-11");
        assert_eq!(human(0.3333333333333333), "0.333333");
        assert_eq!(significant(148.64597, 4), "148.6");
        assert_eq!(csv(12.897935500824541), "12.897935500824541");
        assert_eq!(csv(0.0), "0");
        assert_eq!(csv(6.189952040375121e-11), "6.189952040375121e-11");
    }
}
