//! A tiny deterministic random number generator (SplitMix64, Steele, Lea & Flood 2014).
//!
//! Generators must give the same bytes for the same seed on every machine and with every
//! version of every dependency, so the stream is defined here rather than borrowed from a crate
//! whose algorithm may change between releases.

/// SplitMix64: a 64-bit state advanced by the golden-ratio increment and finalised by a mixer.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator whose stream is fully determined by `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix64(self.state)
    }

    /// A uniform integer in `0..n` (Lemire's multiply-shift with rejection; `n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        debug_assert!(n > 0);
        loop {
            let m = (self.next_u64() as u128) * (n as u128);
            let low = m as u64;
            // Lemire's rejection: the threshold `2^64 mod n` is below `n`, so a `low` of at
            // least `n` is accepted without the division that computes it.
            if low >= n || low >= n.wrapping_neg() % n {
                return (m >> 64) as u64;
            }
        }
    }

    /// A uniform `f32` in `[0, 1)` with 24 random bits.
    #[inline]
    pub fn unit_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// A uniform `f64` in `[0, 1)` with 53 random bits.
    pub fn unit_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The SplitMix64 finaliser: a bijective 64-bit mixer, also used to derive sub-seeds.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A seed for the `index`-th independent sub-stream of `seed` (e.g. one per slice).
pub fn derive_seed(seed: u64, index: u64) -> u64 {
    mix64(seed ^ mix64(index.wrapping_add(0x632B_E59B_D9B4_E019)))
}

/// A seeded bijection of `u32`: distinct inputs give distinct outputs, which look random.
///
/// Void and cluster breaks energy ties by the lowest value of this function of the texel index,
/// computed when needed instead of stored (a table of `n` ranks would cost a cache miss per
/// lookup). Every step (xor with a constant, multiply by an odd constant, xor-shift) is
/// invertible on `u32`, so the ranks are distinct for every mask up to 2^32 texels, and
/// [`TieRank::index`] maps a rank back to its index (the engine's queue keys carry only the rank).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TieRank {
    key: u32,
    mul1: u32,
    mul2: u32,
    inv1: u32,
    inv2: u32,
}

/// The inverse of an odd `m` modulo 2^32, by Newton's iteration (each step doubles the number of
/// correct low bits; `m · m ≡ 1 (mod 8)` gives the first three).
fn inverse_mod_2_32(m: u32) -> u32 {
    let mut inv = m;
    for _ in 0..4 {
        inv = inv.wrapping_mul(2u32.wrapping_sub(m.wrapping_mul(inv)));
    }
    inv
}

impl TieRank {
    /// A bijection drawn from `rng` (three draws).
    pub fn new(rng: &mut SplitMix64) -> Self {
        let key = rng.next_u64() as u32;
        let mul1 = rng.next_u64() as u32 | 1;
        let mul2 = rng.next_u64() as u32 | 1;
        Self {
            key,
            mul1,
            mul2,
            inv1: inverse_mod_2_32(mul1),
            inv2: inverse_mod_2_32(mul2),
        }
    }

    /// The index whose rank is `r`: the inverse of [`TieRank::of`].
    #[inline(always)]
    pub fn index(&self, r: u32) -> u32 {
        let mut x = r ^ (r >> 15) ^ (r >> 30);
        x = x.wrapping_mul(self.inv2);
        x ^= x >> 16;
        x.wrapping_mul(self.inv1) ^ self.key
    }

    /// The rank of index `i`.
    #[inline(always)]
    pub fn of(&self, i: u32) -> u32 {
        let mut x = (i ^ self.key).wrapping_mul(self.mul1);
        x ^= x >> 16;
        x = x.wrapping_mul(self.mul2);
        x ^ (x >> 15)
    }
}

/// `m` distinct indices drawn uniformly from `0..n`, in draw order: the first `m` steps of a
/// forward Fisher–Yates shuffle, so a draw costs one random number however large `n` is.
pub fn sample_distinct(n: usize, m: usize, rng: &mut SplitMix64) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    let m = m.min(n);
    for i in 0..m {
        let j = i + rng.below((n - i) as u64) as usize;
        p.swap(i, j);
    }
    p.truncate(m);
    p
}

/// A uniformly random permutation of `0..n` (Fisher–Yates), as `u32`.
pub fn permutation(n: usize, rng: &mut SplitMix64) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        p.swap(i, j);
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tie_ranks_are_distinct() {
        let t = TieRank::new(&mut SplitMix64::new(3));
        let mut seen: Vec<u32> = (0..1 << 16).map(|i| t.of(i)).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 1 << 16);
    }

    #[test]
    fn index_inverts_the_rank() {
        let mut rng = SplitMix64::new(9);
        for _ in 0..8 {
            let t = TieRank::new(&mut rng);
            for _ in 0..1000 {
                let i = rng.next_u64() as u32;
                assert_eq!(t.index(t.of(i)), i);
                assert_eq!(t.of(t.index(i)), i);
            }
        }
    }

    #[test]
    fn below_is_in_range_and_covers_it() {
        let mut r = SplitMix64::new(1);
        let mut seen = [0u32; 7];
        for _ in 0..7000 {
            seen[r.below(7) as usize] += 1;
        }
        assert!(seen.iter().all(|&c| (850..1150).contains(&c)), "{seen:?}");
    }

    #[test]
    fn samples_are_distinct_and_uniform() {
        let mut r = SplitMix64::new(4);
        let mut hits = [0u32; 10];
        for _ in 0..3000 {
            let s = sample_distinct(10, 3, &mut r);
            let mut d = s.clone();
            d.sort_unstable();
            d.dedup();
            assert_eq!(d.len(), 3);
            s.iter().for_each(|&i| hits[i as usize] += 1);
        }
        // Each index is drawn with probability 3/10: 900 expected, σ ≈ 25.
        assert!(hits.iter().all(|&h| (800..1000).contains(&h)), "{hits:?}");
        assert_eq!(sample_distinct(4, 9, &mut r).len(), 4);
    }

    #[test]
    fn permutation_is_a_bijection() {
        let mut r = SplitMix64::new(3);
        let mut p = permutation(1000, &mut r);
        assert_ne!(p, (0..1000).collect::<Vec<u32>>());
        p.sort_unstable();
        assert_eq!(p, (0..1000).collect::<Vec<u32>>());
    }
}
