//! What a generation will cost, said before it starts: the CLI prints it above its progress
//! bar, and a build script prints it as a `cargo:warning` for bakes long enough to notice.
//!
//! A rough model, right within a small factor: void and cluster places every texel once and
//! updates the energy of its footprint, `n · (a + b · footprint)`; FAST runs rounds over every
//! texel's coupled pairs until the loss stops improving, `n · footprint · rounds · c`, with the
//! round count it typically needs. The constants were fitted to single-thread runs of the
//! generators on a 2-core x86_64 machine; a faster one takes less.

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
const VAC_A: f64 = 9e-7;
/// Seconds per energy update.
const VAC_B: f64 = 8e-10;
/// Seconds per coupled pair and round, scalar FAST.
const FAST_C: f64 = 4e-10;
/// Vector sample spaces cost this much more per pair (a distance in 2–4 dimensions).
const FAST_VECTOR: f64 = 6.0;
/// Rounds FAST typically runs before it converges.
const FAST_ROUNDS: f64 = 40.0;

/// Generations expected to take longer than this get an up-front message.
pub const ANNOUNCE_SECONDS: f64 = 10.0;

/// The estimate of `spec`.
pub fn estimate(spec: &TextureSpec) -> Estimate {
    let n = spec.texels() as u64;
    match &spec.kind {
        Kind::Fast(p) => {
            let fp = p.footprint(&spec.dims).len() as u64;
            let per = if matches!(p.sample_space, SampleSpace::Scalar | SampleSpace::Circle) {
                FAST_C
            } else {
                FAST_C * FAST_VECTOR
            };
            let rounds = p
                .iterations
                .map_or(FAST_ROUNDS, |r| (r as f64).min(FAST_ROUNDS));
            Estimate {
                texels: n,
                footprint: fp,
                seconds: n as f64 * fp as f64 * rounds * per,
            }
        }
        Kind::White => Estimate {
            texels: n,
            footprint: 0,
            seconds: n as f64 * 2e-9,
        },
        _ => {
            let fp = crate::spec::splat_footprint(spec);
            Estimate {
                texels: n,
                footprint: fp,
                seconds: n as f64 * (VAC_A + VAC_B * fp as f64),
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
            "kind = \"fast\"\ndims = [128, 128, 64]\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }",
        ));
        assert!(fast.seconds > ANNOUNCE_SECONDS, "{fast}");
        assert!(format!("{fast}").contains("texels"));
    }
}
