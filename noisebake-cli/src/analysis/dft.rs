//! Discrete Fourier transforms of any size in O(n log n) per line: a radix-2 FFT, and
//! Bluestein's chirp-z algorithm for lengths that are not powers of two. (A direct O(n²) DFT
//! is far too slow on the rows of the largest masks.)

/// Power spectrum `|X(kx, ky)|²` of a real `w × h` image (x fastest), mean removed.
pub fn power2d(img: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mean = img.iter().sum::<f64>() / img.len() as f64;
    let mut re: Vec<f64> = img.iter().map(|v| v - mean).collect();
    let mut im = vec![0.0; w * h];
    for y in 0..h {
        let r = y * w..(y + 1) * w;
        let (a, b) = dft(&re[r.clone()], &im[r.clone()]);
        re[r.clone()].copy_from_slice(&a);
        im[r].copy_from_slice(&b);
    }
    let mut out = vec![0.0; w * h];
    let (mut cr, mut ci) = (vec![0.0; h], vec![0.0; h]);
    for kx in 0..w {
        for y in 0..h {
            cr[y] = re[y * w + kx];
            ci[y] = im[y * w + kx];
        }
        let (a, b) = dft(&cr, &ci);
        for ky in 0..h {
            out[ky * w + kx] = a[ky] * a[ky] + b[ky] * b[ky];
        }
    }
    out
}

/// Power spectrum of a real sequence, mean removed.
pub fn power1d(seq: &[f64]) -> Vec<f64> {
    let n = seq.len();
    let mean = seq.iter().sum::<f64>() / n as f64;
    let re: Vec<f64> = seq.iter().map(|v| v - mean).collect();
    let (a, b) = dft(&re, &vec![0.0; n]);
    a.iter().zip(&b).map(|(a, b)| a * a + b * b).collect()
}

/// The DFT `X_k = Σ_t x_t e^{−2πi kt/n}` of any length in O(n log n): radix-2 for powers of
/// two, Bluestein's chirp-z otherwise (the DFT as a convolution with the chirp
/// `e^{iπk²/n}`, done by power-of-two FFTs).
pub fn dft(re: &[f64], im: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = re.len();
    if n <= 1 || n.is_power_of_two() {
        let (mut a, mut b) = (re.to_vec(), im.to_vec());
        fft(&mut a, &mut b, false);
        return (a, b);
    }
    let m = (2 * n - 1).next_power_of_two();
    // The chirp w_k = e^{−iπ k²/n}, with k² taken modulo 2n so the angle stays exact.
    let chirp: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let k2 = (k as u128 * k as u128 % (2 * n as u128)) as f64;
            let a = -std::f64::consts::PI * k2 / n as f64;
            (a.cos(), a.sin())
        })
        .collect();
    let (mut ar, mut ai) = (vec![0.0; m], vec![0.0; m]);
    for k in 0..n {
        let (c, s) = chirp[k];
        ar[k] = re[k] * c - im[k] * s;
        ai[k] = re[k] * s + im[k] * c;
    }
    let (mut br, mut bi) = (vec![0.0; m], vec![0.0; m]);
    for k in 0..n {
        let (c, s) = chirp[k];
        br[k] = c;
        bi[k] = -s;
        if k > 0 {
            br[m - k] = c;
            bi[m - k] = -s;
        }
    }
    fft(&mut ar, &mut ai, false);
    fft(&mut br, &mut bi, false);
    for k in 0..m {
        let (x, y) = (ar[k] * br[k] - ai[k] * bi[k], ar[k] * bi[k] + ai[k] * br[k]);
        ar[k] = x;
        ai[k] = y;
    }
    fft(&mut ar, &mut ai, true);
    let scale = 1.0 / m as f64;
    let (mut out_r, mut out_i) = (vec![0.0; n], vec![0.0; n]);
    for k in 0..n {
        let (c, s) = chirp[k];
        let (x, y) = (ar[k] * scale, ai[k] * scale);
        out_r[k] = x * c - y * s;
        out_i[k] = x * s + y * c;
    }
    (out_r, out_i)
}

