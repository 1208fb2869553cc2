//! Stochastic-noise report (Fajardo & Pharr, Table 1, measured on this CPU): ns per evaluation
//! of every deterministic and stochastic 3D noise, single thread, random-order points; the
//! stochastic speedup; and the error bought with it — RMSE of the stochastic estimate against
//! the deterministic value when averaging 1, 4, 16 and 64 independent ξ, with ξ from white noise
//! and from an STBN mask (one pixel per point, ξ along the mask's time axis), and the bias (mean
//! error over all points at 64 samples).
//!
//! With the `peers` feature, `noise-functions` and `fastnoise-lite` run in the same process on
//! the same points: 3D Perlin, fBm with 10 octaves, Worley F1, and their cellular F1 against
//! our smooth Voronoi (neither has smooth Voronoi; it is the goal's nearest stand-in).

use build_assets::generate::rng::SplitMix64;
use build_assets::spec::{Format, Histogram, Kind, TextureSpec, VacParams};
use noise_runtime::stochastic::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::Instant;

/// One row of the JSON report (`report --json`; the field names are a documented contract).
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// `perlin3`, `fbm3`, …
    pub noise: String,
    /// `deterministic`, `stochastic`, `stochastic-1term` (sparse convolution with the cell sum
    /// sampled too), `deterministic-batch` and `stochastic-batch` (the batch forms), or a peer
    /// crate's name.
    pub variant: String,
    /// Nanoseconds per evaluation, single thread, random-order points.
    pub ns_per_eval: f64,
    /// RMSE against the deterministic value averaging k = 1, 4, 16, 64 white-noise ξ
    /// (stochastic rows only).
    pub rmse: Option<Errors>,
    /// The same with ξ from an STBN mask.
    pub rmse_stbn: Option<Errors>,
    /// Mean error at 64 samples (stochastic rows only).
    pub bias: Option<f64>,
    /// Our deterministic time / this time: the median over rounds of alternating passes of the
    /// two, so both are measured on the same machine state. For stochastic rows the speedup
    /// bought with the error; for peer rows below 1 when ours is faster. For the batch rows
    /// the deterministic time is the single-point form's (`deterministic-batch`: what the
    /// batch buys) or the deterministic batch's (`stochastic-batch`: what the estimator buys
    /// on lanes).
    pub speedup: Option<f64>,
    /// The spread behind `speedup`: the 3rd and 7th of the rounds' ratios in order (the range
    /// of the middle five of nine), so a reader can tell a verdict from the machine's drift.
    pub speedup_spread: Option<[f64; 2]>,
}

impl Row {
    /// A row with a time only (a deterministic or peer row): no error columns.
    fn timed(noise: &str, variant: &str, ns_per_eval: f64, speedup: Option<f64>) -> Row {
        Row {
            noise: noise.into(),
            variant: variant.into(),
            ns_per_eval,
            rmse: None,
            rmse_stbn: None,
            bias: None,
            speedup,
            speedup_spread: None,
        }
    }

    /// A row timed against our deterministic form: the second function of `t`, its speedup
    /// and spread.
    fn paired(noise: &str, variant: &str, t: Paired) -> Row {
        Row {
            speedup_spread: Some(t.spread),
            ..Row::timed(noise, variant, t.b_ns, Some(t.ratio))
        }
    }

    /// This row with the error columns of an estimator.
    fn with_error(mut self, rmse: Errors, rmse_stbn: Errors, bias: f64) -> Row {
        (self.rmse, self.rmse_stbn, self.bias) = (Some(rmse), Some(rmse_stbn), Some(bias));
        self
    }
}

/// Evaluations timed per function.
const TIMED: usize = 1 << 16;
/// Points whose error is measured (a 64×64 image, one STBN pixel per point).
const SIDE: usize = 64;
/// Sample counts of the error columns.
pub const KS: [usize; 4] = [1, 4, 16, 64];

type Det = Box<dyn Fn([f32; 3]) -> f32>;
type Sto = Box<dyn Fn([f32; 3], f32) -> f32>;

/// A 2D noise seeing the report's 3D points through their `(x, y)`.
struct Xy<N>(N);

impl<N: Noise<[f32; 2]>> Noise<[f32; 3]> for Xy<N> {
    #[inline(always)]
    fn sample(&self, p: [f32; 3]) -> f32 {
        self.0.sample([p[0], p[1]])
    }
    #[inline(always)]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        self.0.estimate([p[0], p[1]], xi)
    }
}

/// A 4D noise seeing the report's 3D points as `(x, y, z, x + z)`.
struct Xyzw<N>(N);

impl<N: Noise<[f32; 4]>> Noise<[f32; 3]> for Xyzw<N> {
    #[inline(always)]
    fn sample(&self, p: [f32; 3]) -> f32 {
        self.0.sample([p[0], p[1], p[2], p[0] + p[2]])
    }
    #[inline(always)]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        self.0.estimate([p[0], p[1], p[2], p[0] + p[2]], xi)
    }
}

