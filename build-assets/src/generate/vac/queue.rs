//! The candidate queue of void and cluster: block minima under a tournament tree.
//!
//! Texels are grouped into blocks of [`BLOCK`] consecutive indices (a run along x). The
//! [`MinTree`] holds one key per block, at most the smallest key among the block's candidates
//! (a lazy lower bound), so its root bounds the best candidate of the whole mask. The engine
//! recomputes the top block until its key is exact ([`BlockQueue::top`], [`BlockQueue::set`])
//! and offers improved keys at once ([`BlockQueue::lower`]). A block's 32 energies fill four
//! cache lines that the prefetcher streams, and the tree has one leaf per 32 texels, so a
//! refresh is cheap and no step rescans the volume. (Measured on `report bench`'s sizes: 16 and 64
//! texels per block were slower, 8 much slower.)

use super::tree::{ABSENT, MinTree};

/// log2 of the block size.
pub const BLOCK_BITS: u32 = 5;
/// Texels per block.
pub const BLOCK: usize = 1 << BLOCK_BITS;

/// A min-queue over blocks of texels; the caller supplies each block's minimum key.
#[derive(Clone, Debug)]
pub struct BlockQueue {
    tree: MinTree,
}

impl BlockQueue {
    /// A queue over `n` texels; `block_min(b)` is the smallest candidate key in block `b`
    /// ([`ABSENT`] when the block holds no candidate).
    pub fn new(n: usize, block_min: impl Fn(usize) -> u64) -> Self {
        let blocks = n.div_ceil(BLOCK).max(1);
        Self {
            tree: MinTree::new((0..blocks).map(block_min)),
        }
    }

    /// The smallest key (the caller knows which texel, hence which block, it names).
    #[inline]
    pub fn top(&self) -> Option<u64> {
        let k = self.tree.min();
        (k != ABSENT).then_some(k)
    }

    /// The key of block `b`.
    #[inline]
    pub fn leaf(&self, b: usize) -> u64 {
        self.tree.get(b)
    }

    /// Offers `key` as a new minimum of block `b` (kept only if smaller).
    #[inline]
    pub fn lower(&mut self, b: usize, key: u64) {
        self.tree.lower(b, key);
    }

    /// Sets the minimum key of block `b`.
    #[inline]
    pub fn set(&mut self, b: usize, key: u64) {
        self.tree.set(b, key);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::rng::SplitMix64;

    #[test]
    fn best_tracks_block_minima() {
        // Keys carry a random score in the high 32 bits and the texel in the low 32.
        let mut rng = SplitMix64::new(2);
        let n = 3 * BLOCK + 5;
        let key = |rng: &mut SplitMix64, i: usize| (rng.next_u64() >> 33) << 32 | i as u64;
        let mut keys: Vec<u64> = (0..n).map(|i| key(&mut rng, i)).collect();
        let block_min = |keys: &[u64], b: usize| {
            keys[b * BLOCK..((b + 1) * BLOCK).min(n)]
                .iter()
                .copied()
                .min()
                .unwrap_or(ABSENT)
        };
        let mut q = BlockQueue::new(n, |b| block_min(&keys, b));
        for _ in 0..200 {
            assert_eq!(q.top(), keys.iter().copied().min());
            let i = rng.below(n as u64) as usize;
            keys[i] = key(&mut rng, i);
            q.set(i / BLOCK, block_min(&keys, i / BLOCK));
        }
        // Lowering keeps only smaller keys.
        let k = q.top().unwrap();
        let b = (k as u32) as usize / BLOCK;
        q.lower(b, k + 1);
        assert_eq!(q.top(), Some(k));
        assert_eq!(q.leaf(b), k);
        let other = (b + 1) % n.div_ceil(BLOCK);
        let smaller = ((k >> 32) - 1) << 32 | (other * BLOCK) as u64;
        q.lower(other, smaller);
        assert_eq!(q.top(), Some(smaller));
    }
}
