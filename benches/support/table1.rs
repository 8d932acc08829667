//! wei2017's published design, which the benchmarks evaluate at.

/// Table 1's design of wei2017 (paper 004): `l2, delta2, t2, l3, delta3, l4, delta4, t4` (SI).
pub fn table1_design() -> [f64; 8] {
    let deg = std::f64::consts::PI / 180.0;
    [
        1.96e-3,
        4.07 * deg,
        0.4e-3,
        8.1e-3,
        4.01 * deg,
        1.96e-3,
        4.07 * deg,
        0.4e-3,
    ]
}
