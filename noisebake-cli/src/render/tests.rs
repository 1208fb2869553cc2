//! The tracer against integrals known in closed form, the à-trous weights' symmetry and
//! normalisation, and the reference's standard error against what independent references say.

use super::denoise::{Denoiser, Filter, atrous_weight, depth_gradient};
use super::scene::{AreaLight, Camera, Scene, Tri};
use super::trace::Tracer;
use super::{GBuffer, shade};
use glam::Vec3;

/// A scene of `triangles` with a light `a × b` at height `c` whose corner is straight above
/// the origin, AO reaching `radius`.
fn scene(triangles: Vec<Tri>, radius: f32, (a, b, c): (f32, f32, f32)) -> Scene {
    Scene {
        name: "test".into(),
        triangles,
        camera: Camera {
            eye: Vec3::new(0.0, 5.0, 5.0),
            target: Vec3::ZERO,
            fov_y: 1.0,
        },
        light: AreaLight {
            corner: Vec3::new(0.0, c, 0.0),
            edges: [Vec3::new(a, 0.0, 0.0), Vec3::new(0.0, 0.0, b)],
            radiance: 1.0,
        },
        ao_radius: radius,
        albedo: 0.5,
        sky: 0.8,
    }
}

/// The floor y = 0, `half` on each side of the origin.
fn floor(half: f32) -> Vec<Tri> {
    let v = |x, z| Vec3::new(x, 0.0, z);
    vec![
        [v(-half, -half), v(-half, half), v(half, half)],
        [v(-half, -half), v(half, half), v(half, -half)],
    ]
}

/// The mean of the three estimates over an `n × n` grid of samples (dims 0–1 and 2–3 each
/// on the grid, in two different orders so the pairs are not one function of the other).
fn mean_shading(s: &Scene, t: &Tracer, p: Vec3, n: usize) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    for i in 0..n {
        for j in 0..n {
            let u = (i as f32 + 0.5) / n as f32;
            let v = (j as f32 + 0.5) / n as f32;
            let (e, _) = shade(s, t, p, Vec3::Y, [u, v, v, u]);
            for c in 0..3 {
                sum[c] += e[c] as f64;
            }
        }
    }
    sum.map(|x| x / (n * n) as f64)
}

