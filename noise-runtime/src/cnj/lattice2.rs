//! CNJ on the 2D triangular lattice: direct jittering of a site, exact closest and k-nearest
//! queries from a fixed candidate set of hex rings, cellular values, and a cached region.

use super::field::velocity2;
use super::{Integrator, TopK};
use crate::hash::hash2;
use crate::math::{ceil_f64, floor_f64, round_f64, sqrt_f64};

/// Row spacing of the triangular lattice in units of the point spacing: √3/2.
const ROW: f64 = 0.866_025_403_784_438_6;

/// The most sites a [`Region2`] caches (32 MiB of points).
pub const MAX_REGION_SITES: usize = 1 << 22;

/// Curl-noise jittering of the 2D triangular lattice.
#[derive(Clone, Copy, Debug, PartialEq)]
///
/// Built from [`Cnj2::PAPER`] (also [`Default`]) with the checked setters of
/// [`Cnj2::with_spacing`], [`Cnj2::with_time`], [`Cnj2::with_scale`], [`Cnj2::with_steps`]; a value no lattice can
/// have (a spacing of 0 or −1, a NaN time) is an error there, never a silent substitute.
///
/// ```
/// use noise_runtime::cnj::Cnj2;
///
/// let cnj = Cnj2::PAPER.with_spacing(12.0)?.with_seed(7);
/// assert_eq!(cnj.spacing(), 12.0);
/// assert!(Cnj2::PAPER.with_spacing(0.0).is_err());
/// assert!(Cnj2::PAPER.with_spacing(-1.0).is_err());
/// # Ok::<(), noise_runtime::cnj::CnjError>(())
/// ```
pub struct Cnj2 {
    /// Streamline time (the paper's `t`).
    t: f32,
    /// Noise cell size in lattice spacings (the paper's `s`).
    s: f32,
    /// Seed of the noise.
    seed: u32,
    /// Distance between neighbouring lattice points, in world units.
    spacing: f32,
    /// Integration steps over `[0, t]`.
    steps: u32,
    /// RK4 (default) or Euler.
    integrator: Integrator,
}

super::parameters!(Cnj2, "lattice spacings", "neighbouring lattice points");

impl Default for Cnj2 {
    fn default() -> Self {
        Cnj2::PAPER
    }
}

/// One point found by a query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbor2 {
    /// The jittered point, world units.
    pub point: [f32; 2],
    /// Its distance to the query, world units.
    pub distance: f32,
    /// Its lattice site `(column, row)`.
    pub site: [i32; 2],
}

impl Neighbor2 {
    const NONE: Neighbor2 = Neighbor2 {
        point: [0.0; 2],
        distance: f32::MAX,
        site: [0; 2],
    };

