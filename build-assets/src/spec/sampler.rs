//! The `sampler` kind: a tile of per-pixel keys for `spp` samples × `sample_dims` dimensions
//! per pixel (`noise_runtime::SamplerTile`: a key is the block of Sobol points a pixel takes),
//! chosen so that the pixels' Monte Carlo errors are blue under the scene's denoiser. Its parameters, their parsing, defaults and validation; the
//! generator (`crate::generate::sampler`) reads them.

use super::fast::{Filter, count, spatial_filter};
use super::{Fields, SpecError};

/// Every parameter of a sampler tile (the `sampler` spec kind).
#[derive(Clone, Debug, PartialEq)]
pub struct SamplerParams {
    /// Samples per pixel per frame, 1 to [`MAX_SPP`].
    pub spp: u32,
    /// Dimensions of each sample, 2 to [`MAX_SAMPLE_DIMS`].
    pub sample_dims: u32,
    /// The denoiser the errors should be blue for (separable in x and y; default Gaussian σ 1).
    pub spatial: Filter,
    /// Frames whose samples (frame `f` takes block `key ^ f`) the keys are chosen for, each
    /// frame's error filtered alone; 1 (the default) optimises the first.
    pub frames: u32,
}

/// Most samples per pixel per frame.
pub const MAX_SPP: u32 = 64;
/// Most dimensions per sample.
pub const MAX_SAMPLE_DIMS: u32 = 8;
/// Most pixels in a tile: a lone last dimension's key (one 16-bit layer) indexes the pool of
/// blocks, which holds at least one per pixel.
pub const MAX_PIXELS: usize = 1 << 16;
/// Most frames the keys are optimised for.
pub const MAX_FRAMES: u32 = 64;
/// The spatial filter when the spec leaves it out.
pub const DEFAULT_FILTER: Filter = Filter::Gauss { sigma: 1.0 };

impl SamplerParams {
    /// The canonical text, field by field in this order: `spp`, `sample_dims`,
    /// `spatial_filter` (a table with its `kind` first), `frames`.
    pub fn canonical(&self) -> String {
        format!(
            "spp={};sample_dims={};spatial_filter={};frames={}",
            self.spp,
            self.sample_dims,
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
    let spatial = match f.get("spatial_filter") {
        None => DEFAULT_FILTER,
        Some(v) => spatial_filter(v)?,
    };
    let frames = count("frames", f.get("frames").cloned(), 1, 1, MAX_FRAMES as i64)? as u32;
    Ok(SamplerParams {
        spp,
        sample_dims,
        spatial,
        frames,
    })
}
