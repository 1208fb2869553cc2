//! Curl-noise jittering (Bærentzen, Frisvad, Martínez 2023): a regular lattice displaced along a
//! divergence-free curl-noise field (eq. 4–5) becomes a blue-noise point set, and because each
//! point depends only on its own lattice site, any point — and the nearest points to any query —
//! can be found without generating the others.
//!
//! - [`Cnj2`]: triangular lattice (rows horizontal, odd rows shifted by half a spacing), 2D
//!   gradient noise with analytic derivatives, one RK4 step with the paper's Perlin parameters
//!   `t = 1.05862`, `s = 2.86207` by default; [`Cnj2::closest`], [`Cnj2::k_nearest`] (K ≤ 4),
//!   Worley/cellular values and the foam SDFs of eq. (11)–(12) in [`Cells`]; [`Region2`] caches the
//!   jittered points of a rectangle for shading whole images.
//! - [`Cnj3`]: body-centred cubic ("octahedral") or cubic lattice displaced by the curl of a
//!   vector potential of three gradient noises; the same queries in 3D.
//!
//! # Precision
//! Lattice sites are `i32` and the field is evaluated from the exact integer site (positions are
//! split in `f64`), so [`Cnj2::point`] / [`Cnj3::point`] are exact for every site, and the `*_f64`
//! queries are exact for any query within the `i32` site range. The `f32` queries are exact while
//! `f32` resolves the query to well below the point spacing: up to |x| ≈ 10⁵ spacings the
//! rounding of the query (≤ 4e-3 spacings) cannot change which point is nearest except for ties
//! closer than that. Beyond it use the `f64` forms. No input makes a query panic or return NaN.
//!
//! # Example
//!
//! ```
//! use noise_runtime::cnj::Cnj2;
//!
//! let cnj = Cnj2::default(); // the paper's parameters, unit point spacing
//! let q = [12.3, -4.5];
//! // The three nearest jittered points, nearest first, found without generating a point set.
//! let near = cnj.k_nearest::<3>(q);
//! assert!(near[0].distance <= near[1].distance && near[1].distance <= near[2].distance);
//! assert_eq!(cnj.closest(q), near[0]);
//! // Every point is a pure function of its lattice site.
//! assert_eq!(cnj.point(near[0].site), near[0].point);
//! // Worley F1 and F2 from the same query.
//! let cells = cnj.cells(q);
//! assert_eq!(cells.f1(), near[0].distance);
//! assert!(cells.f2() >= cells.f1());
//! ```

mod field;
mod lattice2;
mod lattice3;

pub use field::{MIN_SCALE, SOS_WAVES, SumOfSines3, noise2, velocity2, velocity3};
pub use lattice2::{Cells, Cnj2, MAX_REGION_SITES, Neighbor2, Region2};
pub use lattice3::{Cnj3, Lattice3, MAX_REACH, Neighbor3, Potential3};

/// A CNJ parameter no lattice can have: named, with the value given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CnjError {
    /// The point spacing must be finite and positive.
    Spacing(f32),
    /// The streamline time must be finite.
    Time(f32),
    /// The noise cell size must be finite and at least [`MIN_SCALE`].
    Scale(f32),
    /// The integration steps must be in `1..=64`.
    Steps(u32),
}

impl core::fmt::Display for CnjError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CnjError::Spacing(v) => write!(f, "CNJ spacing must be finite and positive, got {v}"),
            CnjError::Time(v) => write!(f, "CNJ streamline time must be finite, got {v}"),
            CnjError::Scale(v) => write!(
                f,
                "CNJ noise cell size must be finite and at least {MIN_SCALE}, got {v}"
            ),
            CnjError::Steps(v) => write!(f, "CNJ integration steps must be 1 to 64, got {v}"),
        }
    }
}

impl core::error::Error for CnjError {}