    /// A hash of the site for colouring cells, uniform in `[0, 1)`.
    #[must_use]
    pub fn cell_id(&self) -> f32 {
        (hash2(self.site[0], self.site[1], 0x9e37_79b9) >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

/// Cellular (Worley) values at a query: the four nearest distances and the nearest site.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cells {
    /// Distances to the 1st…4th nearest jittered points (world units).
    pub d: [f32; 4],
    /// The nearest site.
    pub site: [i32; 2],
}

impl Cells {
    /// The cellular values of the four nearest points (nearest first).
    fn from_nearest(n: [Neighbor2; 4]) -> Cells {
        Cells {
            d: n.map(|k| k.distance),
            site: n[0].site,
        }
    }

    /// F1: distance to the nearest point.
    #[must_use]
    pub fn f1(&self) -> f32 {
        self.d[0]
    }
    /// F2: distance to the second nearest.
    #[must_use]
    pub fn f2(&self) -> f32 {
        self.d[1]
    }
    /// F2 − F1 (cell borders).
    #[must_use]
    pub fn f2_minus_f1(&self) -> f32 {
        self.d[1] - self.d[0]
    }
    /// The foam SDF of eq. (11).
    #[must_use]
    pub fn foam11(&self, alpha: f32, eps: f32) -> f32 {
        super::foam::sdf11(self.d, alpha, eps)
    }
    /// The foam SDF of eq. (12).
    #[must_use]
    pub fn foam12(&self, eps: f32) -> f32 {
        super::foam::sdf12(self.d, eps)
    }
    /// Hash of the nearest site in `[0, 1)`, for colouring.
    #[must_use]
    pub fn cell_id(&self) -> f32 {
        (hash2(self.site[0], self.site[1], 0x9e37_79b9) >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

/// Candidate sites around the site nearest the query: hex rings `0..=R`. One ring … two rings
/// hold 7 / 19 / 37 sites. The nearest jittered point is always within two rings of the nearest
/// site when the largest displacement is below ~1.2 spacings (the paper's parameters give
/// 1.15); k-nearest with k ≥ 2 uses three rings. Exactness is proven by brute force in the
/// tests.
fn for_ring_sites(center: [i32; 2], rings: i32, mut f: impl FnMut([i32; 2])) {
    let [i, j] = center;
    // Work in half spacings: a site's x is 2i + (j & 1) half-units.
    let x0 = 2 * i as i64 + (j & 1) as i64;
    for dj in -rings..=rings {
        let jr = j.wrapping_add(dj);
        let half = 2 * rings as i64 - dj.unsigned_abs() as i64; // |Δx| ≤ rings − |dj|/2
        let par = (jr & 1) as i64;
        // 2i' + par ∈ [x0 − half, x0 + half]
        let lo = (x0 - half - par).div_euclid(2) + ((x0 - half - par).rem_euclid(2) != 0) as i64;
        let hi = (x0 + half - par).div_euclid(2);
        for ii in lo..=hi {
            f([ii as i32, jr]);
        }
    }
}

/// `(Δi, Δj)` of the sites within `rings` hex rings of a site in an even (`odd = false`) or
/// odd row, in scan order: the same set [`for_ring_sites`] visits.
const fn ring_offsets<const N: usize>(rings: i32, odd: bool) -> [(i32, i32); N] {
    let mut out = [(0i32, 0i32); N];
    let mut n = 0;
    let x0: i64 = if odd { 1 } else { 0 };
    let mut dj = -rings;
    while dj <= rings {
        let half = 2 * rings as i64 - (if dj < 0 { -dj } else { dj }) as i64;
        let par: i64 = if odd {
            ((1 + dj) & 1) as i64
        } else {
            (dj & 1) as i64
        };
        let lo_num = x0 - half - par;
        let lo = lo_num.div_euclid(2) + if lo_num.rem_euclid(2) != 0 { 1 } else { 0 };
        let hi = (x0 + half - par).div_euclid(2);
        let mut ii = lo;
        while ii <= hi {
            out[n] = (ii as i32, dj);
            n += 1;
            ii += 1;
        }
        dj += 1;
    }
    assert!(n == N);
    out
}

/// Two hex rings (19 sites) around a site in an even / odd row.
const RING2: [[(i32, i32); 19]; 2] = [ring_offsets::<19>(2, false), ring_offsets::<19>(2, true)];
/// Three hex rings (37 sites).
const RING3: [[(i32, i32); 37]; 2] = [ring_offsets::<37>(3, false), ring_offsets::<37>(3, true)];

impl Cnj2 {
    /// The paper's Perlin-noise parameters (Table 1): `t = 1.05862`, `s = 2.86207`, one RK4 step.
    pub const PAPER: Cnj2 = Cnj2 {
        t: 1.05862,
        s: 2.86207,
        seed: 0,
        spacing: 1.0,
        steps: 1,
        integrator: Integrator::Rk4,
    };

    fn sane(&self) -> (f64, f64, u32, f64) {
        super::sane(self.t, self.s, self.steps, self.spacing)
    }

    /// Position of a lattice site in lattice units (spacing 1).
    #[must_use]
    #[inline]
    pub fn site_position(site: [i32; 2]) -> [f64; 2] {
        [
            site[0] as f64 + 0.5 * (site[1] & 1) as f64,
            site[1] as f64 * ROW,
        ]
    }

    /// The displacement of a site by the flow, lattice units (direct CNJ, eq. 4).
    #[must_use]
    pub fn displacement(&self, site: [i32; 2]) -> [f32; 2] {
        let (t, s, steps, _) = self.sane();
        let p0 = Self::site_position(site);
        let h = (t / steps as f64) as f32;
        let at = |d: [f32; 2]| velocity2([p0[0] + d[0] as f64, p0[1] + d[1] as f64], s, self.seed);
        let mut d = [0.0f32; 2];
        for _ in 0..steps {
            match self.integrator {
                Integrator::Euler => {
                    let k = at(d);
                    d = [d[0] + h * k[0], d[1] + h * k[1]];
                }
                Integrator::Rk4 => {
                    let k1 = at(d);
                    let k2 = at([d[0] + 0.5 * h * k1[0], d[1] + 0.5 * h * k1[1]]);
                    let k3 = at([d[0] + 0.5 * h * k2[0], d[1] + 0.5 * h * k2[1]]);
                    let k4 = at([d[0] + h * k3[0], d[1] + h * k3[1]]);
                    d = [
                        d[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
                        d[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
                    ];
                }
            }
        }
        d
    }

    /// The jittered point of a site in world units, `f64` (exact for every site).
    #[must_use]
    pub fn point_f64(&self, site: [i32; 2]) -> [f64; 2] {
        let (_, _, _, sp) = self.sane();
        let p = Self::site_position(site);
        let d = self.displacement(site);
        [(p[0] + d[0] as f64) * sp, (p[1] + d[1] as f64) * sp]
    }

    /// The jittered point of a site in world units.
    #[must_use]
    pub fn point(&self, site: [i32; 2]) -> [f32; 2] {
        let p = self.point_f64(site);
        [p[0] as f32, p[1] as f32]
    }

    /// The lattice site nearest to a position given in lattice units.
    #[must_use]
    pub fn nearest_site(p: [f64; 2]) -> [i32; 2] {
        let clamp = |v: f64| {
            if v.is_finite() {
                v.clamp(-2.0e9, 2.0e9)
            } else {
                0.0
            }
        };
        let (x, y) = (clamp(p[0]), clamp(p[1]));
        let j0 = round_f64(y / ROW) as i64;
        let mut best = ([0i32; 2], f64::MAX);
        for j in j0 - 1..=j0 + 1 {
            let par = (j & 1) as f64 * 0.5;
            let i = round_f64(x - par) as i64;
            let q = [i as f64 + par, j as f64 * ROW];
            let d = (q[0] - x) * (q[0] - x) + (q[1] - y) * (q[1] - y);
            if d < best.1 {
                best = ([i as i32, j as i32], d);
            }
        }
        best.0
    }

    /// The `K` nearest jittered points to `x` (world units, `f64` query), nearest first.
    /// `K ≤ 4`. Exact: every site in the hex rings around the nearest lattice site that a
    /// jittered point can reach from (displacements below ~1.2 spacings) is compared.
    #[must_use]
    pub fn k_nearest_f64<const K: usize>(&self, x: [f64; 2]) -> [Neighbor2; K] {
        const { assert!(K >= 1 && K <= 4, "k_nearest supports K = 1..=4") };
        let (_, _, _, sp) = self.sane();
        let q = [x[0] / sp, x[1] / sp];
        let center = Self::nearest_site(q);
        let rings = if K == 1 { 2 } else { 3 };
        let mut best = TopK::<K, Neighbor2>::new(Neighbor2::NONE);
        for_ring_sites(center, rings, |site| {
            let p = self.point_f64(site);
            let dd = (p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]);
            best.offer(dd, || Neighbor2 {
                point: [p[0] as f32, p[1] as f32],
                distance: (sqrt_f64(dd) as f32).min(f32::MAX),
                site,
            });
        });
        best.val
    }

    /// The `K ≤ 4` nearest jittered points to `x` (world units), nearest first.
    #[must_use]
    pub fn k_nearest<const K: usize>(&self, x: [f32; 2]) -> [Neighbor2; K] {
        self.k_nearest_f64([x[0] as f64, x[1] as f64])
    }

    /// The nearest jittered point to `x` (world units): point, distance and site.
    #[must_use]
    pub fn closest(&self, x: [f32; 2]) -> Neighbor2 {
        self.k_nearest::<1>(x)[0]
    }

    /// Cellular values at `x`: the four nearest distances (F1…F4) and the nearest site.
    #[must_use]
    pub fn cells(&self, x: [f32; 2]) -> Cells {
        Cells::from_nearest(self.k_nearest::<4>(x))
    }

    /// Sites (columns × rows) a [`Region2`] over the world rectangle `[min, max]` caches: at
    /// most [`MAX_REGION_SITES`] in all (a larger rectangle is cached from its low corner, and
    /// queries beyond the cached block jitter their sites directly, with the same results).
    #[must_use]
    pub fn region_dims(&self, min: [f32; 2], max: [f32; 2]) -> ([i32; 2], [usize; 2]) {
        let (_, _, _, sp) = self.sane();
        let fin = |v: f32| if v.is_finite() { v as f64 / sp } else { 0.0 };
        let (x0, y0, x1, y1) = (fin(min[0]), fin(min[1]), fin(max[0]), fin(max[1]));
        let (x0, x1) = (x0.min(x1), x0.max(x1));
        let (y0, y1) = (y0.min(y1), y0.max(y1));
        // Three rings of margin beyond the nearest site of any query inside.
        let m = 5.0;
        // Site indices are i32: clamp to that range (float-to-int casts saturate), then work
        // in i64 where no difference of two i32 can overflow.
        let idx = |v: f64| v.clamp(i32::MIN as f64, i32::MAX as f64) as i64;
        let i0 = idx(floor_f64(x0 - m));
        let j0 = idx(floor_f64((y0 / ROW) - m));
        let i1 = idx(ceil_f64(x1 + m));
        let j1 = idx(ceil_f64((y1 / ROW) + m));
        let w = (i1 - i0 + 1).clamp(1, MAX_REGION_SITES as i64) as usize;
        let h = (j1 - j0 + 1).clamp(1, (MAX_REGION_SITES / w) as i64) as usize;
        ([i0 as i32, j0 as i32], [w, h])
    }

    /// Jitters every site of the rectangle `[min, max]` once into `buf` (at least
    /// `w · h` entries from [`region_dims`](Self::region_dims)); queries on the returned region
    /// read the cache. Returns `None` if `buf` is too small.
    pub fn region<'a>(
        &self,
        min: [f32; 2],
        max: [f32; 2],
        buf: &'a mut [[f32; 2]],
    ) -> Option<Region2<'a>> {
        let (origin, dims) = self.region_dims(min, max);
        let n = dims[0].saturating_mul(dims[1]);
        if buf.len() < n {
            return None;
        }
        self.fill_rows(origin, dims, 0, &mut buf[..n]);
        Some(Region2::from_parts(*self, origin, dims, &buf[..n]))
    }

    /// Fills rows `row0..` of a region cache (for splitting the work across threads):
    /// `rows` holds whole rows of `dims[0]` points each.
    pub fn fill_rows(
        &self,
        origin: [i32; 2],
        dims: [usize; 2],
        row0: usize,
        rows: &mut [[f32; 2]],
    ) {
        for (r, row) in rows.chunks_mut(dims[0].max(1)).enumerate() {
            let j = origin[1].wrapping_add((row0 + r) as i32);
            for (c, p) in row.iter_mut().enumerate() {
                *p = self.point([origin[0].wrapping_add(c as i32), j]);
            }
        }
    }
}

/// The jittered points of a rectangle, computed once; queries inside it cost only distance
/// comparisons (the way to shade a whole frame).
#[derive(Clone, Copy, Debug)]
pub struct Region2<'a> {
    cnj: Cnj2,
    origin: [i32; 2],
    dims: [usize; 2],
    points: &'a [[f32; 2]],
    /// Index deltas in `points` of the two-ring table, per parity of the centre row.
    delta2: [[i32; 19]; 2],
    /// Same for three rings.
    delta3: [[i32; 37]; 2],
    inv_spacing: f32,
}

impl<'a> Region2<'a> {
    /// Builds a region over an already filled cache (see [`Cnj2::fill_rows`]).
    pub fn from_parts(
        cnj: Cnj2,
        origin: [i32; 2],
        dims: [usize; 2],
        points: &'a [[f32; 2]],
    ) -> Self {
        let w = dims[0].min(1 << 20) as i32;
        let delta = |t: &[(i32, i32)], n: usize| t[n].1 * w + t[n].0;
        Region2 {
            cnj,
            origin,
            dims,
            points,
            delta2: core::array::from_fn(|p| core::array::from_fn(|n| delta(&RING2[p], n))),
            delta3: core::array::from_fn(|p| core::array::from_fn(|n| delta(&RING3[p], n))),
            inv_spacing: 1.0 / cnj.sane().3 as f32,
        }
    }

    #[inline]
    fn point(&self, site: [i32; 2]) -> [f32; 2] {
        let c = site[0].wrapping_sub(self.origin[0]);
        let r = site[1].wrapping_sub(self.origin[1]);
        if c >= 0 && r >= 0 && (c as usize) < self.dims[0] && (r as usize) < self.dims[1] {
            self.points[r as usize * self.dims[0] + c as usize]
        } else {
            self.cnj.point(site)
        }
    }

    /// [`Cnj2::k_nearest`] from the cache: the nearest site from the two rows bracketing the
    /// query (the covering radius 0.58 is below the row spacing 0.87), then a fixed table of
    /// hex-ring offsets read straight from the cache — no noise evaluation, no `f64`.
    #[must_use]
    pub fn k_nearest<const K: usize>(&self, x: [f32; 2]) -> [Neighbor2; K] {
        const { assert!(K >= 1 && K <= 4, "k_nearest supports K = 1..=4") };
        let (qx, qy) = (x[0] * self.inv_spacing, x[1] * self.inv_spacing);
        const ROW32: f32 = ROW as f32;
        let jf = crate::math::split(qy / ROW32).0;
        let mut center = [0i32; 2];
        let mut bd = f32::MAX;
        for j in [jf, jf.wrapping_add(1)] {
            let par = (j & 1) as f32 * 0.5;
            let (i, f) = crate::math::split(qx - par + 0.5);
            let _ = f;
            let dx = qx - (i as f32 + par);
            let dy = qy - j as f32 * ROW32;
            let d = dx * dx + dy * dy;
            if d < bd {
                bd = d;
                center = [i, j];
            }
        }
        let c = center[0].wrapping_sub(self.origin[0]);
        let r = center[1].wrapping_sub(self.origin[1]);
        let odd = (center[1] & 1) as usize;
        let table: &[(i32, i32)] = if K == 1 { &RING2[odd] } else { &RING3[odd] };
        let deltas: &[i32] = if K == 1 {
            &self.delta2[odd]
        } else {
            &self.delta3[odd]
        };
        let m = 3;
        let inside = c >= m
            && r >= m
            && (c as usize) + (m as usize) < self.dims[0]
            && (r as usize) + (m as usize) < self.dims[1];
        // Track (distance², table index) only; build the results at the end.
        let mut d2 = [f32::MAX; K];
        let mut at = [0usize; K];
        let w = self.dims[0] as i32;
        // Only meaningful (and only computed without overflow) inside the cached block.
        let base = if inside { r * w + c } else { 0 };
        let fetch = |n: usize| {
            if inside {
                self.points[(base + deltas[n]) as usize]
            } else {
                let (di, dj) = table[n];
                self.point([center[0].wrapping_add(di), center[1].wrapping_add(dj)])
            }
        };
        if inside && K == 1 {
            // The hot path of image shading: a branch-free minimum over the cached points.
            // Non-negative floats order like their bit patterns, so the key (distance² bits,
            // index) is minimised with an integer min.
            let mut key = u64::MAX;
            for (n, &dl) in deltas.iter().enumerate() {
                let p = self.points[(base + dl) as usize];
                let (dx, dy) = (p[0] - x[0], p[1] - x[1]);
                key = key.min((((dx * dx + dy * dy).to_bits() as u64) << 8) | n as u64);
            }
            d2[0] = f32::from_bits((key >> 8) as u32);
            at[0] = (key & 0xff) as usize;
        } else {
            let mut top = TopK::<K, usize>::new(0);
            for n in 0..table.len() {
                let p = fetch(n);
                let dd = (p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]);
                top.offer(dd as f64, || n);
            }
            for k in 0..K {
                d2[k] = top.key[k] as f32;
                at[k] = top.val[k];
            }
        }
        let mut out = [Neighbor2::NONE; K];
        for k in 0..K {
            let (di, dj) = table[at[k]];
            out[k] = Neighbor2 {
                point: fetch(at[k]),
                distance: crate::math::sqrt(d2[k]),
                site: [center[0].wrapping_add(di), center[1].wrapping_add(dj)],
            };
        }
        out
    }

    /// Worley F1 along a row of pixels: `out[k] = F1(x0 + k·dx, y)` (world units) — the fast
    /// path for shading images. The two lattice rows that can hold the nearest site are fixed
    /// for the whole pixel row, so per pixel only the column of the nearest site and a branch-
    /// free minimum over the 19 cached candidates remain. Pixels whose candidates fall outside
    /// the cache fall back to [`Region2::closest`].
    pub fn f1_row(&self, y: f32, x0: f32, dx: f32, out: &mut [f32]) {
        const ROW32: f32 = ROW as f32;
        let qy = y * self.inv_spacing;
        let jf = crate::math::split(qy / ROW32).0;
        let rows = [jf, jf.wrapping_add(1)];
        let par = rows.map(|j| (j & 1) as f32 * 0.5);
        let dy2 = rows.map(|j| {
            let d = qy - j as f32 * ROW32;
            d * d
        });
        let w = self.dims[0] as i32;
        let mut cand = [[0.0f32; 2]; 19];
        let mut cached_site = [i32::MIN; 2];
        for (k, o) in out.iter_mut().enumerate() {
            let x = x0 + k as f32 * dx;
            let qx = x * self.inv_spacing;
            // Nearest site: the nearer of the two rows' nearest columns.
            let i0 = crate::math::split(qx - par[0] + 0.5).0;
            let i1 = crate::math::split(qx - par[1] + 0.5).0;
            let e0 = qx - (i0 as f32 + par[0]);
            let e1 = qx - (i1 as f32 + par[1]);
            let second = (e1 * e1 + dy2[1] < e0 * e0 + dy2[0]) as usize;
            let (ci, cj) = if second == 1 {
                (i1, rows[1])
            } else {
                (i0, rows[0])
            };
            let c = ci.wrapping_sub(self.origin[0]);
            let r = cj.wrapping_sub(self.origin[1]);
            let inside = c >= 3
                && r >= 3
                && (c as usize) + 3 < self.dims[0]
                && (r as usize) + 3 < self.dims[1];
            if !inside {
                *o = self.closest([x, y]).distance;
                continue;
            }
            // Consecutive pixels mostly share their nearest site: gather its 19 candidates once
            // into a local array and reuse them until the site changes.
            if [ci, cj] != cached_site {
                let base = r * w + c;
                let deltas = &self.delta2[(cj & 1) as usize];
                for (slot, &dl) in cand.iter_mut().zip(deltas) {
                    *slot = self.points[(base + dl) as usize];
                }
                cached_site = [ci, cj];
            }
            // Three running minima keep the dependency chains short (19 = 3·6 + 1).
            let mut best = [f32::MAX; 3];
            let d2 = |p: [f32; 2]| {
                let (ex, ey) = (p[0] - x, p[1] - y);
                ex * ex + ey * ey
            };
            for ch in cand.chunks_exact(3) {
                for a in 0..3 {
                    let d = d2(ch[a]);
                    best[a] = if d < best[a] { d } else { best[a] };
                }
            }
            let d = d2(cand[18]);
            best[0] = if d < best[0] { d } else { best[0] };
            let b = if best[0] < best[1] { best[0] } else { best[1] };
            *o = crate::math::sqrt(if b < best[2] { b } else { best[2] });
        }
    }

    /// [`Cnj2::closest`] from the cache.
    #[must_use]
    pub fn closest(&self, x: [f32; 2]) -> Neighbor2 {
        self.k_nearest::<1>(x)[0]
    }

    /// [`Cnj2::cells`] from the cache.
    #[must_use]
    pub fn cells(&self, x: [f32; 2]) -> Cells {
        Cells::from_nearest(self.k_nearest::<4>(x))
    }
}