/// One row's functions from a noise through the [`Noise`] trait: its `sample`, and its
/// `estimate` when it has a stochastic form (`stochastic`). Each closure is monomorphised
/// over the noise, so a timed call is one indirect call into inlined code.
fn row<N: Noise<[f32; 3]> + 'static>(
    name: &'static str,
    noise: N,
    stochastic: bool,
) -> (&'static str, Det, Option<Sto>) {
    let noise = std::rc::Rc::new(noise);
    let det: Det = Box::new({
        let n = noise.clone();
        move |p| n.sample(p)
    });
    let sto: Option<Sto> =
        stochastic.then(|| -> Sto { Box::new(move |p, x| noise.estimate(p, x)) });
    (name, det, sto)
}

/// The report's noises with the paper's settings, written once: `$m!(name, noise, stochastic)`
/// for each, `stochastic` when the noise has an estimator to measure.
macro_rules! for_each_noise {
    ($m:ident) => {{
        let fbm = Fractal::new(10, 2.0, 0.5);
        $m!("perlin2", Xy(Perlin::new(1)), true);
        $m!("perlin3", Perlin::new(1), true);
        $m!("perlin4", Xyzw(Perlin::new(1)), true);
        $m!("simplex2", Xy(Simplex::new(1)), true);
        $m!("simplex3", Simplex::new(1), true);
        $m!("simplex4", Xyzw(Simplex::new(1)), true);
        $m!("fbm3", Fbm::new(fbm, 1), true);
        $m!("sparse_conv3", SparseConvolution::new(10, 1), true);
        $m!(
            "fbm_sparse_conv3",
            SparseConvolutionFbm::new(fbm, 10, 1),
            true
        );
        // Prepared once, as a renderer keeps it.
        $m!("gabor3", GaborNoise::new(Gabor::default(), 1), true);
        // With the paper's roulette probability, `SMOOTH_VORONOI_Q`.
        $m!("voronoi3", SmoothVoronoi::new(1), true);
        // Worley F1 has no stochastic form.
        $m!("worley3", Worley::new(1), false);
    }};
}

/// The noises of the report, each through the [`Noise`] trait.
fn functions() -> Vec<(&'static str, Det, Option<Sto>)> {
    let mut out = Vec::new();
    macro_rules! push {
        ($name:literal, $noise:expr, $stochastic:expr) => {
            out.push(row($name, $noise, $stochastic))
        };
    }
    for_each_noise!(push);
    out
}

fn random_points(n: usize, seed: u64) -> Vec<[f32; 3]> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| std::array::from_fn(|_| (rng.unit_f64() * 100.0 - 50.0) as f32))
        .collect()
}

/// Seconds for one pass of `f` over `pts`. Generic, so `f` is inlined into the loop as in a
/// renderer's inner loop. The slices, not each point, go through `black_box`: a `black_box`ed
/// `[f32; 3]` is written to the stack and read back in pieces of other widths, which stalls
/// store-to-load forwarding and adds a delay to every call that no renderer pays.
fn pass<F: Fn([f32; 3], f32) -> f32>(pts: &[[f32; 3]], xis: &[f32], f: F) -> f64 {
    let start = Instant::now();
    let mut acc = 0.0f32;
    for (p, &x) in black_box(pts).iter().zip(black_box(xis)) {
        acc += f(*p, x);
    }
    black_box(acc);
    start.elapsed().as_secs_f64()
}

/// Timed rounds (after one warm-up round).
const ROUNDS: usize = 9;
/// Points per chunk of a round.
const CHUNK: usize = 2048;

/// The median of `v`.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// RMSE by sample count.
type Errors = BTreeMap<String, f64>;

/// Two functions timed together ([`time_pair`]).
#[derive(Clone, Copy, Debug)]
struct Paired {
    /// ns per call of the first function, the median over rounds.
    a_ns: f64,
    /// ns per call of the second.
    b_ns: f64,
    /// The median over rounds of the first's time over the second's.
    ratio: f64,
    /// The 3rd and 7th of the rounds' ratios in order.
    spread: [f64; 2],
}

/// Two functions timed together: ns per call of each (the median over rounds) and the median
/// over rounds of the ratio of their times, with its spread. A round runs both over all
/// 65 536 random points (so branch predictors cannot learn the sequence), interleaved in
/// chunks of 2048, the order alternating from chunk to chunk. On a shared machine the clock and the neighbours' load
/// drift over seconds: two functions timed one after the other (as criterion does) can be
/// measured at different speeds, while interleaved chunks, tens of microseconds apart, see
/// the same machine.
fn time_pair<A, B>(pts: &[[f32; 3]], xis: &[f32], a: A, b: B) -> Paired
where
    A: Fn([f32; 3], f32) -> f32 + Copy,
    B: Fn([f32; 3], f32) -> f32 + Copy,
{
    time_passes(pts, xis, |p, x| pass(p, x, a), |p, x| pass(p, x, b))
}

/// A batch function of the report: evaluates the points with their ξ into `out` (of the
/// points' length).
type Batch = fn(&[[f32; 3]], &[f32], &mut [f32]);

