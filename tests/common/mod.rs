//! Shared fixtures of the integration tests.
#![allow(dead_code)]

pub mod exact;
pub mod hs;

use flexopt::model::bridge::dynamics::DynamicsSettings;
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::{Actuator, Bridge, BridgeSettings, Geometry};
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub const MM: f64 = 1e-3;
pub const DEG: f64 = std::f64::consts::PI / 180.0;

/// Paper 004, Sec. 3: w = 10 mm, Al 7075-T6, 17.4 um nominal stroke, 40 N preload.
pub fn wei2017_settings() -> BridgeSettings {
    BridgeSettings {
        hinge_b: HingeKind::Strip,
        hinge_d: HingeKind::Strip,
        width: 10.0 * MM,
        material: Material::al7075_t6(),
        actuator: Actuator {
            nominal_stroke: 17.4e-6,
            preload: 40.0,
            stiffness: None,
        },
        // the stage of problems/wei2017_dynamic.toml, so that every output has a value
        dynamics: Some(DynamicsSettings::new(10e-3, 3e-3, 3e-3, 3e-3, 0.02)),
        part: PartSettings::default(),
    }
}

pub fn wei2017() -> Bridge {
    Bridge::new(wei2017_settings())
}

/// Table 1's optimal result, SI.
pub fn table1_optimum() -> [f64; 8] {
    [
        1.96 * MM,
        4.07 * DEG,
        0.4 * MM,
        8.1 * MM,
        4.01 * DEG,
        1.96 * MM,
        4.07 * DEG,
        0.4 * MM,
    ]
}

/// Table 1's bounds, SI, in parameter order.
pub fn table1_bounds() -> [(f64, f64); 8] {
    let (l, a, t) = (
        (0.5 * MM, 20.0 * MM),
        (-45.0 * DEG, 45.0 * DEG),
        (0.4 * MM, 2.0 * MM),
    );
    [l, a, t, l, a, l, a, t]
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A design drawn uniformly from Table 1's bounds.
pub fn random_design(rng: &mut ChaCha8Rng) -> [f64; 8] {
    table1_bounds().map(|(lo, hi)| rng.random_range(lo..hi))
}

pub fn geometry(x: [f64; 8]) -> Geometry<f64> {
    Geometry::from_array(x)
}

/// Relative difference, with the scale floored so that values near zero compare absolutely
/// against `scale`.
pub fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / b.abs().max(scale)
}

/// Runs the `flexopt` binary with `args` and collects its exit status and output.
pub fn flexopt(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_flexopt"))
        .args(args)
        .output()
        .unwrap()
}

/// Runs the `flexopt` binary with `args`, which must succeed, and returns its output.
pub fn flexopt_ok(args: &[&str]) -> std::process::Output {
    let out = flexopt(args);
    assert!(
        out.status.success(),
        "flexopt {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `x` rounded to `digits` significant digits, the way a paper prints it.
pub fn printed(x: f64, digits: i32) -> f64 {
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}
