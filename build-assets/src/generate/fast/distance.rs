//! The distances of the loss (FAST eq. 6), one type per sample space, each in `f64` (the loss,
//! exact) and in `f32` (the optimiser's screen, which only decides which swaps are worth an
//! exact evaluation: [`super::optimize`]).
//!
//! They are types with `#[inline(always)]` functions rather than closures so that the
//! optimiser's AVX2 copy of its ΔL loops inlines them and compiles them for AVX2 too.

use super::space::acos_fast;

/// A distance between samples of `C` channels.
pub trait Distance<const C: usize>: Copy + Send + Sync + 'static {
    /// The distance's (only) value, for code that names the type.
    fn default_value() -> Self;
    /// The distance, as the loss uses it.
    fn d(a: &[f64; C], b: &[f64; C]) -> f64;
    /// The same in `f32`, for the screen.
    fn d32(a: &[f32; C], b: &[f32; C]) -> f32;
}

/// Scalars: `|a − b|`.
#[derive(Clone, Copy, Debug)]
pub struct Scalar;

impl Distance<1> for Scalar {
    fn default_value() -> Self {
        Scalar
    }
    #[inline(always)]
    fn d(a: &[f64; 1], b: &[f64; 1]) -> f64 {
        (a[0] - b[0]).abs()
    }
    #[inline(always)]
    fn d32(a: &[f32; 1], b: &[f32; 1]) -> f32 {
        (a[0] - b[0]).abs()
    }
}

/// Turns on the unit circle: `min(|a − b|, 1 − |a − b|)`.
#[derive(Clone, Copy, Debug)]
pub struct Circle;

impl Distance<1> for Circle {
    fn default_value() -> Self {
        Circle
    }
    #[inline(always)]
    fn d(a: &[f64; 1], b: &[f64; 1]) -> f64 {
        let d = (a[0] - b[0]).abs();
        d.min(1.0 - d)
    }
    #[inline(always)]
    fn d32(a: &[f32; 1], b: &[f32; 1]) -> f32 {
        let d = (a[0] - b[0]).abs();
        d.min(1.0 - d)
    }
}

/// Vectors: the Euclidean distance.
#[derive(Clone, Copy, Debug)]
pub struct Euclid;

impl<const C: usize> Distance<C> for Euclid {
    fn default_value() -> Self {
        Euclid
    }
    #[inline(always)]
    fn d(a: &[f64; C], b: &[f64; C]) -> f64 {
        let mut s = 0.0;
        for k in 0..C {
            let d = a[k] - b[k];
            s += d * d;
        }
        s.sqrt()
    }
    #[inline(always)]
    fn d32(a: &[f32; C], b: &[f32; C]) -> f32 {
        let mut s = 0.0;
        for k in 0..C {
            let d = a[k] - b[k];
            s += d * d;
        }
        s.sqrt()
    }
}

/// Unit vectors: the angle between them, by [`acos_fast`].
#[derive(Clone, Copy, Debug)]
pub struct Sphere;

impl Distance<3> for Sphere {
    fn default_value() -> Self {
        Sphere
    }
    #[inline(always)]
    fn d(a: &[f64; 3], b: &[f64; 3]) -> f64 {
        acos_fast(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
    }
    #[inline(always)]
    fn d32(a: &[f32; 3], b: &[f32; 3]) -> f32 {
        let x = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let m = x.abs().min(1.0);
        let r = (1.0 - m).sqrt()
            * (1.570_728_8 + m * (-0.212_114_4 + m * (0.074_261 - m * 0.018_729_3)));
        if x >= 0.0 {
            r
        } else {
            core::f32::consts::PI - r
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The screen's distances follow the loss's to f32 precision.
    #[test]
    fn f32_distances_follow_the_f64_ones() {
        let mut rng = crate::generate::rng::SplitMix64::new(3);
        for _ in 0..1000 {
            let v: [f64; 6] = std::array::from_fn(|_| rng.unit_f64() * 2.0 - 1.0);
            let n = |a: [f64; 3]| {
                let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
                a.map(|x| x / l)
            };
            let (a, b) = (n([v[0], v[1], v[2]]), n([v[3], v[4], v[5]]));
            let f = |x: [f64; 3]| x.map(|x| x as f32);
            let close = |x: f64, y: f32| (x - y as f64).abs() < 1e-5;
            assert!(close(Sphere::d(&a, &b), Sphere::d32(&f(a), &f(b))));
            assert!(close(
                <Euclid as Distance<3>>::d(&a, &b),
                <Euclid as Distance<3>>::d32(&f(a), &f(b))
            ));
            let (x, y) = ([v[0].abs()], [v[1].abs()]);
            let g = |x: [f64; 1]| [x[0] as f32];
            assert!(close(Scalar::d(&x, &y), Scalar::d32(&g(x), &g(y))));
            assert!(close(Circle::d(&x, &y), Circle::d32(&g(x), &g(y))));
        }
    }
}
