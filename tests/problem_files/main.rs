//! Problem files and the command line: every rejection rule, the parser under fuzzing, the
//! commands end to end, and flexopt as a designer meets it.
//!
//! One test binary per subject (issue 21): each file is a module, the fixtures are shared.

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod designer;
mod init_choices;
mod limits;
mod messages;
mod names;
mod network_errors;
mod network_refused;
mod network_supports;
mod optimum_report;
mod problem_errors;
mod problem_fuzz;
mod rejected;
mod sets;
mod stdout;
mod stroke_cli;
mod tolerance_cli;
