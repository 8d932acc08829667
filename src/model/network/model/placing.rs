//! The network placed at a design: every expression of the description evaluated (from the
//! compiled tape, or from the trees where it fails, which say which and why), the bodies'
//! reference points, each flexure joined with its compliance, the ports' loads, and the
//! described points the extent and the masses read.

use super::*;

/// The description's expressions at a design as [`NetworkModel::build`] reads them: `raw`
/// gives each expression's value (the tape's, which cannot fail, or the trees'), lengths
/// in the description's `unit`.
pub(super) struct Read<'a, F> {
    raw: &'a F,
    unit: f64,
}

impl<D: Scalar, E: Message, F: Fn(&Keyed) -> Result<D, E>> Read<'_, F> {
    fn eval(&self, e: &Keyed) -> Result<D, String> {
        (self.raw)(e).map_err(Message::message)
    }

    fn length(&self, e: &Keyed) -> Result<D, E> {
        (self.raw)(e).map(|v| v * self.unit)
    }

    fn point(&self, p: &Point) -> Result<[D; 2], E> {
        Ok([self.length(&p[0])?, self.length(&p[1])?])
    }

    /// Written in place: a point returned was a `memcpy` of two `Jet<8>`s.
    fn point_into(&self, p: &Point, out: &mut [D; 2]) -> Result<(), String> {
        out[0] = self.length(&p[0]).map_err(Message::message)?;
        out[1] = self.length(&p[1]).map_err(Message::message)?;
        Ok(())
    }
}

/// What joining a flexure writes ([`join`]): the bodies' reference points and whether each
/// is placed yet, and the described points where they are kept; at the evaluation's modulus.
pub(super) struct Joined<'a, D> {
    modulus: Option<D>,
    references: &'a mut [[D; 2]],
    placed: &'a mut [bool],
    points: Option<&'a mut Vec<[D; 2]>>,
}

impl<D: Scalar> Joined<'_, D> {
    fn join(&mut self, f: &mut Flexure<D>) {
        let points = self.points.as_deref_mut();
        join(f, self.modulus, self.references, self.placed, points);
    }
}

impl NetworkModel {
    /// The value of every expression of the description at the design `x` (SI), by slot;
    /// `None` where one has none.
    pub(super) fn expression_values(&self, x: &[f64]) -> Option<Vec<f64>> {
        let mut work = Work::default();
        let Work {
            values, registers, ..
        } = &mut work;
        let unit = self.description.unit;
        values.extend(x.iter().zip(&self.description.parameters).map(|(&v, p)| {
            if p.dimension == Dimension::Length {
                v * unit.recip()
            } else {
                v
            }
        }));
        values.push(std::f64::consts::PI / 180.0);
        self.tape.run(values, registers).then(|| {
            (0..self.roles.len())
                .map(|slot| registers[self.tape.output(slot)])
                .collect()
        })
    }

