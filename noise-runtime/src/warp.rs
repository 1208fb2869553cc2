//! Sample warps: from uniform numbers in `[0, 1]` to the distributions rendering needs.
//!
//! Every warp takes `ξ` in `[0, 1]` — exactly 0 and exactly 1 included — and returns finite
//! points on (or in) its domain: inputs outside `[0, 1]` (or NaN) are clamped, square roots never
//! see a negative argument, and directions are unit length to within `f32` rounding.

use crate::math::{sincos_turns, sqrt};

#[inline(always)]
fn unit(u: f32) -> f32 {
    if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) }
}

/// Uniform point in the unit disk by Shirley and Chiu's concentric map (area-preserving, low
/// distortion: strata of the square stay compact on the disk).
#[must_use]
#[inline]
pub fn disk_concentric(u: f32, v: f32) -> [f32; 2] {
    let a = 2.0 * unit(u) - 1.0;
    let b = 2.0 * unit(v) - 1.0;
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    // r and θ (in turns) of the concentric map.
    let (r, turns) = if a * a > b * b {
        (a, b / a / 8.0)
    } else {
        (b, 0.25 - a / b / 8.0)
    };
    let (s, c) = sincos_turns(turns);
    [r * c, r * s]
}

/// Uniform point in the unit disk by the polar map: `r = √u`, `φ = 2πv` (Pharr, Jakob and
/// Humphreys, PBRT 4th ed., §A.5.1). `u` is the radius squared and `v` the angle in turns, so a
/// sampler's strata in `u` are rings of equal area and in `v` sectors, and `v` wraps: a
/// rank-1 lattice or a toroidal shift of `(u, v)` keeps its structure on the disk. The map
/// of `sample_space = "disk"` for sampler tiles.
#[must_use]
#[inline]
pub fn disk_polar(u: f32, v: f32) -> [f32; 2] {
    let r = sqrt(unit(u));
    let (s, c) = sincos_turns(unit(v));
    [r * c, r * s]
}

/// Cosine-weighted direction on the upper unit hemisphere (density `cos θ / π`) by the polar
/// map lifted by Malley's method: `r = √u`, `φ = 2πv`, `z = √(1 − u)`. The map of
/// `sample_space = "cosine_hemisphere"` for sampler tiles (ambient occlusion, a diffuse
/// bounce), whose lattice shifts wrap in `v` as the azimuth does.
#[must_use]
#[inline]
pub fn cosine_hemisphere_polar(u: f32, v: f32) -> [f32; 3] {
    let [x, y] = disk_polar(u, v);
    [x, y, sqrt(1.0 - unit(u))]
}

/// Uniform direction on the unit sphere: `z = 1 − 2u`, azimuth `2πv` (Archimedes' hat-box).
#[must_use]
#[inline]
pub fn sphere_uniform(u: f32, v: f32) -> [f32; 3] {
    let z = 1.0 - 2.0 * unit(u);
    let r = sqrt(1.0 - z * z);
    let (s, c) = sincos_turns(unit(v));
    [r * c, r * s, z]
}

/// Uniform direction on the upper (`z ≥ 0`) unit hemisphere: `z = u`, azimuth `2πv`.
#[must_use]
#[inline]
pub fn hemisphere_uniform(u: f32, v: f32) -> [f32; 3] {
    let z = unit(u);
    let r = sqrt(1.0 - z * z);
    let (s, c) = sincos_turns(unit(v));
    [r * c, r * s, z]
}

/// Cosine-weighted direction on the upper unit hemisphere (density `cos θ / π`) by Malley's
/// method: a concentric disk point lifted to the hemisphere.
#[must_use]
#[inline]
pub fn cosine_hemisphere(u: f32, v: f32) -> [f32; 3] {
    let [x, y] = disk_concentric(u, v);
    let z = sqrt(1.0 - x * x - y * y);
    [x, y, z]
}
