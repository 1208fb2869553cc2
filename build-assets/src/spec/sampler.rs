//! The `sampler` kind: a tile of per-pixel shifts for `spp` samples × `sample_dims` dimensions
//! per pixel (`noise_runtime::SamplerTile`: every pixel runs a rank-1 lattice or Owen-scrambled
//! Sobol per pair, moved by its keys), arranged so that the pixels' Monte Carlo errors are blue under the scene's denoiser,
//! in the space the ray uses, on one frame or accumulated. Its parameters, their parsing,
//! defaults and validation; the generator (`crate::generate::sampler`) reads them.

use super::fast::{Filter, TemporalFilter, count, filter_table, spatial_filter, temporal_filter};
use super::{Fields, Shown, SpecError, Value, closest, type_error};

/// The space a pair of dimensions is warped into by the renderer, which decides the integrands
/// the generator trains that pair on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairSpace {
    /// The unit square as it is (a point on an area light): half-planes.
    Square,
    /// Cosine-weighted directions, `r = √u`, `φ = 2πv`, `z = √(1 − u)`
    /// (`noise_runtime::warp::cosine_hemisphere_polar`): half-spaces of directions, as an
    /// occluder's plane cuts the hemisphere (ambient occlusion, a diffuse bounce).
    CosineHemisphere,
    /// The unit disk, `r = √u`, `φ = 2πv` (`noise_runtime::warp::disk_polar`): half-planes of
    /// the disk (a lens, a disk light).
    Disk,
}

/// The spaces' spellings.
pub const PAIR_SPACES: &[&str] = &["square", "cosine_hemisphere", "disk"];

impl PairSpace {
    /// The key's spelling.
    pub fn name(self) -> &'static str {
        match self {
            PairSpace::Square => "square",
            PairSpace::CosineHemisphere => "cosine_hemisphere",
            PairSpace::Disk => "disk",
        }
    }

    fn parse(s: &str) -> Option<PairSpace> {
        match s {
            "square" => Some(PairSpace::Square),
            "cosine_hemisphere" => Some(PairSpace::CosineHemisphere),
            "disk" => Some(PairSpace::Disk),
            _ => None,
        }
    }
}

/// Every parameter of a sampler tile (the `sampler` spec kind).
#[derive(Clone, Debug, PartialEq)]
pub struct SamplerParams {
    /// Samples per pixel per frame, 1 to [`MAX_SPP`].
    pub spp: u32,
    /// Dimensions of each sample, 2 to [`MAX_SAMPLE_DIMS`].
    pub sample_dims: u32,
    /// Per pair of dimensions (0–1, 2–3, …; a lone last dimension is a pair of one, always
    /// `Square`), the space its integrands live in.
    pub sample_space: Vec<PairSpace>,
    /// The denoiser the errors should be blue for (separable in x and y; default Gaussian σ 1).
    pub spatial: Filter,
    /// `None` (each frame denoised on its own: every frame's error counts) or an EMA (`Ema`
    /// with `beta = 0`: the accumulated history's error counts).
    pub temporal: TemporalFilter,
    /// Frames of history the EMA's loss reads (1 without a temporal filter).
    pub frames: u32,
}

/// Most samples per pixel per frame.
pub const MAX_SPP: u32 = 64;
/// Most dimensions per sample (`noise_runtime::sampler::MAX_TILE_DIMS`).
pub const MAX_SAMPLE_DIMS: u32 = 8;
/// Most pixels in a tile: the optimiser holds every pixel's errors on its training integrands.
pub const MAX_PIXELS: usize = 1 << 16;
/// Most frames of history the loss reads.
pub const MAX_FRAMES: u32 = 64;
/// Frames of history under an EMA when the spec leaves `frames` out: `(1 − 0.1)^32 < 4 %` of
/// the newest frame's weight is left beyond them at the default α.
pub const DEFAULT_EMA_FRAMES: u32 = 32;
/// The spatial filter when the spec leaves it out.
pub const DEFAULT_FILTER: Filter = Filter::Gauss { sigma: 1.0 };

impl SamplerParams {
    /// Pairs of dimensions (a lone last dimension counts as one).
    pub fn pairs(&self) -> usize {
        (self.sample_dims as usize).div_ceil(2)
    }

    /// The pairs that run the Sobol sequence (`noise_runtime::SamplerTile::new`'s
    /// `sobol_pairs`, bit `p` for dimensions `2p`, `2p + 1`): those of `sample_space =
    /// "square"`, whose half-planes an Owen-scrambled (0, 2)-sequence's nets stratify, when a
    /// frame holds two samples or more. Warped pairs run the lattice, evenly spread along the
    /// polar angle that wraps; so does every pair at one sample per frame, where a frame's net
    /// is a single point and the lattice's even steps from frame to frame leave less error
    /// (measured by `noisebake report render`).
    pub fn sobol_pairs(&self) -> u8 {
        if self.spp < 2 {
            return 0;
        }
        self.sample_space
            .iter()
            .take(self.pairs())
            .enumerate()
            .filter(|(_, s)| **s == PairSpace::Square)
            .fold(0, |m, (p, _)| m | 1 << p)
    }

