//! 2D point sets in the unit torus `[0, 1)²` for the point-set analysis (CNJ §2.4–2.6): curl-noise
//! jittering (direct and iterative), random jitter, and Bridson's Poisson-disk sampling.

use build_assets::generate::rng::{SplitMix64, derive_seed};
use noise_runtime::cnj::{Cnj2, velocity2};

/// A point-set generator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Curl-noise jittering of the triangular lattice (one RK4 step, the paper's parameters).
    Cnj,
    /// Iterative CNJ: 64 RK4 steps, the time halved each step, a new noise each step.
    CnjIterative,
    /// The triangular lattice without jitter.
    Lattice,
    /// Classic jittered sampling: one uniform point per cell of a square grid.
    Jitter,
    /// Bridson's Poisson-disk sampling (toroidal), k = 30.
    PoissonDisk,
    /// Uniform random points.
    White,
}

/// Every `--method` value.
pub const METHODS: &[&str] = &[
    "cnj",
    "cnj-iterative",
    "lattice",
    "jitter",
    "poisson-disk",
    "white",
];

impl Method {
    /// Parses a `--method` value.
    pub fn parse(s: &str) -> Option<Method> {
        Some(match s {
            "cnj" => Method::Cnj,
            "cnj-iterative" => Method::CnjIterative,
            "lattice" => Method::Lattice,
            "jitter" => Method::Jitter,
            "poisson-disk" => Method::PoissonDisk,
            "white" => Method::White,
            _ => return None,
        })
    }
}

/// Spacing of a triangular lattice with `n` points per unit area.
fn tri_spacing(n: usize) -> f64 {
    (2.0 / (3f64.sqrt() * n as f64)).sqrt()
}

/// Points of a jittered triangular lattice that fall in `[0, 1)²` (about `n` of them): the
/// lattice (spacing for density `n`, random offset) is displaced by `jitter` in lattice units.
/// `progress(rows done, rows)` is called after each row of sites.
fn lattice_points(
    n: usize,
    seed: u64,
    jitter: impl Fn([i32; 2]) -> [f64; 2],
    progress: &mut dyn FnMut(u64, u64),
) -> Vec<[f64; 2]> {
    let d = tri_spacing(n);
    let mut rng = SplitMix64::new(derive_seed(seed, 0x0ff5e7));
    let off = [rng.unit_f64(), rng.unit_f64()];
    // Displacements stay below 1.2 spacings, so two sites of margin on each side suffice.
    let rows = (1.0 / (d * 0.866_025_403_784_438_6)).ceil() as i32 + 2;
    let cols = (1.0 / d).ceil() as i32 + 2;
    let mut out = Vec::with_capacity(n + n / 8);
    let total = (rows + 2) as u64;
    for j in -2..rows {
        progress((j + 2) as u64, total);
        for i in -2..cols {
            let base = Cnj2::site_position([i, j]);
            let jt = jitter([i, j]);
            let x = (base[0] + off[0] + jt[0]) * d;
            let y = (base[1] + off[1] + jt[1]) * d;
            if (0.0..1.0).contains(&x) && (0.0..1.0).contains(&y) {
                out.push([x, y]);
            }
        }
    }
    out
}

/// Generates about `n` points with `method` and `seed`.
pub fn generate(method: Method, n: usize, seed: u64) -> Vec<[f64; 2]> {
    generate_with_progress(method, n, seed, &mut |_, _| {})
}

/// About how many seconds `n` points of `method` take on 2 cores, generation and the CSV: each
/// method's time per million points, timed on such a machine, scaled linearly (`points`
/// announces a run of more than 2 s with it, since a bar shows only on a terminal).
pub fn estimate_seconds(method: Method, n: usize) -> f64 {
    let per_million = match method {
        Method::CnjIterative => 13.7,
        Method::PoissonDisk => 8.1,
        Method::Cnj => 0.7,
        _ => 0.4,
    };
    per_million * n as f64 / 1e6
}