/// The checked setters and the getters both lattices share.
macro_rules! parameters {
    ($ty:ident, $unit:literal, $between:literal) => {
        impl $ty {
            #[doc = concat!("The distance between ", $between, ", in world units: finite and positive.")]
            pub fn with_spacing(mut self, spacing: f32) -> Result<Self, super::CnjError> {
                if !(spacing.is_finite() && spacing > 0.0) {
                    return Err(super::CnjError::Spacing(spacing));
                }
                self.spacing = spacing;
                Ok(self)
            }

            /// The streamline time (the paper's `t`): finite, of either sign.
            pub fn with_time(mut self, t: f32) -> Result<Self, super::CnjError> {
                if !t.is_finite() {
                    return Err(super::CnjError::Time(t));
                }
                self.t = t;
                Ok(self)
            }

            #[doc = concat!("The noise cell size in ", $unit, " (the paper's `s`): finite and at least [`MIN_SCALE`](super::MIN_SCALE).")]
            pub fn with_scale(mut self, s: f32) -> Result<Self, super::CnjError> {
                if !(s.is_finite() && s as f64 >= super::field::MIN_SCALE) {
                    return Err(super::CnjError::Scale(s));
                }
                self.s = s;
                Ok(self)
            }

            /// The integration steps over `[0, t]`, 1 to 64.
            pub fn with_steps(mut self, steps: u32) -> Result<Self, super::CnjError> {
                if !(1..=64).contains(&steps) {
                    return Err(super::CnjError::Steps(steps));
                }
                self.steps = steps;
                Ok(self)
            }

            /// The seed of the noise.
            #[must_use]
            pub const fn with_seed(mut self, seed: u32) -> Self {
                self.seed = seed;
                self
            }

            /// RK4 (default) or Euler.
            #[must_use]
            pub const fn with_integrator(mut self, integrator: super::Integrator) -> Self {
                self.integrator = integrator;
                self
            }

            /// The point spacing in world units.
            pub const fn spacing(&self) -> f32 {
                self.spacing
            }

            /// The streamline time.
            pub const fn time(&self) -> f32 {
                self.t
            }

            #[doc = concat!("The noise cell size in ", $unit, ".")]
            pub const fn scale(&self) -> f32 {
                self.s
            }

            /// The integration steps.
            pub const fn steps(&self) -> u32 {
                self.steps
            }

            /// The seed.
            pub const fn seed(&self) -> u32 {
                self.seed
            }

            /// The integrator.
            pub const fn integrator(&self) -> super::Integrator {
                self.integrator
            }
        }
    };
}
use parameters;

/// The parameters `(t, s, steps, spacing)` made safe: a non-finite `t` becomes 0, a
/// non-positive or non-finite `s` or spacing becomes 1 (and `s ≥` [`MIN_SCALE`]), steps in
/// `1..=64`.
fn sane(t: f32, s: f32, steps: u32, spacing: f32) -> (f64, f64, u32, f64) {
    let pos = |x: f32| if x.is_finite() && x > 0.0 { x } else { 1.0 };
    (
        if t.is_finite() { t as f64 } else { 0.0 },
        (pos(s) as f64).max(field::MIN_SCALE),
        steps.clamp(1, 64),
        pos(spacing) as f64,
    )
}

/// The `K` smallest keys offered so far with their values, in ascending order (insertion into
/// a fixed array: K ≤ 4, so nothing cleverer pays).
struct TopK<const K: usize, T: Copy> {
    key: [f64; K],
    val: [T; K],
}

impl<const K: usize, T: Copy> TopK<K, T> {
    fn new(fill: T) -> Self {
        TopK {
            key: [f64::MAX; K],
            val: [fill; K],
        }
    }

    /// Offers `val` with `key`; `make` builds it only when it enters the list.
    #[inline]
    fn offer(&mut self, key: f64, make: impl FnOnce() -> T) {
        if key < self.key[K - 1] {
            let mut k = K - 1;
            while k > 0 && self.key[k - 1] > key {
                self.key[k] = self.key[k - 1];
                self.val[k] = self.val[k - 1];
                k -= 1;
            }
            self.key[k] = key;
            self.val[k] = make();
        }
    }
}

/// How the streamline is traced (eq. 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Classic 4th-order Runge–Kutta (the paper's choice).
    Rk4,
    /// Forward Euler (for comparison, Fig. 7).
    Euler,
}

/// The foam signed-distance functions of CNJ eq. (11) and (12) from the four nearest distances.
pub mod foam {
    /// Eq. (11): `(d2 − d1)^α + (d3 − d2)^α + (d4 − d3)^α − ε`.
    pub fn sdf11(d: [f32; 4], alpha: f32, eps: f32) -> f32 {
        let pw = |x: f32| if x <= 0.0 { 0.0 } else { pow(x, alpha) };
        pw(d[1] - d[0]) + pw(d[2] - d[1]) + pw(d[3] - d[2]) - eps
    }

    /// `x^a` for `x > 0` as `e^(a ln x)`, finite for any finite `a`.
    fn pow(x: f32, a: f32) -> f32 {
        let l = a * crate::math::ln(x);
        if l <= 0.0 {
            crate::math::exp_neg(l)
        } else {
            1.0 / crate::math::exp_neg(-l).max(1e-30)
        }
    }

    /// Eq. (12): `(1/(d3 − d1) + 1/(d4 − d1))⁻¹ − ε`.
    pub fn sdf12(d: [f32; 4], eps: f32) -> f32 {
        let a = (d[2] - d[0]).max(1e-12);
        let b = (d[3] - d[0]).max(1e-12);
        a * b / (a + b) - eps
    }
}
