//! The candidate queue of void and cluster: lazy keys in per-chunk binary heaps under a
//! tournament tree of chunk minima.
//!
//! Texels are split into chunks of [`CHUNK`] consecutive indices, each with its own binary heap,
//! so the heap a step works in (and the texel records it validates) stay cache-resident; the
//! global minimum is the root of a small [`MinTree`] over the chunks' tops.
//!
//! Keys are *lazy*: a texel's queued key may be stale. The engine pushes a fresh key whenever a
//! texel gets better (so some queued key is always at most the true key) and refreshes a stale key
//! in place when it reaches the top ([`CandidateQueue::refresh_top`]). The popped minimum is
//! exact: the root is at most every candidate's true key and, once validated, equals its own.

use super::tree::{ABSENT, MinTree};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// log2 of the chunk size.
const CHUNK_BITS: u32 = 14;
/// Texels per chunk (16 Ki: 256 KiB of heap, 256 KiB of texel records).
pub const CHUNK: usize = 1 << CHUNK_BITS;

/// Index of the texel a key refers to (the low 32 bits).
#[inline(always)]
pub fn key_index(k: u128) -> usize {
    (k as u32) as usize
}

/// A min-queue of lazy `u128` keys.
#[derive(Debug)]
pub struct CandidateQueue {
    heaps: Vec<BinaryHeap<Reverse<u128>>>,
    top: MinTree,
    len: usize,
}

impl CandidateQueue {
    /// A queue over `n` texels holding `keys`.
    pub fn new(n: usize, keys: impl Iterator<Item = u128>) -> Self {
        let chunks = n.div_ceil(CHUNK).max(1);
        let mut lists: Vec<Vec<Reverse<u128>>> = vec![Vec::new(); chunks];
        let mut len = 0;
        for k in keys {
            lists[key_index(k) >> CHUNK_BITS].push(Reverse(k));
            len += 1;
        }
        let heaps: Vec<BinaryHeap<Reverse<u128>>> =
            lists.into_iter().map(BinaryHeap::from).collect();
        let top = MinTree::new(
            heaps
                .iter()
                .map(|h| h.peek().map_or(ABSENT, |r| r.0))
                .collect::<Vec<_>>()
                .into_iter(),
        );
        Self { heaps, top, len }
    }

    /// The smallest queued key, or `None` when empty.
    #[inline]
    pub fn peek(&self) -> Option<u128> {
        let k = self.top.min();
        (k != ABSENT).then_some(k)
    }

    /// Number of queued keys (stale ones included).
    pub fn len(&self) -> usize {
        self.len
    }

    #[inline]
    fn sync(&mut self, c: usize) {
        let k = self.heaps[c].peek().map_or(ABSENT, |r| r.0);
        self.top.set(c, k);
    }

    /// Queues a key.
    #[inline]
    pub fn push(&mut self, k: u128) {
        let c = key_index(k) >> CHUNK_BITS;
        self.heaps[c].push(Reverse(k));
        self.len += 1;
        if self.heaps[c].peek() == Some(&Reverse(k)) {
            self.top.set(c, k);
        }
    }

    /// Removes the smallest key (the one [`peek`](Self::peek) returned).
    #[inline]
    pub fn pop(&mut self) {
        let Some(k) = self.peek() else { return };
        let c = key_index(k) >> CHUNK_BITS;
        self.heaps[c].pop();
        self.len -= 1;
        self.sync(c);
    }

    /// Replaces the smallest key by `fresh` (a larger key of the same texel) in place.
    #[inline]
    pub fn refresh_top(&mut self, fresh: u128) {
        let Some(k) = self.peek() else { return };
        let c = key_index(k) >> CHUNK_BITS;
        if let Some(mut top) = self.heaps[c].peek_mut() {
            *top = Reverse(fresh);
        }
        self.sync(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn pops_in_order() {
        let mut rng = SplitMix64::new(2);
        let n = 3 * CHUNK + 17;
        let keys: Vec<u128> = (0..n)
            .map(|i| (rng.next_u64() as u128) << 64 | i as u128)
            .collect();
        let mut q = CandidateQueue::new(n, keys.iter().copied());
        let mut sorted = keys.clone();
        sorted.sort_unstable();
        for &k in &sorted {
            assert_eq!(q.peek(), Some(k));
            q.pop();
        }
        assert_eq!(q.peek(), None);
    }
}
