//! `noisebake search-sampler`: the offline search behind the constants of the runtime's
//! `sampler::motion_pairs` (`MOTION_PAIRS`), a free sampler built for a moving camera.
//!
//! For each number of samples per frame `N` it chooses, per pair of dimensions, a rank-1
//! lattice `{i·(1, z)/N}` and a shift linear in the pixel and the frame, by the expected error
//! of [`model`] under many conditions at once: two integrand families (half-planes of the
//! square, half-spaces of cosine-weighted directions), two denoisers (a Gaussian σ 1, an
//! à-trous of three passes), one frame alone, a still camera's EMA and the EMA under pans of
//! up to [`MAX_SPEED`] pixels a frame in every direction ([`cameras`]). A candidate's score is
//! a soft maximum over the conditions of its error's ratio to that of `r2_pairs` (modelled
//! with IGN's and R2's slopes as its shifts), so the search favours the candidate whose worst
//! condition is best, not one that wins on average.
//!
//! The two pairs are searched alike from different seeds, so they differ. Within a frame the
//! runtime pairs sample `i` of the first pair with sample `i + h` of the second, `h` a hash
//! of the pixel and frame: both are lattices moved by a shift, so sample `i` of one would
//! otherwise be sample `i` of the other plus a constant, a correlation an integrand of all
//! four dimensions (a bounce) accumulates as a bias. The hash moves the second pair by a
//! lattice point, which leaves its set, and so its error, unchanged.
//!
//! The search is random sampling of the shifts for every generator `z`, then a local
//! refinement of the best; it is deterministic for a seed on one machine (the model is `f64`
//! arithmetic with the platform's `sin` and `cos`).

pub mod model;
pub mod spectrum;

use build_assets::generate::rng::{SplitMix64, derive_seed};
use model::{Camera, Condition, Denoiser, Shift, Terms, errors};
use rayon::prelude::*;
use spectrum::{Family, Spectrum};

/// The fastest pan searched over, pixels a frame.
pub const MAX_SPEED: f64 = 4.0;
/// Pans searched over (besides a still camera and one frame).
pub const PANS: usize = 64;
/// Integrands per family whose mean spectrum the model uses.
pub const INTEGRANDS: usize = 1024;
/// The reach of the frequencies the model sums, `|k_x|, |k_y| ≤ REACH`.
pub const REACH: i64 = 48;

/// The cameras every candidate is scored under: one frame, a still camera, and [`PANS`]
/// pans spread over the disk of radius [`MAX_SPEED`] (area-uniform by the R2 sequence: as
/// many slow pans as fast ones per unit of area, in every direction).
pub fn cameras() -> Vec<Camera> {
    let mut out = vec![Camera::OneFrame, Camera::Pan([0.0, 0.0])];
    for j in 0..PANS as u32 {
        let (u, v) = noise_runtime::sequence::r2_point(j + 1);
        let r = MAX_SPEED * (f64::from(u) / 4_294_967_296.0).sqrt().max(0.05);
        let a = std::f64::consts::TAU * f64::from(v) / 4_294_967_296.0;
        out.push(Camera::Pan([r * a.cos(), r * a.sin()]));
    }
    out
}

/// The conditions a candidate is scored under, grouped by camera: one frame, a still camera,
/// the mean over moving cameras and the tallest resonance ([`Camera`]).
pub fn conditions() -> Vec<Condition> {
    conditions_for(&[
        Camera::OneFrame,
        Camera::Pan([0.0, 0.0]),
        Camera::MovingMean,
        Camera::Resonance,
    ])
}

/// Every family and denoiser under each of `cameras`, grouped by camera.
pub fn conditions_for(cameras: &[Camera]) -> Vec<Condition> {
    let mut out = Vec::new();
    for &camera in cameras {
        for family in Family::ALL {
            for denoiser in Denoiser::ALL {
                out.push(Condition {
                    family,
                    denoiser,
                    camera,
                });
            }
        }
    }
    out
}