    /// The network and its ports at the design `x` (SI, every parameter) into
    /// `work.evaluated`: the expressions from the tape, or where it fails, from their trees,
    /// which say which one and why.
    pub(super) fn at<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        extent: bool,
        work: &mut Work<D>,
    ) -> Result<(), String> {
        let d = &self.description;
        let unit = d.unit;
        let Work {
            values,
            registers,
            placed,
            evaluated,
            ..
        } = work;
        // the parameters in the expressions' units, then `deg`, written into the tape's
        // registers
        let tape = if extent { &self.tape } else { &self.statics };
        let inputs = tape.inputs_mut(registers);
        let (deg, named) = inputs.split_last_mut().expect("`deg` is a name");
        for ((slot, &v), p) in named.iter_mut().zip(x).zip(&d.parameters) {
            *slot = if p.dimension == Dimension::Length {
                v * unit.recip()
            } else {
                v
            };
        }
        *deg = D::from(std::f64::consts::PI / 180.0);
        if tape.run_in(registers) {
            let registers = &*registers;
            let axes = &self.axes[usize::from(!extent)];
            self.build(
                modulus,
                extent,
                |e: &Keyed| Ok::<_, Infallible>(registers[tape.output(e.slot)]),
                |h| axes[h].map(|(sin, cos)| [registers[cos], registers[sin]]),
                evaluated,
                placed,
            )
        } else {
            // the trees read the names' values, which the tape has kept
            values.clear();
            values.extend_from_slice(&registers[..tape.inputs()]);
            let values = &*values;
            self.build(
                modulus,
                extent,
                |e: &Keyed| {
                    e.expression
                        .eval(values)
                        .map_err(|err| format!("{} = \"{}\": {err}", e.key, e.expression.source()))
                },
                |_| None,
                evaluated,
                placed,
            )
        }
    }

    /// [`NetworkModel::at`] with each expression's value from `eval`, into `out`'s buffers;
    /// the described points for the extent only if `extent`. The tape's `eval` cannot fail
    /// (`E` is [`Infallible`]): its values then pass through no `Result`, whose moves of
    /// `[Jet<8>; 2]` were a copy each.
    pub(super) fn build<D: Scalar, E: Message>(
        &self,
        modulus: Option<D>,
        extent: bool,
        eval: impl Fn(&Keyed) -> Result<D, E>,
        axis: impl Fn(usize) -> Option<[D; 2]>,
        out: &mut Evaluated<D>,
        placed: &mut Vec<bool>,
    ) -> Result<(), String> {
        let d = &self.description;
        let r = Read {
            raw: &eval,
            unit: d.unit,
        };
        let unit = d.unit;
        self.place_bodies(&r, extent, out, placed)?;
        let Evaluated {
            network,
            ports,
            points,
            dims,
            measures,
            ..
        } = out;
        // each flexure written into its slot (a `Flexure` of `Jet<8>`s is 648 bytes, which
        // built and then pushed was copied twice)
        let count = d.hinges.len() + d.beams.len();
        if network.flexures.len() != count {
            network.flexures.clear();
            network.flexures.resize(count, idle_flexure());
        }
        dims.resize_with(count, Vec::new);
        let kept = extent.then_some(points);
        let joined = Joined {
            modulus,
            references: &mut network.references,
            placed,
            points: kept,
        };
        let (hinge_flexures, beam_flexures) = network.flexures.split_at_mut(d.hinges.len());
        let (hinge_dims, beam_dims) = dims.split_at_mut(d.hinges.len());
        let joined = self.join_hinges(&r, &axis, hinge_flexures, hinge_dims, joined)?;
        self.join_beams(&r, beam_flexures, beam_dims, joined)?;
        network.held.clear();
        network.held.extend_from_slice(&self.held);
        network.springs.clear();
        network.guides.clear();
        for g in &d.supports {
            let [dx, dy] = r.point(&g.direction).map_err(Message::message)?;
            let norm = (dx * dx + dy * dy).sqrt();
            if norm.re() == 0.0 || !norm.re().is_finite() {
                return Err(format!(
                    "support ({}.direction): its direction is zero",
                    g.key
                ));
            }
            network.guides.push(Guide {
                body: g.body,
                point: r.point(&g.at).map_err(Message::message)?,
                direction: [dx / norm, dy / norm],
            });
        }
        assert!(
            placed.iter().all(|&p| p),
            "every body has a hinge or a beam, whose end is a point of it"
        );
        // written in place, as the flexures
        if ports.len() != self.directions.len() {
            let zero = D::from(0.0);
            ports.clear();
            ports.resize(
                self.directions.len(),
                Load {
                    body: 0,
                    point: [zero; 2],
                    force: [zero; 2],
                    moment: zero,
                },
            );
        }
        let described = std::iter::once(&d.input).chain(&d.outputs);
        for ((p, known), port) in described.zip(&self.directions).zip(ports.iter_mut()) {
            port.force = match known {
                Some(unit) => unit.map(D::from),
                None => {
                    let [dx, dy] = r.point(&p.direction).map_err(Message::message)?;
                    let norm = (dx * dx + dy * dy).sqrt();
                    if norm.re() == 0.0 {
                        return Err(format!("port \"{}\": its direction is zero", p.name));
                    }
                    [dx / norm, dy / norm]
                }
            };
            port.body = p.body;
            r.point_into(&p.at, &mut port.point)?;
        }
        measures.clear();
        for m in &d.measures {
            let v = r.eval(&m.value)?;
            measures.push(if m.dimension == Dimension::Length {
                v * unit
            } else {
                v
            });
        }
        Ok(())
    }

    /// Each body's reference point (its first point) into the network's references, and
    /// where `extent`, every described point (each body's, then the ground's) with each
    /// body's offset among them and its link's width.
    fn place_bodies<D: Scalar, E: Message>(
        &self,
        r: &Read<'_, impl Fn(&Keyed) -> Result<D, E>>,
        extent: bool,
        out: &mut Evaluated<D>,
        placed: &mut Vec<bool>,
    ) -> Result<(), String> {
        let d = &self.description;
        let Evaluated {
            network,
            points,
            offsets,
            link_widths,
            ..
        } = out;
        points.clear();
        offsets.clear();
        link_widths.clear();
        placed.clear();
        placed.resize(d.bodies.len(), false);
        let references = &mut network.references;
        if references.len() != d.bodies.len() {
            references.clear();
            references.resize(d.bodies.len(), [D::from(0.0); 2]);
        }
        for (b, body) in d.bodies.iter().enumerate() {
            // read by the statics too: a design that leaves a link no width has no value
            let width = body
                .link_width
                .as_ref()
                .map(|w| r.length(w).map_err(Message::message))
                .transpose()?;
            if let (Some(w), Some(keyed)) = (width, &body.link_width) {
                if w.re() <= 0.0 || w.re().is_nan() {
                    return Err(not_positive(&body.name, &keyed.key, "width", w.re()));
                }
            }
            if extent {
                offsets.push(points.len());
                link_widths.push(width);
            }
            // the statics read a body's first point alone, its reference
            if let Some(p) = body.points.first() {
                r.point_into(p, &mut references[b])?;
                placed[b] = true;
                if extent {
                    points.push(references[b]);
                    for p in &body.points[1..] {
                        points.push(r.point(p).map_err(Message::message)?);
                    }
                }
            }
        }
        if extent {
            offsets.push(points.len());
        }
        if extent {
            for p in &d.ground {
                points.push(r.point(p).map_err(Message::message)?);
            }
        }
        Ok(())
    }

    /// Each hinge's dimensions into `dims` and its flexure into `flexures`, joined.
    fn join_hinges<'a, D: Scalar, E: Message>(
        &self,
        r: &Read<'_, impl Fn(&Keyed) -> Result<D, E>>,
        axis: &impl Fn(usize) -> Option<[D; 2]>,
        flexures: &mut [Flexure<D>],
        dims: &mut [Vec<D>],
        mut joined: Joined<'a, D>,
    ) -> Result<Joined<'a, D>, String> {
        let d = &self.description;
        for (i, ((h, dd), f)) in d
            .hinges
            .iter()
            .zip(dims.iter_mut())
            .zip(flexures.iter_mut())
            .enumerate()
        {
            dd.clear();
            for (e, info) in h.dimensions.iter().zip(h.kind.dimensions()) {
                dd.push(if info.dimension == Dimension::Length {
                    r.length(e).map_err(Message::message)?
                } else {
                    r.eval(e)?
                });
            }
            if let Some(why) = domain_error(h, dd) {
                return Err(format!("hinge \"{}\": {why}", h.name));
            }
            f.from = h.from.map_or(Body::Ground, Body::Rigid);
            f.to = h.to.map_or(Body::Ground, Body::Rigid);
            r.point_into(&h.start, &mut f.start)?;
            f.axis = match axis(i) {
                Some(axis) => axis,
                None => {
                    let (s, c) = r.eval(&h.angle)?.sin_cos();
                    [c, s]
                }
            };
            f.length = h.kind.length(dd);
            if f.length.re() <= 0.0 || f.length.re().is_nan() {
                return Err(not_positive(&h.name, &h.key, "length", f.length.re()));
            }
            f.end = end_of(&f.start, &f.axis, f.length);
            hinge_compliance(h.kind, dd, d.width, &self.material, &mut f.compliance);
            joined.join(f);
        }
        Ok(joined)
    }

    /// Each beam's length and thickness into `dims` and its flexure into `flexures`, joined.
    fn join_beams<D: Scalar, E: Message>(
        &self,
        r: &Read<'_, impl Fn(&Keyed) -> Result<D, E>>,
        flexures: &mut [Flexure<D>],
        dims: &mut [Vec<D>],
        mut joined: Joined<'_, D>,
    ) -> Result<(), String> {
        let d = &self.description;
        for ((b, dd), f) in d.beams.iter().zip(dims.iter_mut()).zip(flexures.iter_mut()) {
            let start = r.point(&b.start).map_err(Message::message)?;
            let end = r.point(&b.end).map_err(Message::message)?;
            let thickness = r.length(&b.thickness).map_err(Message::message)?;
            let (dx, dy) = (end[0] - start[0], end[1] - start[1]);
            let l = (dx * dx + dy * dy).sqrt();
            if l.re() == 0.0 {
                return Err(format!(
                    "beam \"{}\" ({}): its start and end are the same point",
                    b.name, b.key
                ));
            }
            if thickness.re() <= 0.0 || !thickness.re().is_finite() {
                return Err(format!(
                    "beam \"{}\" ({}.thickness): the thickness {} m is not positive",
                    b.name,
                    b.key,
                    thickness.re()
                ));
            }
            dd.clear();
            dd.push(l);
            dd.push(thickness);
            *f = Flexure::new(
                b.from.map_or(Body::Ground, Body::Rigid),
                b.to.map_or(Body::Ground, Body::Rigid),
                start,
                [dx / l, dy / l],
                l,
                beam_compliance(l, thickness, d.width, &self.material),
            );
            joined.join(f);
        }
        Ok(())
    }
}

