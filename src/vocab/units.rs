//! Units at the boundary: problem files speak mm, um, degrees, MPa...; the models speak SI.

use super::Dimension;

/// The units accepted for each dimension, with their factor to SI.
const UNITS: &[(Dimension, &[(&str, f64)])] = &[
    (Dimension::Ratio, &[("1", 1.0), ("", 1.0), ("%", 0.01)]),
    (
        Dimension::Length,
        &[
            ("m", 1.0),
            ("cm", 1e-2),
            ("mm", 1e-3),
            ("um", 1e-6),
            ("nm", 1e-9),
        ],
    ),
    (
        Dimension::Angle,
        &[
            ("rad", 1.0),
            ("mrad", 1e-3),
            ("deg", std::f64::consts::PI / 180.0),
        ],
    ),
    (Dimension::Force, &[("N", 1.0), ("kN", 1e3), ("mN", 1e-3)]),
    (
        Dimension::Stress,
        &[("Pa", 1.0), ("kPa", 1e3), ("MPa", 1e6), ("GPa", 1e9)],
    ),
    (
        Dimension::Stiffness,
        &[("N/m", 1.0), ("N/mm", 1e3), ("N/um", 1e6), ("kN/mm", 1e6)],
    ),
    (
        Dimension::Compliance,
        &[("m/N", 1.0), ("mm/N", 1e-3), ("um/N", 1e-6), ("nm/N", 1e-9)],
    ),
    (Dimension::Mass, &[("kg", 1.0), ("g", 1e-3), ("mg", 1e-6)]),
    (
        Dimension::RotationalStiffness,
        &[
            ("N m/rad", 1.0),
            ("N*m/rad", 1.0),
            ("N mm/rad", 1e-3),
            ("N*mm/rad", 1e-3),
        ],
    ),
    (Dimension::Frequency, &[("Hz", 1.0), ("kHz", 1e3)]),
    (Dimension::Time, &[("s", 1.0), ("ms", 1e-3), ("us", 1e-6)]),
];

/// A unit of measure: its name as written and its factor to SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Unit {
    pub name: String,
    pub dimension: Dimension,
    pub to_si: f64,
}

impl Unit {
    /// Looks `name` up among the units of `dimension`.
    pub fn parse(name: &str, dimension: Dimension) -> Result<Unit, String> {
        let table = units_of(dimension);
        match table.iter().find(|(n, _)| *n == name) {
            Some((n, f)) => Ok(Unit {
                name: n.to_string(),
                dimension,
                to_si: *f,
            }),
            None => Err(format!(
                "unknown unit \"{name}\" for a {} quantity; expected one of {}",
                dimension_word(dimension),
                accepted(dimension)
            )),
        }
    }

    /// The SI unit of a dimension.
    pub fn si(dimension: Dimension) -> Unit {
        Unit {
            name: dimension.si_unit().to_string(),
            dimension,
            to_si: 1.0,
        }
    }

    pub fn to_si(&self, value: f64) -> f64 {
        value * self.to_si
    }

    /// `value` (SI) in this unit. A value that came from the file reads back as written:
    /// the shortest decimal of 15 or 16 significant digits that converts back to exactly
    /// `value` is returned, so `-15 deg` is -15, not -14.999999999999998.
    pub fn from_si(&self, value: f64) -> f64 {
        let raw = value / self.to_si;
        if self.to_si == 1.0 || !raw.is_finite() {
            return raw;
        }
        for digits in [15, 16] {
            if let Ok(v) = format!("{raw:.*e}", digits - 1).parse::<f64>() {
                if self.to_si(v) == value {
                    return v;
                }
            }
        }
        raw
    }

    /// Every unit of `dimension`, as [`Unit::parse`] gives them.
    pub fn all(dimension: Dimension) -> Vec<Unit> {
        units_of(dimension)
            .iter()
            .filter(|(n, _)| !n.is_empty())
            .map(|(n, f)| Unit {
                name: n.to_string(),
                dimension,
                to_si: *f,
            })
            .collect()
    }

    /// The unit a quantity of `dimension` is shown in: `display` where it names one of the
    /// dimension's units (an output's own, a stroke in um), else [`Unit::display`].
    pub fn shown(dimension: Dimension, display: Option<&str>) -> Unit {
        display
            .and_then(|name| Unit::parse(name, dimension).ok())
            .unwrap_or_else(|| Unit::display(dimension))
    }

    /// The unit a designer reads a quantity of `dimension` in when the problem file names
    /// none for it: mm, deg, N, MPa, N/um, um/N, g, N mm/rad, Hz, ms.
    pub fn display(dimension: Dimension) -> Unit {
        let name = match dimension {
            Dimension::Ratio => "1",
            Dimension::Length => "mm",
            Dimension::Angle => "deg",
            Dimension::Force => "N",
            Dimension::Stress => "MPa",
            Dimension::Stiffness => "N/um",
            Dimension::Compliance => "um/N",
            Dimension::Mass => "g",
            Dimension::RotationalStiffness => "N mm/rad",
            Dimension::Frequency => "Hz",
            Dimension::Time => "ms",
        };
        Unit::parse(name, dimension).expect("every display unit is in the table")
    }
}

fn units_of(dimension: Dimension) -> &'static [(&'static str, f64)] {
    UNITS
        .iter()
        .find(|(d, _)| *d == dimension)
        .map(|(_, t)| *t)
        .unwrap_or(&[])
}

/// Every unit name of `dimension`, the empty one of a plain ratio included.
pub fn names(dimension: Dimension) -> Vec<&'static str> {
    units_of(dimension).iter().map(|(n, _)| *n).collect()
}

