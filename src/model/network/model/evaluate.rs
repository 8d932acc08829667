//! The network's outputs at a design: the load cases the wanted outputs need solved on one
//! factorization, and each output read from them, over `f64` or over dual numbers for the
//! exact gradients.

use super::at_stroke::{critical_of, end_by_design};
use super::outputs::AtStroke;
use super::*;
use crate::model::large::report::StrokePointOf;

thread_local! {
    /// The thread's spare [`Work`]s, one per scalar type it evaluated with, each with its
    /// type's id: compared here, where asking each box for its type was a virtual call.
    static SPARE: RefCell<Vec<(TypeId, Box<dyn Any>)>> = const { RefCell::new(Vec::new()) };
}

/// The thread's spare [`Work`] for `D`, or a new one. Taken out rather than borrowed, so
/// that an evaluation inside another (none today) would only allocate its own.
fn take<D: 'static>() -> Box<Work<D>> {
    let id = TypeId::of::<Work<D>>();
    SPARE
        .with(|spare| {
            let mut spare = spare.borrow_mut();
            let i = spare.iter().position(|(t, _)| *t == id)?;
            spare.swap_remove(i).1.downcast().ok()
        })
        .unwrap_or_default()
}

/// `work` back among the thread's spares.
fn give<D: 'static>(work: Box<Work<D>>) {
    SPARE.with(|spare| spare.borrow_mut().push((TypeId::of::<Work<D>>(), work)));
}

