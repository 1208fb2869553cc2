//! The expected error of a sampler whose frame is a point set moved by a shift linear in the
//! pixel and the frame, after a denoiser and an EMA whose history follows a pan — in closed
//! form, so a search can score a candidate in a millisecond.
//!
//! A pair's frame at pixel `n` in frame `f` is the set `Q` moved by the shift
//! `s(n, f) = n_x·a + n_y·b + f·g (mod 1)`. For an integrand `h` of the torus its error is
//! `E(s) = (1/N)·Σ_q h(q + s) − ∫h`, whose Fourier coefficients are `ĥ(k)·Q̂(k)` (`Q̂(k)` the
//! mean of `e^{2πik·q}`), so
//! frequency `k` of the integrand becomes, on the screen, the wave `e^{2πi(ω_s·n + ω_t·f)}`
//! with `ω_s = (k·a, k·b)` and `ω_t = k·g` (mod 1). Every operation after the renderer is
//! linear and shift-invariant, so each wave comes out scaled by a response and the expected
//! mean square error, over integrands and over where on the torus the shifts start, is
//!
//! ```text
//! Σ_{k ≠ 0}  P(k) · |Q̂(k)|² · |F(ω_s)|² · |H(ω_s, ω_t)|²
//! ```
//!
//! with `P` the integrands' power spectrum ([`super::spectrum`]), `F` the denoiser (a
//! Gaussian σ 1, or the à-trous of three B3 passes without its edge stops) and `H` the EMA
//! of α 0.1 whose history is resampled bilinearly at `n − v` each frame (a pan of `v` pixels a
//! frame): `H = α / (1 − (1 − α)·B_v(ω_s)·e^{−2πiω_t})`, `B_v` the bilinear resampling's
//! response. A still camera is `v = 0`; one frame alone is `H = 1`.
//!
//! For a rank-1 lattice `{i·(1, z)/N}` moved by `c₀·(1, z)/N + c₁·(0, 1)` (the runtime's
//! `motion_pairs`, shift `c` in lattice coordinates), `Q̂` is 1 on the dual lattice `k_x + z·k_y
//! ≡ 0 (mod N)` and 0 elsewhere, and `k·s = m·c` with `m = ((k_x + z·k_y)/N, k_y)`.

use super::spectrum::{Family, Spectrum};
use std::f64::consts::TAU;

/// The EMA's blend weight.
pub const ALPHA: f64 = 0.1;

/// A denoiser as a linear filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Denoiser {
    /// A Gaussian of σ 1 (9 taps, normalised).
    Gauss,
    /// Three B3-spline à-trous passes (dilations 1, 2, 4), without edge stops.
    Atrous,
}

impl Denoiser {
    /// Both, in the order of every table.
    pub const ALL: [Denoiser; 2] = [Denoiser::Gauss, Denoiser::Atrous];

    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Denoiser::Gauss => "gauss σ1",
            Denoiser::Atrous => "à-trous 3",
        }
    }

    /// `|F(ω)|²` along one axis, `ω` in cycles per pixel.
    pub fn power_1d(self, w: f64) -> f64 {
        match self {
            Denoiser::Gauss => {
                let taps: [f64; 9] = core::array::from_fn(|i| {
                    let d = i as f64 - 4.0;
                    (-0.5 * d * d).exp()
                });
                let sum: f64 = taps.iter().sum();
                let r: f64 = taps
                    .iter()
                    .enumerate()
                    .map(|(i, t)| t / sum * (TAU * w * (i as f64 - 4.0)).cos())
                    .sum();
                r * r
            }
            Denoiser::Atrous => {
                let mut r = 1.0;
                for pass in 0..3 {
                    let s = f64::from(1u32 << pass);
                    r *= 0.375 + 0.5 * (TAU * w * s).cos() + 0.125 * (2.0 * TAU * w * s).cos();
                }
                r * r
            }
        }
    }
}

