//! Under TAA ([`TemporalFilter::Taa`](super::TemporalFilter::Taa)): the 3 × 3 windows of a
//! scalar mask's slices that the history clamp reads, counting the open ones and closing them.
//!
//! A window is *open* when it lacks a value below the coverage or one at or above one less it:
//! there the clamp's neighbourhood min/max of a dither at some coverage in `[c, 1 − c]` is
//! degenerate, and the clamp cuts the history off. The optimiser keeps windows closed as it
//! swaps (`optimize`), but it only tries partners its tiles offer; [`repair`] finishes the job
//! with swaps anywhere in a slice, and [`open_windows`] is what a bake reports.

/// How many 3 × 3 windows (wrapping) of the scalar `values` (`w × h × t`, x fastest) lack a
/// value below `coverage` or one at or above `1 − coverage`, over all slices. A `taa` bake
/// drives this to 0 when it can.
pub fn open_windows(values: &[f64], [w, h, t]: [usize; 3], coverage: f64) -> u64 {
    let mut open = 0;
    for f in 0..t {
        let slice = &values[f * w * h..][..w * h];
        for y in 0..h {
            for x in 0..w {
                let (mut low, mut high) = (false, false);
                for dy in [h - 1, 0, 1] {
                    for dx in [w - 1, 0, 1] {
                        let v = slice[((y + dy) % h) * w + (x + dx) % w];
                        low |= v < coverage;
                        high |= v >= 1.0 - coverage;
                    }
                }
                open += u64::from(!(low && high));
            }
        }
    }
    open
}

/// Closes the windows a `taa` mask's stored texels leave open ([`repair`] on the values as
/// stored, each swap applied to the texels too), so what is counted afterwards
/// ([`crate::generate::open_windows_of`]) is what the repair saw: the unorm formats round a
/// slice's ranks down by up to `1/N` plus a step, which moves values near the coverage across
/// it. `data` holds one scalar texel per value.
pub fn repair_stored(data: &mut [u8], values: &mut [f64], dims: [usize; 3], coverage: f64) {
    let bytes = data.len() / values.len().max(1);
    let [w, h, t] = dims;
    for f in 0..t {
        let base = f * w * h;
        for (a, b) in repair_slice(&mut values[base..][..w * h], w, h, coverage) {
            for k in 0..bytes {
                data.swap((base + a) * bytes + k, (base + b) * bytes + k);
            }
        }
    }
}

/// Closes open windows by swapping values within a slice (so each slice keeps its values, and
/// its histogram): for each open window, the swap of one of its texels with a texel of the
/// class it lacks, anywhere in the slice, that fills the most missing classes in all (the
/// windows of both texels recounted; a window lacking both a low and a high value lacks two),
/// ties broken by the smaller change of value. A swap that fills no more than it empties is
/// never made, so the count only falls. Deterministic.
pub fn repair(values: &mut [f64], [w, h, t]: [usize; 3], coverage: f64) {
    for f in 0..t {
        repair_slice(&mut values[f * w * h..][..w * h], w, h, coverage);
    }
}

/// The 9 texels of the window centred on `i` (wrapping).
fn window(i: usize, w: usize, h: usize) -> [usize; 9] {
    let (x, y) = (i % w, i / w);
    let mut out = [0; 9];
    let mut k = 0;
    for dy in [h - 1, 0, 1] {
        for dx in [w - 1, 0, 1] {
            out[k] = ((y + dy) % h) * w + (x + dx) % w;
            k += 1;
        }
    }
    out
}