/// Seconds for one call of the batch function `f` on `pts`, into `out` (a chunk's length).
fn pass_batch(pts: &[[f32; 3]], xis: &[f32], out: &mut [f32], f: Batch) -> f64 {
    let start = Instant::now();
    f(black_box(pts), black_box(xis), &mut out[..pts.len()]);
    black_box(&*out);
    start.elapsed().as_secs_f64()
}

/// [`time_pair`] for two batch functions: each chunk of points goes to `a` and `b` in one call.
fn time_batch_pair(pts: &[[f32; 3]], xis: &[f32], a: Batch, b: Batch) -> Paired {
    let mut out_a = vec![0.0f32; CHUNK];
    let mut out_b = vec![0.0f32; CHUNK];
    time_passes(
        pts,
        xis,
        |p, x| pass_batch(p, x, &mut out_a, a),
        |p, x| pass_batch(p, x, &mut out_b, b),
    )
}

/// [`time_pair`] for a single-point function `a` against a batch function `b`.
fn time_point_batch<A>(pts: &[[f32; 3]], xis: &[f32], a: A, b: Batch) -> Paired
where
    A: Fn([f32; 3], f32) -> f32 + Copy,
{
    let mut out = vec![0.0f32; CHUNK];
    time_passes(
        pts,
        xis,
        |p, x| pass(p, x, a),
        |p, x| pass_batch(p, x, &mut out, b),
    )
}

/// The rounds behind [`time_pair`], for any two passes (a pass times one chunk, in seconds).
fn time_passes(
    pts: &[[f32; 3]],
    xis: &[f32],
    mut a: impl FnMut(&[[f32; 3]], &[f32]) -> f64,
    mut b: impl FnMut(&[[f32; 3]], &[f32]) -> f64,
) -> Paired {
    let mut round = || {
        let (mut ta, mut tb) = (0.0, 0.0);
        for (k, (p, x)) in pts.chunks(CHUNK).zip(xis.chunks(CHUNK)).enumerate() {
            if k % 2 == 0 {
                ta += a(p, x);
                tb += b(p, x);
            } else {
                tb += b(p, x);
                ta += a(p, x);
            }
        }
        (ta, tb)
    };
    round();
    let rounds: Vec<(f64, f64)> = (0..ROUNDS).map(|_| round()).collect();
    let ns = |t: f64| t * 1e9 / pts.len() as f64;
    let mut ratios: Vec<f64> = rounds.iter().map(|r| r.0 / r.1).collect();
    ratios.sort_by(f64::total_cmp);
    Paired {
        a_ns: median(rounds.iter().map(|r| ns(r.0)).collect()),
        b_ns: median(rounds.iter().map(|r| ns(r.1)).collect()),
        ratio: median(ratios.clone()),
        spread: [ratios[ROUNDS / 4], ratios[ROUNDS - 1 - ROUNDS / 4]],
    }
}

/// ξ sources for the error columns: white noise, or the STBN mask's pixel sequence.
fn rmse(
    pts: &[[f32; 3]],
    exact: &[f32],
    sto: &dyn Fn([f32; 3], f32) -> f32,
    xi: &dyn Fn(usize, usize) -> f32,
) -> (Errors, f64) {
    errors(exact, |j, out| {
        for (i, (o, p)) in out.iter_mut().zip(pts).enumerate() {
            *o = sto(*p, xi(i, j));
        }
    })
}

/// RMSE at each of [`KS`] samples and the bias at the last, of the estimates `sample(j, out)`
/// writes (sample `j` of every point) against `exact`.
fn errors(exact: &[f32], mut sample: impl FnMut(usize, &mut [f32])) -> (Errors, f64) {
    let n = exact.len();
    let mut out = BTreeMap::new();
    let mut bias = 0.0;
    let mut v = vec![0.0f32; n];
    for &k in &KS {
        let mut sum = vec![0.0f64; n];
        for j in 0..k {
            sample(j, &mut v);
            for (s, &v) in sum.iter_mut().zip(&v) {
                *s += v as f64;
            }
        }
        let (mut se, mut me) = (0.0, 0.0);
        for (s, &e) in sum.iter().zip(exact) {
            let d = s / k as f64 - e as f64;
            se += d * d;
            me += d;
        }
        out.insert(k.to_string(), (se / n as f64).sqrt());
        bias = me / n as f64;
    }
    (out, bias)
}

