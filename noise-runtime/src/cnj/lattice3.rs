//! CNJ in 3D: a body-centred cubic ("octahedral", the paper's choice for dense packings) or cubic
//! lattice displaced by the curl of a vector potential of three gradient noises, and exact
//! closest / k-nearest queries by scanning every site within a proven radius.

use super::field::{SumOfSines3, velocity3};
use super::{Integrator, TopK};
use crate::hash::hash4;
use crate::math::{ceil_f64, floor_f64, sqrt_f64};

/// The undisplaced lattice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lattice3 {
    /// Body-centred cubic: cube corners and cube centres (2 points per cube).
    Bcc,
    /// Simple cubic: cube corners.
    Cubic,
}

/// The vector potential whose curl displaces the 3D lattice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Potential3 {
    /// Three improved-Perlin gradient noises with different seeds (default).
    Gradient,
    /// Three sums of sines ([`SumOfSines3`]), CNJ §2.3 in 3D.
    SumOfSines,
}

/// Curl-noise jittering of a 3D lattice. Lengths are in units of the cube edge `spacing`.
#[derive(Clone, Copy, Debug, PartialEq)]
///
/// Built from [`Default`] with the checked setters, as [`Cnj2`](super::Cnj2); `|t|` is clamped at query
/// time so that no site moves more than [`MAX_REACH`] cube edges.
pub struct Cnj3 {
    t: f32,
    s: f32,
    seed: u32,
    spacing: f32,
    steps: u32,
    integrator: Integrator,
    lattice: Lattice3,
    potential: Potential3,
}

super::parameters!(Cnj3, "cube edges", "cube corners (the cube edge)");

impl Cnj3 {
    /// BCC (default) or cubic.
    #[must_use]
    pub const fn with_lattice(mut self, lattice: Lattice3) -> Self {
        self.lattice = lattice;
        self
    }

    /// The potential (gradient noise by default).
    #[must_use]
    pub const fn with_potential(mut self, potential: Potential3) -> Self {
        self.potential = potential;
        self
    }

    /// The lattice.
    pub const fn lattice(&self) -> Lattice3 {
        self.lattice
    }

    /// The potential.
    pub const fn potential(&self) -> Potential3 {
        self.potential
    }
}

impl Default for Cnj3 {
    /// BCC, `t = 0.3`, `s = 2.5`, one RK4 step: displacements up to about 0.55 cube edges
    /// (0.63 of the nearest-neighbour distance), enough to break the lattice's regularity.
    fn default() -> Self {
        Cnj3 {
            t: 0.3,
            s: 2.5,
            seed: 0,
            spacing: 1.0,
            steps: 1,
            integrator: Integrator::Rk4,
            lattice: Lattice3::Bcc,
            potential: Potential3::Gradient,
        }
    }
}

/// One point found by a query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbor3 {
    /// The jittered point, world units.
    pub point: [f32; 3],
    /// Its distance to the query.
    pub distance: f32,
    /// Its site `(i, j, k, b)`: cube `(i, j, k)`, `b = 1` for the cube centre.
    pub site: [i32; 4],
}

impl Neighbor3 {
    const NONE: Neighbor3 = Neighbor3 {
        point: [0.0; 3],
        distance: f32::MAX,
        site: [0; 4],
    };

