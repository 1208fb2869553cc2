//! Moving cameras for `noisebake report render`, as a game's accumulation sees them: every
//! frame traced anew from the camera of that frame, the history reprojected by motion vectors
//! (bilinear, each tap kept only where it sees the same surface: a plane-distance and a normal
//! test, as SVGF's reprojection does) and reset where no tap survives (disocclusion, the
//! border).
//!
//! - [`Motion::Pan`]: the image plane moves by a sub-pixel velocity in any direction (a lens
//!   shift: the image moves uniformly, as it does under a small yaw and pitch), sweeping out
//!   and back;
//! - [`Motion::Parallax`]: the eye trucks sideways and dollies forward and back: near surfaces
//!   move more than far ones, the image magnifies and minifies, surfaces disocclude behind
//!   the boxes and columns;
//! - [`Motion::Yaw`]: the camera turns about its eye, left and back (the picture moves
//!   sideways, faster at the edges, with no parallax);
//! - [`Motion::Dolly`]: the eye moves along the view, in and back out (the picture grows
//!   from its centre, near surfaces faster).
//!
//! `report render` measures a pan and the parallax with every sampler, and with `--held-out`
//! also a fast pan, the yaw and the dolly: motions the search behind `motion_pairs` never saw
//! (it saw pans of up to 4 pixels a frame, in the model of `noisebake_cli::motion_search`).

use super::scene::{Camera, Scene};
use super::trace::Tracer;
use super::{GBuffer, View};
use glam::Vec3;
use rayon::prelude::*;

/// A camera path over frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// The image moves by `velocity` pixels a frame for `sweep` frames, then back (named
    /// `pan`, or `fast pan` from 4 pixels a frame).
    Pan {
        /// Pixels a frame, `(x, y)`; the picture moves by minus this.
        velocity: [f32; 2],
        /// Frames each way.
        sweep: u32,
    },
    /// The eye moves `truck` scene units a frame sideways (the target with it) for `sweep`
    /// frames and back, and `dolly` units a frame along the view for `sweep · 3 / 2` frames
    /// and back.
    Parallax {
        /// Sideways, in units of the scene's AO radius a frame.
        truck: f32,
        /// Forward, in units of the scene's AO radius a frame.
        dolly: f32,
        /// Frames each way of the truck.
        sweep: u32,
    },
    /// The camera turns `turn` radians a frame about the vertical through its eye for `sweep`
    /// frames, then back.
    Yaw {
        /// Radians a frame.
        turn: f32,
        /// Frames each way.
        sweep: u32,
    },
    /// The eye moves `speed` (in units of the scene's AO radius) a frame along the view for
    /// `sweep` frames, then back.
    Dolly {
        /// Units of the AO radius a frame.
        speed: f32,
        /// Frames each way.
        sweep: u32,
    },
}

/// `0, 1, …, n, n − 1, …, 0, 1, …`: a sweep out and back.
pub fn triangle(frame: u32, n: u32) -> f32 {
    let p = frame % (2 * n);
    (if p > n { 2 * n - p } else { p }) as f32
}

impl Motion {
    /// The report's name of the motion.
    pub fn name(&self) -> &'static str {
        match self {
            Motion::Pan { velocity, .. } if velocity[0].hypot(velocity[1]) >= 4.0 => "fast pan",
            Motion::Pan { .. } => "pan",
            Motion::Parallax { .. } => "parallax",
            Motion::Yaw { .. } => "yaw",
            Motion::Dolly { .. } => "dolly",
        }
    }

    /// The view in `frame` of a scene whose still camera is `camera`, AO radius `scale`.
    pub fn view(&self, camera: Camera, scale: f32, frame: u32) -> View {
        match *self {
            Motion::Pan { velocity, sweep } => {
                let t = triangle(frame, sweep);
                View {
                    camera,
                    shift: [velocity[0] * t, velocity[1] * t],
                }
            }
            Motion::Parallax {
                truck,
                dolly,
                sweep,
            } => {
                let forward = (camera.target - camera.eye).normalize();
                let right = forward.cross(Vec3::Y).normalize();
                let side = right * (truck * scale * triangle(frame, sweep));
                let ahead = forward * (dolly * scale * triangle(frame, sweep * 3 / 2));
                View {
                    camera: Camera {
                        eye: camera.eye + side + ahead,
                        target: camera.target + side,
                        fov_y: camera.fov_y,
                    },
                    shift: [0.0, 0.0],
                }
            }
            Motion::Yaw { turn, sweep } => {
                let angle = turn * triangle(frame, sweep);
                let d = camera.target - camera.eye;
                let (s, c) = angle.sin_cos();
                let turned = Vec3::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
                View {
                    camera: Camera {
                        target: camera.eye + turned,
                        ..camera
                    },
                    shift: [0.0, 0.0],
                }
            }
            Motion::Dolly { speed, sweep } => {
                let forward = (camera.target - camera.eye).normalize();
                let ahead = forward * (speed * scale * triangle(frame, sweep));
                View {
                    camera: Camera {
                        eye: camera.eye + ahead,
                        target: camera.target + ahead,
                        fov_y: camera.fov_y,
                    },
                    shift: [0.0, 0.0],
                }
            }
        }
    }
}

