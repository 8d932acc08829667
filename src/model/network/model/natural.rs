//! The network's natural modes: the degrees of freedom of each family of modes the mirror
//! axes leave, the mass matrix of the bodies, the payloads and the stack's share, and the
//! lowest frequencies from the structure's stiffness ([`super::super::modes`]).

use super::*;

/// One family of modes ([`families`]): the network with the family's holds and the stack
/// where it is stretched (on a part unfolded about its mounting, the whole about that line),
/// the bodies' inertias with the payload (and the images'), the stack's directed masses,
/// each described body's image (empty unless unfolded), the axes the modes are
/// antisymmetric about, whether the stack is stretched, and the line unfolded about (`true`
/// the line `y = 0`).
pub(crate) struct Family<D> {
    pub network: Network<D>,
    pub inertia: Vec<Inertia<D>>,
    pub directed: Vec<DirectedMass<D>>,
    pub images: Vec<Body>,
    pub anti: Vec<Axis>,
    pub stretched: bool,
    pub unfolded: Option<bool>,
}

impl NetworkModel {
    /// Why the natural frequency `i` (from 0) has no value on this network, the output named
    /// `name` (`f1`, or `nl_f1` at the working stroke, which has a value where the linear
    /// model's has one): a support, no density, a part that nothing holds, no stack's
    /// stiffness, a body without a mass, or fewer degrees of freedom than modes.
    pub(super) fn frequency_unavailable(&self, i: usize, name: &str) -> Option<String> {
        let d = &self.description;
        if let Some(g) = d.supports.first() {
            return Some(format!(
                "output \"{name}\": the natural frequencies of a network with supports \
                 ({}) are not modelled",
                g.key
            ));
        }
        if !self.material.density.is_finite() {
            return Some(format!(
                "output \"{name}\" needs the material's density: give `[material] density` \
                 (e.g. \"2810 kg/m3\") or a preset"
            ));
        }
        if !d.mirror.is_empty() && !self.grounded() {
            match self.mounting() {
                None => {
                    return Some(format!(
                        "output \"{name}\": the part has no ground, and neither its input nor \
                         its first output is across a mirror axis: nothing holds it"
                    ))
                }
                Some((1, _)) if d.input.across.is_none() => {
                    return Some(format!(
                        "output \"{name}\": the part stands on the first output's image, and \
                         the input is across no mirror axis, so the stack's far end has no \
                         place: give `network.input.across` or join a hinge to the ground"
                    ))
                }
                _ => {}
            }
        }
        if self.actuator.stiffness.is_none() {
            return Some(format!(
                "output \"{name}\" needs the actuator's stiffness (`[actuator] stiffness`): the \
                 input stands on it in every mode"
            ));
        }
        if let Some(body) = d
            .bodies
            .iter()
            .find(|body| body.link_width.is_none() && body.points.len() < 3)
        {
            return Some(format!(
                "output \"{name}\" needs every body's mass: body \"{}\" ({}) has no outline or \
                 link to give it",
                body.name, body.key
            ));
        }
        let dofs = self.mode_dofs();
        if i >= dofs {
            return Some(format!(
                "output \"{name}\": the network has {dofs} degrees of freedom, so {dofs} modes"
            ));
        }
        None
    }

    /// How many natural frequencies the model has values for: `f1` to `f{n}`, and at the
    /// working stroke `nl_f1` to `nl_f{n}`.
    pub(crate) fn frequency_count(&self) -> usize {
        (0..super::outputs::FREQUENCIES)
            .take_while(|&i| self.frequency_unavailable(i, "").is_none())
            .count()
    }

    /// How many modes [`Self::frequencies`] finds: the degrees of freedom of the described
    /// part in each family of modes ([`families`]), or of the whole about the axis its
    /// mounting stands across.
    pub(super) fn mode_dofs(&self) -> usize {
        let d = &self.description;
        let mounting = self.mounting();
        let line = mounting.map(|(_, line)| line);
        let mount = mounting.map(|(port, _)| {
            if port == 0 {
                d.input.body
            } else {
                d.outputs[0].body
            }
        });
        let mut dofs = 0;
        for anti in families(&self.family_axes()) {
            let held = axis_holds(d, line, &anti);
            dofs += 3 * d.bodies.len() - held.len();
            if let (Some(line), Some(mount)) = (line, mount) {
                for (b, body) in d.bodies.iter().enumerate() {
                    if b != mount && !body.on_axis.contains(&line) {
                        dofs += 3 - held.iter().filter(|h| h.0 == b).count();
                    }
                }
            }
        }
        dofs
    }

