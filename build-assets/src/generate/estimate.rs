//! What a generation will cost, said before it starts: the CLI prints it above its progress
//! bar, and a build script prints it as a `cargo:warning` for bakes long enough to notice.
//!
//! A rough model, held within a factor of two of the measured time by `noisebake report bench`
//! (every kind at three sizes, on one and two threads): void and cluster places every texel once
//! and updates the energy of its footprint, `n · (a + b · footprint)`, slower per texel once its
//! energy field no longer fits in the caches (it runs on one thread); FAST runs rounds over every
//! texel's coupled pairs, `n · footprint · rounds · c`, with the round count it typically needs,
//! shared among as many threads as a colour has tiles. The constants were fitted on a 2-core
//! x86_64 machine; a faster one takes less.

use crate::generate::fast::SampleSpace;
use crate::spec::{Kind, TextureSpec};

/// The expected cost of generating a texture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// Texels.
    pub texels: u64,
    /// Texel–neighbour updates per placement (void and cluster) or coupled pairs per texel
    /// and round (FAST).
    pub footprint: u64,
    /// Expected seconds.
    pub seconds: f64,
}

/// Seconds per placed texel, fixed part.
const VAC_A: f64 = 4.0e-7;
/// Seconds per energy update.
const VAC_B: f64 = 3.6e-10;
/// Exponent of the slowdown once the energy field outgrows the caches.
const VAC_SPILL: f64 = 0.55;
/// CPU seconds per coupled pair and round, scalar FAST (the screen gives up on most proposals
/// after a small share of a long footprint).
const FAST_C: f64 = 7.4e-11;
/// CPU seconds per proposal (one per texel and round), whatever the footprint.
const FAST_PROPOSAL: f64 = 5.0e-7;
/// Vector sample spaces cost this much more per pair (a distance in 2–4 dimensions, and their
/// short footprints are walked further before the screen decides).
const FAST_VECTOR: f64 = 14.0;
/// Rounds FAST typically runs before its gain is spent (`optimize::CONVERGED`).
const FAST_ROUNDS: f64 = 18.0;
/// The same for directions, which stop at `optimize::CONVERGED_DIRECTIONS`.
const FAST_ROUNDS_DIRECTIONS: f64 = 10.0;

/// How much more a coupling costs when a `taa` filter's `motion` shears the footprint: its
/// offsets reach across the texture, out of the caches (fitted to `report taa`'s moving masks).
const FAST_MOVING: f64 = 2.5;

/// Seconds per (pixel, training integrand) of a sampler bake's sweeps, all of them (the number
/// a bake typically runs before `Schedule::stop_gain` ends it folded in), fixed part.
const SAMPLER_SWEEPS_A: f64 = 5.4e-7;
/// The same, per pixel of the filter's support.
const SAMPLER_SWEEPS_B: f64 = 1.05e-9;
/// Seconds per (pixel, training integrand, sample) of the errors' table, for one frame.
const SAMPLER_TABLE_C: f64 = 3.6e-8;
/// Each frame of history beyond the first costs this share of the first (the EMA's weights
/// fold the older frames into running sums).
const SAMPLER_HISTORY: f64 = 1.0 / 3.0;

/// Generations expected to take longer than this get an up-front message.
pub const ANNOUNCE_SECONDS: f64 = 10.0;

/// The line every way in prints before a generation expected to take longer than
/// `threshold` seconds (a build script uses [`ANNOUNCE_SECONDS`], interactive tools less):
/// `generating `NAME` (KIND DIMS): estimated …`; `None` below it.
pub fn announcement(spec: &TextureSpec, threshold: f64) -> Option<String> {
    let est = estimate(spec);
    (est.seconds > threshold).then(|| {
        format!(
            "generating `{}` ({} {:?}): estimated {est}",
            spec.name,
            spec.kind.name(),
            spec.dims
        )
    })
}

/// The estimate of `spec` on the threads the generator will get (rayon's current pool).
pub fn estimate(spec: &TextureSpec) -> Estimate {
    estimate_with_threads(spec, rayon::current_num_threads())
}