/// How the camera moves: a pan of `v` pixels a frame, one frame alone (no EMA), or the mean
/// over pans.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Camera {
    /// One frame, not accumulated.
    OneFrame,
    /// The EMA with the picture moving by `v` pixels a frame (`[0, 0]`: a still camera).
    Pan([f64; 2]),
    /// The EMA's mean over pans fast enough that every wave's temporal phase along the motion,
    /// `ω_t + ω_s·v`, is spread over the circle, and whose sub-pixel parts are uniform:
    /// `α² / (1 − (1 − α)²·E|B|²)` with `E|B|² = Π_axes (2 + cos 2πω)/3`. It depends on the
    /// wave's spatial frequency only: under motion, a sampler keeps what its frame's spatial
    /// spectrum gives, and the bilinear resampling's blur.
    MovingMean,
    /// The worst single wave under any pan of up to [`RESONANCE_REACH`] pixels a frame: the
    /// largest term whose phase `ω_t + ω_s·v` some such pan keeps constant (a resonance), at
    /// the EMA's full response 1. A sampler whose strong waves all sit at high spatial
    /// frequency has no tall resonance.
    Resonance,
}

/// The fastest pan a [`Camera::Resonance`] considers, pixels a frame.
pub const RESONANCE_REACH: f64 = 4.0;

/// `|H|²` of the EMA for the wave `(ω_x, ω_y, ω_t)` under `camera`, given `e^{2πiω}` of each
/// (`ex`, `ey`, `et` as (re, im)).
fn ema_power(camera: Camera, ex: (f64, f64), ey: (f64, f64), et: (f64, f64)) -> f64 {
    let v = match camera {
        Camera::OneFrame => return 1.0,
        Camera::MovingMean => {
            let b2 = (2.0 + ex.0) / 3.0 * (2.0 + ey.0) / 3.0;
            let r = 1.0 - ALPHA;
            return ALPHA * ALPHA / (1.0 - r * r * b2);
        }
        Camera::Resonance => unreachable!("resonances are taken term by term"),
        Camera::Pan(v) => v,
    };
    // B_v(ω) = Π_axes ((1 − φ) + φ·e^{2πiω})·e^{2πiω·⌊−v⌋}, φ = frac(−v): the history at n − v,
    // bilinear between ⌊n − v⌋ and ⌊n − v⌋ + 1.
    let mut m = (1.0, 0.0);
    for (e, va) in [(ex, v[0]), (ey, v[1])] {
        let fl = (-va).floor();
        let phi = -va - fl;
        let lerp = (1.0 - phi + phi * e.0, phi * e.1);
        m = cmul(m, cmul(lerp, cpow(e, fl as i32)));
    }
    // 1 − (1 − α)·B·e^{−2πiω_t}
    let t = cmul(m, (et.0, -et.1));
    let d = (1.0 - (1.0 - ALPHA) * t.0, -(1.0 - ALPHA) * t.1);
    ALPHA * ALPHA / (d.0 * d.0 + d.1 * d.1)
}

fn cmul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn cpow(e: (f64, f64), n: i32) -> (f64, f64) {
    let (mut base, mut k) = (if n < 0 { (e.0, -e.1) } else { e }, n.unsigned_abs());
    let mut out = (1.0, 0.0);
    while k > 0 {
        if k & 1 == 1 {
            out = cmul(out, base);
        }
        base = cmul(base, base);
        k >>= 1;
    }
    out
}

/// The frequencies a frame's set carries error at: per term, the integer vector the shift's
/// coordinates multiply (`m`) and, per family, its weight `P(k)·|Q̂(k)|²`.
#[derive(Clone, Debug)]
pub struct Terms {
    /// Per term, `m`.
    pub m: Vec<[f64; 2]>,
    /// Per family (in [`Family::ALL`] order), per term, the weight.
    pub weight: [Vec<f64>; 2],
}

impl Terms {
    /// The dual lattice of the `n`-point rank-1 lattice with generator `(1, z)`, every `k ≠ 0`
    /// with `|k_x|, |k_y| ≤ reach`.
    pub fn lattice(n: u32, z: u32, reach: i64, spectra: &[Spectrum; 2]) -> Terms {
        let (n, z) = (i64::from(n), i64::from(z));
        let mut m = Vec::new();
        let mut weight = [Vec::new(), Vec::new()];
        for ky in -reach..=reach {
            for kx in -reach..=reach {
                let dual = kx + z * ky;
                if (kx, ky) == (0, 0) || dual.rem_euclid(n) != 0 {
                    continue;
                }
                m.push([(dual / n) as f64, ky as f64]);
                for (w, s) in weight.iter_mut().zip(spectra) {
                    w.push(s.at(kx, ky));
                }
            }
        }
        Terms { m, weight }
    }