/// Peer rows (same points, same process).
#[cfg(feature = "peers")]
fn peers(pts: &[[f32; 3]], xis: &[f32]) -> Vec<Row> {
    use fastnoise_lite::{
        CellularDistanceFunction, CellularReturnType, FastNoiseLite, FractalType, NoiseType,
    };
    use noise_functions::{CellDistance, Noise, Perlin};
    let fbm = Fractal::new(10, 2.0, 0.5);
    let fnl = |t: NoiseType, fractal: bool| {
        let mut n = FastNoiseLite::new();
        n.set_noise_type(Some(t));
        n.set_frequency(Some(1.0));
        if fractal {
            n.set_fractal_type(Some(FractalType::FBm));
            n.set_fractal_octaves(Some(10));
            n.set_fractal_lacunarity(Some(2.0));
            n.set_fractal_gain(Some(0.5));
        }
        n.set_cellular_return_type(Some(CellularReturnType::Distance));
        n.set_cellular_distance_function(Some(CellularDistanceFunction::Euclidean));
        n
    };
    let (p1, p10, cell) = (
        fnl(NoiseType::Perlin, false),
        fnl(NoiseType::Perlin, true),
        fnl(NoiseType::Cellular, false),
    );
    let nf_fbm = Perlin.fbm(10, 0.5, 2.0);
    let nf_cell = CellDistance::default();
    let mut rows = Vec::new();
    rows.extend(against_peers(
        pts,
        xis,
        "perlin3",
        |p, _| noise_runtime::stochastic::Perlin::new(1).sample(p),
        |p, _| Perlin.sample3(p),
        |p, _| p1.get_noise_3d(p[0], p[1], p[2]),
    ));
    rows.extend(against_peers(
        pts,
        xis,
        "fbm3",
        move |p, _| Fbm::new(fbm, 1).sample(p),
        |p, _| nf_fbm.sample3(p),
        |p, _| p10.get_noise_3d(p[0], p[1], p[2]),
    ));
    rows.extend(against_peers(
        pts,
        xis,
        "worley3",
        |p, _| Worley::new(1).f1(p),
        |p, _| nf_cell.sample3(p),
        |p, _| cell.get_noise_3d(p[0], p[1], p[2]),
    ));
    // Neither peer has smooth Voronoi; their nearest function, cellular F1, stands in.
    rows.extend(against_peers(
        pts,
        xis,
        "voronoi3",
        |p, _| SmoothVoronoi::new(1).sample(p),
        |p, _| nf_cell.sample3(p),
        |p, _| cell.get_noise_3d(p[0], p[1], p[2]),
    ));
    rows
}

/// The rows of `noise` for the two peers, `noise-functions` (`nf`) and `fastnoise-lite`
/// (`fnl`): each timed in alternating passes with `ours` (see [`time_pair`]), its `speedup`
/// ours / theirs (below 1: ours is faster).
#[cfg(feature = "peers")]
fn against_peers<O, N, F>(
    pts: &[[f32; 3]],
    xis: &[f32],
    noise: &str,
    ours: O,
    nf: N,
    fnl: F,
) -> [Row; 2]
where
    O: Fn([f32; 3], f32) -> f32 + Copy,
    N: Fn([f32; 3], f32) -> f32 + Copy,
    F: Fn([f32; 3], f32) -> f32 + Copy,
{
    [
        Row::paired(noise, "noise-functions", time_pair(pts, xis, ours, nf)),
        Row::paired(noise, "fastnoise-lite", time_pair(pts, xis, ours, fnl)),
    ]
}

#[cfg(not(feature = "peers"))]
fn peers(_: &[[f32; 3]], _: &[f32]) -> Vec<Row> {
    Vec::new()
}

/// Whether peer crates are compiled in.
pub const HAS_PEERS: bool = cfg!(feature = "peers");

/// Runs the report.
pub fn run() -> Vec<Row> {
    run_with(TIMED)
}

/// Runs the report timing `timed` random points (fewer points: quicker, noisier timings; the
/// error columns are unchanged).
pub fn run_with(timed: usize) -> Vec<Row> {
    let timed = timed.max(1);
    let pts = random_points(timed, 1);
    let mut rng = SplitMix64::new(2);
    let xis: Vec<f32> = (0..timed).map(|_| rng.unit_f64() as f32).collect();
    // Error points: a 64×64 image of the plane z = 0.37 at 0.173 units per pixel.
    let img: Vec<[f32; 3]> = (0..SIDE * SIDE)
        .map(|i| [(i % SIDE) as f32 * 0.173, (i / SIDE) as f32 * 0.173, 0.37])
        .collect();
    let stbn = build_assets::generate(
        &TextureSpec {
            name: "XI".into(),
            kind: Kind::Stbn(VacParams::stbn(1.9, 1.9, 0.1, Histogram::Slice)),
            dims: vec![SIDE, SIDE, 64],
            seed: 3,
            format: Format::F32,
        },
        &mut |_, _| {},
    )
    .values();
    let white: Vec<f32> = {
        let mut r = SplitMix64::new(4);
        (0..SIDE * SIDE * 64).map(|_| r.unit_f64() as f32).collect()
    };
    // Timing, monomorphised per noise (boxing would hide inlining and skew the ratios): each
    // noise's `sample` against its `estimate`, through the `Noise` trait.
    let mut times = BTreeMap::new();
    macro_rules! time {
        ($name:literal, $noise:expr, $stochastic:expr) => {{
            let noise = $noise;
            times.insert(
                $name,
                time_pair(
                    &pts,
                    &xis,
                    |p, _| noise.sample(p),
                    |p, x| noise.estimate(p, x),
                ),
            );
        }};
    }
    for_each_noise!(time);
    let fbm = Fractal::new(10, 2.0, 0.5);
    let mut rows = Vec::new();
    for (name, det, sto) in functions() {
        let t = times[name];
        rows.push(Row::timed(name, "deterministic", t.a_ns, None));
        if let Some(sto) = sto {
            let exact: Vec<f32> = img.iter().map(|&p| det(p)).collect();
            let (w, bias) = rmse(&img, &exact, &*sto, &|i, j| white[j * SIDE * SIDE + i]);
            let (b, _) = rmse(&img, &exact, &*sto, &|i, j| {
                stbn[j * SIDE * SIDE + i] as f32
            });
            rows.push(Row::paired(name, "stochastic", t).with_error(w, b, bias));
        }
    }
    // The one-term estimators: the 27-cell sum sampled as well (one kernel evaluation).
    let one_term: [(&str, Paired, Sto); 2] = [
        (
            "sparse_conv3",
            time_pair(
                &pts,
                &xis,
                |p, _| SparseConvolution::new(10, 1).sample(p),
                |p, x| SparseConvolution::new(10, 1).estimate_one_term(p, x),
            ),
            Box::new(|p, x| SparseConvolution::new(10, 1).estimate_one_term(p, x)),
        ),
        (
            "fbm_sparse_conv3",
            time_pair(
                &pts,
                &xis,
                |p, _| SparseConvolutionFbm::new(fbm, 10, 1).sample(p),
                |p, x| SparseConvolutionFbm::new(fbm, 10, 1).estimate_one_term(p, x),
            ),
            Box::new(move |p, x| SparseConvolutionFbm::new(fbm, 10, 1).estimate_one_term(p, x)),
        ),
    ];
    for (name, t, sto) in one_term {
        let det = functions()
            .into_iter()
            .find(|f| f.0 == name)
            .expect("listed")
            .1;
        let exact: Vec<f32> = img.iter().map(|&p| det(p)).collect();
        let (w, bias) = rmse(&img, &exact, &*sto, &|i, j| white[j * SIDE * SIDE + i]);
        let (b, _) = rmse(&img, &exact, &*sto, &|i, j| {
            stbn[j * SIDE * SIDE + i] as f32
        });
        rows.push(Row::paired(name, "stochastic-1term", t).with_error(w, b, bias));
    }
    rows.extend(batch_rows(&pts, &xis, &img, &white, &stbn));
    rows.extend(peers(&pts, &xis));
    rows
}