    /// A hash of the site in `[0, 1)` for colouring cells.
    #[must_use]
    pub fn cell_id(&self) -> f32 {
        let s = self.site;
        (hash4(s[0], s[1], s[2], s[3], 0x9e37_79b9) >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

impl Cnj3 {
    /// The parameters made safe (see [`super::sane`]), with `|t|` at most the time that moves
    /// a site [`MAX_REACH`] cube edges at the potential's bound speed: a query scans every
    /// site within `r_K + 2·max_displacement`, so this bounds its cost (about 5 000 sites).
    fn sane(&self) -> (f64, f64, u32, f64) {
        let (t, s, steps, sp) = super::sane(self.t, self.s, self.steps, self.spacing);
        let tmax = MAX_REACH * s / self.speed();
        (t.clamp(-tmax, tmax), s, steps, sp)
    }

    fn speed(&self) -> f64 {
        match self.potential {
            Potential3::Gradient => MAX_SPEED,
            Potential3::SumOfSines => MAX_SPEED_SOS,
        }
    }

    /// Position of a site in cube units.
    #[must_use]
    pub fn site_position(site: [i32; 4]) -> [f64; 3] {
        let b = 0.5 * (site[3] & 1) as f64;
        [site[0] as f64 + b, site[1] as f64 + b, site[2] as f64 + b]
    }

    /// The displacement of a site by the flow, cube units.
    #[must_use]
    pub fn displacement(&self, site: [i32; 4]) -> [f32; 3] {
        let (t, s, steps, _) = self.sane();
        let p0 = Self::site_position(site);
        let h = (t / steps as f64) as f32;
        let sos = (self.potential == Potential3::SumOfSines).then(|| SumOfSines3::new(self.seed));
        let at = |d: [f32; 3]| {
            let q = [
                p0[0] + d[0] as f64,
                p0[1] + d[1] as f64,
                p0[2] + d[2] as f64,
            ];
            match &sos {
                Some(w) => w.velocity(q, s),
                None => velocity3(q, s, self.seed),
            }
        };
        let add =
            |a: [f32; 3], k: [f32; 3], c: f32| [a[0] + c * k[0], a[1] + c * k[1], a[2] + c * k[2]];
        let mut d = [0.0f32; 3];
        for _ in 0..steps {
            match self.integrator {
                Integrator::Euler => d = add(d, at(d), h),
                Integrator::Rk4 => {
                    let k1 = at(d);
                    let k2 = at(add(d, k1, 0.5 * h));
                    let k3 = at(add(d, k2, 0.5 * h));
                    let k4 = at(add(d, k3, h));
                    for a in 0..3 {
                        d[a] += h / 6.0 * (k1[a] + 2.0 * k2[a] + 2.0 * k3[a] + k4[a]);
                    }
                }
            }
        }
        d
    }

    /// The jittered point of a site, world units, `f64`.
    #[must_use]
    pub fn point_f64(&self, site: [i32; 4]) -> [f64; 3] {
        let sp = self.sane().3;
        let p = Self::site_position(site);
        let d = self.displacement(site);
        [
            (p[0] + d[0] as f64) * sp,
            (p[1] + d[1] as f64) * sp,
            (p[2] + d[2] as f64) * sp,
        ]
    }

    /// The jittered point of a site, world units.
    #[must_use]
    pub fn point(&self, site: [i32; 4]) -> [f32; 3] {
        let p = self.point_f64(site);
        [p[0] as f32, p[1] as f32, p[2] as f32]
    }

    /// An upper bound on |displacement| in cube units for these parameters: the velocity is at
    /// most `6.5 / s` per unit time for the gradient-noise potential (the largest streamline
    /// speed measured over 27 648 sites was 4.5/s; the bound adds ~40 %, and the tests check
    /// it) and `15 / s` for the sum of sines, times `t`.
    #[must_use]
    pub fn max_displacement(&self) -> f64 {
        let (t, s, _, _) = self.sane();
        t.abs() * self.speed() / s
    }

    /// The `K ≤ 4` nearest jittered points to `x` (world units, `f64`), nearest first: every
    /// site within `r_K + 2·max_displacement` of the query is jittered and compared, where `r_K`
    /// bounds the distance from any point to its K-th nearest lattice site — so the result is
    /// exact.
    #[must_use]
    pub fn k_nearest_f64<const K: usize>(&self, x: [f64; 3]) -> [Neighbor3; K] {
        const { assert!(K >= 1 && K <= 4, "k_nearest supports K = 1..=4") };
        let sp = self.sane().3;
        let q = x.map(|v| {
            if v.is_finite() {
                (v / sp).clamp(-2.0e9, 2.0e9)
            } else {
                0.0
            }
        });
        let r_k = match (self.lattice, K) {
            (Lattice3::Bcc, 1) => 0.559_017,   // √5/4, the BCC covering radius
            (Lattice3::Cubic, 1) => 0.866_026, // √3/2
            _ => 1.118_034,                    // √5/2 ≥ distance to the 4th nearest site
        };
        let r = r_k + 2.0 * self.max_displacement();
        let r2 = r * r;
        let mut best = TopK::<K, Neighbor3>::new(Neighbor3::NONE);
        let subs: &[i32] = match self.lattice {
            Lattice3::Bcc => &[0, 1],
            Lattice3::Cubic => &[0],
        };
        for &b in subs {
            let off = 0.5 * b as f64;
            let lo = |v: f64| ceil_f64(v - off - r) as i64;
            let hi = |v: f64| floor_f64(v - off + r) as i64;
            for k in lo(q[2])..=hi(q[2]) {
                let dz = k as f64 + off - q[2];
                for j in lo(q[1])..=hi(q[1]) {
                    let dy = j as f64 + off - q[1];
                    if dy * dy + dz * dz > r2 {
                        continue;
                    }
                    for i in lo(q[0])..=hi(q[0]) {
                        let dx = i as f64 + off - q[0];
                        if dx * dx + dy * dy + dz * dz > r2 {
                            continue;
                        }
                        let site = [i as i32, j as i32, k as i32, b];
                        let p = self.point_f64(site);
                        let dd = (0..3).map(|a| (p[a] - x[a]) * (p[a] - x[a])).sum::<f64>();
                        best.offer(dd, || Neighbor3 {
                            point: [p[0] as f32, p[1] as f32, p[2] as f32],
                            distance: (sqrt_f64(dd) as f32).min(f32::MAX),
                            site,
                        });
                    }
                }
            }
        }
        best.val
    }

    /// The `K ≤ 4` nearest jittered points to `x` (world units), nearest first.
    #[must_use]
    pub fn k_nearest<const K: usize>(&self, x: [f32; 3]) -> [Neighbor3; K] {
        self.k_nearest_f64([x[0] as f64, x[1] as f64, x[2] as f64])
    }

    /// The nearest jittered point.
    #[must_use]
    pub fn closest(&self, x: [f32; 3]) -> Neighbor3 {
        self.k_nearest::<1>(x)[0]
    }

    /// The four nearest distances (F1…F4) for Worley noise and the foam SDFs
    /// ([`super::foam`]).
    #[must_use]
    pub fn distances(&self, x: [f32; 3]) -> [f32; 4] {
        let n = self.k_nearest::<4>(x);
        [n[0].distance, n[1].distance, n[2].distance, n[3].distance]
    }
}

/// The farthest the flow may move a site, in cube edges: `t` is clamped so that
/// [`Cnj3::max_displacement`] stays within it (the defaults move sites about 0.8).
pub const MAX_REACH: f64 = 4.0;

/// Bound on the curl-noise speed times `s` (see [`Cnj3::max_displacement`]).
pub const MAX_SPEED: f64 = 6.5;
/// The same for the sum-of-sines potential: its waves reach higher speeds (largest streamline
/// speed measured 10.6/s over 27 648 sites; the bound adds ~40 %). With the default `t` it
/// displaces up to ~1.3 cube edges, so choose `t ≈ 0.15` for a BCC packing.
pub const MAX_SPEED_SOS: f64 = 15.0;