    /// Any set of points `q` (a pattern moved by a shift in the unit square's own coordinates):
    /// every `k ≠ 0` with `|k_x|, |k_y| ≤ reach`, weighted by `|Q̂(k)|²`.
    pub fn pattern(q: &[[f64; 2]], reach: i64, spectra: &[Spectrum; 2]) -> Terms {
        let mut m = Vec::new();
        let mut weight = [Vec::new(), Vec::new()];
        for ky in -reach..=reach {
            for kx in -reach..=reach {
                if (kx, ky) == (0, 0) {
                    continue;
                }
                let (mut re, mut im) = (0.0, 0.0);
                for p in q {
                    let a = TAU * (kx as f64 * p[0] + ky as f64 * p[1]);
                    re += a.cos();
                    im += a.sin();
                }
                let q2 = (re * re + im * im) / (q.len() * q.len()) as f64;
                m.push([kx as f64, ky as f64]);
                for (w, s) in weight.iter_mut().zip(spectra) {
                    w.push(s.at(kx, ky) * q2);
                }
            }
        }
        Terms { m, weight }
    }
}

/// A shift linear in the pixel and the frame: `c = n_x·a + n_y·b + f·g`, each a pair of
/// fractions (lattice coordinates for a lattice's terms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shift {
    /// Per pixel step in x.
    pub a: [f64; 2],
    /// Per pixel step in y.
    pub b: [f64; 2],
    /// Per frame.
    pub g: [f64; 2],
}

/// One condition the error is measured under.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Condition {
    /// The integrands.
    pub family: Family,
    /// The denoiser.
    pub denoiser: Denoiser,
    /// The camera.
    pub camera: Camera,
}

/// `|F(ω)|²` of both denoisers tabulated over `ω ∈ [−½, ½]` (a search evaluates it millions
/// of times), read with linear interpolation.
struct PowerTable {
    steps: usize,
    table: [Vec<f64>; 2],
}

impl PowerTable {
    fn get() -> &'static PowerTable {
        static TABLE: std::sync::OnceLock<PowerTable> = std::sync::OnceLock::new();
        TABLE.get_or_init(|| {
            let steps = 1 << 13;
            PowerTable {
                steps,
                table: Denoiser::ALL.map(|d| {
                    (0..=steps)
                        .map(|i| d.power_1d(i as f64 / steps as f64 - 0.5))
                        .collect()
                }),
            }
        })
    }

    fn at(&self, den: usize, w: f64) -> f64 {
        let x = (w + 0.5) * self.steps as f64;
        let i = (x.floor() as usize).min(self.steps - 1);
        let f = x - i as f64;
        let t = &self.table[den];
        t[i] + f * (t[i + 1] - t[i])
    }
}

/// The expected mean square error of `shift` over `terms`, under every one of `conditions`
/// (group the conditions by camera: the EMA's response is computed once per run of them).
pub fn errors(terms: &Terms, shift: &Shift, conditions: &[Condition]) -> Vec<f64> {
    let table = PowerTable::get();
    let mut out: Vec<f64> = vec![0.0; conditions.len()];
    let wrap = |x: f64| x - x.round();
    let e = |w: f64| {
        let (s, c) = (TAU * w).sin_cos();
        (c, s)
    };
    for (t, m) in terms.m.iter().enumerate() {
        let dot = |v: [f64; 2]| wrap(m[0] * v[0] + m[1] * v[1]);
        let (wx, wy, wt) = (dot(shift.a), dot(shift.b), dot(shift.g));
        let spatial = [0, 1].map(|d| table.at(d, wx) * table.at(d, wy));
        let (ex, ey, et) = (e(wx), e(wy), e(wt));
        // A pan of speed up to R turns the phase by up to R·|ω_s|: it can hold the wave in
        // phase if that reaches ω_t's distance from a whole turn.
        let resonant = RESONANCE_REACH * wx.hypot(wy) >= wt.abs();
        let mut last: Option<(Camera, f64)> = None;
        for (o, c) in out.iter_mut().zip(conditions) {
            let h = match (last, c.camera) {
                (_, Camera::Resonance) => f64::from(u8::from(resonant)),
                (Some((cam, h)), _) if cam == c.camera => h,
                _ => ema_power(c.camera, ex, ey, et),
            };
            last = Some((c.camera, h));
            let fam = match c.family {
                Family::Square => 0,
                Family::Cosine => 1,
            };
            let den = match c.denoiser {
                Denoiser::Gauss => 0,
                Denoiser::Atrous => 1,
            };
            let term = terms.weight[fam][t] * spatial[den] * h;
            if c.camera == Camera::Resonance {
                *o = f64::max(*o, term);
            } else {
                *o += term;
            }
        }
    }
    out
}
