//! The part and the finite elements: the bridge's outline and its checks, the elements
//! against exact solutions and against CalculiX, the check of a design, and the refinement
//! of an optimum against the finite elements, and the sets of files the commands write.
//!
//! One test binary per subject (issue 21): each file is a module, the fixtures are shared.

#[path = "../common/mod.rs"]
mod common;

mod actuated;
mod display_units;
mod dxf_audit;
mod fe_budget;
mod fe_calculix;
mod fe_exact;
mod fe_fillet;
mod fe_generic;
mod fe_verify;
mod first_mode;
mod footprint;
mod link_width;
mod meshing;
mod network_beams;
mod network_modes;
mod network_part;
mod network_rules;
mod part;
mod part_rules;
mod refine;
mod report_html;
mod report_integrity;
mod report_review;
mod sets;
mod specification;
mod stack_mass;
mod step;