/// What the search needs: the spectra, the conditions.
pub struct Setup {
    /// Per family, the integrands' spectrum.
    pub spectra: [Spectrum; 2],
    /// The conditions.
    pub conditions: Vec<Condition>,
}

impl Setup {
    /// The spectra of [`INTEGRANDS`] integrands per family (a few seconds) and
    /// [`conditions`].
    pub fn new() -> Setup {
        Setup {
            spectra: Family::ALL.map(|f| Spectrum::of(f, INTEGRANDS, 0x005e_ed0f_5a3d)),
            conditions: conditions(),
        }
    }
}

impl Default for Setup {
    fn default() -> Setup {
        Setup::new()
    }
}

/// `1/ρ` and `1/ρ²`, ρ the plastic number: R2's steps.
const R2: [f64; 2] = [0.754_877_666_246_692_7, 0.569_840_290_998_053_3];
/// Interleaved gradient noise's slopes mod 1: `52.9829189 · (0.06711056, 0.00583715)`.
const IGN_SLOPE: [f64; 2] = [3.555_741_9, 0.309_267_5];

/// `r2_pairs`'s first pair at `n` samples per frame, as the model sees it: the frame is `n`
/// consecutive points of R2 moved by IGN (first dimension) and the R2 grid (second), each
/// taken at its slope, and by `n` steps of R2 per frame.
pub fn r2_pairs_model(n: u32, setup: &Setup) -> Vec<f64> {
    r2_pairs_model_to(n, REACH, setup)
}

/// [`r2_pairs_model`] under `conditions`.
pub fn r2_pairs_errors(n: u32, conditions: &[Condition], setup: &Setup) -> Vec<f64> {
    r2_pairs_model_under(n, REACH, conditions, setup)
}

/// [`r2_pairs_model`] summed to `reach`.
fn r2_pairs_model_to(n: u32, reach: i64, setup: &Setup) -> Vec<f64> {
    r2_pairs_model_under(n, reach, &setup.conditions, setup)
}

fn r2_pairs_model_under(n: u32, reach: i64, conditions: &[Condition], setup: &Setup) -> Vec<f64> {
    let q: Vec<[f64; 2]> = (0..n)
        .map(|i| [(i as f64 * R2[0]).fract(), (i as f64 * R2[1]).fract()])
        .collect();
    let terms = Terms::pattern(&q, reach, &setup.spectra);
    let shift = Shift {
        a: [IGN_SLOPE[0].fract(), R2[0]],
        b: [IGN_SLOPE[1], R2[1]],
        g: [(n as f64 * R2[0]).fract(), (n as f64 * R2[1]).fract()],
    };
    errors(&terms, &shift, conditions)
}

/// The score to minimise: a soft maximum (β = 8) of the log ratios of the candidate's errors
/// `errs` to `base` (`r2_pairs`'s) under [`conditions`]: one frame and the tallest resonance
/// at half weight, a still camera and the mean over moving cameras at full weight.
pub fn score(errs: &[f64], base: &[f64], conditions: &[Condition]) -> f64 {
    const BETA: f64 = 8.0;
    let logs: Vec<f64> = conditions
        .iter()
        .zip(errs.iter().zip(base))
        .map(|(c, (e, b))| {
            let weight = match c.camera {
                Camera::OneFrame | Camera::Resonance => 0.5,
                _ => 1.0,
            };
            weight * (e / b).ln() * BETA
        })
        .collect();
    let top = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mean = logs.iter().map(|l| (l - top).exp()).sum::<f64>() / logs.len() as f64;
    (top + mean.ln()) / BETA
}

/// One pair's choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair {
    /// The lattice generator.
    pub z: u32,
    /// The shift, in lattice coordinates.
    pub shift: Shift,
    /// Its score ([`score`]).
    pub score: f64,
}

/// How much searching.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Random shifts tried per generator.
    pub samples: usize,
    /// Rounds of local refinement of the best.
    pub rounds: usize,
    /// Proposals per round.
    pub proposals: usize,
}