/// The swaps made, in order, as pairs of indices into the slice.
fn repair_slice(s: &mut [f64], w: usize, h: usize, coverage: f64) -> Vec<(usize, usize)> {
    let mut swaps = Vec::new();
    let n = w * h;
    let low = |v: f64| v < coverage;
    let high = |v: f64| v >= 1.0 - coverage;
    // A window is open unless it holds a low and a high value.
    let is_open = |s: &[f64], c: usize| {
        let win = window(c, w, h);
        !(win.iter().any(|&j| low(s[j])) && win.iter().any(|&j| high(s[j])))
    };
    // The classes missing from the windows of texels `a` and `b` (a window is centred within
    // one texel of a member, so these are the windows a swap of `a` and `b` can change),
    // summed: a window lacking both a low and a high value counts twice, so the first of the
    // two swaps it needs already counts as progress.
    let local_missing = |s: &[f64], a: usize, b: usize| -> usize {
        let mut centres: Vec<usize> = window(a, w, h).into_iter().chain(window(b, w, h)).collect();
        centres.sort_unstable();
        centres.dedup();
        centres
            .into_iter()
            .map(|c| {
                let win = window(c, w, h);
                usize::from(!win.iter().any(|&j| low(s[j])))
                    + usize::from(!win.iter().any(|&j| high(s[j])))
            })
            .sum()
    };
    // Each pass visits every window once; a pass that closes none ends the repair.
    for _ in 0..8 {
        let mut closed_any = false;
        for c in 0..n {
            if !is_open(s, c) {
                continue;
            }
            let win = window(c, w, h);
            let lacks_low = !win.iter().any(|&j| low(s[j]));
            let wanted = |v: f64| if lacks_low { low(v) } else { high(v) };
            let mut best: Option<(usize, f64, usize, usize)> = None;
            for &a in &win {
                if wanted(s[a]) {
                    continue;
                }
                for b in 0..n {
                    if !wanted(s[b]) || win.contains(&b) {
                        continue;
                    }
                    let before = local_missing(s, a, b);
                    s.swap(a, b);
                    let after = local_missing(s, a, b);
                    s.swap(a, b);
                    if after >= before {
                        continue;
                    }
                    let gain = before - after;
                    let change = (s[a] - s[b]).abs();
                    let better = match best {
                        None => true,
                        Some((g, ch, _, _)) => gain > g || (gain == g && change < ch),
                    };
                    if better {
                        best = Some((gain, change, a, b));
                    }
                }
            }
            if let Some((_, _, a, b)) = best {
                s.swap(a, b);
                swaps.push((a, b));
                closed_any = true;
            }
        }
        if !closed_any {
            break;
        }
    }
    swaps
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::rng::SplitMix64;
    use crate::spec::fast::texels_to_cover;

    /// A random slice's open windows fall to zero when the classes are ample, and the repair
    /// keeps the slice's values (a permutation).
    #[test]
    fn repair_closes_windows_and_keeps_the_values() {
        let (w, h, t) = (16, 12, 2);
        let mut rng = SplitMix64::new(3);
        let mut v: Vec<f64> = (0..w * h * t).map(|_| rng.unit_f64()).collect();
        // Each slice sorted: its lows fill the top rows and its highs the bottom ones, so
        // every window of the middle rows is open.
        for slice in v.chunks_mut(w * h) {
            slice.sort_by(f64::total_cmp);
        }
        let before = open_windows(&v, [w, h, t], 0.2);
        assert!(before > 50, "{before}");
        let mut sorted_before = v.clone();
        sorted_before.sort_by(f64::total_cmp);
        repair(&mut v, [w, h, t], 0.2);
        assert_eq!(open_windows(&v, [w, h, t], 0.2), 0);
        let mut sorted_after = v.clone();
        sorted_after.sort_by(f64::total_cmp);
        assert_eq!(sorted_before, sorted_after);
    }

    /// Fewer lows than a cover needs cannot close every window, and the repair never opens
    /// more than there were.
    #[test]
    fn too_few_values_leave_windows_open() {
        let (w, h) = (9, 9);
        assert_eq!(texels_to_cover(w, h), 9);
        assert_eq!(texels_to_cover(5, 3), 2);
        // 8 lows (values 0.01) and plenty of highs: at least one window stays open.
        let mut v: Vec<f64> = (0..w * h)
            .map(|i| if i < 8 { 0.01 } else { 0.95 })
            .collect();
        let before = open_windows(&v, [w, h, 1], 0.1);
        repair(&mut v, [w, h, 1], 0.1);
        let after = open_windows(&v, [w, h, 1], 0.1);
        assert!(after > 0 && after <= before, "{before} -> {after}");
    }
}
