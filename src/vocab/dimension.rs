//! Physical dimensions: what a parameter or output measures, and its SI unit.

use serde::Serialize;

/// The physical dimension of a parameter or output; the problem layer converts units
/// against it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Dimension {
    /// Dimensionless.
    Ratio,
    /// m
    Length,
    /// rad
    Angle,
    /// N
    Force,
    /// Pa
    Stress,
    /// N/m
    Stiffness,
    /// m/N
    Compliance,
    /// kg
    Mass,
    /// N m/rad
    RotationalStiffness,
    /// Hz
    Frequency,
    /// s
    Time,
}

impl Dimension {
    /// The SI unit, as printed in outputs.
    pub fn si_unit(self) -> &'static str {
        match self {
            Dimension::Ratio => "1",
            Dimension::Length => "m",
            Dimension::Angle => "rad",
            Dimension::Force => "N",
            Dimension::Stress => "Pa",
            Dimension::Stiffness => "N/m",
            Dimension::Compliance => "m/N",
            Dimension::Mass => "kg",
            Dimension::RotationalStiffness => "N m/rad",
            Dimension::Frequency => "Hz",
            Dimension::Time => "s",
        }
    }
}