impl Default for Budget {
    fn default() -> Budget {
        Budget {
            samples: 65536,
            rounds: 24,
            proposals: 48,
        }
    }
}

/// The generators worth trying for `n` points: those coprime with `n` up to `n/2` (`z` and
/// `n − z` are mirror images), and 0 for one point.
pub fn generators(n: u32) -> Vec<u32> {
    fn gcd(a: u32, b: u32) -> u32 {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    if n == 1 {
        return vec![0];
    }
    (1..=n / 2).filter(|&z| gcd(z, n) == 1).collect()
}

/// A uniform shift from `rng`.
fn random_shift(rng: &mut SplitMix64) -> Shift {
    let mut u = || rng.unit_f64();
    Shift {
        a: [u(), u()],
        b: [u(), u()],
        g: [u(), u()],
    }
}

/// `s` moved by a normal step of `scale` in every coordinate (Box–Muller from `rng`).
fn perturb(s: &Shift, scale: f64, rng: &mut SplitMix64) -> Shift {
    let mut normal = || {
        let (u, v) = (rng.unit_f64().max(1e-300), rng.unit_f64());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    let mut step = |x: f64| (x + scale * normal()).rem_euclid(1.0);
    Shift {
        a: s.a.map(&mut step),
        b: s.b.map(&mut step),
        g: s.g.map(&mut step),
    }
}

/// The reach of the frequencies the first, coarse screening of random shifts sums.
pub const SCREEN_REACH: i64 = 16;
/// Random shifts per generator kept from the screening for the full model.
pub const KEEP: usize = 64;
/// Of those, the best refined locally.
pub const REFINED: usize = 4;

/// The best pair for `n` points a frame: for every generator, [`Budget::samples`] random
/// shifts screened by the model summed to [`SCREEN_REACH`], the best [`KEEP`] scored by the
/// full model, and the best [`REFINED`] of those refined for [`Budget::rounds`].
pub fn search_pair(n: u32, setup: &Setup, base: &[[f64; 2]], budget: Budget, seed: u64) -> Pair {
    let (coarse_base, fine_base): (Vec<f64>, Vec<f64>) = base.iter().map(|b| (b[0], b[1])).unzip();
    let mut best: Option<Pair> = None;
    for z in generators(n) {
        let coarse = Terms::lattice(n, z, SCREEN_REACH, &setup.spectra);
        let fine = Terms::lattice(n, z, REACH, &setup.spectra);
        let eval = |t: &Terms, b: &[f64], s: &Shift| {
            score(&errors(t, s, &setup.conditions), b, &setup.conditions)
        };
        let stream = derive_seed(seed, u64::from(z));
        let by_score = |a: &(f64, usize, Shift), b: &(f64, usize, Shift)| {
            a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
        };
        let mut tried: Vec<(f64, usize, Shift)> = (0..budget.samples)
            .into_par_iter()
            .map(|i| {
                let mut rng = SplitMix64::new(derive_seed(stream, i as u64));
                let s = random_shift(&mut rng);
                (eval(&coarse, &coarse_base, &s), i, s)
            })
            .collect();
        tried.sort_by(by_score);
        tried.truncate(KEEP);
        let mut kept: Vec<(f64, usize, Shift)> = tried
            .into_par_iter()
            .map(|(_, i, s)| (eval(&fine, &fine_base, &s), i, s))
            .collect();
        kept.sort_by(by_score);
        for &(start, i, s) in kept.iter().take(REFINED) {
            let (mut top, mut shift) = (start, s);
            let mut scale = 0.01;
            for round in 0..budget.rounds {
                let proposals: Vec<(f64, usize, Shift)> = (0..budget.proposals)
                    .into_par_iter()
                    .map(|k| {
                        let mut rng = SplitMix64::new(derive_seed(
                            stream ^ (0xfeed + i as u64),
                            (round * budget.proposals + k) as u64,
                        ));
                        let s = perturb(&shift, scale, &mut rng);
                        (eval(&fine, &fine_base, &s), k, s)
                    })
                    .collect();
                let (t, _, s) = proposals
                    .into_iter()
                    .min_by(by_score)
                    .expect("at least one proposal");
                if t < top {
                    (top, shift) = (t, s);
                } else {
                    scale *= 0.8;
                }
            }
            if best.is_none_or(|b| top < b.score) {
                best = Some(Pair {
                    z,
                    shift,
                    score: top,
                });
            }
        }
    }
    best.expect("at least one generator")
}

/// Both pairs for `n` points a frame, each searched on its own (from its own seed).
pub fn search(n: u32, setup: &Setup, budget: Budget, seed: u64) -> [Pair; 2] {
    let base: Vec<[f64; 2]> = r2_pairs_model_to(n, SCREEN_REACH, setup)
        .into_iter()
        .zip(r2_pairs_model(n, setup))
        .map(|(c, f)| [c, f])
        .collect();
    [0, 1].map(|k| {
        search_pair(
            n,
            setup,
            &base,
            budget,
            derive_seed(seed, 2 * u64::from(n) + k),
        )
    })
}

/// A fraction in `[0, 1)` as 32 bits, rounded.
pub fn bits(v: f64) -> u32 {
    ((v.rem_euclid(1.0) * 4_294_967_296.0).round() as u64 & 0xffff_ffff) as u32
}

/// A pair's constants as the runtime's `PairDrift` literal.
pub fn literal(p: &Pair) -> String {
    let s = &p.shift;
    format!(
        "PairDrift {{ z: {}, x: [0x{:08x}, 0x{:08x}], y: [0x{:08x}, 0x{:08x}], frame: [0x{:08x}, 0x{:08x}] }}",
        p.z,
        bits(s.a[0]),
        bits(s.a[1]),
        bits(s.b[0]),
        bits(s.b[1]),
        bits(s.g[0]),
        bits(s.g[1])
    )
}

/// The runtime's `motion_table.rs` for `rows` (spp 1, 2, … in order).
pub fn table_source(rows: &[[Pair; 2]]) -> String {
    let mut s = String::from(
        "//! The constants of `motion_pairs`, written by `noisebake search-sampler --all --out \
         noise-runtime/src/sampler/motion_table.rs`: do not edit, search again.\n\nuse \
         super::motion::PairDrift;\n\n/// Per samples-per-frame `N` (index `N − 1`), the two \
         pairs' constants.\n#[rustfmt::skip]\npub(super) const TABLE: [[PairDrift; 2]; 16] = [\n",
    );
    for (i, pairs) in rows.iter().enumerate() {
        s += &format!(
            "    // {} sample(s) a frame\n    [\n        {},\n        {},\n    ],\n",
            i + 1,
            literal(&pairs[0]),
            literal(&pairs[1])
        );
    }
    s += "];\n";
    s
}

/// Seconds one spp's search takes on 2 threads at `budget`: `search-sampler --all` at the
/// default budget took 106 s for the 16 values on 2 cores (from 18 s at 1 spp, which has the
/// most frequencies, to 4 s at 16), scaled by the samples screened.
pub fn estimate_seconds(budget: Budget) -> f64 {
    106.0 / 16.0 * budget.samples as f64 / Budget::default().samples as f64
}

/// The model's RMSE ratios of `pair` to `r2_pairs` at `n` samples a frame, per family and
/// denoiser: one frame, a still camera, and the pans' worst and mean.
pub fn describe(n: u32, pair: &Pair, setup: &Setup) -> Vec<String> {
    let conditions = conditions_for(&cameras());
    let base = r2_pairs_errors(n, &conditions, setup);
    let terms = Terms::lattice(n, pair.z, REACH, &setup.spectra);
    let errs = errors(&terms, &pair.shift, &conditions);
    let mut out = vec![format!(
        "z {}, score {:.3}; RMSE / r2_pairs's (model): one frame, still, {PANS} pans worst and mean",
        pair.z, pair.score
    )];
    for family in Family::ALL {
        for denoiser in Denoiser::ALL {
            let ratios: Vec<(Camera, f64)> = conditions
                .iter()
                .zip(errs.iter().zip(&base))
                .filter(|(c, _)| c.family == family && c.denoiser == denoiser)
                .map(|(c, (e, b))| (c.camera, (e / b).sqrt()))
                .collect();
            let pans: Vec<f64> = ratios
                .iter()
                .filter(|(c, _)| matches!(c, Camera::Pan(v) if *v != [0.0, 0.0]))
                .map(|r| r.1)
                .collect();
            let of = |cam: Camera| ratios.iter().find(|r| r.0 == cam).map_or(f64::NAN, |r| r.1);
            out.push(format!(
                "{:<6} {:<9}  {:.3}  {:.3}  {:.3}  {:.3}",
                family.name(),
                denoiser.name(),
                of(Camera::OneFrame),
                of(Camera::Pan([0.0, 0.0])),
                pans.iter().copied().fold(0.0, f64::max),
                pans.iter().sum::<f64>() / pans.len() as f64
            ));
        }
    }
    out
}

/// The model's RMSE ratio of `pair` to `r2_pairs` at `n` samples a frame under `camera`,
/// per family and denoiser (`[family][denoiser]`, in their `ALL` orders).
pub fn ratios_at(n: u32, pair: &Pair, camera: Camera, setup: &Setup) -> [[f64; 2]; 2] {
    let conditions: Vec<Condition> = Family::ALL
        .iter()
        .flat_map(|&family| {
            Denoiser::ALL.map(|denoiser| Condition {
                family,
                denoiser,
                camera,
            })
        })
        .collect();
    let q: Vec<[f64; 2]> = (0..n)
        .map(|i| [(i as f64 * R2[0]).fract(), (i as f64 * R2[1]).fract()])
        .collect();
    let base_shift = Shift {
        a: [IGN_SLOPE[0].fract(), R2[0]],
        b: [IGN_SLOPE[1], R2[1]],
        g: [(n as f64 * R2[0]).fract(), (n as f64 * R2[1]).fract()],
    };
    let base = errors(
        &Terms::pattern(&q, REACH, &setup.spectra),
        &base_shift,
        &conditions,
    );
    let errs = errors(
        &Terms::lattice(n, pair.z, REACH, &setup.spectra),
        &pair.shift,
        &conditions,
    );
    let r: Vec<f64> = errs
        .iter()
        .zip(&base)
        .map(|(e, b)| (e / b).sqrt())
        .collect();
    [[r[0], r[1]], [r[2], r[3]]]
}

/// The WGSL table of `rows` (`NB_MOTION`, two `vec4<u32>` per spp and pair: `(z, x₀, x₁, y₀)`,
/// `(y₁, g₀, g₁, 0)`), between the markers the library's copy sits between.
pub fn table_wgsl(rows: &[[Pair; 2]]) -> String {
    let mut s = String::from(WGSL_BEGIN);
    s += &format!(
        "\nvar<private> NB_MOTION: array<vec4<u32>, {}> = array<vec4<u32>, {}>(\n",
        rows.len() * 4,
        rows.len() * 4
    );
    for (i, pairs) in rows.iter().enumerate() {
        for (k, p) in pairs.iter().enumerate() {
            let v = |x: f64| format!("0x{:08x}u", bits(x));
            let sh = &p.shift;
            s += &format!(
                "    vec4<u32>({}u, {}, {}, {}), vec4<u32>({}, {}, {}, 0u), // spp {}, pair {k}\n",
                p.z,
                v(sh.a[0]),
                v(sh.a[1]),
                v(sh.b[0]),
                v(sh.b[1]),
                v(sh.g[0]),
                v(sh.g[1]),
                i + 1
            );
        }
    }
    s += ");\n";
    s += WGSL_END;
    s
}

/// The line before the WGSL library's copy of the table.
pub const WGSL_BEGIN: &str = "// motion_pairs table (noisebake search-sampler --all --wgsl): begin";
/// The line after it.
pub const WGSL_END: &str = "// motion_pairs table: end";