/// `f` joined to the network, its compliance at the evaluation's modulus where one is given:
/// its ends the reference points of the bodies that have none yet, and among the described
/// `points` when they are kept.
pub(super) fn join<D: Scalar>(
    f: &mut Flexure<D>,
    modulus: Option<D>,
    references: &mut [[D; 2]],
    placed: &mut [bool],
    points: Option<&mut Vec<[D; 2]>>,
) {
    if let Some(m) = modulus {
        f.compliance = f.compliance.with_modulus(m);
    }
    for (body, p) in [(f.from, &f.start), (f.to, &f.end)] {
        if let Body::Rigid(b) = body {
            if !placed[b] {
                references[b] = *p;
                placed[b] = true;
            }
        }
    }
    if let Some(points) = points {
        points.push(f.start);
        points.push(f.end);
    }
}

/// Hinge `kind`'s compliance at `dims` (SI) into `out`: where the scalar is a number of first
/// derivatives alone and the kind has its partial derivatives in closed form, its tangent
/// is their chain rule, a few products a coefficient where the formula's every operation
/// over the number was one; elsewhere the kind's formula over the scalar. The values are
/// the formula's, bit for bit, either way.
#[inline(always)]
pub(super) fn hinge_compliance<D: Scalar>(
    kind: HingeKind,
    dims: &[D],
    width: f64,
    material: &Material,
    out: &mut Compliance<D>,
) {
    if D::FROM_PARTIALS && dims.len() <= MAX_HINGE_DIMENSIONS {
        let mut plain = [0.0; MAX_HINGE_DIMENSIONS];
        for (p, v) in plain.iter_mut().zip(dims) {
            *p = v.re();
        }
        if let Some((c, by)) = kind.compliance_partials(&plain[..dims.len()], width, material) {
            let n = dims.len();
            let chain = |re: f64, pick: fn(&Compliance<f64>) -> f64| {
                let partials: [f64; MAX_HINGE_DIMENSIONS] = std::array::from_fn(|k| pick(&by[k]));
                D::from_partials(re, dims, &partials[..n])
            };
            out.c11 = chain(c.c11, |c| c.c11);
            out.c22 = chain(c.c22, |c| c.c22);
            out.c23 = chain(c.c23, |c| c.c23);
            out.c33 = chain(c.c33, |c| c.c33);
            return;
        }
    }
    *out = kind.compliance(dims, width, material);
}

