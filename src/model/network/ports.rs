//! A network's ports: points of bodies where a load goes in or a motion is read, each
//! along a unit direction (an actuator's axis, an output's). Their compliance matrix
//! `C_ij`, the motion of port `i` along its direction under a unit force at port `j` along
//! its own, gives every output the mechanism's ports define: amplification, input and
//! output stiffness with the input free, held by an actuator or blocked.
//!
//! One solve per port that is loaded; the other entries follow from Maxwell-Betti's
//! reciprocity (`C_ij = C_ji`), which the tests check rather than assume.

use super::structure::{Body, Load, Network, NetworkError};
use crate::model::scalar::Scalar;

/// A point of a body and a unit direction.
#[derive(Debug, Clone, Copy)]
pub struct Port<D> {
    pub body: usize,
    pub point: [D; 2],
    pub direction: [D; 2],
}

/// The compliance among ports: row `i`, column `j`, row-major (`ports.len()` squared),
/// from a unit load at each port of `loaded` (the columns not loaded are left zero).
pub fn compliance<D: Scalar>(
    network: &Network<D>,
    ports: &[Port<D>],
    loaded: &[usize],
) -> Result<Vec<D>, NetworkError> {
    let m = ports.len();
    let mut c = vec![D::from(0.0); m * m];
    for &j in loaded {
        let p = &ports[j];
        let u = network.solve(&[Load {
            body: p.body,
            point: p.point,
            force: p.direction,
            moment: D::from(0.0),
        }])?;
        for (i, q) in ports.iter().enumerate() {
            c[i * m + j] = u.along(Body::Rigid(q.body), q.point, q.direction);
        }
    }
    Ok(c)
}

/// The outputs between an input port and an output port, from their 2 x 2 compliance
/// `[c_ii c_io; c_oi c_oo]`.
#[derive(Debug, Clone, Copy)]
pub struct PortOutputs<D> {
    /// The output's motion over the input's under a load at the input.
    pub amplification: D,
    /// Force over motion at the input.
    pub input_stiffness: D,
    /// Force over motion at the output, the input free.
    pub output_stiffness_free: D,
    /// The same with the input held by an actuator of stiffness `k_a` (static condensation
    /// of the input: `1 / (c_oo - c_oi c_io / (c_ii + 1 / k_a))`).
    pub output_stiffness_actuated: D,
    /// The same with the input blocked (`k_a` infinite).
    pub output_stiffness_blocked: D,
}

impl<D: Scalar> PortOutputs<D> {
    /// From the compliance entries and the actuator's stiffness `k_a` (N/m).
    pub fn new(c_ii: D, c_io: D, c_oi: D, c_oo: D, actuator: D) -> Self {
        let condensed = |input: D| (c_oo - c_oi * c_io / input).recip();
        PortOutputs {
            amplification: c_oi / c_ii,
            input_stiffness: c_ii.recip(),
            output_stiffness_free: c_oo.recip(),
            output_stiffness_actuated: condensed(c_ii + actuator.recip()),
            output_stiffness_blocked: condensed(c_ii),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::structure::{Dof, Flexure, Spring};
    use super::*;
    use crate::model::hinge::HingeKind;
    use crate::model::material::Material;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs())
    }

    /// A lever: a body pivoting on a short strip from the ground at the origin, pushed up
    /// 3 mm from it and read 30 mm from it (an ideal lever's ratio 10).
    fn lever() -> (Network<f64>, [Port<f64>; 2]) {
        let c = HingeKind::Strip.compliance(&[0.001, 0.0003], 0.01, &Material::al7075_t6());
        let net = Network {
            references: vec![[0.0, 0.0]],
            flexures: vec![Flexure::new(
                Body::Ground,
                Body::Rigid(0),
                [0.0, -0.001],
                [0.0, 1.0],
                0.001,
                c,
            )],
            springs: vec![],
            held: vec![],
            guides: Vec::new(),
        };
        let port = |x: f64| Port {
            body: 0,
            point: [x, 0.0],
            direction: [0.0, 1.0],
        };
        (net, [port(0.003), port(0.03)])
    }

    /// Reciprocity, and the condensed output stiffness against the network solved with the
    /// actuator's spring on the input, and with the input body held.
    #[test]
    fn the_condensed_stiffnesses_are_those_of_the_held_network() {
        let (net, ports) = lever();
        let c = compliance(&net, &ports, &[0, 1]).unwrap();
        assert!(close(c[1], c[2], 1e-10), "Maxwell-Betti: {} {}", c[1], c[2]);
        let k_a = 5e7;
        let o = PortOutputs::new(c[0], c[1], c[2], c[3], k_a);
        // the pivot's own give (its shear and bending translation) takes a little off
        assert!(
            o.amplification > 9.0 && o.amplification < 10.0,
            "a lever: {}",
            o.amplification
        );
        let mut actuated = net.clone();
        actuated.springs.push(Spring {
            body: 0,
            point: ports[0].point,
            direction: ports[0].direction,
            stiffness: k_a,
        });
        let c_a = compliance(&actuated, &ports, &[1]).unwrap();
        assert!(close(o.output_stiffness_actuated, 1.0 / c_a[3], 1e-9));
        // blocked: a spring a million times stiffer than the actuator tends to it
        let mut blocked = net.clone();
        blocked.springs.push(Spring {
            stiffness: k_a * 1e6,
            ..actuated.springs[0]
        });
        let c_b = compliance(&blocked, &ports, &[1]).unwrap();
        assert!(close(o.output_stiffness_blocked, 1.0 / c_b[3], 1e-5));
        assert!(o.output_stiffness_free < o.output_stiffness_actuated);
        assert!(o.output_stiffness_actuated < o.output_stiffness_blocked);
        // the input's own stiffness, by a body held where the input port acts: the
        // free body's rotation about the hinge is what the lever's input sees
        let mut held = net.clone();
        held.held.push((0, Dof::Rotation));
        let c_h = compliance(&held, &ports, &[0]).unwrap();
        assert!(
            1.0 / c_h[0] > o.input_stiffness,
            "holding the rotation stiffens"
        );
    }
}