/// [`generate`], calling `progress(done, total)` as it goes (rows of lattice sites for the
/// lattice methods; once at the end for the others) so long runs can show a bar.
pub fn generate_with_progress(
    method: Method,
    n: usize,
    seed: u64,
    progress: &mut dyn FnMut(u64, u64),
) -> Vec<[f64; 2]> {
    let n = n.max(1);
    let pts = match method {
        Method::Lattice => lattice_points(n, seed, |_| [0.0, 0.0], progress),
        Method::Cnj => {
            let c = Cnj2::default().with_seed(seed as u32);
            lattice_points(
                n,
                seed,
                |s| {
                    let d = c.displacement(s);
                    [d[0] as f64, d[1] as f64]
                },
                progress,
            )
        }
        Method::CnjIterative => {
            let (t0, s) = (Cnj2::PAPER.time() as f64, Cnj2::PAPER.scale() as f64);
            lattice_points(
                n,
                seed,
                |site| {
                    let p0 = Cnj2::site_position(site);
                    let mut p = p0;
                    let mut t = t0;
                    for it in 0..64u32 {
                        let sd = (seed as u32).wrapping_add(it.wrapping_mul(0x9e37_79b9));
                        let v = |q: [f64; 2]| {
                            let v = velocity2(q, s, sd);
                            [v[0] as f64, v[1] as f64]
                        };
                        let k1 = v(p);
                        let k2 = v([p[0] + 0.5 * t * k1[0], p[1] + 0.5 * t * k1[1]]);
                        let k3 = v([p[0] + 0.5 * t * k2[0], p[1] + 0.5 * t * k2[1]]);
                        let k4 = v([p[0] + t * k3[0], p[1] + t * k3[1]]);
                        for a in 0..2 {
                            p[a] += t / 6.0 * (k1[a] + 2.0 * k2[a] + 2.0 * k3[a] + k4[a]);
                        }
                        t *= 0.5;
                    }
                    [p[0] - p0[0], p[1] - p0[1]]
                },
                progress,
            )
        }
        Method::Jitter => {
            let side = (n as f64).sqrt().round().max(1.0) as usize;
            let mut rng = SplitMix64::new(seed);
            (0..side * side)
                .map(|c| {
                    [
                        ((c % side) as f64 + rng.unit_f64()) / side as f64,
                        ((c / side) as f64 + rng.unit_f64()) / side as f64,
                    ]
                })
                .collect()
        }
        Method::White => {
            let mut rng = SplitMix64::new(seed);
            (0..n).map(|_| [rng.unit_f64(), rng.unit_f64()]).collect()
        }
        Method::PoissonDisk => bridson(n, seed),
    };
    progress(1, 1);
    pts
}

/// Bridson (2007) Poisson-disk sampling on the unit torus with `k = 30` candidates per active
/// point; the radius is chosen so that a maximal set holds about `n` points.
fn bridson(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let r = (0.7 / n as f64).sqrt();
    let cell = r / 2f64.sqrt();
    let g = (1.0 / cell).ceil().max(1.0) as usize;
    let cell = 1.0 / g as f64;
    let mut grid: Vec<Option<usize>> = vec![None; g * g];
    let mut rng = SplitMix64::new(seed);
    let mut pts: Vec<[f64; 2]> = Vec::new();
    let mut active = Vec::new();
    let idx = |p: [f64; 2]| ((p[1] / cell) as usize % g) * g + (p[0] / cell) as usize % g;
    let first = [rng.unit_f64(), rng.unit_f64()];
    grid[idx(first)] = Some(0);
    pts.push(first);
    active.push(0);
    let tor = |a: f64| {
        let a = a.abs();
        a.min(1.0 - a)
    };
    while !active.is_empty() {
        let ai = rng.below(active.len() as u64) as usize;
        let p = pts[active[ai]];
        let mut found = false;
        for _ in 0..30 {
            let rad = r * (1.0 + rng.unit_f64());
            let ang = rng.unit_f64() * std::f64::consts::TAU;
            let q = [
                (p[0] + rad * ang.cos()).rem_euclid(1.0),
                (p[1] + rad * ang.sin()).rem_euclid(1.0),
            ];
            let (cx, cy) = ((q[0] / cell) as i64, (q[1] / cell) as i64);
            let mut ok = true;
            'scan: for dy in -2..=2 {
                for dx in -2..=2 {
                    let c = ((cy + dy).rem_euclid(g as i64) * g as i64
                        + (cx + dx).rem_euclid(g as i64)) as usize;
                    if let Some(o) = grid[c] {
                        let (ex, ey) = (tor(pts[o][0] - q[0]), tor(pts[o][1] - q[1]));
                        if ex * ex + ey * ey < r * r {
                            ok = false;
                            break 'scan;
                        }
                    }
                }
            }
            if ok {
                grid[idx(q)] = Some(pts.len());
                active.push(pts.len());
                pts.push(q);
                found = true;
                break;
            }
        }
        if !found {
            active.swap_remove(ai);
        }
    }
    pts
}