/// The batch forms (`perlin3_batch`, `fbm3_batch` and their estimators: eight points per
/// instruction on AVX2, one at a time elsewhere): `deterministic-batch` rows, whose speedup
/// is over the single-point deterministic form, and `stochastic-batch` rows, whose speedup is
/// over the deterministic batch, with their error measured through the batch function.
fn batch_rows(
    pts: &[[f32; 3]],
    xis: &[f32],
    img: &[[f32; 3]],
    white: &[f32],
    stbn: &[f64],
) -> Vec<Row> {
    type Single = fn([f32; 3], f32) -> f32;
    let forms: [(&str, Single, Batch, Batch); 2] = [
        (
            "perlin3",
            |p, _| noise_runtime::stochastic::Perlin::new(1).sample(p),
            |p, _, o| {
                Perlin::new(1).sample_batch(p, o).unwrap();
            },
            |p, x, o| {
                Perlin::new(1).estimate_batch(p, x, o).unwrap();
            },
        ),
        (
            "fbm3",
            |p, _| Fbm::new(Fractal::new(10, 2.0, 0.5), 1).sample(p),
            |p, _, o| {
                Fbm::new(Fractal::new(10, 2.0, 0.5), 1)
                    .sample_batch(p, o)
                    .unwrap();
            },
            |p, x, o| {
                Fbm::new(Fractal::new(10, 2.0, 0.5), 1)
                    .estimate_batch(p, x, o)
                    .unwrap();
            },
        ),
    ];
    let mut rows = Vec::new();
    for (name, single, det, sto) in forms {
        let t = time_point_batch(pts, xis, single, det);
        rows.push(Row::paired(name, "deterministic-batch", t));
        let t = time_batch_pair(pts, xis, det, sto);
        let mut exact = vec![0.0f32; img.len()];
        det(img, &[], &mut exact);
        let (w, bias) = rmse_batch(img, &exact, sto, &|i, j| white[j * SIDE * SIDE + i]);
        let (b, _) = rmse_batch(img, &exact, sto, &|i, j| stbn[j * SIDE * SIDE + i] as f32);
        rows.push(Row::paired(name, "stochastic-batch", t).with_error(w, b, bias));
    }
    rows
}

/// [`rmse`] through a batch estimator: sample `j` of every point at once.
fn rmse_batch(
    pts: &[[f32; 3]],
    exact: &[f32],
    sto: Batch,
    xi: &dyn Fn(usize, usize) -> f32,
) -> (Errors, f64) {
    errors(exact, |j, out| {
        let x: Vec<f32> = (0..pts.len()).map(|i| xi(i, j)).collect();
        sto(pts, &x, out);
    })
}

/// One goal of the report, checked against a run's rows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Goal {
    /// What is measured: `perlin3 deterministic`, `gabor3 speedup`, …
    pub what: String,
    /// The goal, e.g. `≤ 25 ns` or `≥ 6×`.
    pub goal: String,
    /// What this run measured.
    pub measured: String,
    /// Whether the run meets it.
    pub met: bool,
}

