use flexopt::optim::multistart::{start_points, Sampling};
use flexopt::optim::sqp::{solve, SqpSettings};
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem;
fn main() {
    let p = Problem::load(std::path::Path::new("problems/wei2017.toml")).unwrap();
    let nlp = DesignNlp::new(&p);
    let i: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let starts = start_points(&[0.0; 8], &[1.0; 8], 300, 2017, Sampling::Uniform);
    let s = solve(
        &nlp,
        &starts[i],
        &SqpSettings {
            tolerance: 1e-10,
            max_iterations: 500,
        },
    );
    println!(
        "{:?} it {} f {} kkt {:?}",
        s.status, s.iterations, s.objective, s.kkt_residual
    );
}