/// A flexure of zeros, for a slot that each evaluation overwrites.
pub(super) fn idle_flexure<D: Scalar>() -> Flexure<D> {
    let zero = D::from(0.0);
    Flexure {
        from: Body::Ground,
        to: Body::Ground,
        start: [zero; 2],
        axis: [zero; 2],
        length: zero,
        end: [zero; 2],
        compliance: Compliance {
            c11: zero,
            c22: zero,
            c23: zero,
            c33: zero,
        },
    }
}

/// The unit direction `(dx, dy)` (m) where a scalar's normalization, by a reciprocal or by
/// a division, gives the same numbers (both give them for an axis): `None` where they
/// differ or the direction is zero, and the scalars normalize it at each evaluation.
pub(super) fn constant_direction(dx: f64, dy: f64) -> Option<[f64; 2]> {
    let norm = (dx * dx + dy * dy).sqrt();
    if norm == 0.0 || !norm.is_finite() {
        return None;
    }
    let inv = 1.0 / norm;
    let (by_reciprocal, by_division) = ([dx * inv, dy * inv], [dx / norm, dy / norm]);
    (by_reciprocal == by_division).then_some(by_division)
}

/// The message of an expression's failure: the trees' own, or none from the tape.
pub(super) trait Message {
    fn message(self) -> String;
}

