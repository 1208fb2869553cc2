//! The figures of one run against its reference: RMSE over the measured frames, raw and after a
//! Gaussian of σ 1 px (what the eye sees), per surface class and over the whole image; the
//! flicker (the RMS of the frame-to-frame change of the Gaussian-filtered error); and the static
//! part (the RMS over pixels of the Gaussian-filtered error's mean over the measured frames):
//! what stays put, a bias per pixel that no longer averaging removes, against what a noise's
//! stratification can lower.

/// One frame: linear RGB, `w × h` pixels, row-major, top row first.
pub type Frame = Vec<[f32; 3]>;

/// The classes of surface a pixel can see, by the code the class run writes.
pub const CLASSES: [(&str, u32); 8] = [
    ("pane 30 %", 1),
    ("card 10 %", 2),
    ("card 25 %", 3),
    ("card 50 %", 4),
    ("card 75 %", 5),
    ("card 90 %", 6),
    ("fog", 7),
    ("image", 0),
];

/// Per pixel, the class code a class frame shows (green channel × 16, rounded; 0: none).
pub fn classes(frame: &Frame) -> Vec<u32> {
    frame
        .iter()
        .map(|p| {
            let c = p[1] * 16.0;
            if (c - c.round()).abs() < 0.2 && p[0].abs() < 0.05 {
                c.round().clamp(0.0, 15.0) as u32
            } else {
                0
            }
        })
        .collect()
}

/// A Gaussian of σ 1 px (9 taps, normalised), borders clamped.
pub fn gauss(frame: &Frame, w: usize, h: usize) -> Frame {
    let taps: [f32; 9] = core::array::from_fn(|i| (-0.5 * (i as f32 - 4.0).powi(2)).exp());
    let sum: f32 = taps.iter().sum();
    let pass = |src: &Frame, dx: isize, dy: isize| -> Frame {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as isize, (i / w) as isize);
                let mut out = [0.0f32; 3];
                for (k, t) in taps.iter().enumerate() {
                    let o = k as isize - 4;
                    let xx = (x + o * dx).clamp(0, w as isize - 1) as usize;
                    let yy = (y + o * dy).clamp(0, h as isize - 1) as usize;
                    let p = src[yy * w + xx];
                    for c in 0..3 {
                        out[c] += t / sum * p[c];
                    }
                }
                out
            })
            .collect()
    };
    pass(&pass(frame, 1, 0), 0, 1)
}

/// What one noise left under one camera path.
#[derive(Clone, Debug, Default)]
pub struct Figures {
    /// Per class of [`CLASSES`]: RMSE raw and after the Gaussian, over the class's pixels and
    /// the measured frames (`NaN` where no pixel shows the class).
    pub rmse: Vec<[f64; 2]>,
    /// Per class: the flicker, RMS of the change of the Gaussian-filtered error from one
    /// measured frame to the next.
    pub flicker: Vec<f64>,
    /// Per class: the static part, RMS over the class's pixels (in the last measured frame) of
    /// the Gaussian-filtered error's mean over the measured frames.
    pub static_part: Vec<f64>,
}

/// The figures of `frames` against `reference`, over frames `measured` (the class map of each
/// frame in `class_maps`).
pub fn figures(
    frames: &[Frame],
    reference: &[Frame],
    class_maps: &[Vec<u32>],
    measured: std::ops::Range<usize>,
    w: usize,
    h: usize,
) -> Figures {
    let n = CLASSES.len();
    let (mut raw, mut filtered, mut flick) = (vec![0.0f64; n], vec![0.0f64; n], vec![0.0f64; n]);
    let (mut count, mut flick_count) = (vec![0usize; n], vec![0usize; n]);
    let mut previous: Option<Frame> = None;
    let mut mean = vec![[0.0f64; 3]; w * h];
    let frames_measured = measured.len();
    let last = measured.end.saturating_sub(1);
    for f in measured {
        let err: Frame = frames[f]
            .iter()
            .zip(&reference[f])
            .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2]])
            .collect();
        let g = gauss(&err, w, h);
        for (m, p) in mean.iter_mut().zip(&g) {
            for c in 0..3 {
                m[c] += f64::from(p[c]) / frames_measured as f64;
            }
        }
        for (i, class) in class_maps[f].iter().enumerate() {
            for (k, &(_, code)) in CLASSES.iter().enumerate() {
                if code != 0 && code != *class {
                    continue;
                }
                count[k] += 3;
                for c in 0..3 {
                    raw[k] += f64::from(err[i][c]).powi(2);
                    filtered[k] += f64::from(g[i][c]).powi(2);
                }
                if let Some(p) = &previous {
                    flick_count[k] += 3;
                    for c in 0..3 {
                        flick[k] += f64::from(g[i][c] - p[i][c]).powi(2);
                    }
                }
            }
        }
        previous = Some(g);
    }
    let rms = |s: f64, n: usize| {
        if n == 0 {
            f64::NAN
        } else {
            (s / n as f64).sqrt()
        }
    };
    let (mut stat, mut stat_count) = (vec![0.0f64; n], vec![0usize; n]);
    if frames_measured > 0 {
        for (i, class) in class_maps[last].iter().enumerate() {
            for (k, &(_, code)) in CLASSES.iter().enumerate() {
                if code != 0 && code != *class {
                    continue;
                }
                stat_count[k] += 3;
                stat[k] += mean[i].iter().map(|v| v * v).sum::<f64>();
            }
        }
    }
    Figures {
        static_part: (0..n).map(|k| rms(stat[k], stat_count[k])).collect(),
        rmse: (0..n)
            .map(|k| [rms(raw[k], count[k]), rms(filtered[k], count[k])])
            .collect(),
        flicker: (0..n).map(|k| rms(flick[k], flick_count[k])).collect(),
    }
}

/// The frames as float32 `(frames, H, W, 3)` in a `.npy`.
pub fn npy(frames: &[Frame], w: usize, h: usize) -> Vec<u8> {
    let data: Vec<f32> = frames.iter().flatten().flatten().copied().collect();
    build_assets::export::npy::f32_array(&[frames.len(), h, w, 3], &data)
}
