//! The FE refinement of paper 004's optimum: its time against its peers in the same run.
//!
//! `cargo bench --bench refine` runs, three times each and alternating, the whole job a
//! designer runs (`run problems/wei2017.toml --refine fe` without its files: the 300-start
//! study, then the refinement), the study alone, and one FE check of the analytic optimum
//! (the check a designer runs by hand after each nudge of the geometry). Writes
//! `results/bench/refine.json` and the table `results/bench/refine.txt`: the times, their
//! ratios, the FE checks spent, and the analytic optimum against the refined design, both
//! as the FE measures them.

use std::path::Path;
use std::time::Instant;

use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::problem::Problem;
use flexopt::refine::study::refine_study;
use flexopt::refine::RefineStatus;
use flexopt::report::refine::{RefineSummary, RefinedReport};
use flexopt::report::write_json;
use flexopt::study::{self, StudyOptions};
use serde::Serialize;

const REPEATS: usize = 3;

#[derive(Serialize)]
struct Report {
    refine_job_seconds: Vec<f64>,
    study_seconds: Vec<f64>,
    fe_check_seconds: Vec<f64>,
    medians: [f64; 3],
    /// The whole job over one FE check, and over the study.
    job_over_fe_check: f64,
    job_over_study: f64,
    fe_checks: usize,
    converged: bool,
    refined: RefinedReport,
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

fn main() {
    let mut problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    problem.refine.enabled = true;
    let options = StudyOptions::from_problem(&problem);
    let (mut job, mut alone, mut check) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..REPEATS {
        let t = Instant::now();
        let s = study::run(&problem, &options);
        let r = refine_study(&problem, &s);
        job.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let s2 = study::run(&problem, &options);
        alone.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        verify_design(
            problem.mechanism(),
            s2.reported_design(),
            &VerifySettings::default(),
        )
        .unwrap();
        check.push(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    let r = last.unwrap();
    let chosen = &r.all[r.chosen].1;
    let refined = RefinedReport::new(&problem, &problem.refine, &r);
    let medians = [median(&job), median(&alone), median(&check)];
    let report = Report {
        job_over_fe_check: medians[0] / medians[2],
        job_over_study: medians[0] / medians[1],
        fe_checks: chosen.measurements,
        converged: chosen.status == RefineStatus::Converged,
        refine_job_seconds: job,
        study_seconds: alone,
        fe_check_seconds: check,
        medians,
        refined,
    };
    let mut text = format!(
        "wei2017, run --refine fe (study + refinement), medians of {REPEATS}, alternating\n\
         whole job        {:8.3} s   ({} FE checks, {})\n\
         study alone      {:8.3} s\n\
         one FE check     {:8.3} s\n\
         job / FE check   {:8.1}\n\
         job / study      {:8.0}\n\n",
        medians[0],
        report.fe_checks,
        if report.converged {
            "converged"
        } else {
            "NOT converged"
        },
        medians[1],
        medians[2],
        report.job_over_fe_check,
        report.job_over_study,
    );
    text += &RefineSummary(&report.refined).to_string();
    std::fs::create_dir_all("results/bench").unwrap();
    write_json(Path::new("results/bench/refine.json"), &report).unwrap();
    flexopt::report::write_atomic(Path::new("results/bench/refine.txt"), text.as_bytes()).unwrap();
    print!("{text}");
}