/// The absolute goals: the deterministic 3D Perlin and 10-octave fBm within these times, and
/// what the peer `noise-functions` takes for the same function on the reference machine
/// (a 2-core x86_64 cloud machine: 3D Perlin ≈ 32 ns, fBm10 ≈ 309 ns, single thread). This
/// machine's speed drifts by up to 1.5× (its neighbours' load); the report prints, beside
/// each goal's time, the time scaled to the reference by the interleaved ratio to the peer.
/// Met or not is decided on this run's own time.
pub const REFERENCE_NS: [(&str, f64, f64); 2] = [("perlin3", 25.0, 32.0), ("fbm3", 240.0, 309.0)];

/// The variants of our own rows; any other variant is a peer crate's.
pub const OURS: [&str; 5] = [
    "deterministic",
    "stochastic",
    "stochastic-1term",
    "deterministic-batch",
    "stochastic-batch",
];

/// The paper's GPU speedups (Fajardo & Pharr, Table 1) that each estimator should reach.
pub const PAPER_SPEEDUPS: [(&str, f64); 6] = [
    ("perlin3", 1.9),
    ("fbm3", 12.0),
    ("sparse_conv3", 11.0),
    ("fbm_sparse_conv3", 85.0),
    ("gabor3", 6.0),
    ("voronoi3", 4.0),
];