/// The estimate of `spec` on `threads` worker threads.
pub fn estimate_with_threads(spec: &TextureSpec, threads: usize) -> Estimate {
    let n = spec.texels() as u64;
    match &spec.kind {
        Kind::Fast(p) => {
            let fp = p.footprint(&spec.dims).len() as u64;
            let per = if matches!(p.sample_space, SampleSpace::Scalar | SampleSpace::Circle) {
                FAST_C
            } else {
                FAST_C * FAST_VECTOR
            };
            let typical = if crate::generate::fast::converged(p.sample_space)
                > crate::generate::fast::optimize::CONVERGED
            {
                FAST_ROUNDS_DIRECTIONS
            } else {
                FAST_ROUNDS
            };
            let rounds = p.iterations.map_or(typical, |r| (r as f64).min(typical));
            // Tiles of one colour run in parallel (`optimize`): at least 16 texels and the
            // footprint's radius wide, an even number per axis.
            let f = p.footprint(&spec.dims);
            let tiles = |size: usize, r: usize| (size / 16usize.max(r + 1) / 2).max(1);
            let parallel =
                (tiles(spec.dims[0], f.radius[0]) * tiles(spec.dims[1], f.radius[1])) as f64;
            let speedup = (threads as f64).min(parallel).max(1.0);
            let per = if p.temporal.motion().is_some() {
                per * FAST_MOVING
            } else {
                per
            };
            Estimate {
                texels: n,
                footprint: fp,
                seconds: n as f64 * rounds * (FAST_PROPOSAL + fp as f64 * per) / speedup,
            }
        }
        Kind::Sampler(p) => {
            // Per pair: every pixel's errors on the training integrands (each weighing the
            // spp samples of one frame, or of `frames` frames under an EMA), then sweeps in
            // which every pixel scores `candidates` swaps (a pass over its errors) and a share
            // of them update the filter's support; pairs run on their own threads. Fitted to
            // the tiles of `report render` (1, 4 and 16 spp, Gaussian and à-trous, with and
            // without an EMA; `docs/measured/render.md` lists each bake beside this estimate).
            let s = crate::generate::sampler::Schedule::DEFAULT;
            let pixels = (spec.dims[0] * spec.dims[1]) as f64;
            let len = s.integrands(p) as f64;
            let history = match p.temporal {
                crate::spec::fast::TemporalFilter::Ema { .. } => p.frames as f64,
                _ => 1.0,
            };
            let pairs = p.sample_dims.div_ceil(2) as f64;
            let width = |n: usize| crate::generate::sampler::support_width(p.spatial, n) as f64;
            let support = width(spec.dims[0]) * width(spec.dims[1]);
            let frames = 1.0 + (history - 1.0) * SAMPLER_HISTORY;
            let table = pixels * len * p.spp as f64 * frames * SAMPLER_TABLE_C;
            let sweeps = pixels * len * (SAMPLER_SWEEPS_A + SAMPLER_SWEEPS_B * support);
            let waves = (pairs / threads.max(1) as f64).ceil();
            Estimate {
                texels: n,
                footprint: support as u64,
                seconds: waves * (table + sweeps),
            }
        }
        Kind::White => Estimate {
            texels: n,
            footprint: 0,
            seconds: n as f64 * 2e-9,
        },
        _ => {
            let fp = crate::spec::splat_footprint(spec);
            // Past a megabyte of energies (4 bytes a texel) the field spills out of the
            // caches and every splat and queue refresh waits on memory: measured 1.8–2.1×
            // slower per texel for each 4× texels beyond it.
            let spill = (n as f64 * 4.0 / (1u64 << 20) as f64)
                .max(1.0)
                .powf(VAC_SPILL);
            Estimate {
                texels: n,
                footprint: fp,
                seconds: n as f64 * (VAC_A + VAC_B * fp as f64) * spill,
            }
        }
    }
}

impl std::fmt::Display for Estimate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let t = self.seconds;
        if t < 1.0 {
            write!(f, "under a second")
        } else if t < 120.0 {
            write!(f, "about {t:.0} s")
        } else {
            write!(f, "about {:.0} min", t / 60.0)
        }?;
        write!(f, " ({} texels × {} coupled)", self.texels, self.footprint)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(body: &str) -> TextureSpec {
        crate::spec::parse_toml(&format!("[[texture]]\nname = \"T\"\n{body}"))
            .unwrap()
            .textures
            .remove(0)
    }

    #[test]
    fn estimates_grow_with_size_and_footprint() {
        let small = estimate(&spec("kind = \"stbn\"\ndims = [32, 32, 8]"));
        let big = estimate(&spec("kind = \"stbn\"\ndims = [128, 128, 32]"));
        let wide = estimate(&spec("kind = \"stbn\"\ndims = [32, 32, 8]\nsigma_xy = 4.0"));
        assert!(big.seconds > 30.0 * small.seconds);
        assert!(wide.footprint > small.footprint && wide.seconds > small.seconds);
        let fast = estimate(&spec(
            "kind = \"fast\"\ndims = [256, 256, 64]\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }",
        ));
        assert!(fast.seconds > ANNOUNCE_SECONDS, "{fast}");
        assert!(format!("{fast}").contains("texels"));
    }

    /// FAST shares a round among the tiles of a colour: two threads halve a large mask's
    /// estimate, and do nothing for one whose colours have a single tile; void and cluster
    /// runs on one thread whatever the pool.
    #[test]
    fn estimates_follow_the_parallelism_the_generators_have() {
        let big = spec("kind = \"fast\"\ndims = [128, 128, 64]");
        let small = spec("kind = \"fast\"\ndims = [32, 32, 64]");
        let stbn = spec("kind = \"stbn\"\ndims = [64, 64, 32]");
        let t = |s: &TextureSpec, n| estimate_with_threads(s, n).seconds;
        assert!((t(&big, 1) / t(&big, 2) - 2.0).abs() < 1e-9);
        assert_eq!(t(&small, 1), t(&small, 2));
        assert_eq!(t(&stbn, 1), t(&stbn, 2));
    }

    /// A sampler tile's estimate follows what its bake does: a wider filter support costs
    /// more per sweep, and under an EMA every sample of the history adds to the errors'
    /// table, so the EMA tile's estimate grows with spp where a one-frame tile's barely does.
    #[test]
    fn sampler_estimates_follow_filter_spp_and_history() {
        let tile = |spp: u32, filter: &str, ema: bool| {
            let t = if ema {
                "\ntemporal_filter = { kind = \"ema\", alpha = 0.1 }"
            } else {
                ""
            };
            estimate_with_threads(
                &spec(&format!(
                    "kind = \"sampler\"\ndims = [128, 128]\nspp = {spp}\nsample_dims = 4\nspatial_filter = {filter}{t}"
                )),
                2,
            )
            .seconds
        };
        let gauss = "{ kind = \"gauss\", sigma = 1 }";
        let atrous = "{ kind = \"atrous\", passes = 3 }";
        for ema in [false, true] {
            for spp in [1, 4, 16] {
                assert!(
                    tile(spp, atrous, ema) > tile(spp, gauss, ema),
                    "{spp} {ema}"
                );
            }
        }
        let growth = |ema| tile(16, gauss, ema) / tile(1, gauss, ema);
        assert!(growth(true) > 3.0 && growth(false) < 3.0);
        assert!(tile(16, gauss, true) > tile(16, gauss, false));
    }
}