    /// The mirror axes the modes are symmetric or antisymmetric about: every one, but that
    /// the part stands across ([`Self::mounting`]), about which it is unfolded whole.
    pub(super) fn family_axes(&self) -> Vec<Axis> {
        let line = self.mounting().map(|(_, line)| line);
        let d = &self.description;
        d.mirror
            .iter()
            .copied()
            .filter(|&a| Some(a) != line)
            .collect()
    }

    /// Whether a hinge or a beam joins the ground.
    pub(super) fn grounded(&self) -> bool {
        let d = &self.description;
        d.hinges.iter().any(|h| h.from.is_none() || h.to.is_none())
            || d.beams.iter().any(|b| b.from.is_none() || b.to.is_none())
    }

    /// The port whose image across its axis holds a part with mirror axes and no ground:
    /// the first output's, else the input's, as the part's check clamps it. `None` where
    /// the ground holds the part, or there are no mirror axes.
    pub(super) fn mounting(&self) -> Option<(usize, Axis)> {
        let d = &self.description;
        if d.mirror.is_empty() || self.grounded() {
            return None;
        }
        d.outputs[0]
            .across
            .map(|a| (1, a))
            .or(d.input.across.map(|a| (0, a)))
    }

    /// Each body's mass, centroid and moment of inertia at the evaluated design: its plate
    /// (its outline's or its link's, the described piece where it lies across an axis),
    /// with each beam's mass lumped at its ends.
    fn body_inertia<D: Scalar>(&self, e: &Evaluated<D>) -> Vec<Inertia<D>> {
        let d = &self.description;
        let (density, width) = (self.material.density, d.width);
        let mut inertia: Vec<Inertia<D>> = d
            .bodies
            .iter()
            .enumerate()
            .map(|(b, body)| {
                let points = &e.points[e.offsets[b]..e.offsets[b + 1]];
                let axes: Vec<bool> = body.on_axis.iter().map(|a| *a == Axis::X).collect();
                match e.link_widths[b] {
                    Some(t) if axes.is_empty() => {
                        Inertia::link(points[0], points[1], t, density, width)
                    }
                    Some(t) => {
                        let band = link_band(points[0], points[1], t);
                        Inertia::polygon(&described_piece(&band, &axes), density, width)
                    }
                    None if points.len() >= 3 => {
                        Inertia::polygon(&described_piece(points, &axes), density, width)
                    }
                    None => Inertia {
                        mass: D::from(0.0),
                        centroid: e.network.references[b],
                        moment: D::from(0.0),
                    },
                }
            })
            .collect();
        // each beam's mass lumped at its ends, half to each body (the consistent mass of a
        // frame element would couple the bodies; the lumped one keeps them apart, and is
        // close while a beam weighs little against the bodies it joins)
        let flexures = e.network.flexures[d.hinges.len()..].iter();
        for ((b, f), dims) in d.beams.iter().zip(flexures).zip(&e.dims[d.hinges.len()..]) {
            let half = dims[0] * dims[1] * (0.5 * density * width);
            for (body, at) in [(b.from, f.start), (b.to, f.end)] {
                if let Some(body) = body {
                    inertia[body] = inertia[body].with_point_mass(half, at);
                }
            }
        }
        inertia
    }

    /// The message of a failed modal solve in the family of modes antisymmetric about
    /// `anti`, a massless body named by the body it images (`images`, on a part unfolded).
    fn mode_error(&self, err: ModeError, images: &[Body], anti: &[Axis]) -> String {
        let d = &self.description;
        let family = if anti.is_empty() {
            String::new()
        } else {
            let names: Vec<&str> = anti.iter().map(|a| a.name()).collect();
            format!(
                " in the modes antisymmetric about the {} axis",
                names.join(" and ")
            )
        };
        match err {
            ModeError::Network(err) => format!("{}{family}", self.network_error(err)),
            ModeError::Massless { body } => {
                let b = (0..d.bodies.len())
                    .find(|&b| body == b || images.get(b) == Some(&Body::Rigid(body)))
                    .unwrap_or(0);
                format!(
                    "body \"{}\" ({}) has no mass where it can move{family}",
                    d.bodies[b].name, d.bodies[b].key
                )
            }
        }
    }

