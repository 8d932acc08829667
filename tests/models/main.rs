//! The mechanism models: the general bridge (statics, dynamics, hinges and their ranges of
//! fit, stability far beyond Table 1's bounds), the papers' tables and equations, the 3-PRR
//! and 3-PSS mechanisms, the Runge-Kutta step responses, a model added from outside the library, and the layout of `src/`
//! that lets one be added (no import cycle between its folders, no model's name outside
//! `src/model/`).
//!
//! One test binary per subject (issue 21): each file is a module, the fixtures are shared.

#[path = "../common/mod.rs"]
mod common;

mod bridge_dynamics;
mod bridge_model;
mod critical_load;
mod fit_ranges;
mod hinges;
mod large_deflection;
mod large_stroke;
mod layout;
mod model_stability;
mod network_beams;
mod network_bridge;
mod network_mirror_modes;
mod network_modulus;
mod network_shipped;
mod network_supports;
mod paper001;
mod paper004_tables;
mod prr3;
mod pss3;
mod rooms;
mod step_response;
mod stroke_frequencies;
mod stroke_gradients;
mod stroke_matters;
mod toy_model;
