//! The per-dimension dispatch of [`LatticePoint`]: each point type to its dimension's Perlin
//! and simplex kernels (and 3D to their lane batch kernels).

use super::noise::LatticePoint;
use super::{perlin, simplex};

macro_rules! lattice_point {
    ($n:literal, $perlin:ident, $pe:ident, $pg:ident, $simplex:ident, $se:ident, $sg:ident $(, $lanes:ident)?) => {
        impl LatticePoint for [f32; $n] {
            $(
                #[inline]
                fn perlin_batch(points: &[Self], seed: u32, out: &mut [f32]) {
                    let _ = stringify!($lanes);
                    perlin::batch::perlin3_batch(points, seed, out);
                }
                #[inline]
                fn perlin_estimate_batch(points: &[Self], seed: u32, xi: &[f32], out: &mut [f32]) {
                    perlin::batch::perlin3_stochastic_batch(points, seed, xi, out);
                }
            )?
            #[inline(always)]
            fn perlin(self, seed: u32) -> f32 {
                perlin::$perlin(self, seed)
            }
            #[inline(always)]
            fn perlin_estimate(self, seed: u32, xi: f32) -> f32 {
                perlin::$pe(self, seed, xi)
            }
            #[inline(always)]
            fn perlin_gradient(self, seed: u32) -> (f32, Self) {
                perlin::$pg(self, seed)
            }
            #[inline(always)]
            fn simplex(self, seed: u32) -> f32 {
                simplex::$simplex(self, seed)
            }
            #[inline(always)]
            fn simplex_estimate(self, seed: u32, xi: f32) -> f32 {
                simplex::$se(self, seed, xi)
            }
            #[inline(always)]
            fn simplex_gradient(self, seed: u32) -> (f32, Self) {
                simplex::$sg(self, seed)
            }
        }
    };
}
lattice_point!(
    2,
    perlin2,
    perlin2_stochastic,
    perlin2_grad,
    simplex2,
    simplex2_stochastic,
    simplex2_grad
);
lattice_point!(
    3,
    perlin3,
    perlin3_stochastic,
    perlin3_grad,
    simplex3,
    simplex3_stochastic,
    simplex3_grad,
    lanes
);
lattice_point!(
    4,
    perlin4,
    perlin4_stochastic,
    perlin4_grad,
    simplex4,
    simplex4_stochastic,
    simplex4_grad
);
