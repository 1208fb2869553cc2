//! What the sampler optimiser trains on: integrands in the space the ray uses, and every
//! pixel's error on each of them for the shift it holds.
//!
//! - `square`: random half-planes of the unit square (the visibility edge an occluder casts
//!   over an area light);
//! - `cosine_hemisphere`: random half-spaces of directions `[a · ω < c]` through the polar warp
//!   (an occluder's plane cutting the hemisphere of ambient occlusion or a bounce);
//! - `disk`: random half-planes of the unit disk through the polar warp;
//! - a lone dimension: random thresholds `[u < c]`.
//!
//! Each integrand also gets a random offset of the torus: frame `f` of a tile is frame 0 with
//! every shift moved by `f · spp · α`, so an integrand met at a random offset stands for every
//! frame at once. A pixel's error on integrand `k` is its estimate there less the mean over the
//! tile's pixels (the pixels' shifts, the start's, are a stratified set, so the mean is the
//! integral to a fraction of the errors; the loss is blind to a constant anyway).

use crate::generate::rng::SplitMix64;
use crate::spec::sampler::PairSpace;
use noise_runtime::sampler::tile_point;
use rayon::prelude::*;

/// One training integrand, in the pair's own unit square.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// `a·u + b·v < c` (square), or of the warped disk point (disk).
    Edge { a: f32, b: f32, c: f32, disk: bool },
    /// `a · ω(u, v) < c` for the cosine-weighted direction `ω`.
    Directions { a: [f32; 3], c: f32 },
    /// `u < c` (a lone dimension).
    Threshold { c: f32 },
}

/// Integrands with their offsets.
pub(super) struct Integrands {
    shapes: Vec<Shape>,
    offsets: Vec<[u32; 2]>,
    tables: Warp,
}

/// The polar warp's factors at 2^16 steps of `u` and of `v` (`√u`, `√(1 − u)`, `cos 2πv`,
/// `sin 2πv`), through the runtime's own square root and sine so every machine computes the same
/// bits: a point's 32-bit fraction indexes them by its top 16 bits.
struct Warp {
    r: Vec<f32>,
    z: Vec<f32>,
    cos: Vec<f32>,
    sin: Vec<f32>,
}

impl Warp {
    fn new() -> Warp {
        let n = 1usize << 16;
        let mid = |i: usize| (i as f32 + 0.5) / n as f32;
        Warp {
            r: (0..n).map(|i| noise_runtime::math::sqrt(mid(i))).collect(),
            z: (0..n)
                .map(|i| noise_runtime::math::sqrt(1.0 - mid(i)))
                .collect(),
            cos: (0..n)
                .map(|i| noise_runtime::math::sincos_turns(mid(i)).1)
                .collect(),
            sin: (0..n)
                .map(|i| noise_runtime::math::sincos_turns(mid(i)).0)
                .collect(),
        }
    }
}

/// A random unit vector (rejection from the cube, so no transcendental decides a bit).
fn unit3(rng: &mut SplitMix64) -> [f32; 3] {
    loop {
        let v = [
            2.0 * rng.unit_f64() - 1.0,
            2.0 * rng.unit_f64() - 1.0,
            2.0 * rng.unit_f64() - 1.0,
        ];
        let r2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if r2 > 1e-4 && r2 <= 1.0 {
            let r = r2.sqrt();
            return v.map(|x| (x / r) as f32);
        }
    }
}

impl Integrands {
    /// `count` integrands of `space` (`axes` 1 for a lone dimension), from `rng`.
    pub fn new(space: PairSpace, axes: usize, count: usize, rng: &mut SplitMix64) -> Integrands {
        let mut shapes = Vec::with_capacity(count);
        let mut offsets = Vec::with_capacity(count);
        for _ in 0..count {
            let shape = if axes == 1 {
                Shape::Threshold {
                    c: rng.unit_f64() as f32,
                }
            } else {
                match space {
                    PairSpace::Square => {
                        let [a, b, c] = random_edge(rng);
                        Shape::Edge {
                            a: a as f32,
                            b: b as f32,
                            c: c as f32,
                            disk: false,
                        }
                    }
                    PairSpace::Disk => {
                        // A line through a uniform point of the disk's bounding square.
                        let [a, b, c] = random_edge(rng);
                        Shape::Edge {
                            a: a as f32,
                            b: b as f32,
                            c: (2.0 * c - a - b) as f32,
                            disk: true,
                        }
                    }
                    PairSpace::CosineHemisphere => Shape::Directions {
                        a: unit3(rng),
                        c: (rng.unit_f64() - 0.5) as f32,
                    },
                }
            };
            shapes.push(shape);
            offsets.push([rng.next_u64() as u32, rng.next_u64() as u32]);
        }
        Integrands {
            shapes,
            offsets,
            tables: Warp::new(),
        }
    }

