//! From a validated spec to a texture: dispatch to the generator of each kind and encode.
//!
//! The second stage of the pipeline (spec → **generate** → cache → codegen/export → bake):
//! [`vac`] (void and cluster in N dimensions), [`fast`] (the FAST swap optimiser),
//! [`sampler`] (sampler tiles' keys), [`baselines`] (white noise, per-slice and golden-ratio-animated 2D blue noise), [`estimate`]
//! (what a generation will cost, before it starts) and [`rng`] (the seeded generators). Every
//! module reads the spec's parameter types; none is read by the spec.

pub mod baselines;
pub mod estimate;
pub mod fast;
pub mod rng;
pub mod sampler;
pub mod vac;

use crate::encoding::{encode_ranks, encode_unit};
use crate::spec::vac::{DEFAULT_CUTOFF, Group};
use crate::spec::{Histogram, Kind, TextureSpec};
use crate::texture::Texture;
use vac::{Axis, VacConfig};

/// Version of the generators' output. Bump it whenever any generator's bytes change for an
/// unchanged spec: the cache key includes it, so stale entries are never served.
pub const ALGORITHM_VERSION: u32 = 20;

/// Progress callback: `(done, total)` texels ranked.
pub type Progress<'a> = &'a mut dyn FnMut(u64, u64);

fn vac_config(
    dims: &[usize],
    toroidal: &[bool],
    groups: Vec<Group>,
    density: f64,
    seed: u64,
) -> VacConfig {
    VacConfig {
        axes: dims
            .iter()
            .zip(toroidal)
            .map(|(&size, &toroidal)| Axis { size, toroidal })
            .collect(),
        groups,
        initial_density: density,
        seed,
        cutoff: DEFAULT_CUTOFF,
    }
}

/// Ranks of a 2D mask (σ, density, seed) — the building block of the 2D baselines.
pub fn blue2d_ranks(w: usize, h: usize, sigma: f64, density: f64, seed: u64) -> Vec<u32> {
    let g = vec![Group {
        axes: vec![0, 1],
        sigma,
    }];
    vac::rank(
        &vac_config(&[w, h], &[true, true], g, density, seed),
        &mut |_, _| {},
    )
    .0
}

/// Under a `taa` temporal filter, how many 3 × 3 windows of the texture's slices the history
/// clamp finds without a value below the coverage or one at or above one less it (counted on
/// the stored values, [`fast::open_windows`]); `None` for every other texture. A bake reports a
/// count above 0, and the cache entry records it.
pub fn open_windows_of(spec: &TextureSpec, t: &Texture) -> Option<u64> {
    let Kind::Fast(params) = &spec.kind else {
        return None;
    };
    let coverage = params.temporal.clamp_coverage()?;
    let values = fast::decode(params, &t.data, spec.format.scalar);
    let d = &spec.dims;
    let dims = [d[0], d[1], d.get(2).copied().unwrap_or(1)];
    (values.len() == dims.iter().product::<usize>())
        .then(|| fast::open_windows(&values, dims, coverage))
}

/// Generates a texture and counts what its cache entry records ([`open_windows_of`]): what a
/// bake hands [`crate::cache::Cache::get_or_insert_with`].
pub fn bake_texture(spec: &TextureSpec, progress: Progress) -> crate::texture::Baked {
    let texture = generate(spec, progress);
    let open_windows = open_windows_of(spec, &texture).unwrap_or(0);
    crate::texture::Baked {
        texture,
        open_windows,
    }
}

/// Generates a texture. Pure: the same spec gives the same bytes on any machine and thread count.
pub fn generate(spec: &TextureSpec, progress: Progress) -> Texture {
    let dims = &spec.dims;
    let n = spec.texels();
    let scalar = spec.format.scalar;
    let slice = dims[0] * dims.get(1).copied().unwrap_or(1);
    let ranked = |ranks: Vec<u32>, histogram: Histogram| match histogram {
        Histogram::Volume => encode_ranks(&ranks, n as u32, scalar),
        Histogram::Slice if dims.len() > 2 => encode_ranks(
            &vac::rank_per_slice(&ranks, dims[0], dims[1]),
            slice as u32,
            scalar,
        ),
        Histogram::Slice => encode_ranks(&ranks, n as u32, scalar),
    };
    let data = match &spec.kind {
        // Blue2d ranks its plane over the whole texture, as `Histogram::Volume` does.
        Kind::Blue2d(p) | Kind::Stbn(p) | Kind::Vac(p) => {
            let cfg = vac_config(
                dims,
                &p.toroidal,
                p.groups.clone(),
                p.initial_density,
                spec.seed,
            );
            ranked(vac::rank(&cfg, progress).0, p.histogram)
        }
        Kind::White => encode_unit(&baselines::white(n, spec.seed), scalar),
        Kind::Independent2d(p) => {
            let sigma = p.groups[0].sigma;
            let ranks = baselines::independent2d(n / slice, spec.seed, |s| {
                blue2d_ranks(dims[0], dims[1], sigma, p.initial_density, s)
            });
            progress(n as u64, n as u64);
            encode_ranks(&ranks, slice as u32, scalar)
        }
        Kind::Golden(p) => {
            let ranks = blue2d_ranks(
                dims[0],
                dims[1],
                p.groups[0].sigma,
                p.initial_density,
                spec.seed,
            );
            progress(n as u64, n as u64);
            encode_unit(&baselines::golden(&ranks, dims[2]), scalar)
        }
        Kind::Fast(params) => {
            let out = crate::generate::fast::generate(params, dims, spec.seed, progress);
            let mut data = crate::generate::fast::encode(params, dims, &out.samples, scalar);
            // Windows the optimiser's tiles left open are closed by swaps anywhere in their
            // slice, on the values as stored.
            if let Some(coverage) = params.temporal.clamp_coverage() {
                let mut values = fast::decode(params, &data, scalar);
                let d = [dims[0], dims[1], dims.get(2).copied().unwrap_or(1)];
                fast::windows::repair_stored(&mut data, &mut values, d, coverage);
            }
            data
        }
        Kind::Sampler(params) => {
            let (keys, _) = sampler::generate(params, dims[0], dims[1], spec.seed, progress);
            keys.iter().flat_map(|k| k.to_le_bytes()).collect()
        }
    };
    Texture {
        name: spec.name.clone(),
        dims: spec.storage_dims(),
        format: spec.format,
        data,
    }
}