/// How a frame's pixels find their history in the frame before: per pixel, the continuous
/// position of its surface in the previous frame (its motion vector), and the bilinear taps
/// that see the same surface there, with weights summing to 1 (none: the history resets).
#[derive(Clone, Debug)]
pub struct Reprojection {
    /// Per pixel, `(x, y)` in the previous frame, pixel centres at integers.
    pub prev: Vec<[f32; 2]>,
    /// Per pixel, up to four `(pixel, weight)` taps in the previous frame.
    pub taps: Vec<Vec<(u32, f32)>>,
}

/// Largest distance of a tap's surface point from the plane of the pixel's, relative to the
/// pixel's distance from the previous eye.
const PLANE: f32 = 0.02;
/// Smallest cosine between a tap's normal and the pixel's.
const NORMAL: f32 = 0.9;

impl Reprojection {
    /// The reprojection of `now` (seen from `view`) into `before` (seen from `prev_view`).
    pub fn new(now: &GBuffer, before: &GBuffer, prev_view: &View) -> Reprojection {
        let (w, h) = (now.width, now.height);
        let eye = prev_view.camera.eye;
        type Row = (Vec<[f32; 2]>, Vec<Vec<(u32, f32)>>);
        let rows: Vec<Row> = (0..h)
            .into_par_iter()
            .map(|y| {
                let mut prev = Vec::with_capacity(w);
                let mut taps = Vec::with_capacity(w);
                for x in 0..w {
                    let i = y * w + x;
                    if !now.hit[i] {
                        prev.push([x as f32, y as f32]);
                        taps.push(Vec::new());
                        continue;
                    }
                    let p = now.position[i];
                    let n = now.normal[i];
                    let Some(q) = prev_view.project(p, w, h) else {
                        prev.push([f32::NAN, f32::NAN]);
                        taps.push(Vec::new());
                        continue;
                    };
                    prev.push(q);
                    let (fx, fy) = (q[0].floor(), q[1].floor());
                    let (ax, ay) = (q[0] - fx, q[1] - fy);
                    let range = PLANE * (p - eye).length();
                    let mut t = Vec::with_capacity(4);
                    let mut sum = 0.0;
                    for (dx, dy, wt) in [
                        (0, 0, (1.0 - ax) * (1.0 - ay)),
                        (1, 0, ax * (1.0 - ay)),
                        (0, 1, (1.0 - ax) * ay),
                        (1, 1, ax * ay),
                    ] {
                        let (tx, ty) = (fx as i64 + dx, fy as i64 + dy);
                        if wt <= 0.0 || tx < 0 || ty < 0 || tx >= w as i64 || ty >= h as i64 {
                            continue;
                        }
                        let j = ty as usize * w + tx as usize;
                        if !before.hit[j]
                            || before.normal[j].dot(n) < NORMAL
                            || (before.position[j] - p).dot(n).abs() > range
                        {
                            continue;
                        }
                        t.push((j as u32, wt));
                        sum += wt;
                    }
                    if sum < 1e-3 {
                        t.clear();
                    }
                    t.iter_mut().for_each(|(_, v)| *v /= sum);
                    taps.push(t);
                }
                (prev, taps)
            })
            .collect();
        let mut out = Reprojection {
            prev: Vec::with_capacity(w * h),
            taps: Vec::with_capacity(w * h),
        };
        for (p, t) in rows {
            out.prev.extend(p);
            out.taps.extend(t);
        }
        out
    }

    /// The EMA's next history: each pixel's reprojected history blended with `now` by
    /// `alpha`, or `now` where the history resets.
    pub fn blend(&self, history: &[f32], now: &[f32], alpha: f32) -> Vec<f32> {
        now.iter()
            .zip(&self.taps)
            .map(|(&e, taps)| {
                if taps.is_empty() {
                    e
                } else {
                    let h: f32 = taps.iter().map(|&(j, w)| w * history[j as usize]).sum();
                    h + alpha * (e - h)
                }
            })
            .collect()
    }

    /// The share of `hit` pixels whose history resets.
    pub fn reset_share(&self, hit: &[bool]) -> f64 {
        let surface = hit.iter().filter(|&&h| h).count().max(1);
        let reset = self
            .taps
            .iter()
            .zip(hit)
            .filter(|(t, h)| **h && t.is_empty())
            .count();
        reset as f64 / surface as f64
    }

    /// The mean length of the motion vectors of `hit` pixels that keep their history, in
    /// pixels.
    pub fn mean_motion(&self, hit: &[bool], width: usize) -> f64 {
        let mut n = 0usize;
        let mut sum = 0.0;
        for (i, (p, t)) in self.prev.iter().zip(&self.taps).enumerate() {
            if hit[i] && !t.is_empty() {
                let (x, y) = ((i % width) as f32, (i / width) as f32);
                sum += ((p[0] - x).hypot(p[1] - y)) as f64;
                n += 1;
            }
        }
        sum / n.max(1) as f64
    }
}

/// Every frame's view, G-buffer and reprojection (frame 0 has none) of `motion` over `frames`
/// frames at `size`.
pub fn path(
    scene: &Scene,
    tracer: &Tracer,
    motion: Motion,
    size: [usize; 2],
    frames: u32,
) -> Vec<(View, GBuffer, Option<Reprojection>)> {
    let mut out: Vec<(View, GBuffer, Option<Reprojection>)> = Vec::new();
    for f in 0..frames {
        let view = motion.view(scene.camera, scene.ao_radius, f);
        let g = GBuffer::of_view(scene, tracer, &view, size);
        let r = out.last().map(|(pv, pg, _)| Reprojection::new(&g, pg, pv));
        out.push((view, g, r));
    }
    out
}