/// The form factor from a point to a parallel `a × b` rectangle at height `c` whose corner is
/// straight above it (Howell's catalogue, C-11).
fn corner_form_factor(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

/// An open plane: nothing occludes (AO 1 from every direction, the bounce escapes to the sky),
/// and the shadow estimate converges to the light's form factor.
#[test]
fn an_open_plane_sees_the_sky_and_the_lights_form_factor() {
    let (a, b, c) = (1.2f32, 0.7f32, 1.5f32);
    let s = scene(floor(50.0), 1.0, (a, b, c));
    let t = Tracer::new(&s.triangles);
    let p = Vec3::new(0.0, 1e-4, 0.0);
    let m = mean_shading(&s, &t, p, 128);
    assert_eq!(m[0], 1.0, "AO");
    assert!(
        (m[2] - (s.albedo * s.sky) as f64).abs() < 1e-6,
        "bounce {}",
        m[2]
    );
    let want = corner_form_factor(a as f64, b as f64, c as f64);
    assert!(
        (m[1] / want - 1.0).abs() < 2e-3,
        "shadow {} vs {want}",
        m[1]
    );
    // Beside the light's corner the estimate is not the corner's value: the test can fail.
    let off = mean_shading(&s, &t, Vec3::new(-1.0, 1e-4, -1.0), 64);
    assert!((off[1] / want - 1.0).abs() > 0.1, "{}", off[1]);
}

/// A point on the floor `d` from an infinitely wide wall of height `h` (and no AO radius):
/// the wall covers a cosine-weighted share `(1 − d/√(d² + h²))/2` of the hemisphere, so AO is
/// one minus that; at the crease (`d → 0`) it is ½.
#[test]
fn ao_beside_a_wall_and_in_a_crease_is_the_analytic_value() {
    let (h, half) = (1.0f32, 400.0f32);
    let mut tris = floor(half);
    let v = |x, y| Vec3::new(x, y, 0.0);
    tris.push([v(-half, 0.0), v(half, 0.0), v(half, h)]);
    tris.push([v(-half, 0.0), v(half, h), v(-half, h)]);
    let s = scene(tris, 1e6, (0.1, 0.1, 50.0));
    let t = Tracer::new(&s.triangles);
    for d in [0.002f32, 0.3, 1.0, 2.5] {
        let ao = mean_shading(&s, &t, Vec3::new(0.0, 1e-4, d), 256)[0];
        let dd = d as f64;
        let want = 1.0 - (1.0 - dd / (dd * dd + 1.0).sqrt()) / 2.0;
        assert!((ao - want).abs() < 4e-3, "d {d}: {ao} vs {want}");
    }
    // With a radius shorter than the wall's distance, nothing occludes.
    let near = scene(s.triangles.clone(), 0.5, (0.1, 0.1, 50.0));
    let ao = mean_shading(&near, &t, Vec3::new(0.0, 1e-4, 0.6), 64)[0];
    assert_eq!(ao, 1.0);
}

/// The à-trous weights, before normalisation, are symmetric in the two pixels, and each
/// pixel's normalised weights sum to one; they stop at the room's edges (some weight below
/// the kernel's own).
#[test]
fn atrous_weights_are_symmetric_and_normalised() {
    let s = Scene::room();
    let t = Tracer::new(&s.triangles);
    let g = GBuffer::new(&s, &t, 40, 30, [0, 0]);
    let grad = depth_gradient(&g);
    let mut stopped = 0;
    for p in (0..g.width * g.height).step_by(7) {
        for q in (0..g.width * g.height).step_by(11) {
            let a = atrous_weight(&g, &grad, p, q, 2.0, 0.1);
            let b = atrous_weight(&g, &grad, q, p, 2.0, 0.1);
            assert_eq!(a, b, "{p} {q}");
            stopped += usize::from(a < 0.05);
        }
    }
    assert!(stopped > 0);
    let f = Filter::new(Denoiser::Atrous { passes: 3 }, &g);
    for pass in 0..3 {
        for p in 0..g.width * g.height {
            let sum: f32 = f.atrous_row(pass, p).unwrap().iter().sum();
            assert!((sum - 1.0).abs() < 1e-5, "pass {pass} pixel {p}: {sum}");
        }
    }
    // A constant image stays constant.
    let one = vec![1.0f32; g.width * g.height];
    assert!(f.apply(&one).iter().all(|v| (v - 1.0).abs() < 1e-5));
}

/// The reference's standard error is what independent references say: two references from
/// disjoint seeds differ by about √2 times it.
#[test]
fn the_references_standard_error_matches_independent_references() {
    use crate::report::render::{reference, standard_error};
    let s = Scene::room();
    let t = Tracer::new(&s.triangles);
    let g = GBuffer::new(&s, &t, 32, 24, [0, 0]);
    let none = Filter::new(Denoiser::None, &g);
    let (a, reps) = reference(&s, &t, &g, 64, 4, 0);
    let (b, _) = reference(&s, &t, &g, 64, 4, 1);
    for c in 0..3 {
        let r: Vec<&[f32]> = reps.iter().map(|x| x[c].as_slice()).collect();
        let se = standard_error(&a[c], &r, &none, &g.hit);
        let px = g.surface_pixels() as f64;
        let diff = (a[c]
            .iter()
            .zip(&b[c])
            .zip(&g.hit)
            .filter(|(_, h)| **h)
            .map(|((x, y), _)| ((x - y) as f64).powi(2))
            .sum::<f64>()
            / px)
            .sqrt();
        let ratio = diff / (std::f64::consts::SQRT_2 * se);
        assert!(
            (0.7..1.4).contains(&ratio),
            "integrand {c}: {diff} vs se {se}: {ratio}"
        );
    }
}

/// A user's `.obj`: every face is triangulated, degenerate ones dropped, the camera sees the
/// scene, the light sits above it; files that are not scenes get an error naming the file.
#[test]
fn an_obj_scene_loads_and_bad_ones_are_named() {
    let dir = std::env::temp_dir().join(format!("noisebake-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 4 × 4 floor as one quad, a unit cube on it (six quads), and a degenerate triangle.
    let obj = "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 4 3 2\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 5 8 7 6\nf 9 10 11 12\nf 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\nf 8 5 9 12\nf 5 5 6\n";
    let path = dir.join("box.obj");
    std::fs::write(&path, obj).unwrap();
    let s = Scene::from_obj(&path).unwrap();
    assert_eq!(
        s.triangles.len(),
        2 + 12,
        "quads split in two, the degenerate face dropped"
    );
    assert!(
        (s.ao_radius - 1.0).abs() < 1e-6,
        "a quarter of the 4-unit bounds"
    );
    assert!(
        s.light.corner.y > 1.0 && s.light.normal().y < 0.0,
        "the light shines down from above"
    );
    let t = Tracer::new(&s.triangles);
    let g = GBuffer::new(&s, &t, 32, 24, [0, 0]);
    assert!(
        g.surface_pixels() > 32 * 24 / 4,
        "{} pixels see the scene",
        g.surface_pixels()
    );
    // Beside the cube on the floor, AO is below 1; the floor's far corner sees more sky.
    let near = mean_shading(&s, &t, Vec3::new(1.05, 1e-4, 0.5), 64)[0];
    let far = mean_shading(&s, &t, Vec3::new(-1.9, 1e-4, -1.9), 64)[0];
    assert!(
        near < 0.8 && far > near + 0.1,
        "AO beside the cube {near}, far {far}"
    );
    for (name, text) in [
        ("empty.obj", "v 0 0 0\n"),
        ("bad.obj", "v 0 0 0\nf 1 2 3\n"),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        let e = Scene::from_obj(&p).unwrap_err();
        assert!(e.contains(name), "{e}");
    }
    let e = Scene::from_obj(&dir.join("missing.obj")).unwrap_err();
    assert!(e.contains("missing.obj"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `View::project` inverts `View::ray`: the point a pixel's ray hits projects back to that
/// pixel, shifted or not, at any position within the pixel.
#[test]
fn projection_inverts_the_ray() {
    let s = Scene::room();
    for shift in [[0.0, 0.0], [3.25, -1.5]] {
        let view = super::View {
            camera: s.camera,
            shift,
        };
        for (x, y) in [(0.0f32, 0.0f32), (17.3, 40.9), (159.0, 119.0)] {
            let p = s.camera.eye + view.ray(x, y, 160, 120) * 3.7;
            let q = view.project(p, 160, 120).expect("in front of the eye");
            assert!(
                (q[0] - x).abs() < 1e-3 && (q[1] - y).abs() < 1e-3,
                "{q:?} vs ({x}, {y})"
            );
        }
        let behind = s.camera.eye * 2.0 - s.camera.target;
        assert!(view.project(behind, 160, 120).is_none());
    }
}

/// A pan by whole pixels reprojects exactly: the pixel the picture came from takes the
/// weight; pixels that come in at the border reset; a blend of the previous frame's
/// picture through the reprojection is the new frame's picture where history is kept.
#[test]
fn a_whole_pixel_pan_reprojects_exactly() {
    use super::motion::{Motion, Reprojection};
    let s = Scene::room();
    let t = Tracer::new(&s.triangles);
    let m = Motion::Pan {
        velocity: [2.0, -1.0],
        sweep: 4,
    };
    let (w, h) = (32usize, 24usize);
    let v0 = m.view(s.camera, s.ao_radius, 1);
    let v1 = m.view(s.camera, s.ao_radius, 2);
    let g0 = GBuffer::of_view(&s, &t, &v0, [w, h]);
    let g1 = GBuffer::of_view(&s, &t, &v1, [w, h]);
    let r = Reprojection::new(&g1, &g0, &v0);
    let mut kept = 0;
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if !g1.hit[i] {
                continue;
            }
            let (px, py) = (x as i64 + 2, y as i64 - 1);
            let inside = px < w as i64 && py >= 0;
            if inside && g0.hit[py as usize * w + px as usize] {
                let j = py as usize * w + px as usize;
                // The surface point sits a hair off its surface (the G-buffer's offset), so
                // its projection is within a few thousandths of a pixel of the centre.
                let (tap, weight) = r.taps[i]
                    .iter()
                    .copied()
                    .max_by(|a, b| a.1.total_cmp(&b.1))
                    .expect("a kept pixel has taps");
                assert_eq!(tap as usize, j, "pixel ({x}, {y}): {:?}", r.taps[i]);
                assert!(weight > 0.99, "pixel ({x}, {y}): {:?}", r.taps[i]);
                kept += 1;
            } else if !inside {
                // Came in at the border: its surface was off-screen, at least a pixel beyond
                // the last column or row less the projection's hair.
                let q = r.prev[i];
                assert!(
                    r.taps[i].is_empty() || q[0] > (w - 1) as f32 + 0.99 || q[1] < 0.01,
                    "pixel ({x}, {y}) came in at the border: {q:?}, {:?}",
                    r.taps[i]
                );
            }
        }
    }
    assert!(kept > w * h / 2, "{kept} pixels kept their history");
    let depth0: Vec<f32> = g0.depth.iter().map(|d| d.min(100.0)).collect();
    let depth1: Vec<f32> = g1.depth.iter().map(|d| d.min(100.0)).collect();
    let blended = r.blend(&depth0, &depth1, 0.25);
    let x_inside = |i: usize| i % w + 2 < w && i / w >= 1;
    for i in 0..w * h {
        if r.taps[i].is_empty() {
            assert_eq!(blended[i], depth1[i]);
        } else if r.taps[i].iter().any(|t| t.1 > 0.999) && x_inside(i) {
            // One tap holds the weight (elsewhere a hair of a neighbour on the same plane,
            // at another depth, may share it).
            assert!(
                (blended[i] - depth1[i]).abs() < 1e-2 * depth1[i],
                "pixel {i}: {} vs {}, {:?}",
                blended[i],
                depth1[i],
                r.taps[i]
            );
        }
    }
    assert!(r.reset_share(&g1.hit) > 0.0);
    assert!((r.mean_motion(&g1.hit, w) - 5f64.sqrt()).abs() < 1e-3);
}

/// The camera paths sweep out and back: the pan's shift and the parallax camera return to
/// the still camera after two sweeps, and the triangle wave steps by one.
#[test]
fn motions_sweep_out_and_back() {
    use super::motion::{Motion, triangle};
    for f in 1..100 {
        assert_eq!((triangle(f, 7) - triangle(f - 1, 7)).abs(), 1.0);
    }
    assert_eq!(
        (triangle(0, 7), triangle(7, 7), triangle(14, 7)),
        (0.0, 7.0, 0.0)
    );
    let s = Scene::room();
    let pan = Motion::Pan {
        velocity: [1.5, 0.5],
        sweep: 10,
    };
    assert_eq!(pan.view(s.camera, 1.0, 10).shift, [15.0, 5.0]);
    assert_eq!(pan.view(s.camera, 1.0, 20).shift, [0.0, 0.0]);
    let par = Motion::Parallax {
        truck: 0.1,
        dolly: 0.1,
        sweep: 4,
    };
    let moved = par.view(s.camera, 1.0, 3).camera;
    assert!((moved.eye - s.camera.eye).length() > 0.1);
    // Truck period 8, dolly period 12: both are home at frame 24.
    let home = par.view(s.camera, 1.0, 24).camera;
    assert!((home.eye - s.camera.eye).length() < 1e-5);
}