/// In-place iterative radix-2 FFT (unscaled; `inverse` flips the exponent's sign). `re.len()`
/// must be a power of two.
fn fft(re: &mut [f64], im: &mut [f64], inverse: bool) {
    let n = re.len();
    if n <= 1 {
        return;
    }
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let a = sign * std::f64::consts::TAU / len as f64;
        // Twiddles computed directly per index, not by recurrence, to keep them accurate.
        let tw: Vec<(f64, f64)> = (0..len / 2)
            .map(|k| {
                let (s, c) = (a * k as f64).sin_cos();
                (c, s)
            })
            .collect();
        for start in (0..n).step_by(len) {
            for (k, &(c, s)) in tw.iter().enumerate() {
                let (i, l) = (start + k, start + k + len / 2);
                let (xr, xi) = (re[l] * c - im[l] * s, re[l] * s + im[l] * c);
                re[l] = re[i] - xr;
                im[l] = im[i] - xi;
                re[i] += xr;
                im[i] += xi;
            }
        }
        len <<= 1;
    }
}

/// Signed frequency of DFT bin `k` of `n`, in cycles per sample, in `(-0.5, 0.5]`.
pub fn freq(k: usize, n: usize) -> f64 {
    let k = if 2 * k > n {
        k as f64 - n as f64
    } else {
        k as f64
    };
    k / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct O(n²) DFT, the reference the fast one must match.
    fn direct(re: &[f64], im: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = re.len();
        (0..n)
            .map(|k| {
                let (mut a, mut b) = (0.0, 0.0);
                for t in 0..n {
                    let ang = -std::f64::consts::TAU * ((k * t) % n) as f64 / n as f64;
                    let (s, c) = ang.sin_cos();
                    a += re[t] * c - im[t] * s;
                    b += re[t] * s + im[t] * c;
                }
                (a, b)
            })
            .unzip()
    }

    #[test]
    fn fast_dft_matches_the_direct_sum_for_every_kind_of_length() {
        for n in [
            1usize, 2, 3, 5, 7, 8, 12, 16, 17, 31, 64, 100, 127, 128, 243,
        ] {
            let re: Vec<f64> = (0..n)
                .map(|i| ((i * 7919 + 3) % 101) as f64 / 50.0 - 1.0)
                .collect();
            let im: Vec<f64> = (0..n)
                .map(|i| ((i * 104_729) % 37) as f64 / 18.0 - 1.0)
                .collect();
            let (a, b) = dft(&re, &im);
            let (x, y) = direct(&re, &im);
            let err = a
                .iter()
                .zip(&x)
                .chain(b.iter().zip(&y))
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-9 * n as f64, "n = {n}: max error {err}");
        }
    }

    #[test]
    fn long_lines_are_fast() {
        // 2^17 and a prime near it: O(n²) would take minutes.
        for n in [1usize << 17, 131_071] {
            let seq: Vec<f64> = (0..n).map(|i| (i % 7) as f64).collect();
            let p = power1d(&seq);
            assert_eq!(p.len(), n);
            assert!(p.iter().all(|v| v.is_finite()));
        }
    }

    #[test]
    fn parseval_holds() {
        let img: Vec<f64> = (0..35).map(|i| ((i * 7919) % 13) as f64).collect();
        let mean = img.iter().sum::<f64>() / 35.0;
        let energy: f64 = img.iter().map(|v| (v - mean) * (v - mean)).sum();
        let p: f64 = power2d(&img, 7, 5).iter().sum();
        assert!((p / 35.0 - energy).abs() < 1e-9 * energy);
    }

    #[test]
    fn a_cosine_lands_in_its_bin() {
        let seq: Vec<f64> = (0..16)
            .map(|t| (std::f64::consts::TAU * 3.0 * t as f64 / 16.0).cos())
            .collect();
        let p = power1d(&seq);
        assert!(p[3] > 60.0 && p[13] > 60.0);
        assert!(
            p.iter()
                .enumerate()
                .all(|(k, &v)| k == 3 || k == 13 || v < 1e-9)
        );
    }
}