    /// The canonical text, field by field in this order: `spp`, `sample_dims`, `sample_space`
    /// (a list, one word per pair), `spatial_filter` (a table with its `kind` first),
    /// `temporal_filter` (`{kind=none}` or `{kind=ema,alpha=…}`), `frames`.
    pub fn canonical(&self) -> String {
        use super::canonical::num;
        let spaces: Vec<&str> = self.sample_space.iter().map(|s| s.name()).collect();
        let temporal = match self.temporal {
            TemporalFilter::Ema { alpha, .. } => format!("{{kind=ema,alpha={}}}", num(alpha)),
            _ => "{kind=none}".to_string(),
        };
        format!(
            "spp={};sample_dims={};sample_space=[{}];spatial_filter={};temporal_filter={temporal};frames={}",
            self.spp,
            self.sample_dims,
            spaces.join(","),
            self.spatial.canonical(),
            self.frames
        )
    }
}

/// Reads the `sampler` keys.
pub(super) fn parse(f: &mut Fields<'_>) -> Result<SamplerParams, SpecError> {
    let spp = count("spp", f.get("spp").cloned(), 1, 1, MAX_SPP as i64)? as u32;
    let sample_dims = count(
        "sample_dims",
        f.get("sample_dims").cloned(),
        2,
        2,
        MAX_SAMPLE_DIMS as i64,
    )? as u32;
    let pairs = (sample_dims as usize).div_ceil(2);
    let lone = sample_dims % 2 == 1;
    let word = |v: &super::Spanned<Value>| -> Result<PairSpace, SpecError> {
        let Value::Str(s) = &v.value else {
            return Err(type_error(
                "sample_space",
                "a word or a list of words like [\"cosine_hemisphere\", \"square\"]",
                v,
            ));
        };
        PairSpace::parse(s).ok_or_else(|| {
            let hint = closest(s, PAIR_SPACES)
                .map(|c| format!(" (did you mean `{c}`?)"))
                .unwrap_or_default();
            SpecError::at(
                "sample_space",
                v.span,
                format!(
                    "unknown `sample_space` \"{}\"{hint}; valid: {}",
                    Shown(s),
                    PAIR_SPACES.join(", ")
                ),
            )
        })
    };
    let sample_space = match f.get("sample_space") {
        None => vec![PairSpace::Square; pairs],
        Some(v) => match &v.value {
            Value::Array(items) => {
                if items.len() != pairs {
                    return Err(SpecError::at(
                        "sample_space",
                        v.span,
                        format!(
                            "`sample_space` has {} entries; `sample_dims = {sample_dims}` makes {pairs} pairs (dimensions 0-1, 2-3, …{}), one entry each",
                            items.len(),
                            if lone { ", the last one alone" } else { "" }
                        ),
                    ));
                }
                items.iter().map(word).collect::<Result<Vec<_>, _>>()?
            }
            _ => {
                let s = word(v)?;
                let mut all = vec![s; pairs];
                if lone {
                    // A lone last dimension has no second value to warp: it stays a scalar.
                    all[pairs - 1] = PairSpace::Square;
                }
                all
            }
        },
    };
    if lone && sample_space[pairs - 1] != PairSpace::Square {
        return Err(SpecError::at(
            "sample_space",
            f.get("sample_space").and_then(|v| v.span),
            format!(
                "dimension {} is alone (sample_dims = {sample_dims} is odd): it has no second value to warp, so its entry must be \"square\"",
                sample_dims - 1
            ),
        ));
    }
    let spatial = match f.get("spatial_filter") {
        None => DEFAULT_FILTER,
        Some(v) => spatial_filter(v)?,
    };
    let temporal_v = f.get("temporal_filter").cloned();
    let temporal = match &temporal_v {
        None => TemporalFilter::None,
        Some(v) => {
            let (kind, _) = filter_table("temporal_filter", v)?;
            if !matches!(kind, "none" | "ema") {
                return Err(SpecError::at(
                    "temporal_filter",
                    v.span,
                    format!(
                        "unknown temporal filter \"{}\" (a sampler tile's is the accumulation a renderer runs over its frames); valid: none, ema",
                        super::error::Shown(kind)
                    ),
                ));
            }
            match temporal_filter(v)? {
                t @ (TemporalFilter::None | TemporalFilter::Ema { beta: 0.0, .. }) => t,
                _ => {
                    return Err(SpecError::at(
                        "temporal_filter",
                        v.span,
                        "a sampler tile's `temporal_filter` is the accumulation a renderer runs: `{ kind = \"ema\", alpha = 0.1 }` (no history rejection, `beta` 0) or `{ kind = \"none\" }`",
                    ));
                }
            }
        }
    };
    let accumulates = matches!(temporal, TemporalFilter::Ema { .. });
    let frames_v = f.get("frames").cloned();
    let frames = match (&frames_v, accumulates) {
        (None, true) => DEFAULT_EMA_FRAMES,
        (None, false) => 1,
        (Some(v), true) => count("frames", Some(v.clone()), 1, 2, MAX_FRAMES as i64)? as u32,
        (Some(v), false) => {
            let n = count("frames", Some(v.clone()), 1, 1, MAX_FRAMES as i64)?;
            if n != 1 {
                return Err(SpecError::at(
                    "frames",
                    v.span,
                    "`frames` counts the history an accumulating filter reads: give `temporal_filter = { kind = \"ema\", alpha = 0.1 }` too (every frame of a tile is its first frame moved, so frames are not scored one by one)",
                ));
            }
            1
        }
    };
    Ok(SamplerParams {
        spp,
        sample_dims,
        sample_space,
        spatial,
        temporal,
        frames,
    })
}
