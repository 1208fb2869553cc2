//! What the sampler optimiser trains on: random half-planes (the visibility edges of occlusion
//! and shadows), and the table of every candidate block's hits on them.

use crate::generate::rng::SplitMix64;
use noise_runtime::sampler::{tile_index, tile_value};
use noise_runtime::sequence::to_unit;

/// One training integrand: the indicator of `a·u + b·v < c` over the unit square (or of
/// `u < c` for a lone dimension), and its exact integral.
#[derive(Clone, Copy, Debug)]
pub(super) struct Edge {
    a: f64,
    b: f64,
    c: f64,
    pub(super) integral: f64,
}

impl Edge {
    pub(super) fn random(rng: &mut SplitMix64, axes: usize) -> Edge {
        if axes == 1 {
            let c = rng.unit_f64();
            return Edge {
                a: 1.0,
                b: 0.0,
                c,
                integral: c,
            };
        }
        let [a, b, c] = random_edge(rng);
        Edge {
            a,
            b,
            c,
            integral: half_plane_area(a, b, c),
        }
    }

    #[inline]
    fn inside(&self, u: f64, v: f64) -> bool {
        self.a * u + self.b * v < self.c
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

/// Every candidate block's hits on the training integrands.
///
/// Frame `f` of a pixel holding block `b` samples block `b ^ f`, and is scored on its own slice
/// of the integrands, `[f·per_frame, (f + 1)·per_frame)`. So a pixel's error vector over all
/// `frames · per_frame` values is `hits[b ^ f][t] / spp − integral[t]` on slice `f`: the table
/// holds one row of hits per block, and a pixel's vector is gathered from `frames` rows.
pub(super) struct Table {
    /// Training values per pixel: `frames · per_frame`.
    pub len: usize,
    pub per_frame: usize,
    pub frames: usize,
    /// `blocks × len` hit counts (at most 64, the largest spp).
    hits: Vec<u8>,
    /// `1 / spp`.
    pub scale: f32,
    /// The integrals, one per training value.
    pub integral: Vec<f32>,
}

impl Table {
    /// Samples every one of `blocks` blocks (a power of two at least the frames, so `b ^ f`
    /// stays in the pool) of pair `pair` (`axes` 2, or 1 for a lone dimension) and counts its
    /// samples inside each integrand of each frame's slice.
    pub fn build(
        edges: &[Edge],
        blocks: usize,
        frames: usize,
        spp: u32,
        pair: u32,
        axes: usize,
    ) -> Table {
        let len = edges.len();
        let per_frame = len / frames;
        let mut hits = vec![0u8; blocks * len];
        let mut pts = Vec::with_capacity(spp as usize);
        for (b, row) in hits.chunks_exact_mut(len).enumerate() {
            pts.clear();
            pts.extend((0..spp).map(|i| {
                let index = tile_index(b as u32, 0, i, spp);
                let u = to_unit(tile_value(index, pair, 0)) as f64;
                let v = if axes == 2 {
                    to_unit(tile_value(index, pair, 1)) as f64
                } else {
                    0.0
                };
                (u, v)
            }));
            for (h, e) in row.iter_mut().zip(edges) {
                *h = pts.iter().filter(|&&(u, v)| e.inside(u, v)).count() as u8;
            }
        }
        Table {
            len,
            per_frame,
            frames,
            hits,
            scale: 1.0 / spp as f32,
            integral: edges.iter().map(|e| e.integral as f32).collect(),
        }
    }

    /// The hits of block `b` on the integrands of frame `f`'s slice.
    #[inline]
    pub fn slice(&self, b: usize, f: usize) -> &[u8] {
        let o = b * self.len + f * self.per_frame;
        &self.hits[o..o + self.per_frame]
    }

    /// Asks the processor to bring the rows a pixel holding block `b` reads into its caches
    /// (the optimiser scores candidates from random rows of a table far larger than the caches,
    /// and waited on memory: `perf`). A hint only: it changes no value.
    #[inline]
    pub fn prefetch(&self, b: usize) {
        #[cfg(target_arch = "x86_64")]
        for f in 0..self.frames {
            for line in self.slice(b ^ f, f).chunks(64) {
                // SAFETY: SSE is part of the x86_64 baseline, and a prefetch reads nothing.
                unsafe {
                    core::arch::x86_64::_mm_prefetch::<{ core::arch::x86_64::_MM_HINT_T0 }>(
                        line.as_ptr() as *const i8,
                    )
                };
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = b;
    }

    /// The error vector of a pixel holding block `b`, written into `out` (`len` values).
    pub fn errors(&self, b: usize, out: &mut [f32]) {
        for f in 0..self.frames {
            let range = f * self.per_frame..(f + 1) * self.per_frame;
            let hits = self.slice(b ^ f, f);
            for ((o, &h), &i) in out[range.clone()]
                .iter_mut()
                .zip(hits)
                .zip(&self.integral[range])
            {
                *o = h as f32 * self.scale - i;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_plane_areas_are_exact() {
        assert!((half_plane_area(1.0, 0.0, 0.25) - 0.25).abs() < 1e-15);
        assert!((half_plane_area(0.0, -1.0, -0.75) - 0.25).abs() < 1e-15);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        // x + y < 1: half of the square; x + y < 0.5: a triangle of area 1/8.
        assert!((half_plane_area(s, s, s) - 0.5).abs() < 1e-12);
        assert!((half_plane_area(s, s, 0.5 * s) - 0.125).abs() < 1e-12);
        assert_eq!(half_plane_area(1.0, 0.0, -1.0), 0.0);
        assert!((half_plane_area(1.0, 0.0, 2.0) - 1.0).abs() < 1e-15);
    }

    /// A pixel's error vector takes frame `f`'s slice from block `b ^ f`, and a block's hits
    /// are its samples' inside counts.
    #[test]
    fn error_vectors_gather_each_frame_from_its_block() {
        let mut rng = SplitMix64::new(3);
        let edges: Vec<Edge> = (0..64).map(|_| Edge::random(&mut rng, 2)).collect();
        let t = Table::build(&edges, 16, 2, 4, 0, 2);
        let mut e = vec![0.0; 64];
        t.errors(5, &mut e);
        for k in 0..64 {
            let (f, b) = if k < 32 { (0, 5) } else { (1, 4) };
            let inside = (0..4)
                .filter(|&i| {
                    let index = tile_index(b, 0, i, 4);
                    let u = to_unit(tile_value(index, 0, 0)) as f64;
                    let v = to_unit(tile_value(index, 0, 1)) as f64;
                    edges[k].inside(u, v)
                })
                .count();
            assert_eq!(t.slice(b as usize, f)[k - 32 * f] as usize, inside);
            let want = inside as f32 / 4.0 - edges[k].integral as f32;
            assert_eq!(e[k], want, "value {k}");
        }
    }
}
