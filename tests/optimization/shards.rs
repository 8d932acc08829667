//! A study in shards: start ranges solved apart and merged are the whole study, and shards
//! that do not make one study are refused with what is wrong.

use std::path::Path;

use flexopt::problem::Problem;
use flexopt::study::{self, Study, StudyOptions};

fn wei2017() -> Problem {
    Problem::load(Path::new("problems/wei2017.toml")).unwrap()
}

fn zone_counts(s: &Study) -> Vec<(usize, usize)> {
    s.clustering
        .zones
        .iter()
        .map(|z| (z.rank, z.count))
        .collect()
}

#[test]
fn shards_merged_in_any_order_are_the_whole_study() {
    let p = wei2017();
    let options = StudyOptions::from_problem(&p);
    let whole = study::run(&p, &options);
    let n = options.starts;
    let cut = [0, 7, n / 2, n - 1, n];
    let mut shards: Vec<Study> = cut
        .windows(2)
        .map(|w| study::run_range(&p, &options, w[0]..w[1]).unwrap())
        .collect();
    assert_eq!(shards[0].runs.len(), 7);
    assert_eq!(shards[0].range, 0..7);
    assert_eq!(shards[3].runs[0].start, n - 1);
    shards.reverse();
    let merged = study::merge(&p, shards).unwrap();
    assert_eq!(merged.range, 0..n);
    assert_eq!(merged.best, whole.best);
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(&merged.runs[merged.best].x_end),
        bits(&whole.runs[whole.best].x_end)
    );
    assert_eq!(
        bits(merged.reported_design()),
        bits(whole.reported_design())
    );
    assert_eq!(
        merged.reported_objective().to_bits(),
        whole.reported_objective().to_bits()
    );
    assert_eq!(zone_counts(&merged), zone_counts(&whole));
    assert_eq!(
        merged.clustering.optima.len(),
        whole.clustering.optima.len()
    );
    assert_eq!(merged.feasible_runs, whole.feasible_runs);
    assert_eq!(merged.ends, whole.ends);
    for (a, b) in merged.runs.iter().zip(&whole.runs) {
        assert_eq!(
            (a.start, a.optimum, a.zone),
            (b.start, b.optimum, b.zone),
            "start {}",
            b.start
        );
        assert_eq!(bits(&a.x_start), bits(&b.x_start), "start {}", b.start);
        assert_eq!(bits(&a.x_end), bits(&b.x_end), "start {}", b.start);
    }
    assert!(!merged.interrupted);
}

#[test]
fn shards_that_do_not_make_one_study_are_refused() {
    let p = wei2017();
    let options = StudyOptions {
        starts: 6,
        ..StudyOptions::from_problem(&p)
    };
    let shard = |r: std::ops::Range<usize>| study::run_range(&p, &options, r).unwrap();
    let message = |shards: Vec<Study>| study::merge(&p, shards).unwrap_err().to_string();
    assert_eq!(
        study::run_range(&p, &options, 3..3)
            .unwrap_err()
            .to_string(),
        "the start range 3..3 is empty"
    );
    assert_eq!(
        study::run_range(&p, &options, 4..7)
            .unwrap_err()
            .to_string(),
        "the start range 4..7 is not within the study's 6 starts"
    );
    assert_eq!(
        message(vec![shard(0..2), shard(3..6)]),
        "the shards' start ranges leave a gap at start 2"
    );
    assert_eq!(
        message(vec![shard(0..3), shard(2..6)]),
        "the shards' start ranges overlap at start 2"
    );
    assert_eq!(
        message(vec![shard(0..3)]),
        "the shards' start ranges end at 3, not at the study's 6 starts"
    );
    assert_eq!(message(Vec::new()), "no shards to merge");
    let reseeded = StudyOptions {
        seed: options.seed + 1,
        ..options.clone()
    };
    let other = study::run_range(&p, &reseeded, 3..6).unwrap();
    assert_eq!(
        message(vec![shard(0..3), other]),
        "the shards are of different studies: 6 starts, seed 2017, solver sqp against 6 \
         starts, seed 2018, solver sqp"
    );
}