impl Message for String {
    fn message(self) -> String {
        self
    }
}

impl Message for Infallible {
    fn message(self) -> String {
        match self {}
    }
}

/// The rectangle `thickness` wide around the segment `a b`, counterclockwise.
pub(super) fn link_band<D: Scalar>(a: [D; 2], b: [D; 2], thickness: D) -> Vec<[D; 2]> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let scale = thickness * 0.5 / (dx * dx + dy * dy).sqrt();
    let (nx, ny) = (-dy * scale, dx * scale);
    vec![
        [a[0] - nx, a[1] - ny],
        [b[0] - nx, b[1] - ny],
        [b[0] + nx, b[1] + ny],
        [a[0] + nx, a[1] + ny],
    ]
}

/// The message of a body's or a flexure's size `value` (m) that the design makes zero or
/// negative, naming its key.
pub(super) fn not_positive(name: &str, key: &str, size: &str, value: f64) -> String {
    format!(
        "\"{name}\" ({key}): its {size} {} m is not positive at this design: a size is \
         positive; keep its expression above zero over the bounds",
        crate::vocab::units::short(value)
    )
}

/// The first outline, a body's or the ground's, that crosses itself at the evaluated
/// design: no solid has it.
pub(super) fn outline_crossing(d: &Description, e: &Evaluated<f64>) -> Option<String> {
    let bodies = d.bodies.iter().enumerate().filter_map(|(b, body)| {
        let points = &e.points[e.offsets[b]..e.offsets[b + 1]];
        (body.link_width.is_none()).then(|| {
            let what = format!("body \"{}\" ({}.outline)", body.name, body.key);
            (what, points)
        })
    });
    let ground_at = e.offsets[d.bodies.len()];
    let ground = std::iter::once((
        "the ground's outline".to_string(),
        &e.points[ground_at..ground_at + d.ground.len()],
    ));
    bodies.chain(ground).find_map(|(what, points)| {
        let (i, j) = super::super::checks::crossing(points)?;
        Some(format!(
            "{what} crosses itself at this design (its edges from points {i} and {j}): list \
             its points in order around it"
        ))
    })
}

/// Why hinge `h`'s dimensions `dims` (SI) make no hinge of its kind, named by their keys;
/// the check on the values alone, without allocating, and the names only for a message.
pub(super) fn domain_error<D: Scalar>(h: &HingeDescription, dims: &[D]) -> Option<String> {
    const MOST: usize = 8;
    if dims.len() <= MOST {
        let mut plain = [0.0; MOST];
        for (p, v) in plain.iter_mut().zip(dims) {
            *p = v.re();
        }
        // the names only make the message, which the second call below makes (a constant:
        // an array of them built at each call was 128 bytes written)
        const NONE: [&str; MOST] = [""; MOST];
        h.kind
            .domain_error(&plain[..dims.len()], &NONE[..dims.len()])?;
    }
    let names: Vec<&str> = h.dimensions.iter().map(|e| e.key.as_str()).collect();
    let plain: Vec<f64> = dims.iter().map(|v| v.re()).collect();
    h.kind.domain_error(&plain, &names)
}