    /// The `count` lowest natural frequencies of the network `e` (Hz): each body a plate of
    /// the material's density and the part's width cut to its outline or its link, the
    /// first output's payload at its point, the actuator a spring to the ground at the
    /// input along its direction (the stack's far end on the base), the flexures massless
    /// ([`super::modes`]). [`Model::unavailable`] has checked that every body has a shape
    /// and that the part has a mounting.
    ///
    /// With mirror axes the described part carries its share of each body across an axis
    /// ([`described_piece`]), and the modes are found family by family ([`families`]): those
    /// symmetric about every axis, then those antisymmetric about one or both, each family
    /// its own holds on the bodies across the axes ([`axis_holds`]); the lowest `count` of
    /// all are the whole part's. The stack, between the input's face and its image across
    /// `network.input.across`, is not stretched in a mode antisymmetric about that axis (the
    /// two faces move alike), and is left out of those families. A grounded part's payload
    /// rides on each image of the first output's face. A part without ground stands on the
    /// image of a port across an axis ([`Self::mounting`]), which breaks the symmetry about
    /// that axis: the described part is joined to its image across it, that port's image the
    /// ground ([`Network::unfolded`]), the payload on the port's face alone, and the
    /// families are those about the other axis.
    pub(super) fn frequencies<D: Scalar>(
        &self,
        e: &Evaluated<D>,
        count: usize,
    ) -> Result<Vec<D>, String> {
        let mut found: Vec<D> = Vec::new();
        for f in self.families_of(e) {
            let modes = f
                .network
                .modes_with(&f.inertia, &f.directed, count)
                .map_err(|err| self.mode_error(err, &f.images, &f.anti))?;
            found.extend(modes.into_iter().map(|m| m.frequency));
        }
        if found.len() < count {
            return Err(format!(
                "the network has {} modes; f{count} asks for more",
                found.len()
            ));
        }
        // by value, the families' order breaking ties, so that the same design gives the
        // same order
        found.sort_by(|a, b| a.re().total_cmp(&b.re()));
        found.truncate(count);
        Ok(found)
    }

    /// The families of modes of [`Self::frequencies`] at the design `x` (SI), for the modes
    /// about an equilibrium at stroke ([`super::stroke_modes`]), which takes their
    /// holds, masses and images and puts its own stiffness in the place of the networks'.
    pub(crate) fn modal_families<D: Scalar>(&self, x: &[D]) -> Result<Vec<Family<D>>, String> {
        let mut work = Work::<D>::default();
        self.at(x, None, true, &mut work)?;
        Ok(self.families_of(&work.evaluated))
    }

    /// Each family of modes of [`Self::frequencies`] at the evaluated design `e`.
    fn families_of<D: Scalar>(&self, e: &Evaluated<D>) -> Vec<Family<D>> {
        let d = &self.description;
        let mounting = self.mounting();
        let inertia = self.body_inertia(e);
        let stack = self.actuator.stiffness.map(|k| {
            let port = &e.ports[0];
            Spring {
                body: port.body,
                point: port.point,
                direction: port.force,
                stiffness: D::from(k * self.read[0] * self.share[0]),
            }
        });
        let line = mounting.map(|(_, line)| line);
        // a body across an axis is held at its point on the axis: in a mode antisymmetric
        // about it, it turns about that point, and a hold of its motion along the axis at a
        // reference off it would turn it about the reference instead (in a symmetric mode it
        // neither turns nor moves across, and the reference does not matter)
        let mut on_axes = e.network.clone();
        for (b, body) in d.bodies.iter().enumerate() {
            for a in &body.on_axis {
                match a {
                    Axis::X => on_axes.references[b][1] = D::from(0.0),
                    Axis::Y => on_axes.references[b][0] = D::from(0.0),
                }
            }
        }
        let mut out = Vec::new();
        for anti in families(&self.family_axes()) {
            let mut network = on_axes.clone();
            let held = axis_holds(d, line, &anti);
            let stretched = !d.input.across.is_some_and(|a| anti.contains(&a));
            network.springs.extend(stack.filter(|_| stretched));
            let mut directed = self.stack_masses(e, stretched);
            let mut inertia = inertia.clone();
            let mut payload_share = self.share[1];
            let mut images = Vec::new();
            let mut unfolded = None;
            if let Some((port, line)) = mounting {
                let flip_y = line == Axis::X;
                let across: Vec<bool> =
                    d.bodies.iter().map(|b| b.on_axis.contains(&line)).collect();
                let (whole, image) = network.unfolded(flip_y, &across, &held, e.ports[port].body);
                for (b, im) in image.iter().enumerate() {
                    match *im {
                        Body::Rigid(i) if i == b => inertia[b] = inertia[b].doubled(flip_y),
                        Body::Rigid(_) => inertia.push(inertia[b].reflected(flip_y)),
                        Body::Ground => {}
                    }
                }
                if across[d.outputs[0].body] {
                    payload_share *= 2.0;
                }
                directed = DirectedMass::unfolded(&directed, &image, flip_y);
                network = whole;
                images = image;
                unfolded = Some(flip_y);
            } else {
                network.held = held;
            }
            let (body, at) = (e.ports[1].body, e.ports[1].point);
            inertia[body] = inertia[body].with_point_mass(d.outputs[0].payload * payload_share, at);
            out.push(Family {
                network,
                inertia,
                directed,
                images,
                anti,
                stretched,
                unfolded,
            });
        }
        out
    }