    /// Integrands.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether the point of 32-bit fractions `(u, v)` is inside integrand `k`.
    #[inline(always)]
    fn inside(&self, k: usize, u: u32, v: u32) -> bool {
        let w = &self.tables;
        match self.shapes[k] {
            Shape::Edge { a, b, c, disk } => {
                let (x, y) = if disk {
                    let (r, iv) = (w.r[(u >> 16) as usize], (v >> 16) as usize);
                    (r * w.cos[iv], r * w.sin[iv])
                } else {
                    (
                        noise_runtime::sequence::to_unit(u),
                        noise_runtime::sequence::to_unit(v),
                    )
                };
                a * x + b * y < c
            }
            Shape::Directions { a, c } => {
                let (iu, iv) = ((u >> 16) as usize, (v >> 16) as usize);
                let r = w.r[iu];
                r * (a[0] * w.cos[iv] + a[1] * w.sin[iv]) + a[2] * w.z[iu] < c
            }
            Shape::Threshold { c } => noise_runtime::sequence::to_unit(u) < c,
        }
    }
}

/// Every pixel's errors, row by row (`len` values a pixel), for the shifts it holds.
pub(super) struct Errors {
    /// Values per pixel: one per integrand.
    pub len: usize,
    /// `pixels × len`.
    pub values: Vec<f32>,
}

/// How a pixel's samples are weighed into its error: the sample indices `n` of the sequence
/// (relative to the newest frame's first) and their weights. One frame: `n = 0 … spp − 1`,
/// each `1/spp`. Under an EMA of weight `α` over `frames` frames, frame `j` back holds `n =
/// −j·spp … −j·spp + spp − 1` with weight `α(1 − α)^j / spp`, normalised to sum to 1.
pub(super) fn sample_weights(spp: u32, ema: Option<(f64, u32)>) -> Vec<(u32, f32)> {
    match ema {
        None => (0..spp).map(|i| (i, 1.0 / spp as f32)).collect(),
        Some((alpha, frames)) => {
            let w: Vec<f64> = (0..frames)
                .map(|j| alpha * (1.0 - alpha).powi(j as i32))
                .collect();
            let total: f64 = w.iter().sum();
            (0..frames)
                .flat_map(|j| {
                    let wj = (w[j as usize] / total / spp as f64) as f32;
                    (0..spp).map(move |i| (i.wrapping_sub(j * spp), wj))
                })
                .collect()
        }
    }
}

impl Errors {
    /// The errors of pixels holding `shifts` (per pixel, the pair's two 16-bit shifts; the
    /// second unused for a lone dimension), for the pair whose dimensions are `dims` of a
    /// `total`-dimensional tile, weighing samples by `weights` ([`sample_weights`]).
    pub fn new(
        ints: &Integrands,
        shifts: &[[u16; 2]],
        dims: [u32; 2],
        total: u32,
        sobol_pairs: u8,
        weights: &[(u32, f32)],
    ) -> Errors {
        // An integrand's offset moves the points as the pair's structure moves frames: added
        // for the lattice (frame f is frame 0 so moved, for every pixel); XORed for Sobol,
        // whose frames are other scrambled nets: an XOR keeps a net a net, so the training
        // sees the integrand's positions relative to a net, as every frame does.
        let sobol = sobol_pairs >> (dims[0] / 2) & 1 == 1;
        let point = move |n: u32, d: u32, key: u16, o: u32| {
            let x = tile_point(n, d, total, key, sobol_pairs);
            if sobol { x ^ o } else { x.wrapping_add(o) }
        };
        let len = ints.len();
        let mut values: Vec<f32> = shifts
            .par_iter()
            .flat_map_iter(|s| {
                (0..len).map(move |k| {
                    let o = ints.offsets[k];
                    let mut est = 0.0f32;
                    for &(n, w) in weights {
                        let u = point(n, dims[0], s[0], o[0]);
                        let v = point(n, dims[1], s[1], o[1]);
                        if ints.inside(k, u, v) {
                            est += w;
                        }
                    }
                    est
                })
            })
            .collect();
        // Each integrand's mean over the pixels is its integral's estimate: subtract it.
        let pixels = shifts.len();
        for k in 0..len {
            let mean = (0..pixels).map(|p| values[p * len + k] as f64).sum::<f64>() / pixels as f64;
            for p in 0..pixels {
                values[p * len + k] -= mean as f32;
            }
        }
        Errors { len, values }
    }

    /// Pixel `p`'s row.
    #[inline]
    pub fn row(&self, p: usize) -> &[f32] {
        &self.values[p * self.len..(p + 1) * self.len]
    }