/// Every dimension with its units and their factors to SI, as [`Unit::parse`] reads them.
pub fn tables() -> &'static [(Dimension, &'static [(&'static str, f64)])] {
    UNITS
}

/// The accepted unit names of a dimension, for messages.
pub fn accepted(dimension: Dimension) -> String {
    units_of(dimension)
        .iter()
        .filter(|(n, _)| !n.is_empty())
        .map(|(n, _)| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A word for a dimension, for messages.
pub fn dimension_word(dimension: Dimension) -> &'static str {
    match dimension {
        Dimension::Ratio => "dimensionless",
        Dimension::Length => "length",
        Dimension::Angle => "angle",
        Dimension::Force => "force",
        Dimension::Stress => "stress",
        Dimension::Stiffness => "stiffness",
        Dimension::Compliance => "compliance",
        Dimension::Mass => "mass",
        Dimension::RotationalStiffness => "rotational stiffness",
        Dimension::Frequency => "frequency",
        Dimension::Time => "time",
    }
}

/// Parses a quantity written as `"<number> <unit>"` (for example `"72 GPa"`) into SI.
pub fn parse_quantity(text: &str, dimension: Dimension) -> Result<f64, String> {
    let text = text.trim();
    let split = text.find(|c: char| c.is_whitespace()).unwrap_or(text.len());
    let (number, unit) = text.split_at(split);
    let value: f64 = number.parse().map_err(|_| {
        format!(
            "\"{text}\" is not a {} quantity: write a number and a unit, e.g. \"{}\"",
            dimension_word(dimension),
            example(dimension)
        )
    })?;
    if !value.is_finite() {
        return Err(format!("\"{text}\" is not a finite number"));
    }
    let unit = Unit::parse(unit.trim(), dimension)?;
    let si = unit.to_si(value);
    physical(si, dimension).map_err(|why| format!("\"{text}\" {why}"))?;
    Ok(si)
}

/// The sizes (SI) a non-zero value of each dimension may take: wide enough for any
/// mechanism from a MEMS flexure to a machine frame, narrow enough that every product the
/// models form stays finite and normal in f64.
pub fn physical_range(dimension: Dimension) -> (f64, f64) {
    match dimension {
        Dimension::Ratio => (1e-12, 1e12),
        Dimension::Length => (1e-12, 1e3),
        Dimension::Angle => (1e-12, 1e3),
        Dimension::Force => (1e-12, 1e9),
        Dimension::Stress => (1e-3, 1e15),
        Dimension::Stiffness => (1e-9, 1e15),
        Dimension::Compliance => (1e-15, 1e9),
        Dimension::Mass => (1e-15, 1e6),
        Dimension::RotationalStiffness => (1e-12, 1e12),
        Dimension::Frequency => (1e-9, 1e12),
        Dimension::Time => (1e-15, 1e9),
    }
}

/// Why the SI value `v` is no value a quantity of `dimension` can take, if it is not: zero,
/// or a size within [`physical_range`].
pub fn physical(v: f64, dimension: Dimension) -> Result<(), String> {
    let (lo, hi) = physical_range(dimension);
    if v == 0.0 || (v.is_finite() && (lo..=hi).contains(&v.abs())) {
        return Ok(());
    }
    Err(format!(
        "is {} {} in SI units, outside the sizes a {} can take ({} to {} {})",
        short(v),
        dimension.si_unit(),
        dimension_word(dimension),
        short(lo),
        short(hi),
        dimension.si_unit()
    ))
}

/// A number for a message: plain where that is short, else in scientific form (no
/// 300-digit decimals).
pub fn short(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-4..1e7).contains(&a) {
        // seven significant digits: 0.0016, not 0.0015999999999999996
        let rounded: f64 = format!("{v:.6e}").parse().unwrap_or(v);
        return format!("{rounded}");
    }
    // seven significant digits, trailing zeros dropped: 1e-303, not 1.0000000000000001e-303
    let s = format!("{v:.6e}");
    match s.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => {
            format!(
                "{}e{exponent}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            )
        }
        _ => s,
    }
}

fn example(dimension: Dimension) -> &'static str {
    match dimension {
        Dimension::Ratio => "0.5",
        Dimension::Length => "10 mm",
        Dimension::Angle => "5 deg",
        Dimension::Force => "40 N",
        Dimension::Stress => "505 MPa",
        Dimension::Stiffness => "7e6 N/m",
        Dimension::Compliance => "1.4 um/N",
        Dimension::Mass => "60 g",
        Dimension::RotationalStiffness => "34.53 N m/rad",
        Dimension::Frequency => "1200 Hz",
        Dimension::Time => "20 ms",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_convert_to_si() {
        assert_eq!(parse_quantity("72 GPa", Dimension::Stress).unwrap(), 72e9);
        assert_eq!(
            parse_quantity("17.4 um", Dimension::Length).unwrap(),
            17.4e-6
        );
        assert!(
            (parse_quantity("180 deg", Dimension::Angle).unwrap() - std::f64::consts::PI).abs()
                < 1e-15
        );
    }

    #[test]
    fn wrong_units_and_numbers_are_explained() {
        let e = parse_quantity("72 GPa", Dimension::Length).unwrap_err();
        assert!(e.contains("\"GPa\"") && e.contains("\"mm\""), "{e}");
        let e = parse_quantity("lots mm", Dimension::Length).unwrap_err();
        assert!(e.contains("\"lots mm\""), "{e}");
        assert!(parse_quantity("inf mm", Dimension::Length).is_err());
        assert!(parse_quantity("NaN mm", Dimension::Length).is_err());
    }

    #[test]
    fn round_trip() {
        let u = Unit::parse("mm", Dimension::Length).unwrap();
        assert_eq!(u.from_si(u.to_si(1.96)), 1.96);
    }
}
