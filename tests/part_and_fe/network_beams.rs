//! Flexible beams in a network's part (issue 25): a stage on two parallel beams from the
//! ground (a parallelogram guide of beams) drawn as one closed outline, its beams cut as the
//! strip of their length and thickness (a flexure site each, filleted, held on the ground's
//! pads); its `k_in` against flexopt's FE of the part, in plane stress, and that FE against
//! CalculiX on the same mesh; a beam crossing another solid refused, the beam named.

use std::path::Path;

use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::fe::Fidelity;
use flexopt::part::Part;
use flexopt::problem::Problem;

use crate::network_part::{analytic, ccx_agrees, fe};

/// The guide of beams: `L` long, `t` thick, `d` apart, from the ground's pads to a stage
/// drawn 0.5 mm beyond their ends (their fillets and pads bridge the gap), pushed across
/// them on its lower edge, read along them; `extra` adds members or bodies, `mirror` the
/// `[network]` line of mirror axes.
fn guide(members: &str, extra: &str) -> String {
    format!(
        r#"
name = "beam_guide"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
parameters = [["L", "length"], ["t", "length"], ["d", "length"]]
input = {{ body = "stage", at = ["L + 4", "0"], direction = ["0", "1"] }}
outputs = [{{ name = "along", body = "stage", at = ["L + 4", "0"], direction = ["1", "0"] }}]

[[network.bodies]]
name = "stage"
outline = [["L + 0.5", "-d/2 - 3"], ["L + 8", "-d/2 - 3"], ["L + 8", "d/2 + 3"], ["L + 0.5", "d/2 + 3"]]

{extra}

{members}

[actuator]
nominal_stroke = "0.1 mm"
preload = "0 N"

[[variables]]
name = "L"
unit = "mm"
lower = 5
upper = 40

[[variables]]
name = "t"
unit = "mm"
lower = 0.3
upper = 2

[[variables]]
name = "d"
unit = "mm"
lower = 6
upper = 30

[objective]
minimize = "k_in"

[part]
"#
    )
}

fn beam(name: &str, start: [&str; 2], end: [&str; 2]) -> String {
    format!(
        "[[network.beams]]\nname = \"{name}\"\nfrom = \"ground\"\nto = \"stage\"\n\
         start = [\"{}\", \"{}\"]\nend = [\"{}\", \"{}\"]\nthickness = \"t\"\n",
        start[0], start[1], end[0], end[1]
    )
}

/// The parallel pair, `d/2` above and below the x axis.
fn pair() -> String {
    beam("top", ["0", "d/2"], ["L", "d/2"]) + &beam("bottom", ["0", "-d/2"], ["L", "-d/2"])
}

fn parse(text: &str) -> Problem {
    Problem::parse(Path::new("beam_guide.toml"), text).unwrap()
}

/// The guide is one closed outline: the beams cut where the model has them, each a
/// flexure site of its thickness (kind "beam", filleted at its roots), the ground its pads
/// held on their far sides; its DXF one closed polyline per loop. Described as the half
/// above the x axis with the stage across it, the part has the beam and its image.
#[test]
fn a_guide_of_beams_is_one_closed_outline_its_beams_flexures() {
    let p = parse(&guide(&pair(), ""));
    for [l, t, d] in [[20.0, 1.0, 10.0], [10.0, 1.0, 6.0], [40.0, 0.3, 30.0]] {
        let x = [l * 1e-3, t * 1e-3, d * 1e-3];
        let spec = p.mechanism().part_spec(&x).unwrap().unwrap();
        let part = Part::build(&spec).unwrap_or_else(|e| panic!("{x:?}: {e}"));
        assert_eq!(part.loops.iter().filter(|l| l.outer).count(), 1, "{x:?}");
        assert_eq!(part.hinges.len(), 2);
        for (h, y) in part.hinges.iter().zip([0.5 * d, -0.5 * d]) {
            assert_eq!(h.kind, "beam");
            assert_eq!((h.start, h.end), ([0.0, y * 1e-3], [l * 1e-3, y * 1e-3]));
            assert_eq!((h.thickness, h.root, h.fillet), (x[1], x[1], 0.2e-3));
        }
        // held on the two pads' far sides, 2.2 mm behind the beams' roots
        let clamps: Vec<_> = spec.faces.iter().filter(|f| f.name == "clamp").collect();
        assert_eq!(clamps.len(), 2);
        assert!(clamps
            .iter()
            .all(|f| (f.a[0] + 2.2e-3).abs() < 1e-15 && (f.b[0] + 2.2e-3).abs() < 1e-15));

        let bytes = flexopt::part::dxf::to_bytes(&part).unwrap();
        let drawing = dxf::Drawing::load(&mut bytes.as_slice()).unwrap();
        let closed: Vec<bool> = drawing
            .entities()
            .filter_map(|e| match &e.specific {
                dxf::entities::EntityType::LwPolyline(p) => Some(p.is_closed()),
                _ => None,
            })
            .collect();
        assert_eq!(closed, vec![true; part.loops.len()]);
    }

    // the half above the axis: the top beam and its image about it
    let half = guide(
        &beam("top", ["0", "d/2"], ["L", "d/2"]),
        "on_axis = [\"x\"]",
    )
    .replace("width = \"10 mm\"", "width = \"10 mm\"\nmirror = [\"x\"]")
    .replace("direction = [\"0\", \"1\"]", "direction = [\"1\", \"0\"]");
    let p = parse(&half);
    let x = [20e-3, 1e-3, 10e-3];
    let spec = p.mechanism().part_spec(&x).unwrap().unwrap();
    let part = Part::build(&spec).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(part.loops.iter().filter(|l| l.outer).count(), 1);
    let names: Vec<&str> = part.hinges.iter().map(|h| h.name.as_str()).collect();
    assert_eq!(names, ["top", "top (mirror x)"]);
    assert_eq!(part.hinges[1].start, [0.0, -5e-3]);
}

