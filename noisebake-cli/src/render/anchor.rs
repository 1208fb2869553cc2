//! An experiment `noisebake report render` measures (`… + anchor` rows): a per-pixel anchor a
//! renderer would carry through its reprojection, as it carries the history, so that a
//! screen-space table keeps its temporal structure while the camera moves. Measured, it does
//! not (the report's rows say by how much), so it is not in the runtime; it stays here as the
//! measured mechanism to beat.
//!
//! A screen-anchored table gives pixel `p` in frame `f` the sample `S(p, f)`. With a still
//! camera a surface stays on one pixel and its history averages one pixel's sequence. When the
//! picture moves, the history of a surface is fed by the pixels along its path,
//! `S(p_0 + v·f, f)`: points of different pixels' sequences. An [`Anchor`] is the picture's
//! displacement `D` since the surface was first seen, in fixed point (1/128 px); the table is
//! read at `p − round(D)` instead of `p`.
//!
//! Each frame, pixel `p` whose surface was at `prev` a frame ago (its motion vector, pixel
//! centres at integers) takes the anchor of the pixel nearest `prev` (clamped to the image,
//! visible there or not), adds `p − prev`, and reads the table at [`Anchor::pixel`]. Why it
//! fails: under a sub-pixel pan, the rounding of `D` makes neighbouring surfaces alternate
//! between two to four anchored pixels, so no surface keeps one pixel's sequence; under
//! parallax the anchored pixels repeat and skip where the picture stretches, which breaks
//! the spatial arrangement a frame's denoiser relies on. 4 bytes a pixel.

/// A pixel's anchor: the picture's displacement since its surface was first seen, two 16-bit
/// two's-complement fixed-point numbers in 1/128 pixel (`x` in the low half, `y` in the high).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Anchor(pub u32);

/// Fractional bits of an [`Anchor`]'s displacement.
pub const ANCHOR_FRACTION_BITS: u32 = 7;

impl Anchor {
    /// No displacement: the screen pixel itself (frame 0, a new image).
    pub const START: Anchor = Anchor(0);

    /// The displacement `(x, y)` in 1/128 pixel.
    #[must_use]
    #[inline(always)]
    pub const fn displacement(self) -> [i32; 2] {
        [
            self.0 as u16 as i16 as i32,
            (self.0 >> 16) as u16 as i16 as i32,
        ]
    }

    /// The anchor of pixel `(x, y)` whose surface was at `prev` (continuous pixel position,
    /// pixel centres at integers) in the previous frame, where that frame's anchor (at the
    /// pixel nearest `prev`) was `self`: the displacement grows by `(x, y) − prev`, rounded to
    /// 1/128 pixel (`floor((p − prev) · 128 + ½)`, exact in `f32` for motions below 2^16
    /// pixels), and wraps at ±256 pixels.
    #[must_use]
    #[inline(always)]
    pub fn follow(self, x: i32, y: i32, prev: [f32; 2]) -> Anchor {
        let step = |p: i32, q: f32| {
            let d = (p as f32 - q) * 128.0 + 0.5;
            // NaN and motions beyond the range leave the displacement as it was.
            if d.abs() < 8_388_608.0 {
                floor(d) as i32
            } else {
                0
            }
        };
        let [dx, dy] = self.displacement();
        let nx = dx.wrapping_add(step(x, prev[0])) as u16 as u32;
        let ny = dy.wrapping_add(step(y, prev[1])) as u16 as u32;
        Anchor(nx | ny << 16)
    }

    /// The pixel a screen-space table is read at for pixel `(x, y)`: `(x, y) − round(D)`.
    #[must_use]
    #[inline(always)]
    pub const fn pixel(self, x: i32, y: i32) -> [i32; 2] {
        let [dx, dy] = self.displacement();
        let half = 1 << (ANCHOR_FRACTION_BITS - 1);
        [
            x.wrapping_sub((dx + half) >> ANCHOR_FRACTION_BITS),
            y.wrapping_sub((dy + half) >> ANCHOR_FRACTION_BITS),
        ]
    }
}

fn floor(v: f32) -> f32 {
    v.floor()
}

/// The pixel whose anchor a frame reads for the continuous position `prev` in a `w × h`
/// image: the nearest pixel centre, clamped to the image (the first step of a frame).
#[must_use]
#[inline(always)]
pub fn nearest_pixel(prev: [f32; 2], w: u32, h: u32) -> [u32; 2] {
    let near = |v: f32, n: u32| {
        // NaN and infinities read pixel 0 (WGSL has no isNan: `abs(v) < 3e38` is its test).
        let r = floor(
            if v.abs() < 3.0e38 {
                v.clamp(-1.0, n as f32)
            } else {
                0.0
            } + 0.5,
        );
        (r.max(0.0) as u32).min(n - 1)
    };
    [near(prev[0], w), near(prev[1], h)]
}