    /// The stack's own mass (`[actuator] mass`) on the input port, the described part's
    /// share of it, in the family of modes where the stack is `stretched` or not
    /// ([`DirectedMass::stack`]).
    pub(super) fn stack_masses<D: Scalar>(
        &self,
        e: &Evaluated<D>,
        stretched: bool,
    ) -> Vec<DirectedMass<D>> {
        let Some(mass) = self.actuator.mass.filter(|&m| m > 0.0) else {
            return Vec::new();
        };
        let port = &e.ports[0];
        let mirrored = self.read[0] > 1.0;
        DirectedMass::stack(
            mass * self.share[0],
            (mirrored, stretched),
            port.body,
            port.point,
            port.force,
        )
        .to_vec()
    }
}

/// The degrees of freedom the mirror axes hold (all but `except`), sorted, in the modes
/// symmetric about every axis but those `antisymmetric`. A body across an axis keeps, in
/// a motion symmetric about it, its motion across the axis and its rotation at zero; in one
/// antisymmetric about it, its motion along the axis (the field at a point's image is
/// minus the point's reflected, which on the axis leaves the motion across it and the
/// turn free). The statics' loads are symmetric: `antisymmetric` empty.
pub(super) fn axis_holds(
    d: &Description,
    except: Option<Axis>,
    antisymmetric: &[Axis],
) -> Vec<(usize, Dof)> {
    let mut held = Vec::new();
    for (b, body) in d.bodies.iter().enumerate() {
        for a in body.on_axis.iter().filter(|&&a| Some(a) != except) {
            let (across, along) = match a {
                Axis::X => (Dof::Y, Dof::X),
                Axis::Y => (Dof::X, Dof::Y),
            };
            if antisymmetric.contains(a) {
                held.push((b, along));
            } else {
                held.push((b, across));
                held.push((b, Dof::Rotation));
            }
        }
    }
    held.sort_by_key(|&(b, dof)| (b, dof as usize));
    held.dedup();
    held
}

/// The families of modes of a part mirrored about `axes`: each set of the axes its modes
/// are antisymmetric about (the empty set first, the modes symmetric about every axis).
/// The whole part's modes are the union of the families' (a mode of a symmetric structure
/// is symmetric or antisymmetric about each of its mirror axes, and the two kinds do not
/// couple: Kangwai, Guest and Pellegrino, "An introduction to the analysis of symmetric
/// structures", Computers & Structures 71 (1999) 671-688; Bartilson, Jang and Smyth,
/// Mech. Syst. Signal Process. 143 (2020) 106797, Sec. 2).
pub(super) fn families(axes: &[Axis]) -> Vec<Vec<Axis>> {
    (0..1usize << axes.len())
        .map(|mask| {
            axes.iter()
                .enumerate()
                .filter(|(i, _)| mask >> i & 1 == 1)
                .map(|(_, a)| *a)
                .collect()
        })
        .collect()
}