impl NetworkModel {
    /// The wanted outputs at `x` into `out`, or why the design has none.
    pub fn evaluate_generic<D: Scalar + 'static>(
        &self,
        x: &[D],
        modulus: Option<D>,
        wanted: &[usize],
        out: &mut [D],
    ) -> Result<(), String> {
        let mut work = take::<D>();
        let result = self.evaluate_in(x, modulus, wanted, out, &mut work);
        give(work);
        result
    }

    /// The load cases the wanted outputs need, solved on one factorization of the evaluated
    /// network `e`: the input's where `input`, the first output's where `output` (read at
    /// the input too where its compliance is `condensed` out of the output's).
    fn solve_wanted<'a, D: Scalar>(
        &self,
        e: &'a Evaluated<D>,
        needs_input: bool,
        needs_output: bool,
        condenses: bool,
        solve: &'a mut SolveBuffers<D>,
    ) -> Result<[Option<Displacements<'a, D>>; 2], String> {
        // the load cases wanted, from one factorization: the input's, the first output's
        let (load_in, load_out) = (
            std::slice::from_ref(&e.ports[0]),
            std::slice::from_ref(&e.ports[1]),
        );
        // the output's case is read at the output alone, or at the input too where the
        // input's compliance is condensed out
        let port_bodies = [e.ports[1].body, e.ports[0].body];
        let read_out = &port_bodies[..if condenses { 2 } else { 1 }];
        let mut cases = [Case {
            loads: &[],
            read: None,
        }; 2];
        let mut count = 0;
        for (needed, loads, read) in [
            (needs_input, load_in, None),
            (needs_output, load_out, Some(read_out)),
        ] {
            if needed {
                cases[count] = Case { loads, read };
                count += 1;
            }
        }
        let solved = if count == 0 {
            None
        } else {
            Some(
                e.network
                    .solve_cases_in(&cases[..count], solve)
                    .map_err(|err| self.network_error(err))?,
            )
        };
        let case = |c: usize| solved.as_ref().map(|s| s.case(c));
        let input = if needs_input { case(0) } else { None };
        let output = if needs_output { case(count - 1) } else { None };
        Ok([input, output])
    }

    /// Each flexure's stresses at its ends on `from` and on `to` under the loads the input's
    /// case `input` gives, times `shared`, the described part's share of the largest
    /// actuator force.
    fn end_stresses<D: Scalar>(
        &self,
        e: &Evaluated<D>,
        input: &Displacements<D>,
        shared: D,
        out: &mut Vec<(D, D)>,
    ) {
        let ends = |h: usize| {
            let l = e.network.flexure_loads(h, input);
            let loads = HingeLoads {
                axial: l.axial * shared,
                shear: l.shear * shared,
                moment: l.moment * shared,
            };
            // a beam's stresses are a strip's: the same beam, the same linear moment
            let kind = self
                .description
                .hinges
                .get(h)
                .map_or(HingeKind::Strip, |hinge| hinge.kind);
            // (loaded end, clamped end): the loads are at its end on `to`
            let (to, from) = kind.end_stresses(&e.dims[h], self.description.width, &loads);
            (from, to)
        };
        out.extend((0..e.network.flexures.len()).map(ends));
    }

    /// [`NetworkModel::evaluate_generic`] in the buffers of `work`.
    pub(super) fn evaluate_in<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        wanted: &[usize],
        out: &mut [D],
        work: &mut Work<D>,
    ) -> Result<(), String> {
        let Needs {
            modes,
            extent,
            footprint,
            input: needs_input,
            output: needs_output,
            condenses,
            stresses: needs_stresses,
            stroke: needs_stroke,
            stroke_modes,
            critical: needs_critical,
        } = self.needs(wanted);
        self.at(x, modulus, extent, work)?;
        let Work {
            evaluated: e,
            solve,
            stresses,
            ..
        } = work;
        let e = &*e;
        use Quantity::*;
        // read in place: a port copied out of the list, or into a load, was a `memcpy`
        let along = |u: &Displacements<D>, i: usize| {
            let p = &e.ports[i];
            u.along_ref(Body::Rigid(p.body), &p.point, &p.force)
        };
        let [input, output] = self.solve_wanted(e, needs_input, needs_output, condenses, solve)?;
        // W_ij = read_i C_ij share_j
        let w =
            |u: &Displacements<D>, i: usize, j: usize| along(u, i) * (self.read[i] * self.share[j]);
        let w_ii = input.as_ref().map(|u| w(u, 0, 0));
        let k_in = || w_ii.expect("listed").recip();
        let stroke_in = || match self.actuator.stiffness {
            None => D::from(self.actuator.nominal_stroke),
            Some(k_a) => {
                let ka = w_ii.expect("listed") * k_a;
                ka * self.actuator.nominal_stroke / (ka + 1.0)
            }
        };
        let amplification = |o: usize| {
            let u = input.as_ref().expect("listed");
            w(u, o + 1, 0) / w_ii.expect("listed")
        };
        // the first output's stiffnesses: the input free, on the actuator, held
        let condensed = |actuator: Option<f64>| {
            let (u_in, u_out) = (
                input.as_ref().expect("listed"),
                output.as_ref().expect("listed"),
            );
            let (c_oo, c_oi, c_io) = (w(u_out, 1, 1), w(u_in, 1, 0), w(u_out, 0, 1));
            let c_ii = w(u_in, 0, 0) + actuator.map_or(0.0, f64::recip);
            (c_oo - c_oi * c_io / c_ii).recip()
        };
        // the hinges' loads and stresses under the largest actuator force, found once: at
        // the true stroke (Eq. 13), which a stack of finite stiffness makes under the part
        let largest = w_ii.map(|w| w.recip() * stroke_in() + self.actuator.preload);
        // the described part's share of it, once for every flexure
        let shared = largest.map(|f| f * self.share[0]);
        // each hinge's two end stresses once, however many outputs read them
        stresses.clear();
        if needs_stresses {
            let u = input.as_ref().expect("listed");
            self.end_stresses(e, u, shared.expect("listed"), stresses);
        }
        let stresses = &*stresses;
        // each read in place: the pair copied out was two `Jet<8>`s for one
        let extent = |i: usize| span(&e.points, i);
        let frequencies = modes.map_or(Ok(Vec::new()), |count| self.frequencies(e, count))?;
        let footprint = self.footprint_of(footprint, x)?;
        let at_stroke = needs_stroke.then_some(stroke_modes);
        let (stroke, critical) = self.large(x, modulus, at_stroke, needs_critical)?;
        for (&k, slot) in wanted.iter().zip(out.iter_mut()) {
            *slot = match self.quantities[k] {
                Amplification(o) => amplification(o),
                KIn => k_in(),
                KOut => w(output.as_ref().expect("listed"), 1, 1).recip(),
                KOutActuated => condensed(self.actuator.stiffness),
                KOutBlocked => condensed(None),
                StrokeIn => stroke_in(),
                StrokeOut => amplification(0) * stroke_in(),
                BlockedForce => amplification(0) * stroke_in() * condensed(self.actuator.stiffness),
                StressMax => (stresses.iter().map(|&(a, b)| max(a, b)))
                    .reduce(max)
                    .unwrap_or(D::from(0.0)),
                Stress(h) => max(stresses[h].0, stresses[h].1),
                StressEnd(h, true) => stresses[h].1,
                StressEnd(h, false) => stresses[h].0,
                Rotation(h) => {
                    let u = input.as_ref().expect("listed");
                    let f = &e.network.flexures[h];
                    let turn = u.at(f.to, f.end)[2] - u.at(f.from, f.start)[2];
                    turn * shared.expect("listed")
                }
                SpanX => extent(0),
                SpanY => extent(1),
                PartWidth => footprint[0],
                PartHeight => footprint[1],
                Measure(m) => e.measures[m],
                Frequency(i) => frequencies[i],
                AtStroke(q) => stroke_output(stroke.as_ref().expect("solved"), q),
                Critical => critical.expect("solved"),
            };
            if !slot.re().is_finite() {
                return Err(format!(
                    "output \"{}\" is not finite at this design",
                    self.outputs[k].name
                ));
            }
        }
        Ok(())
    }

    /// The part's footprint where `wanted`, else not-a-number.
    fn footprint_of<D: Scalar>(&self, wanted: bool, x: &[D]) -> Result<[D; 2], String> {
        match (wanted, &self.drawing) {
            (true, Some(drawing)) => drawing
                .footprint(x)
                .ok_or_else(|| "the part's outline has no value at this design".into()),
            _ => Ok([D::from(f64::NAN); 2]),
        }
    }

    /// The outputs at the working stroke, with the `frequencies` lowest natural frequencies
    /// about its equilibrium, their derivatives through the implicit function theorem
    /// ([`crate::model::large::sensitivity`]): first derivatives only, by the design and by
    /// the modulus's factor where it is given.
    fn at_stroke<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        frequencies: usize,
    ) -> Result<StrokePointOf<D>, String> {
        let settings = self.stroke_settings::<D>()?;
        end_by_design(
            self,
            x,
            modulus,
            settings.elements,
            settings.steps,
            frequencies,
        )
    }

    /// The solve at the working stroke (with `stroke`'s count of natural frequencies about
    /// its equilibrium, where any) and the critical load factor, each where asked for.
    fn large<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        stroke: Option<Option<usize>>,
        critical: bool,
    ) -> Result<(Option<StrokePointOf<D>>, Option<D>), String> {
        let point = stroke
            .map(|modes| self.at_stroke(x, modulus, modes.unwrap_or(0)))
            .transpose()?;
        let lambda = critical.then(|| self.critical(x, modulus)).transpose()?;
        Ok((point, lambda))
    }

    /// The critical load factor of the working stroke (`nl_critical`), with its derivatives
    /// at the critical point ([`crate::model::large::critical::by_design`]), under the same
    /// terms as [`Self::at_stroke`].
    fn critical<D: Scalar>(&self, x: &[D], modulus: Option<D>) -> Result<D, String> {
        let settings = self.stroke_settings::<D>()?;
        critical_of(self, x, modulus, settings.elements, settings.critical_up_to)
    }

    /// The large-deflection settings, for first derivatives (`D`).
    fn stroke_settings<D: Scalar>(&self) -> Result<LargeSettings, String> {
        let settings = self
            .large_settings()
            .ok_or("the outputs at stroke need `[analysis] deflection = \"large\"`")?;
        if D::SECOND_ORDER {
            return Err(
                "the outputs at the working stroke have first derivatives only: a robust \
                 study cannot use them"
                    .into(),
            );
        }
        Ok(settings)
    }

    /// What the `wanted` outputs need.
    pub(super) fn needs(&self, wanted: &[usize]) -> Needs {
        let mut n = wanted
            .iter()
            .fold(Needs::default(), |n, &w| n.or(self.needs[w]));
        n.extent |= n.modes.is_some();
        n
    }

    pub(super) fn gradients<const N: usize>(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let seeded: [Jet<N>; N] = std::array::from_fn(|i| Jet::variable(x[i], i));
        let mut work = take::<Jet<N>>();
        // the outputs' buffer is the thread's too: allocated for each evaluation, it cost
        // about as much as the seeding and the unseeding together
        let mut y = std::mem::take(&mut work.outputs);
        // zeroed only when the count changes: the evaluation writes every slot it returns
        if y.len() != wanted.len() {
            y.clear();
            y.resize(wanted.len(), Jet::from(0.0));
        }
        if self
            .evaluate_in(&seeded, None, wanted, &mut y, &mut work)
            .is_ok()
        {
            unseed(&y, out, jacobian);
        } else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
        }
        work.outputs = y;
        give(work);
    }
}

/// Output `q` of the solve at the working stroke `p`.
fn stroke_output<D: Scalar>(p: &StrokePointOf<D>, q: AtStroke) -> D {
    match q {
        AtStroke::StrokeIn => p.stroke_in,
        AtStroke::StrokeOut => p.stroke_out,
        AtStroke::Amplification => p.amplification,
        AtStroke::AmplificationTangent => p.amplification_tangent,
        AtStroke::KIn => p.k_in,
        AtStroke::KOut => p.k_out,
        AtStroke::StressMax => p.stress_max,
        AtStroke::Stress(h) => p.stresses[h],
        AtStroke::Across(o) => p.parasitic[o].across,
        AtStroke::Turn(o) => p.parasitic[o].rotation,
        AtStroke::Frequency(i) => p.frequencies[i],
    }
}

/// The extent of the described `points` along axis `i` (m): the largest coordinate less
/// the least.
fn span<D: Scalar>(points: &[[D; 2]], i: usize) -> D {
    let hi = points
        .iter()
        .skip(1)
        .fold(points[0][i], |m, p| max(m, p[i]));
    let lo = points
        .iter()
        .skip(1)
        .fold(-points[0][i], |m, p| max(m, -p[i]));
    hi + lo
}