/// The guide's `k_in` against flexopt's FE of its part in plane stress, where beam theory
/// and the plane-stress FE share `E`. The model's guided pair (with Cowper's shear) holds
/// its beams' roots rigid; the part's roots turn in the pads and the stage they are cut
/// from, as a beam built into an elastic support does (O'Donnell, J. Appl. Mech. 27 (1960)
/// 461: a root rotation proportional to `M / (E w t^2)`), which adds `M^2 c` of each root to
/// a guided beam's compliance, a share `~ t / L` of its bending's. So the FE is softer by
/// 2.5 to 3.8 times `t / L` (measured 2.8 to 3.5 over L/t = 10 to 40: +32 % at 10, +16 % at
/// 20, +9 % at 40; docs/guide/src/networks.md). The largest section stress, the beams' here,
/// is the model's `stress_max` under the FE's own actuation force (the stack's stroke on
/// `fe_k_in`): each beam's end moment is `F L / 2` by statics however its roots give.
/// The FE against CalculiX on the same mesh.
#[test]
fn a_guide_of_beams_k_in_is_beam_theorys_by_the_parts_fe_and_ccx_agrees() {
    let p = parse(&guide(&pair(), ""));
    let settings = VerifySettings {
        modal: false,
        solid: false,
        ..VerifySettings::default()
    };
    for ([l, t, d], name) in [
        ([20.0, 1.0, 10.0], "beam_guide_20"),
        ([10.0, 1.0, 10.0], "beam_guide_10"),
        ([20.0, 0.5, 10.0], "beam_guide_40"),
    ] {
        let x = [l * 1e-3, t * 1e-3, d * 1e-3];
        let v = verify_design(p.mechanism(), &x, &settings).unwrap();
        assert!(v.whole_part);
        let plane = Fidelity::PlaneStress;
        let ratio = analytic(&p, &x, "k_in") / fe(&v, plane, "fe_k_in");
        let excess = (ratio - 1.0) * l / t;
        // the FE's actuation force is the stroke on its own stiffness
        let stress = analytic(&p, &x, "stress_max") / fe(&v, plane, "fe_stress_section") / ratio;
        eprintln!(
            "L/t = {}: analytic k_in over FE (plane stress) {:+.5}, {excess:.3} t/L; \
             stress_max over fe_stress_section at the FE's force {stress:.5}",
            l / t,
            ratio - 1.0
        );
        assert!((2.5..3.8).contains(&excess), "L/t = {}: {excess}", l / t);
        assert!((stress - 1.0).abs() < 0.005, "L/t = {}: {stress}", l / t);
        ccx_agrees(&v, &mut v.full_model(0).unwrap(), name);
    }
}

/// A beam is a flexure to the checks: a solid across it (the ground's block) or another
/// beam crossing it is refused, the beam named.
#[test]
fn a_beam_crossing_another_solid_is_refused_naming_it() {
    let x = [20e-3, 1e-3, 10e-3];
    let block = "[[network.bodies]]\nname = \"ground\"\noutline = [[\"L/2 - 1\", \"d/2 - 2\"], \
                 [\"L/2 + 1\", \"d/2 - 2\"], [\"L/2 + 1\", \"d/2 + 2\"], [\"L/2 - 1\", \"d/2 + 2\"]]";
    let crossed =
        beam("rising", ["0", "-d/2"], ["L", "d/2"]) + &beam("falling", ["0", "d/2"], ["L", "-d/2"]);
    for (text, names) in [
        (guide(&pair(), block), ["the ground", "top"]),
        (guide(&crossed, ""), ["beam falling", "rising"]),
    ] {
        let p = parse(&text);
        let spec = p.mechanism().part_spec(&x).unwrap().unwrap();
        let problems = Part::build(&spec).unwrap_err().problems;
        assert!(
            problems
                .iter()
                .any(|m| m.contains(names[0]) && m.contains(names[1])),
            "{problems:?}"
        );
    }
}
