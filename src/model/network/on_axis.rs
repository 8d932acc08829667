//! A flexure lying on a mirror axis, refused.
//!
//! A mirrored description is a half (or a quarter) of the part, and every flexure in it
//! stands for itself and its image across each axis. A flexure whose centre line lies on
//! the axis is its own image: the part has it once, but the half would count it whole
//! while it carries only half of the part's load, so the half's stiffnesses through it
//! would be twice the part's (a block on one strip along the axis reported 144 N/um where
//! the part written whole has 72), and its mode families would get it twice. Until a
//! flexure can be declared cut by the axis (half its stiffness in the half, its loads
//! doubled for its stress), such a description is refused with the flexure named.

use super::description::{Axis, Description};
use super::structure::Flexure;

/// How close to the axis, relative to the flexure's length, an end counts as on it: far
/// below any dimension a wire can cut, far above the rounding of `l*sin(0)`.
const ON_AXIS: f64 = 1e-9;

/// The first flexure (hinges, then beams, as the network holds them) whose start and end
/// both lie on one of `d`'s mirror axes at this design, as a message naming its key.
pub fn flexure_on_mirror_axis(d: &Description, flexures: &[Flexure<f64>]) -> Option<String> {
    let names = d
        .hinges
        .iter()
        .map(|h| ("hinge", h.name.as_str(), &h.key))
        .chain(d.beams.iter().map(|b| ("beam", b.name.as_str(), &b.key)));
    for (f, (what, name, key)) in flexures.iter().zip(names) {
        let end = f.end;
        for &axis in &d.mirror {
            let across = |p: [f64; 2]| match axis {
                Axis::X => p[1],
                Axis::Y => p[0],
            };
            let tolerance = ON_AXIS * f.length.abs();
            if across(f.start).abs() <= tolerance && across(end).abs() <= tolerance {
                let line = match axis {
                    Axis::X => "y = 0",
                    Axis::Y => "x = 0",
                };
                return Some(format!(
                    "{what} \"{name}\" ({key}) lies on the mirror axis \"{}\" (the line {line}): \
                     it is its own mirror image, which the described part would count a second \
                     time (twice the part's stiffness through it); move it off the axis (a pair \
                     either side of it), or describe the part without that mirror axis",
                    axis.name()
                ));
            }
        }
    }
    None
}