/// One frame of the carry over a `w × h` image: each pixel's anchor from the previous
/// frame's `anchors` and its motion `prev` (row-major, `(x, y)` positions in the previous
/// frame), written to `out`.
///
/// # Panics
///
/// If the slices are not `w · h` long.
pub fn follow_frame(anchors: &[Anchor], prev: &[[f32; 2]], w: u32, h: u32, out: &mut [Anchor]) {
    let n = (w * h) as usize;
    assert!(
        anchors.len() == n && prev.len() == n && out.len() == n,
        "w · h anchors"
    );
    for (i, o) in out.iter_mut().enumerate() {
        let (x, y) = ((i as u32 % w) as i32, (i as u32 / w) as i32);
        let [nx, ny] = nearest_pixel(prev[i], w, h);
        *o = anchors[(ny * w + nx) as usize].follow(x, y, prev[i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniform sub-pixel pan: every pixel's anchored pixel moves with the picture, so a
    /// surface point keeps the anchored pixel it was first seen at, up to the rounding of its
    /// own sub-pixel position (within one pixel), frame after frame.
    #[test]
    fn a_pan_keeps_each_surface_on_its_anchored_pixel() {
        let (w, h) = (24u32, 16u32);
        let v = [0.37f32, -0.81];
        let mut anchors = vec![Anchor::START; (w * h) as usize];
        let mut next = anchors.clone();
        for f in 1..100 {
            // The surface at pixel p was at p + v a frame ago (the picture moves by −v).
            let prev: Vec<[f32; 2]> = (0..w * h)
                .map(|i| [(i % w) as f32 + v[0], (i / w) as f32 + v[1]])
                .collect();
            follow_frame(&anchors, &prev, w, h, &mut next);
            core::mem::swap(&mut anchors, &mut next);
            // Every anchor holds the same displacement: f·(−v) to 1/128 px a frame.
            let d = anchors[0].displacement();
            assert!(anchors.iter().all(|a| a.displacement() == d), "frame {f}");
            for k in 0..2 {
                let want = -v[k] * f as f32 * 128.0;
                assert!(
                    (d[k] as f32 - want).abs() <= f as f32 * 0.5 + 1.0,
                    "{f}: {d:?}"
                );
            }
            // The surface point first seen at pixel (5, 7) is now at (5, 7) − f·v: the
            // pixel nearest it reads (5, 7) or a neighbour.
            let (sx, sy) = (5.0 - v[0] * f as f32, 7.0 - v[1] * f as f32);
            let [ax, ay] = Anchor(anchors[0].0).pixel(sx.round() as i32, sy.round() as i32);
            assert!(
                (ax - 5).abs() <= 1 && (ay - 7).abs() <= 1,
                "{f}: ({ax}, {ay})"
            );
        }
    }

    /// The fixed point: displacements wrap at ±256 px, and pixel() rounds to nearest.
    #[test]
    fn displacement_rounds_and_wraps() {
        let a = Anchor::START.follow(10, 4, [9.4, 4.6]);
        // (10 − 9.4)·128 = 76.8 and (4 − 4.6)·128 = −76.8, rounded to nearest.
        assert_eq!(a.displacement(), [77, -77]);
        // The surface came from (9.4, 4.6): the table is read at the pixel nearest that.
        assert_eq!(a.pixel(10, 4), [9, 5]);
        let b = Anchor::START.follow(300, 0, [0.0, 0.0]);
        // 300 px is 38400 units, which wraps to 38400 − 65536 = −27136 (−212 px).
        assert_eq!(b.displacement()[0], -27136);
        assert_eq!(b.pixel(0, 0), [212, 0]);
        // NaN and absurd motions leave the anchor unchanged.
        assert_eq!(a.follow(0, 0, [f32::NAN, 1e30]), a);
    }

    #[test]
    fn nearest_pixel_clamps() {
        assert_eq!(nearest_pixel([-3.0, 2.49], 8, 4), [0, 2]);
        assert_eq!(nearest_pixel([7.6, 3.5], 8, 4), [7, 3]);
        assert_eq!(nearest_pixel([f32::NAN, f32::INFINITY], 8, 4), [0, 0]);
    }
}
