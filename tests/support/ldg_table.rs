//! The blog's low-discrepancy-grid statistics, shared by `tests/ldg.rs` (as bounds) and
//! `examples/ldg_table.rs` (as a printed table): stochastic-transparency coverage at 10–40 %
//! and the spread of values in plus-shaped and 3×3 neighbourhoods (standard deviation of the
//! gaps between the sorted values on the circle).
#![allow(dead_code)]

use noisebake::ldg;

const N: i32 = 64;

fn blue(x: i32, y: i32) -> f32 {
    use std::sync::OnceLock;
    static MASK: OnceLock<Vec<u32>> = OnceLock::new();
    let r = MASK.get_or_init(|| build_assets::generate::blue2d_ranks(64, 64, 1.9, 0.1, 1));
    (r[(y.rem_euclid(N) * N + x.rem_euclid(N)) as usize] as f32 + 0.5) / 4096.0
}

fn white(x: i32, y: i32) -> f32 {
    let h = build_assets::generate::rng::mix64(((x as u64) << 32) ^ y as u32 as u64);
    (h >> 40) as f32 / (1u64 << 24) as f32
}

type Grid = (&'static str, fn(i32, i32) -> f32);
const GRIDS: [Grid; 6] = [
    ("white", white),
    ("blue", blue),
    ("bayer8", |x, y| ldg::bayer::<8>(x, y)),
    ("ign", ldg::ign),
    ("r2", ldg::r2),
    ("plus", ldg::plus),
];

fn coverage(g: fn(i32, i32) -> f32, p: f32) -> f32 {
    let on = (0..N)
        .flat_map(|y| (0..N).map(move |x| (x, y)))
        .filter(|&(x, y)| g(x, y) < p)
        .count();
    on as f32 / (N * N) as f32
}

fn spread(g: fn(i32, i32) -> f32, offsets: &[(i32, i32)]) -> f64 {
    let mut total = 0.0;
    for y in 0..N {
        for x in 0..N {
            let mut v: Vec<f64> = offsets
                .iter()
                .map(|&(dx, dy)| g(x + dx, y + dy) as f64)
                .collect();
            v.sort_by(f64::total_cmp);
            let k = v.len();
            let gaps: Vec<f64> = (0..k)
                .map(|i| {
                    if i + 1 < k {
                        v[i + 1] - v[i]
                    } else {
                        v[0] + 1.0 - v[k - 1]
                    }
                })
                .collect();
            let mean = 1.0 / k as f64;
            total += (gaps.iter().map(|g| (g - mean) * (g - mean)).sum::<f64>() / k as f64).sqrt();
        }
    }
    total / (N * N) as f64
}

/// One row: grid name, coverage error at 10/20/30/40 %, plus-shaped spread, 3×3 spread.
pub type Row = (&'static str, Vec<f32>, f64, f64);

/// The table over every grid.
pub fn table() -> Vec<Row> {
    let plus_nb = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)];
    let box_nb: Vec<(i32, i32)> = (-1..=1)
        .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
        .collect();
    GRIDS
        .iter()
        .map(|&(name, g)| {
            let cov: Vec<f32> = [0.1, 0.2, 0.3, 0.4]
                .iter()
                .map(|&p| coverage(g, p) - p)
                .collect();
            (name, cov, spread(g, &plus_nb), spread(g, &box_nb))
        })
        .collect()
}

/// Prints the table.
pub fn print(table: &[Row]) {
    println!(
        "{:8} {:>7} {:>7} {:>7} {:>7} {:>9} {:>9}",
        "grid", "10%", "20%", "30%", "40%", "plus-std", "3x3-std"
    );
    for (name, cov, sp, sb) in table {
        println!(
            "{name:8} {:>7.4} {:>7.4} {:>7.4} {:>7.4} {sp:>9.4} {sb:>9.4}",
            cov[0], cov[1], cov[2], cov[3]
        );
    }
}