/// The goals of the report checked against `rows`: the deterministic 3D Perlin within 25 ns
/// and fBm with 10 octaves within 240 ns, Worley F1 and smooth Voronoi faster than every peer
/// crate in the run (for smooth Voronoi, which no peer has, than the peers' cellular F1), and
/// each estimator's speedup at least [`PAPER_SPEEDUPS`]. A goal whose rows the run lacks
/// (peers not compiled in) is left out. The times are this machine's, in this run: on a
/// shared machine they move with its load, the speedups much less.
pub fn goals(rows: &[Row]) -> Vec<Goal> {
    let find = |noise: &str, variant: &str| {
        rows.iter()
            .find(|r| r.noise == noise && r.variant == variant)
    };
    let mut out = Vec::new();
    for (noise, limit, reference) in REFERENCE_NS {
        if let Some(r) = find(noise, "deterministic") {
            // The time is this run's; beside it, the same time at the reference machine's
            // speed, from the interleaved ratio to the peer (when the run has the peer).
            let scaled = find(noise, "noise-functions")
                .and_then(|p| p.speedup)
                .map(|s| {
                    format!(
                        " (at reference speed {:.0} ns: {s:.2}× of {reference} ns)",
                        s * reference
                    )
                })
                .unwrap_or_default();
            out.push(Goal {
                what: format!("{noise} deterministic"),
                goal: format!("≤ {limit} ns"),
                measured: format!("{:.1} ns{scaled}", r.ns_per_eval),
                met: r.ns_per_eval <= limit,
            });
        }
    }
    // A peer row's speedup is our time over the peer's: below 1 when ours is faster. Neither
    // peer has smooth Voronoi; their cellular F1 stands in for it (the goal says so).
    for (noise, goal) in [
        ("worley3", "faster than every peer"),
        ("voronoi3", "faster than every peer's F1"),
    ] {
        let fastest_peer = rows
            .iter()
            .filter(|r| r.noise == noise && !OURS.contains(&r.variant.as_str()))
            .filter_map(|r| r.speedup.map(|s| (s, r)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((s, peer)) = fastest_peer {
            out.push(Goal {
                what: format!("{noise} deterministic"),
                goal: goal.into(),
                measured: format!("{s:.2}× the time of {}{}", peer.variant, spread(peer)),
                met: s < 1.0,
            });
        }
    }
    for (noise, want) in PAPER_SPEEDUPS {
        // The batch forms' estimator against the deterministic batch: the CPU's counterpart
        // of the paper's GPU, where a warp evaluates its pixels' points side by side.
        if let Some(r) = find(noise, "stochastic-batch")
            && let Some(s) = r.speedup
        {
            out.push(Goal {
                what: format!("{noise} speedup (batch)"),
                goal: format!("≥ {want}×"),
                measured: format!("{s:.2}×{}", spread(r)),
                met: s >= want,
            });
        }
        if let Some(r) = find(noise, "stochastic")
            && let Some(s) = r.speedup
        {
            let window = match (
                noise,
                find(noise, "deterministic"),
                find(noise, "stochastic"),
            ) {
                ("voronoi3", Some(d), Some(e)) => {
                    roulette_window(d.ns_per_eval, e.ns_per_eval, want)
                }
                _ => String::new(),
            };
            out.push(Goal {
                what: format!("{noise} speedup"),
                goal: format!("≥ {want}×"),
                measured: format!("{s:.2}×{}{window}", spread(r)),
                met: s >= want,
            });
        }
    }
    out
}

/// The spread of a row's speedup over the middle rounds, for a goal's line (empty where the
/// row has none): a verdict whose goal lies inside it is the machine's drift as much as the
/// code's.
fn spread(r: &Row) -> String {
    r.speedup_spread
        .map(|[lo, hi]| format!(" (middle rounds {lo:.2}–{hi:.2}×)"))
        .unwrap_or_default()
}

/// What the smooth-Voronoi estimator's speedup asks of the full function, from this run's
/// times: the estimator costs `c + (1 − q) F` (a cheap path `c` always, the full function `F`
/// when the roulette does not keep the approximation), so `c` is its time less `(1 − q) F`,
/// and a speedup of `want` needs `F ≥ c / (1/want − (1 − q))` (8c for 4× at q = 0.875). A
/// faster `F` alone lowers the speedup: the line shows how far `F` may fall before it fails.
fn roulette_window(full_ns: f64, estimator_ns: f64, want: f64) -> String {
    let rare = 1.0 - f64::from(SMOOTH_VORONOI_Q);
    let cheap = estimator_ns - rare * full_ns;
    let room = 1.0 / want - rare;
    if cheap <= 0.0 || room <= 0.0 {
        return String::new();
    }
    format!(
        " (cheap path ≈ {cheap:.1} ns: {want}× needs the full function ≥ {:.1} ns; it takes {full_ns:.1})",
        cheap / room
    )
}

/// The section as text: its legend, one line per row, and the reference figures against this
/// run's.
pub fn describe(rows: &[Row]) -> Vec<String> {
    let mut out = vec![
        "stochastic noise (3D unless named, single thread, random-order points):".to_string(),
        "  (ns/eval: median of 9 rounds; speedup: our deterministic time / this one, the median over 9 rounds".to_string(),
        "   of the two run in interleaved chunks of the same points; for peer crates below 1 when ours is faster)".to_string(),
    ];
    if !HAS_PEERS {
        out.push("  (peers not compiled in: add `--features peers` to measure noise-functions and fastnoise-lite in this run)".to_string());
    }
    out.push("  (rmse@k: RMSE against the deterministic value of the mean of k estimates with white-noise ξ;".to_string());
    out.push("   stbn@16: the same at 16 with ξ from a 2D×1D blue-noise mask; bias: mean error of many estimates, 0 when unbiased)".to_string());
    out.push(format!(
        "  {:<18} {:<20} {:>9} {:>8} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10}",
        "noise",
        "variant",
        "ns/eval",
        "speedup",
        "rmse@1",
        "rmse@4",
        "rmse@16",
        "rmse@64",
        "stbn@16",
        "bias"
    ));
    let g = |m: &Option<std::collections::BTreeMap<String, f64>>, k: &str| {
        m.as_ref()
            .map_or("-".to_string(), |m| format!("{:.4}", m[k]))
    };
    for r in rows {
        out.push(format!(
            "  {:<18} {:<20} {:>9.1} {:>8} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10}",
            r.noise,
            r.variant,
            r.ns_per_eval,
            r.speedup.map_or("-".into(), |s| if s < 10.0 {
                format!("{s:.2}x")
            } else {
                format!("{s:.1}x")
            }),
            g(&r.rmse, "1"),
            g(&r.rmse, "4"),
            g(&r.rmse, "16"),
            g(&r.rmse, "64"),
            g(&r.rmse_stbn, "16"),
            r.bias.map_or("-".into(), |b| format!("{b:+.1e}")),
        ));
    }
    out.push("  against the reference figures (the peer crates' times on a reference 2-core machine, the paper's GPU".to_string());
    out.push("  speedups of its Table 1; the times are this machine's, in this run):".to_string());
    out.push(format!(
        "  {:<28} {:<24} {:>36}  reached",
        "function", "reference", "this run"
    ));
    for g in goals(rows) {
        out.push(format!(
            "  {:<28} {:<24} {:>36}  {}",
            g.what,
            g.goal,
            g.measured,
            if g.met { "yes" } else { "no" }
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn goals_are_checked_against_the_rows() {
        let mut rows = vec![
            Row::timed("perlin3", "deterministic", 24.9, None),
            Row::timed("perlin3", "stochastic", 13.0, Some(1.3)),
            Row::timed("fbm3", "deterministic", 241.0, None),
            Row::timed("gabor3", "stochastic", 500.0, Some(6.0)),
            Row::timed("worley3", "deterministic", 50.0, None),
            Row::timed("worley3", "noise-functions", 80.0, Some(0.62)),
            Row::timed("worley3", "fastnoise-lite", 160.0, Some(0.31)),
        ];
        let met = |g: &[Goal], what: &str| g.iter().find(|g| g.what == what).map(|g| g.met);
        let g = goals(&rows);
        assert_eq!(met(&g, "perlin3 deterministic"), Some(true));
        assert_eq!(met(&g, "fbm3 deterministic"), Some(false));
        assert_eq!(met(&g, "perlin3 speedup"), Some(false));
        assert_eq!(met(&g, "gabor3 speedup"), Some(true), "6.0 meets ≥ 6");
        assert_eq!(met(&g, "worley3 deterministic"), Some(true));
        // Rows the run lacks give no goal.
        assert_eq!(met(&g, "sparse_conv3 speedup"), None);
        assert_eq!(g.len(), 5);
        // With the peer's row, the time at reference speed stands beside this run's time;
        // the verdict stays with this run's.
        rows.push(Row::timed("fbm3", "noise-functions", 400.0, Some(0.6)));
        let g = goals(&rows);
        let f = g.iter().find(|g| g.what == "fbm3 deterministic").unwrap();
        assert_eq!(
            f.measured,
            "241.0 ns (at reference speed 185 ns: 0.60× of 309 ns)"
        );
        assert!(!f.met);
        rows.pop();
        // One peer faster than ours fails the Worley goal, and the measure names it.
        rows.push(Row::timed("worley3", "other-crate", 40.0, Some(1.25)));
        let g = goals(&rows);
        let w = g
            .iter()
            .find(|g| g.what == "worley3 deterministic")
            .unwrap();
        assert!(!w.met);
        assert_eq!(w.measured, "1.25× the time of other-crate");
        // Without peers there is no Worley goal.
        rows.retain(|r| r.noise != "worley3" || r.variant == "deterministic");
        assert_eq!(met(&goals(&rows), "worley3 deterministic"), None);
        // Smooth Voronoi against the peers' F1: its estimator's row is not a peer.
        rows.push(Row::timed("voronoi3", "deterministic", 400.0, None));
        rows.push(Row::timed("voronoi3", "stochastic", 80.0, Some(5.0)));
        assert_eq!(met(&goals(&rows), "voronoi3 deterministic"), None);
        rows.push(Row::timed("voronoi3", "noise-functions", 130.0, Some(3.1)));
        let g = goals(&rows);
        let v = g
            .iter()
            .find(|g| g.what == "voronoi3 deterministic")
            .unwrap();
        assert!(!v.met);
        assert_eq!(v.measured, "3.10× the time of noise-functions");
        assert_eq!(met(&g, "voronoi3 speedup"), Some(true));
        // The speedup's line says how fast the full function may get: 80 ns = c + 400/8
        // gives c = 30 ns, and 4× needs F ≥ 8c = 240 ns.
        let s = g.iter().find(|g| g.what == "voronoi3 speedup").unwrap();
        assert_eq!(
            s.measured,
            "5.00× (cheap path ≈ 30.0 ns: 4× needs the full function ≥ 240.0 ns; it takes 400.0)"
        );
        // Other speedups carry no such line.
        let p = g.iter().find(|g| g.what == "perlin3 speedup").unwrap();
        assert_eq!(p.measured, "1.30×");
    }

    #[test]
    fn batch_rows_get_their_own_goal_lines_and_are_not_peers() {
        let rows = vec![
            Row::timed("perlin3", "stochastic", 13.0, Some(1.3)),
            Row::timed("perlin3", "deterministic-batch", 3.0, Some(4.0)),
            Row::paired(
                "perlin3",
                "stochastic-batch",
                Paired {
                    a_ns: 3.0,
                    b_ns: 1.5,
                    ratio: 2.0,
                    spread: [1.8, 2.1],
                },
            ),
            Row::timed("fbm3", "stochastic-batch", 3.0, Some(11.9)),
            Row::timed("worley3", "deterministic", 50.0, None),
            Row::timed("worley3", "deterministic-batch", 12.0, Some(4.2)),
            Row::timed("worley3", "noise-functions", 80.0, Some(0.62)),
        ];
        let g = goals(&rows);
        let get = |what: &str| g.iter().find(|g| g.what == what).cloned();
        let b = get("perlin3 speedup (batch)").unwrap();
        assert!(b.met);
        // With the spread of the middle rounds, which here straddles the goal.
        assert_eq!(
            (b.goal.as_str(), b.measured.as_str()),
            ("≥ 1.9×", "2.00× (middle rounds 1.80–2.10×)")
        );
        assert_eq!(b.measured, format!("2.00×{}", spread(&rows[2])));
        assert!(
            !get("perlin3 speedup").unwrap().met,
            "the single-point line stands apart"
        );
        assert!(!get("fbm3 speedup (batch)").unwrap().met, "11.9 < 12");
        // Our batch row is not a peer: the Worley goal names the one peer.
        let w = get("worley3 deterministic").unwrap();
        assert!(w.met);
        assert_eq!(w.measured, "0.62× the time of noise-functions");
    }

    #[test]
    fn paired_times_give_the_median_ratio_and_the_middle_rounds_spread() {
        // One chunk a round: `a` takes 1 s, `b` takes the next of these (the first is the
        // warm-up round's), so the rounds' ratios are 1/b.
        let pts = vec![[0.0f32; 3]; CHUNK];
        let xis = vec![0.0f32; CHUNK];
        let mut b_times = [9.0, 0.5, 0.2, 0.25, 1.0, 0.4, 0.125, 2.0, 0.1, 0.3].into_iter();
        let t = time_passes(&pts, &xis, |_, _| 1.0, |_, _| b_times.next().unwrap());
        // Ratios in order: 0.5, 1, 2, 2.5, 3.33, 4, 5, 8, 10 (the warm-up's 1/9 is dropped).
        assert_eq!(t.ratio, 1.0 / 0.3);
        assert_eq!(t.spread, [2.0, 5.0]);
        assert_eq!((t.a_ns, t.b_ns), (1e9 / CHUNK as f64, 0.3e9 / CHUNK as f64));
    }
}
