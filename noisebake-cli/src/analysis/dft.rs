//! Discrete Fourier transforms of any size (separable direct DFT with twiddle tables).
//! Analysis masks are at most a few hundred texels per axis, where O(n²) per line is fast enough
//! and exact for every size, powers of two or not.

/// Power spectrum `|X(kx, ky)|²` of a real `w × h` image (x fastest), mean removed.
pub fn power2d(img: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mean = img.iter().sum::<f64>() / img.len() as f64;
    let (cw, sw) = twiddles(w);
    let (ch, sh) = twiddles(h);
    // Rows: (re, im) per (y, kx).
    let mut rows = vec![(0.0, 0.0); w * h];
    for y in 0..h {
        let row = &img[y * w..(y + 1) * w];
        for kx in 0..w {
            let (mut re, mut im) = (0.0, 0.0);
            for (x, &v) in row.iter().enumerate() {
                let i = (kx * x) % w;
                re += (v - mean) * cw[i];
                im -= (v - mean) * sw[i];
            }
            rows[y * w + kx] = (re, im);
        }
    }
    let mut out = vec![0.0; w * h];
    for kx in 0..w {
        for ky in 0..h {
            let (mut re, mut im) = (0.0, 0.0);
            for y in 0..h {
                let i = (ky * y) % h;
                let (a, b) = rows[y * w + kx];
                // (a + ib)(c − is)
                re += a * ch[i] + b * sh[i];
                im += b * ch[i] - a * sh[i];
            }
            out[ky * w + kx] = re * re + im * im;
        }
    }
    out
}

/// Power spectrum of a real sequence, mean removed.
pub fn power1d(seq: &[f64]) -> Vec<f64> {
    let n = seq.len();
    let mean = seq.iter().sum::<f64>() / n as f64;
    let (c, s) = twiddles(n);
    (0..n)
        .map(|k| {
            let (mut re, mut im) = (0.0, 0.0);
            for (t, &v) in seq.iter().enumerate() {
                let i = (k * t) % n;
                re += (v - mean) * c[i];
                im -= (v - mean) * s[i];
            }
            re * re + im * im
        })
        .collect()
}

fn twiddles(n: usize) -> (Vec<f64>, Vec<f64>) {
    let a = |i: usize| std::f64::consts::TAU * i as f64 / n as f64;
    (
        (0..n).map(|i| a(i).cos()).collect(),
        (0..n).map(|i| a(i).sin()).collect(),
    )
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
