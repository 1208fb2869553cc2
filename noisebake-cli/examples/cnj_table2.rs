//! Reproduces CNJ Table 2's quality columns for the implicit methods on this implementation:
//! 1000-point sets, averaged over 20 seeds.
//!
//! `cargo run --release -p noisebake-cli --example cnj_table2`

use noisebake_cli::analysis::points::{analyze, mean};
use noisebake_cli::points::{Method, generate};
use std::time::Instant;

fn main() {
    println!(
        "{:<16} {:>6} {:>8} {:>10} {:>9}",
        "method", "ν_eff", "ā", "q", "time"
    );
    for (name, m) in [
        ("cnj", Method::Cnj),
        ("cnj-iterative", Method::CnjIterative),
        ("jitter", Method::Jitter),
        ("poisson-disk", Method::PoissonDisk),
        ("lattice", Method::Lattice),
        ("white", Method::White),
    ] {
        let start = Instant::now();
        let sets: Vec<_> = (0..20).map(|s| generate(m, 1000, s)).collect();
        let per_set = start.elapsed().as_secs_f64() / 20.0;
        let stats: Vec<_> = sets.iter().map(|p| analyze(p)).collect();
        let (nu, a, q) = mean(&stats);
        println!(
            "{name:<16} {nu:>6.3} {a:>8.2} {q:>10.5} {:>7.2}ms",
            per_set * 1e3
        );
    }
}
