//! The low-discrepancy-grid claims of the plus-shaped / R2 blog post, as bounds: stochastic-
//! transparency coverage at 10–40 % and the spread of values in plus-shaped and 3×3
//! neighbourhoods (standard deviation of the gaps between the sorted values on the circle).

use noisebake::ldg;

const N: i32 = 64;

fn blue(x: i32, y: i32) -> f32 {
    use std::sync::OnceLock;
    static MASK: OnceLock<Vec<u32>> = OnceLock::new();
    let r = MASK.get_or_init(|| build_assets::generate::blue2d_ranks(64, 64, 1.9, 0.1, 1));
    (r[(y.rem_euclid(N) * N + x.rem_euclid(N)) as usize] as f32 + 0.5) / 4096.0
}

fn white(x: i32, y: i32) -> f32 {
    let h = build_assets::rng::mix64(((x as u64) << 32) ^ y as u32 as u64);
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

#[test]
fn coverage_and_neighbourhood_spread_match_the_blog() {
    let plus_nb = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)];
    let box_nb: Vec<(i32, i32)> = (-1..=1)
        .flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
        .collect();
    let mut table = Vec::new();
    println!(
        "{:8} {:>7} {:>7} {:>7} {:>7} {:>9} {:>9}",
        "grid", "10%", "20%", "30%", "40%", "plus-std", "3x3-std"
    );
    for (name, g) in GRIDS {
        let cov: Vec<f32> = [0.1, 0.2, 0.3, 0.4]
            .iter()
            .map(|&p| coverage(g, p) - p)
            .collect();
        let (sp, sb) = (spread(g, &plus_nb), spread(g, &box_nb));
        println!(
            "{name:8} {:>7.4} {:>7.4} {:>7.4} {:>7.4} {sp:>9.4} {sb:>9.4}",
            cov[0], cov[1], cov[2], cov[3]
        );
        table.push((name, cov, sp, sb));
    }
    let get = |n: &str| table.iter().find(|r| r.0 == n).unwrap().clone();
    // Coverage: every grid but plus (and white) is within 1 % of the target at every level;
    // plus is exact at 20 % and 40 % and off by 10 % at 10 % and 30 % (its values are fifths).
    for n in ["blue", "bayer8", "ign", "r2"] {
        assert!(
            get(n).1.iter().all(|e| e.abs() < 0.01),
            "{n}: {:?}",
            get(n).1
        );
    }
    let plus = get("plus");
    // (64² texels is not a multiple of 5: "exact" is within 1e-3.)
    assert!(
        plus.1[1].abs() < 1e-3
            && plus.1[3].abs() < 1e-3
            && (plus.1[0].abs() - 0.1).abs() < 1e-3
            && (plus.1[2].abs() - 0.1).abs() < 1e-3
    );
    // Plus-shaped neighbourhoods: plus is perfect, R2 beats IGN, white is worst.
    assert!(plus.2 < 1e-6);
    assert!(
        get("r2").2 < get("ign").2
            && get("ign").2 < get("white").2
            && get("blue").2 < get("white").2
    );
    // 3×3 neighbourhoods: IGN (built for them) beats R2; plus, with only five values, is poor.
    assert!(get("ign").3 < get("r2").3 && get("r2").3 < plus.3);
}
