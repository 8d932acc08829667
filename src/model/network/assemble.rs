//! The network as a [`Mechanism`]: its sections read ([`super::file`]) into a
//! [`super::description::Description`], and from it the model and, with a `[part]` section, the part. Apart from
//! the parser so that reading a file and building from it import each other's types in one
//! direction only.

use super::checks;
use super::file::describe;
use super::model::{LargeSettings, NetworkModel, CRITICAL_UP_TO};
use super::part::{Counterparts, Drawing, NetworkPart, PartSettings, RawNetworkPart};
use super::raw::{Deflection, RawAnalysis, RawNetwork};
use crate::model::actuator::{Actuator, RawActuator};
use crate::model::material::{Material, RawMaterial};
use crate::model::Mechanism;
use crate::model::Model;
use crate::part::Actuation;
use crate::vocab::reader::{k, Res};
use crate::vocab::sections::Sections;
use std::sync::Arc;

/// Reads the network's sections and builds the model.
pub fn build(s: &mut Sections) -> Res<Mechanism> {
    let m: RawMaterial = s.required("material")?;
    let n: RawNetwork = s.required("network")?;
    let a: RawActuator = s.required("actuator")?;
    let material = Material::from_section(s, &m)?;
    let description = describe(s, &n)?;
    let actuator = Actuator::read(s, &a)?;
    let part: Option<RawNetworkPart> = s.optional("part")?;
    let part = part.map(|p| PartSettings::read(s, &p)).transpose()?;
    if let (Some(_), Some(g)) = (&part, description.supports.first()) {
        // the part's check holds whole faces (the ground's), not one direction of a face
        return Err(s.err(
            &[k("network"), k("supports")],
            format!(
                "a network with supports has no part: its finite-element check cannot hold a \
                 face in one direction only ({}); remove the [part] section or the supports",
                g.key
            ),
        ));
    }
    let actuation = Actuation {
        nominal_stroke: actuator.nominal_stroke,
        preload: actuator.preload,
        stiffness: actuator.stiffness,
        payload_mass: description.outputs[0].payload,
        stack_mass: actuator.mass.unwrap_or(0.0),
    };
    let drawing = part.map(|settings| Arc::new(Drawing::new(description.clone(), settings)));
    let large = analysis(s)?;
    let mut model = NetworkModel::new(description, material, actuator);
    if let Some(drawing) = &drawing {
        model = model.with_drawing(drawing.clone());
    }
    if let Some(settings) = large {
        model = model.with_large(settings);
    }
    let names: Vec<&str> = model.outputs().iter().map(|o| o.name.as_ref()).collect();
    if let Some((path, why)) = checks::name_error(model.description())
        .or_else(|| checks::output_clash(&names, model.description()))
    {
        return Err(s.err(&path, why));
    }
    let counterparts = Counterparts {
        amplification: model.output_index("amplification"),
        k_in: model.output_index("k_in"),
        k_out: model.output_index("k_out"),
        stress_max: model.output_index("stress_max"),
        f1: model.output_index("f1"),
        actuated: super::part::ACTUATED_OUTPUTS.map(|name| model.output_index(name)),
        // the spans, the outline's box and the described measures are sizes of the part
        // as drawn
        drawn: ["span_x", "span_y", "part_width", "part_height"]
            .into_iter()
            .chain(model.description().measures.iter().map(|m| m.name.as_str()))
            .filter_map(|name| model.output_index(name))
            .collect(),
    };
    let model = Arc::new(model);
    let mut mechanism = Mechanism::physics_only(model.clone()).with_modulus_scaling(model.clone());
    mechanism.large = Some(model.clone());
    mechanism.depiction = Some(model);
    if let Some(drawing) = drawing {
        mechanism.part_maker = Some(Arc::new(NetworkPart {
            drawing,
            actuation,
            counterparts,
        }));
    }
    Ok(mechanism)
}

/// The `[analysis]` section: the outputs at the working stroke, where it asks for large
/// deflection, and how they are solved.
fn analysis(s: &Sections) -> Res<Option<LargeSettings>> {
    let Some(raw) = s.optional::<RawAnalysis>("analysis")? else {
        return Ok(None);
    };
    let count = |key: &str, value: Option<usize>, default: usize, most: usize| {
        let n = value.unwrap_or(default);
        if (1..=most).contains(&n) {
            Ok(n)
        } else {
            Err(s.err(
                &[k("analysis"), k(key)],
                format!("{n}: expected a whole number from 1 to {most}"),
            ))
        }
    };
    let up_to = raw.critical_up_to.unwrap_or(CRITICAL_UP_TO);
    if !(up_to > 1.0 && up_to <= 100.0) {
        return Err(s.err(
            &[k("analysis"), k("critical_up_to")],
            format!("{up_to}: expected a number above 1 and at most 100"),
        ));
    }
    let settings = LargeSettings {
        elements: count("elements", raw.elements, 8, 64)?,
        steps: count("steps", raw.steps, 10, 200)?,
        critical_up_to: up_to,
    };
    let tuned = raw.elements.is_some() || raw.steps.is_some() || raw.critical_up_to.is_some();
    match raw.deflection.unwrap_or(Deflection::Small) {
        Deflection::Small if tuned => Err(s.err(
            &[k("analysis"), k("deflection")],
            "`elements`, `steps` and `critical_up_to` set how the large-deflection solve runs: \
             give `deflection = \"large\"` with them, or remove them"
                .to_string(),
        )),
        Deflection::Small => Ok(None),
        Deflection::Large => Ok(Some(settings)),
    }
}
