//! A tournament tree (implicit binary tree of subtree minima) over one `u64` key per leaf (per
//! block of texels, in [`super::queue::BlockQueue`]).
//!
//! Updating a leaf walks up only while the subtree minimum changes, and lowering one only while
//! the new key wins, so no step rescans the volume; the minimum is the root. Exact for keys that
//! move in either direction, so the same structure serves relaxation and phases I–III. (A 4-ary
//! tree with one cache line per sibling group halves the depth but measured slower.)

/// Keys of absent texels (on texels in the void tree, off texels in the cluster tree).
pub const ABSENT: u64 = u64::MAX;

/// A min-tournament tree over `n` keys.
#[derive(Clone, Debug)]
pub struct MinTree {
    leaves: usize,
    nodes: Vec<u64>,
}

impl MinTree {
    /// A tree over `keys` (one per texel).
    pub fn new(keys: impl ExactSizeIterator<Item = u64>) -> Self {
        let leaves = keys.len().next_power_of_two().max(2);
        let mut nodes = vec![ABSENT; 2 * leaves];
        for (i, k) in keys.enumerate() {
            nodes[leaves + i] = k;
        }
        for i in (1..leaves).rev() {
            nodes[i] = nodes[2 * i].min(nodes[2 * i + 1]);
        }
        Self { leaves, nodes }
    }

    /// The smallest key, or [`ABSENT`] when every key is absent.
    #[inline]
    pub fn min(&self) -> u64 {
        self.nodes[1]
    }

    /// Sets the key of texel `i`.
    #[inline]
    pub fn set(&mut self, i: usize, key: u64) {
        let mut at = self.leaves + i;
        self.nodes[at] = key;
        while at > 1 {
            // The winner's index by arithmetic, then one load: the comparison is a coin flip,
            // and LLVM turns a `min` of keys into a branch that mispredicts half the time.
            let win = at ^ (self.nodes[at ^ 1] < self.nodes[at]) as usize;
            let m = self.nodes[win];
            at >>= 1;
            if self.nodes[at] == m {
                break;
            }
            self.nodes[at] = m;
        }
    }
}

impl MinTree {
    /// The key of texel `i`.
    #[inline]
    pub fn get(&self, i: usize) -> u64 {
        self.nodes[self.leaves + i]
    }

    /// Lowers the key of texel `i` to `key` if that is smaller (a no-op otherwise).
    #[inline]
    pub fn lower(&mut self, i: usize, key: u64) {
        let mut at = self.leaves + i;
        while at >= 1 && self.nodes[at] > key {
            self.nodes[at] = key;
            at >>= 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::rng::SplitMix64;

    #[test]
    fn root_is_the_minimum_after_arbitrary_updates() {
        let mut rng = SplitMix64::new(5);
        let n = 1000;
        let mut keys: Vec<u64> = (0..n).map(|_| rng.next_u64()).collect();
        let mut t = MinTree::new(keys.iter().copied());
        for step in 0..20_000 {
            let i = rng.below(n as u64) as usize;
            keys[i] = if step % 7 == 0 {
                ABSENT
            } else {
                rng.next_u64()
            };
            t.set(i, keys[i]);
            assert_eq!(t.min(), *keys.iter().min().unwrap());
        }
    }
}