    /// Swaps the rows of pixels `p` and `q`.
    pub fn swap(&mut self, p: usize, q: usize) {
        if p == q {
            return;
        }
        let (a, b) = (p.min(q), p.max(q));
        let (head, tail) = self.values.split_at_mut(b * self.len);
        head[a * self.len..(a + 1) * self.len].swap_with_slice(&mut tail[..self.len]);
    }
}

/// A random half-plane `[a, b, c]` (`a·u + b·v < c`, `(a, b)` a unit normal) through a
/// uniform point of the unit square, with a uniform direction drawn by rejection, so no
/// transcendental function decides a bit.
pub fn random_edge(rng: &mut SplitMix64) -> [f64; 3] {
    let (a, b) = loop {
        let (a, b) = (2.0 * rng.unit_f64() - 1.0, 2.0 * rng.unit_f64() - 1.0);
        let r2 = a * a + b * b;
        if r2 > 1e-4 && r2 <= 1.0 {
            let r = r2.sqrt();
            break (a / r, b / r);
        }
    };
    let (qx, qy) = (rng.unit_f64(), rng.unit_f64());
    [a, b, a * qx + b * qy]
}

/// The area of `{(u, v) ∈ [0, 1]²: a·u + b·v < c}`: the unit square clipped by the half-plane
/// (one Sutherland–Hodgman pass), by the shoelace formula.
pub fn half_plane_area(a: f64, b: f64, c: f64) -> f64 {
    let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let side = |p: (f64, f64)| c - (a * p.0 + b * p.1);
    let mut poly: Vec<(f64, f64)> = Vec::with_capacity(5);
    for i in 0..4 {
        let (p, q) = (square[i], square[(i + 1) % 4]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            poly.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            let t = sp / (sp - sq);
            poly.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
        }
    }
    let n = poly.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (p, q) = (poly[i], poly[(i + 1) % n]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum();
    (twice / 2.0).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The half-plane area against a Monte Carlo count.
    #[test]
    fn half_plane_areas_match_a_count() {
        let mut rng = SplitMix64::new(5);
        for _ in 0..20 {
            let [a, b, c] = random_edge(&mut rng);
            let n = 400;
            let inside = (0..n * n)
                .filter(|i| {
                    let (u, v) = (
                        (i % n) as f64 / n as f64 + 0.5 / n as f64,
                        (i / n) as f64 / n as f64 + 0.5 / n as f64,
                    );
                    a * u + b * v < c
                })
                .count();
            let got = half_plane_area(a, b, c);
            assert!((got - inside as f64 / (n * n) as f64).abs() < 5e-3, "{got}");
        }
    }

    /// The EMA's weights sum to one, reach back `frames` frames of `spp` samples, and the
    /// newest frame weighs most.
    #[test]
    fn ema_weights_reach_back_and_sum_to_one() {
        let w = sample_weights(4, Some((0.1, 8)));
        assert_eq!(w.len(), 32);
        let sum: f32 = w.iter().map(|x| x.1).sum();
        assert!((sum - 1.0).abs() < 1e-5);
        assert_eq!(w[0].0, 0);
        assert_eq!(w[4].0, 0u32.wrapping_sub(4));
        assert!(w[0].1 > w[4].1);
        let one = sample_weights(4, None);
        assert_eq!(one, vec![(0, 0.25), (1, 0.25), (2, 0.25), (3, 0.25)]);
    }

    /// Errors are centred per integrand, and a pixel's error depends on its own shift only,
    /// for the lattice and for Sobol.
    #[test]
    fn errors_are_centred_and_follow_the_shift() {
        let mut rng = SplitMix64::new(9);
        for (space, sp) in [
            (PairSpace::Square, 1u8),
            (PairSpace::Square, 0),
            (PairSpace::CosineHemisphere, 0),
            (PairSpace::Disk, 0),
        ] {
            let ints = Integrands::new(space, 2, 16, &mut rng);
            let shifts: Vec<[u16; 2]> = (0..64u32)
                .map(|i| [(i * 1021) as u16, (i * 40_503) as u16])
                .collect();
            let w = sample_weights(4, None);
            let e = Errors::new(&ints, &shifts, [0, 1], 4, sp, &w);
            for k in 0..16 {
                let s: f32 = (0..64).map(|p| e.row(p)[k]).sum();
                assert!(s.abs() < 1e-3, "{space:?} {k}: {s}");
            }
            let mut swapped = shifts.clone();
            swapped.swap(3, 10);
            let f = Errors::new(&ints, &swapped, [0, 1], 4, sp, &w);
            assert_eq!(e.row(3), f.row(10));
            assert_eq!(e.row(10), f.row(3));
            let mut g = Errors::new(&ints, &shifts, [0, 1], 4, sp, &w);
            g.swap(3, 10);
            assert_eq!(g.values, f.values);
        }
    }
}
