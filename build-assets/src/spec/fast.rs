//! The `fast` kind: its parameter types (sample space, distribution, filters, combination,
//! start), their parsing, defaults and validation. The generator (`crate::generate::fast`)
//! reads these types and adds the filters' overlaps; nothing here depends on it.

use super::{Fields, Span, Spanned, SpecError, Value, number, type_error};
use crate::spec::{Format, Num, Scalar, Shown, closest};

/// Every parameter of a FAST mask (the `fast` spec kind).
#[derive(Clone, Debug, PartialEq)]
pub struct FastParams {
    /// Where samples live.
    pub sample_space: SampleSpace,
    /// Distribution of scalar samples.
    pub distribution: Distribution,
    /// Spatial filter (separable in x and y).
    pub spatial: Filter,
    /// Temporal filter.
    pub temporal: TemporalFilter,
    /// How spatial and temporal overlaps combine.
    pub combine: Combine,
    /// Optional cap on optimisation rounds (by default until converged, at most the generator's `MAX_ROUNDS`).
    pub iterations: Option<u32>,
    /// Where the optimiser starts.
    pub start: Start,
}

/// The optimiser's starting arrangement of each slice's samples. The default is [`Start::Ign`]
/// for scalar sample spaces; for the spaces made from two values (vec2, sphere, hemispheres)
/// [`Start::IgnR2`] under a box spatial filter and [`Start::RdIgnR2`] under any other; and
/// [`Start::Random`] for vec3 and vec4.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// A random order per slice (FAST §4).
    Random,
    /// Scalar samples in the order of interleaved gradient noise's ranks in that slice, IGN
    /// animated by 5.588238 pixels per frame (Jimenez 2014): a swap optimiser started there can
    /// only end below IGN's loss.
    Ign,
    /// Vectors warped from the free pair of `noise_runtime::sampler::ign_r2` (interleaved
    /// gradient noise and the R2 grid, golden-ratio animated) by the runtime's warp for the
    /// sample space: the mask starts as that free construction, so the optimiser can only end
    /// below its loss. For the two-parameter spaces (vec2, sphere, hemispheres).
    IgnR2,
    /// As [`Start::IgnR2`] from `noise_runtime::sampler::rd_ign_r2` (the R2 sequence over
    /// frames, rotated per pixel by IGN and the R2 grid).
    RdIgnR2,
}

impl Start {
    /// Its name in a spec (`start = "…"`) and in the cache key.
    pub fn name(self) -> &'static str {
        match self {
            Start::Random => "random",
            Start::Ign => "ign",
            Start::IgnR2 => "ign_r2",
            Start::RdIgnR2 => "rd_ign_r2",
        }
    }
}

/// A 1D filter along a spatial axis (applied separably in x and y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    /// No filtering along the axis (a single unit tap).
    None,
    /// An `n`-tap box.
    Box {
        /// Tap count.
        size: usize,
    },
    /// A Gaussian of standard deviation σ, truncated at `ceil(3σ)`.
    Gauss {
        /// Standard deviation in texels.
        sigma: f64,
    },
    /// The binomial filter of order N (`C(N, k) / 2^N`, N + 1 taps).
    Binomial {
        /// Order.
        order: usize,
    },
    /// The à-trous wavelet filter of SVGF-style denoisers (Dammertz et al. 2010; Schied et al.
    /// 2017, §4.4) without its edge-stopping weights: `passes` convolutions with the B3 spline
    /// `(1, 4, 6, 4, 1)/16`, the taps of pass `k` spread `2^k` texels apart. A fixed linear
    /// filter, separable, `4·(2^passes − 1) + 1` taps wide; a denoiser's edge-stopping weights
    /// cut it at edges, which the loss cannot know.
    Atrous {
        /// Passes (1 to 5).
        passes: usize,
    },
}

impl Filter {
    /// The canonical text: a table with its `kind` first, e.g. `{kind=gauss,sigma=1.3435}`.
    pub fn canonical(self) -> String {
        use super::canonical::num;
        match self {
            Filter::None => "{kind=none}".to_string(),
            Filter::Box { size } => format!("{{kind=box,size={size}}}"),
            Filter::Gauss { sigma } => format!("{{kind=gauss,sigma={}}}", num(sigma)),
            Filter::Binomial { order } => format!("{{kind=binomial,order={order}}}"),
            Filter::Atrous { passes } => format!("{{kind=atrous,passes={passes}}}"),
        }
    }

    /// The normalised taps (they sum to 1), centred.
    pub fn taps(self) -> Vec<f64> {
        let t: Vec<f64> = match self {
            Filter::None => vec![1.0],
            Filter::Box { size } => vec![1.0; size.max(1)],
            Filter::Gauss { sigma } => {
                let r = (3.0 * sigma).ceil() as i64;
                (-r..=r)
                    .map(|x| crate::detmath::exp(-((x * x) as f64) / (2.0 * sigma * sigma)))
                    .collect()
            }
            Filter::Binomial { order } => {
                let mut row = vec![1.0f64];
                for _ in 0..order {
                    let mut next = vec![1.0; row.len() + 1];
                    for k in 1..row.len() {
                        next[k] = row[k - 1] + row[k];
                    }
                    row = next;
                }
                row
            }
            Filter::Atrous { passes } => {
                let mut taps = vec![1.0f64];
                for k in 0..passes {
                    let step = 1usize << k;
                    let mut next = vec![0.0; taps.len() + 4 * step];
                    for (i, &t) in taps.iter().enumerate() {
                        for (j, b) in [1.0, 4.0, 6.0, 4.0, 1.0].iter().enumerate() {
                            next[i + j * step] += t * b / 16.0;
                        }
                    }
                    taps = next;
                }
                taps
            }
        };
        let sum: f64 = t.iter().sum();
        t.into_iter().map(|x| x / sum).collect()
    }
}

/// A filter along time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TemporalFilter {
    /// No temporal filtering.
    None,
    /// An `n`-frame box.
    Box {
        /// Frame count.
        size: usize,
    },
    /// A Gaussian over frames.
    Gauss {
        /// Standard deviation in frames.
        sigma: f64,
    },
    /// Exponential moving average (FAST eq. 14–17): each frame blends `α` of the new sample
    /// into the history; with probability `β` per frame the history is rejected (eq. 17).
    /// `β = 0` is the plain EMA a game's accumulation runs, at its steady state over the
    /// looping texture.
    Ema {
        /// Blend weight of the new frame, in (0, 1].
        alpha: f64,
        /// History-rejection probability, in [0, 1]; 0 for a plain EMA.
        beta: f64,
    },
    /// Temporal anti-aliasing as games run it (Karis 2014): the plain EMA, with the history
    /// clamped to the min/max of the current frame's 3 × 3 neighbourhood before each blend.
    ///
    /// The clamp is what breaks blue noise under TAA: a window whose nine values all fall on
    /// one side of a dither's threshold has a box of a single value, and the history collapses
    /// onto the current frame. So the optimiser keeps every 3 × 3 window of every slice holding
    /// a value below `coverage` and one at or above `1 − coverage` (the property the R2 grid has
    /// by construction): for a dither `[s < a]` at any coverage `a` in `[coverage, 1 −
    /// coverage]` every box then spans 0 to 1, the clamp never acts, and the error is the
    /// EMA's, which the loss measures exactly. Scalar masks only. `noisebake report taa`
    /// measures it, with variance clipping and a moving camera too.
    ///
    /// With `motion` the camera also moves: a game's TAA reprojects the history, so under a
    /// motion of `v` pixels per frame a pixel's EMA runs along the line `x − k·v` through the
    /// slices, and a mask arranged for a static pixel loses its temporal order there. The loss
    /// then weighs the sheared filter too: `(1 − moving) · F(d, τ) + moving · F(d − τ·v, τ)`
    /// (for the EMA `f(x, t)` followed along `v`, the overlap `f ⋆ f` is the static one shifted
    /// by `τ·v`), trading some of the static error for the moving one. Its footprint reaches
    /// `τ·|v|` pixels, so the bake takes several times longer (`noisebake report taa`).
    Taa {
        /// Blend weight of the new frame, in (0, 1].
        alpha: f64,
        /// The lowest coverage (and one less the highest) whose dither every window keeps, in
        /// [0.15, 0.5]: below 1/9 no arrangement can give every window a value under it, and
        /// below 0.15 the bakes measured left windows open (32×32×8: 724 of 8 192 at 0.12).
        coverage: f64,
        /// The camera's motion in pixels per frame the loss also weighs (`[0, 0]`: static
        /// only), each component in `[-MAX_MOTION, MAX_MOTION]`.
        motion: [i32; 2],
        /// The share of the loss given to the moving camera, in [0, 1) (0 without `motion`).
        moving: f64,
    },
}

/// Most pixels per frame along each axis of a `taa` filter's `motion`.
pub const MAX_MOTION: i64 = 8;

/// The share of the loss a `taa` filter gives its `motion` when the spec leaves `moving` out: a
/// quarter, so the moving camera's error reaches IGN's while the static one stays near it
/// (`noisebake report taa` measures both).
pub const DEFAULT_MOVING: f64 = 0.25;

/// The default `coverage` of a `taa` temporal filter.
pub const DEFAULT_TAA_COVERAGE: f64 = 0.2;

impl TemporalFilter {
    /// The filter the loss sees: a `taa` filter's EMA (its clamp is a constraint on the
    /// arrangement, not a weight: see [`TemporalFilter::Taa`]).
    pub fn weights(self) -> TemporalFilter {
        match self {
            TemporalFilter::Taa { alpha, .. } => TemporalFilter::Ema { alpha, beta: 0.0 },
            t => t,
        }
    }

    /// A `taa` filter's motion and the share of the loss it gets, `None` for a static camera
    /// and every other filter.
    pub fn motion(self) -> Option<([i32; 2], f64)> {
        match self {
            TemporalFilter::Taa { motion, moving, .. } if motion != [0, 0] && moving > 0.0 => {
                Some((motion, moving))
            }
            _ => None,
        }
    }

    /// The coverage a `taa` filter's windows keep, `None` for every other filter.
    pub fn clamp_coverage(self) -> Option<f64> {
        match self {
            TemporalFilter::Taa { coverage, .. } => Some(coverage),
            _ => None,
        }
    }
}

impl TemporalFilter {
    /// Frames the filter spans (1 for none).
    pub fn width(self) -> usize {
        match self {
            TemporalFilter::None | TemporalFilter::Ema { .. } | TemporalFilter::Taa { .. } => 1,
            TemporalFilter::Box { size } => size,
            TemporalFilter::Gauss { sigma } => Filter::Gauss { sigma }.taps().len(),
        }
    }
}

/// How the spatial and temporal overlaps combine (FAST §5.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Combine {
    /// `F = F_xy · F_t`: the result is filtered in space and time.
    Product,
    /// `F = w · F_xy` within a frame `+ (1 − w) · F_t` at the same pixel (Wolfe et al. 2022's
    /// separate spatial and temporal objectives).
    Separate(f64),
}

/// Where the samples live.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleSpace {
    /// A scalar (distribution chosen by [`Distribution`]); distance `|x − y|`.
    Scalar,
    /// An angle in turns, `[0, 1)`; distance wrapped around the circle.
    Circle,
    /// Uniform in `[0, 1)^2`; Euclidean distance.
    Vec2,
    /// Uniform in `[0, 1)^3`; Euclidean distance.
    Vec3,
    /// Uniform in `[0, 1)^4`; Euclidean distance.
    Vec4,
    /// Unit vectors, uniform on the sphere; geodesic distance.
    Sphere,
    /// Unit vectors, uniform on the `z ≥ 0` hemisphere; geodesic distance.
    Hemisphere,
    /// Unit vectors, cosine-weighted on the `z ≥ 0` hemisphere; geodesic distance.
    CosineHemisphere,
}

/// Every `sample_space` value.
pub const SAMPLE_SPACES: &[&str] = &[
    "scalar",
    "circle",
    "vec2",
    "vec3",
    "vec4",
    "sphere",
    "hemisphere",
    "cosine_hemisphere",
];

/// The distribution of scalar samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// Uniform on `[0, 1)`.
    Uniform,
    /// Triangular on `[0, 1)`, peak at ½.
    Tent,
    /// Standard normal (mean 0, σ 1); f32 storage only.
    Gauss,
}

impl SampleSpace {
    /// Parses a `sample_space` value.
    pub fn parse(s: &str) -> Option<SampleSpace> {
        Some(match s {
            "scalar" => SampleSpace::Scalar,
            "circle" => SampleSpace::Circle,
            "vec2" => SampleSpace::Vec2,
            "vec3" => SampleSpace::Vec3,
            "vec4" => SampleSpace::Vec4,
            "sphere" => SampleSpace::Sphere,
            "hemisphere" => SampleSpace::Hemisphere,
            "cosine_hemisphere" => SampleSpace::CosineHemisphere,
            _ => return None,
        })
    }

    /// The key's spelling.
    pub fn name(self) -> &'static str {
        SAMPLE_SPACES[self as usize]
    }

    /// Channels per sample.
    pub fn channels(self) -> usize {
        match self {
            SampleSpace::Scalar | SampleSpace::Circle => 1,
            SampleSpace::Vec2 => 2,
            SampleSpace::Vec3
            | SampleSpace::Sphere
            | SampleSpace::Hemisphere
            | SampleSpace::CosineHemisphere => 3,
            SampleSpace::Vec4 => 4,
        }
    }

    /// Whether a sample is made from two uniform values (a pair, or a direction warped from
    /// one): the spaces a free pair can start ([`Start::IgnR2`]).
    pub fn from_two_values(self) -> bool {
        matches!(
            self,
            SampleSpace::Vec2
                | SampleSpace::Sphere
                | SampleSpace::Hemisphere
                | SampleSpace::CosineHemisphere
        )
    }

    /// Whether samples are unit vectors (stored as `0.5 + 0.5·v`).
    pub fn is_unit_vector(self) -> bool {
        matches!(
            self,
            SampleSpace::Sphere | SampleSpace::Hemisphere | SampleSpace::CosineHemisphere
        )
    }
}

impl FastParams {
    /// The canonical text of the parameters, field by field in this order (see
    /// [`TextureSpec::canonical`](super::TextureSpec::canonical) for the grammar):
    /// `sample_space`, `distribution`, `spatial_filter`, `temporal_filter` (each filter as a
    /// table with its `kind` first), `combine` (`product` or `{separate=w}`), `iterations` (a
    /// count or `converged`), `start`.
    pub fn canonical(&self) -> String {
        use super::canonical::num;
        let spatial = self.spatial.canonical();
        let temporal = match self.temporal {
            TemporalFilter::None => "{kind=none}".to_string(),
            TemporalFilter::Box { size } => format!("{{kind=box,size={size}}}"),
            TemporalFilter::Gauss { sigma } => format!("{{kind=gauss,sigma={}}}", num(sigma)),
            TemporalFilter::Ema { alpha, beta } => {
                format!("{{kind=ema,alpha={},beta={}}}", num(alpha), num(beta))
            }
            TemporalFilter::Taa {
                alpha,
                coverage,
                motion,
                moving,
            } => {
                format!(
                    "{{kind=taa,alpha={},coverage={},motion=[{},{}],moving={}}}",
                    num(alpha),
                    num(coverage),
                    motion[0],
                    motion[1],
                    num(moving)
                )
            }
        };
        let combine = match self.combine {
            Combine::Product => "product".to_string(),
            Combine::Separate(w) => format!("{{separate={}}}", num(w)),
        };
        let iterations = self
            .iterations
            .map_or_else(|| "converged".to_string(), |n| n.to_string());
        format!(
            "sample_space={};distribution={};spatial_filter={spatial};temporal_filter={temporal};combine={combine};iterations={iterations};start={}",
            self.sample_space.name(),
            self.distribution.name(),
            self.start.name()
        )
    }
}

impl Distribution {
    /// The key's spelling.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Uniform => "uniform",
            Distribution::Tent => "tent",
            Distribution::Gauss => "gauss",
        }
    }
}

/// The smallest `coverage` a `taa` filter takes.
pub const MIN_TAA_COVERAGE: f64 = 0.15;

/// How many of a slice's `n` ranked values lie below `coverage` and how many at or above one
/// less it, as `scalar` stores them (rank `r` of `n` is `⌊r · 2^bits / n⌋` in the unorm
/// formats, read at its step's centre: a few steps below `(r + 0.5) / n` for a small slice).
pub fn clamp_classes(coverage: f64, n: usize, scalar: Scalar) -> [usize; 2] {
    let ranks: Vec<u32> = (0..n as u32).collect();
    let values = crate::encoding::decode_unit(
        &crate::encoding::encode_ranks(&ranks, n as u32, scalar),
        scalar,
    );
    [
        values.iter().filter(|&&v| v < coverage).count(),
        values.iter().filter(|&&v| v >= 1.0 - coverage).count(),
    ]
}

/// The fewest texels of a `w × h` slice (wrapping) whose 3 × 3 windows cover every texel: the
/// domination number of the king's graph on that torus, `⌈w/3⌉ · ⌈h/3⌉` (a texel's window
/// spans 3 columns and 3 rows of centres). Under a `taa` filter a slice needs this many values
/// below the coverage, and as many at or above one less it, for every window to be closed.
pub fn texels_to_cover(w: usize, h: usize) -> usize {
    w.div_ceil(3) * h.div_ceil(3)
}

/// The EMA's blend weight when a spec leaves it out (FAST §7 uses 0.1).
const DEFAULT_ALPHA: f64 = 0.1;
/// The smallest EMA blend weight a spec takes: a history of about a thousand frames. Below it
/// the filter is no longer one a renderer runs (`5e-324` was accepted, and a moving camera's
/// footprint then reached past every frame).
pub const MIN_ALPHA: f64 = 1e-3;

/// Reads the `fast` keys for a texture of `dims` stored as `format`.
pub(super) fn parse(
    f: &mut Fields<'_>,
    dims: &[usize],
    format: Format,
    format_span: Option<Span>,
) -> Result<FastParams, SpecError> {
    let sample_space = match f.string("sample_space")? {
        None => SampleSpace::Scalar,
        Some((s, span)) => SampleSpace::parse(s).ok_or_else(|| {
            let hint = closest(s, SAMPLE_SPACES)
                .map(|c| format!(" (did you mean `{c}`?)"))
                .unwrap_or_default();
            SpecError::at(
                "sample_space",
                span,
                format!(
                    "unknown `sample_space` \"{}\"{hint}; valid: {}",
                    Shown(s),
                    SAMPLE_SPACES.join(", ")
                ),
            )
        })?,
    };
    let distribution = match f.string("distribution")? {
        None => Distribution::Uniform,
        Some((s, span)) => {
            let d = match s {
                "uniform" => Distribution::Uniform,
                "tent" => Distribution::Tent,
                "gauss" => Distribution::Gauss,
                _ => {
                    return Err(SpecError::at(
                        "distribution",
                        span,
                        format!(
                            "`distribution` must be \"uniform\", \"tent\" or \"gauss\", got \"{}\"",
                            Shown(s)
                        ),
                    ));
                }
            };
            if sample_space != SampleSpace::Scalar && d != Distribution::Uniform {
                return Err(SpecError::at(
                    "distribution",
                    span,
                    format!(
                        "`distribution` applies to scalar samples only; sample space `{}` has its own",
                        sample_space.name()
                    ),
                ));
            }
            d
        }
    };
    let want = sample_space.channels();
    if format.channels as usize != want {
        let example = if want == 1 {
            "u8, u16 or f32".to_string()
        } else {
            format!("u8x{want} or f32x{want}")
        };
        return Err(SpecError::at(
            "format",
            format_span,
            format!(
                "sample space `{}` has {want} channel(s); `format` must be {example}, got {format}",
                sample_space.name()
            ),
        ));
    }
    if distribution == Distribution::Gauss && format.scalar != Scalar::F32 {
        return Err(SpecError::at(
            "format",
            format_span,
            format!("Gaussian samples are unbounded and need `format = \"f32\"`, got {format}"),
        ));
    }
    let given = f.get("spatial_filter");
    let spatial = match given {
        None => Filter::Gauss { sigma: 1.3435 },
        Some(v) => spatial_filter(v)?,
    };
    let taps = spatial.taps().len();
    if taps > dims[0] || taps > dims[1] {
        let what = if given.is_some() {
            "`spatial_filter`".to_string()
        } else {
            "the default `spatial_filter` (Gaussian σ 1.3435)".to_string()
        };
        return Err(SpecError::at(
            "spatial_filter",
            given.and_then(|v| v.span),
            format!(
                "{what} is {taps} texels wide, wider than the texture ({}×{}); give a narrower filter",
                dims[0], dims[1]
            ),
        ));
    }
    let frames = dims.get(2).copied().unwrap_or(1);
    let temporal = match f.get("temporal_filter") {
        // The filter a game's plain accumulation runs: an EMA with α 0.1 and no history
        // rejection. EA's published texture was made for β 0.1 (eq. 17); that is a choice the
        // spec states, not a default a game would silently get.
        None if frames > 1 => TemporalFilter::Ema {
            alpha: DEFAULT_ALPHA,
            beta: 0.0,
        },
        None => TemporalFilter::None,
        Some(v) => {
            let t = temporal_filter(v)?;
            if frames == 1 && t != TemporalFilter::None {
                return Err(SpecError::at(
                    "temporal_filter",
                    v.span,
                    "`temporal_filter` needs a time axis: give `dims` three entries [x, y, t]",
                ));
            }
            if t.width() > frames {
                return Err(SpecError::at(
                    "temporal_filter",
                    v.span,
                    format!(
                        "`temporal_filter` spans {} frames, more than the texture's {frames}",
                        t.width()
                    ),
                ));
            }
            if t.clamp_coverage().is_some() {
                if sample_space != SampleSpace::Scalar {
                    return Err(SpecError::at(
                        "temporal_filter",
                        v.span,
                        format!(
                            "a `taa` temporal filter keeps scalar masks' 3×3 windows spread over [0, 1]; `sample_space` \"{}\" is not scalar (use `ema`)",
                            sample_space.name()
                        ),
                    ));
                }
                if dims[0] < 3 || dims[1] < 3 {
                    return Err(SpecError::at(
                        "temporal_filter",
                        v.span,
                        "a `taa` temporal filter needs slices of at least 3×3 texels (its clamp's window)",
                    ));
                }
                let coverage = t.clamp_coverage().unwrap_or_default();
                let [low, high] = clamp_classes(coverage, dims[0] * dims[1], format.scalar);
                let need = texels_to_cover(dims[0], dims[1]);
                if low.min(high) < need {
                    return Err(SpecError::at(
                        "temporal_filter.coverage",
                        v.span,
                        format!(
                            "a `taa` filter with coverage {} keeps {low} values of a {}×{} slice below it and {high} at or above one less it (as {} stores them), but closing every 3×3 window needs {need} of each (⌈w/3⌉·⌈h/3⌉): raise `coverage` or make the slices larger",
                            Num(coverage),
                            dims[0],
                            dims[1],
                            format
                        ),
                    ));
                }
            }
            t
        }
    };
    let combine = match f.get("combine") {
        None => Combine::Product,
        Some(Spanned {
            value: Value::Str(s),
            ..
        }) if s == "product" => Combine::Product,
        Some(
            v @ Spanned {
                value: Value::Table(t),
                ..
            },
        ) if t.len() == 1 && t[0].0.value == "separate" => {
            let w = number("combine.separate", &t[0].1)?;
            if !(0.0..=1.0).contains(&w) {
                return Err(SpecError::at(
                    "combine.separate",
                    t[0].1.span.or(v.span),
                    format!("`combine.separate` is a weight in [0, 1], got {}", Num(w)),
                ));
            }
            if temporal.motion().is_some() {
                return Err(SpecError::at(
                    "combine",
                    v.span,
                    "a `taa` filter's `motion` follows the camera through space and time together; it needs `combine = \"product\"` (the default)",
                ));
            }
            Combine::Separate(w)
        }
        Some(v) => {
            return Err(SpecError::at(
                "combine",
                v.span,
                "`combine` must be \"product\" or { separate = w } with w in [0, 1]",
            ));
        }
    };
    let iterations = match f.get("iterations") {
        None => None,
        Some(v) => match v.value {
            Value::Int(i) if (1..=1_000_000).contains(&i) => Some(i as u32),
            Value::Int(i) => {
                return Err(SpecError::at(
                    "iterations",
                    v.span,
                    format!("`iterations` must be in 1..=1000000, got {i}"),
                ));
            }
            _ => return Err(type_error("iterations", "an integer", v)),
        },
    };
    let start = match f.string("start")? {
        // Measured: from IGN's ranks the swap optimiser ends lower than from a random order,
        // for every filter tried (the `report fast` comparison); vectors have no such order.
        None if sample_space.channels() == 1 => Start::Ign,
        // Measured (`noisebake report vector`, 128×128×32 cosine hemisphere and sphere): a
        // random start ends 2–92 % above the best free construction; from the free pair it
        // ends at or below it. After a box filter IGN × R2 is the better start, after a
        // Gaussian the rotated R2 sequence.
        None if sample_space.from_two_values() => match spatial {
            Filter::Box { .. } => Start::IgnR2,
            _ => Start::RdIgnR2,
        },
        None | Some(("random", _)) => Start::Random,
        Some(("ign", span)) => {
            if sample_space.channels() != 1 {
                return Err(SpecError::at(
                    "start",
                    span,
                    "`start = \"ign\"` orders scalar samples; this sample space has vectors",
                ));
            }
            Start::Ign
        }
        Some((name @ ("ign_r2" | "rd_ign_r2"), span)) => {
            if !sample_space.from_two_values() {
                return Err(SpecError::at(
                    "start",
                    span,
                    format!(
                        "`start = \"{name}\"` warps a pair of values; sample_space \"{}\" is not made from two (use vec2, sphere, hemisphere or cosine_hemisphere)",
                        sample_space.name()
                    ),
                ));
            }
            if name == "ign_r2" {
                Start::IgnR2
            } else {
                Start::RdIgnR2
            }
        }
        Some((other, span)) => {
            return Err(SpecError::at(
                "start",
                span,
                format!(
                    "`start` must be \"random\", \"ign\", \"ign_r2\" or \"rd_ign_r2\", got \"{}\"",
                    Shown(other)
                ),
            ));
        }
    };
    let params = FastParams {
        sample_space,
        distribution,
        spatial,
        temporal,
        combine,
        iterations,
        start,
    };
    // No refusal by work: a long bake is announced with its estimate (`crate::generate::estimate`) and
    // shows progress; memory is bounded by the texel limit every kind shares.
    Ok(params)
}

/// The entries of a nested table.
type Entries<'a> = &'a [(Spanned<String>, Spanned<Value>)];

/// Reads the `kind` of a filter table and checks that only `allowed` other keys appear.
pub(super) fn filter_table<'a>(
    key: &str,
    v: &'a Spanned<Value>,
) -> Result<(&'a str, Entries<'a>), SpecError> {
    let Value::Table(t) = &v.value else {
        return Err(type_error(
            key,
            "a table like { kind = \"gauss\", sigma = 1.0 }",
            v,
        ));
    };
    let kind = t
        .iter()
        .find(|(k, _)| k.value == "kind")
        .ok_or_else(|| SpecError::at(key, v.span, format!("`{key}` needs a `kind`")))?;
    match &kind.1.value {
        Value::Str(s) => Ok((s.as_str(), t.as_slice())),
        _ => Err(type_error(&format!("{key}.kind"), "a string", &kind.1)),
    }
}

/// The one parameter key of a filter, validated.
/// A `taa` filter's `motion`: two integers, pixels per frame, each at most [`MAX_MOTION`] in
/// size.
fn motion_pair(v: &Spanned<Value>) -> Result<[i32; 2], SpecError> {
    const KEY: &str = "temporal_filter.motion";
    let Value::Array(items) = &v.value else {
        return Err(type_error(
            KEY,
            "two integers like [3, 1] (pixels per frame)",
            v,
        ));
    };
    if items.len() != 2 {
        return Err(SpecError::at(
            KEY,
            v.span,
            format!(
                "`{KEY}` takes two integers (pixels per frame in x and y), got {}",
                items.len()
            ),
        ));
    }
    let mut out = [0i32; 2];
    for (o, item) in out.iter_mut().zip(items) {
        let Value::Int(i) = item.value else {
            return Err(type_error(KEY, "integers (whole pixels per frame)", item));
        };
        if i.abs() > MAX_MOTION {
            return Err(SpecError::at(
                KEY,
                item.span,
                format!("`{KEY}` must be within ±{MAX_MOTION} pixels per frame, got {i}"),
            ));
        }
        *o = i as i32;
    }
    Ok(out)
}

fn param(
    key: &str,
    t: &[(Spanned<String>, Spanned<Value>)],
    name: &str,
    span: Option<Span>,
    allowed_extra: &[&str],
) -> Result<Option<Spanned<Value>>, SpecError> {
    for (k, _) in t {
        if k.value != "kind" && k.value != name && !allowed_extra.contains(&k.value.as_str()) {
            // Name every key this kind of filter takes, not only the one being read.
            let mut keys: Vec<&str> = std::iter::once(name)
                .chain(allowed_extra.iter().copied())
                .filter(|k| *k != "-")
                .collect();
            keys.sort_unstable();
            let kind = t
                .iter()
                .find(|(k, _)| k.value == "kind")
                .and_then(|(_, v)| match &v.value {
                    Value::Str(s) => Some(s.as_str()),
                    _ => None,
                })
                .unwrap_or("?");
            let takes = if keys.is_empty() {
                "takes only `kind`".to_string()
            } else {
                let listed: Vec<String> = keys.iter().map(|k| format!("`{k}`")).collect();
                format!("takes `kind`, {}", listed.join(", "))
            };
            return Err(SpecError::at(
                format!("{key}.{}", Shown(&k.value)),
                k.span.or(span),
                format!(
                    "unknown key `{}` in `{key}`; a \"{}\" filter {takes}",
                    Shown(&k.value),
                    Shown(kind)
                ),
            ));
        }
    }
    Ok(t.iter()
        .find(|(k, _)| k.value == name)
        .map(|(_, v)| v.clone()))
}

fn positive(
    key: &str,
    v: Option<Spanned<Value>>,
    default: f64,
    max: f64,
) -> Result<f64, SpecError> {
    let Some(v) = v else { return Ok(default) };
    let x = number(key, &v)?;
    if !(x > 0.0 && x <= max) {
        return Err(SpecError::at(
            key,
            v.span,
            format!("`{key}` must be in (0, {max}], got {}", Num(x)),
        ));
    }
    Ok(x)
}

pub(super) fn count(
    key: &str,
    v: Option<Spanned<Value>>,
    default: i64,
    lo: i64,
    hi: i64,
) -> Result<usize, SpecError> {
    let Some(v) = v else {
        return Ok(default as usize);
    };
    match v.value {
        Value::Int(i) if (lo..=hi).contains(&i) => Ok(i as usize),
        Value::Int(i) => Err(SpecError::at(
            key,
            v.span,
            format!("`{key}` must be in {lo}..={hi}, got {i}"),
        )),
        _ => Err(type_error(key, "an integer", &v)),
    }
}

pub(super) fn spatial_filter(v: &Spanned<Value>) -> Result<Filter, SpecError> {
    const K: &str = "spatial_filter";
    let (kind, t) = filter_table(K, v)?;
    Ok(match kind {
        "none" => {
            param(K, t, "-", v.span, &[])?;
            Filter::None
        }
        "box" => Filter::Box {
            size: count(
                "spatial_filter.size",
                param(K, t, "size", v.span, &[])?,
                5,
                1,
                64,
            )?,
        },
        "gauss" => Filter::Gauss {
            sigma: positive(
                "spatial_filter.sigma",
                param(K, t, "sigma", v.span, &[])?,
                1.0,
                16.0,
            )?,
        },
        "binomial" => Filter::Binomial {
            order: count(
                "spatial_filter.order",
                param(K, t, "order", v.span, &[])?,
                2,
                1,
                64,
            )?,
        },
        "atrous" => Filter::Atrous {
            passes: count(
                "spatial_filter.passes",
                param(K, t, "passes", v.span, &[])?,
                3,
                1,
                5,
            )?,
        },
        other => {
            return Err(SpecError::at(
                "spatial_filter.kind",
                v.span,
                format!(
                    "unknown spatial filter \"{}\"; valid: none, box, gauss, binomial, atrous",
                    Shown(other)
                ),
            ));
        }
    })
}

pub(super) fn temporal_filter(v: &Spanned<Value>) -> Result<TemporalFilter, SpecError> {
    const K: &str = "temporal_filter";
    let (kind, t) = filter_table(K, v)?;
    Ok(match kind {
        "none" => {
            param(K, t, "-", v.span, &[])?;
            TemporalFilter::None
        }
        "box" => TemporalFilter::Box {
            size: count(
                "temporal_filter.size",
                param(K, t, "size", v.span, &[])?,
                4,
                1,
                256,
            )?,
        },
        "gauss" => TemporalFilter::Gauss {
            sigma: positive(
                "temporal_filter.sigma",
                param(K, t, "sigma", v.span, &[])?,
                1.0,
                64.0,
            )?,
        },
        "ema" => {
            let alpha = param(K, t, "alpha", v.span, &["beta"])?;
            let beta = param(K, t, "beta", v.span, &["alpha"])?;
            // α in (0, 1]; β (history rejection) in [0, 1], 0 meaning a plain EMA at its steady
            // state over the looping texture.
            // Left out, α is 0.1 and β 0 (a plain EMA), as when the whole key is left out.
            let unit =
                |key: &str, v: Option<Spanned<Value>>, zero: bool| -> Result<f64, SpecError> {
                    let Some(v) = v else {
                        return Ok(if zero { 0.0 } else { DEFAULT_ALPHA });
                    };
                    let x = number(key, &v)?;
                    let ok = if zero {
                        (0.0..=1.0).contains(&x)
                    } else {
                        (MIN_ALPHA..=1.0).contains(&x)
                    };
                    if !ok {
                        let range = if zero { "[0, 1]" } else { "[0.001, 1]" };
                        return Err(SpecError::at(
                            key,
                            v.span,
                            format!("`{key}` must be in {range}, got {}", Num(x)),
                        ));
                    }
                    Ok(x)
                };
            TemporalFilter::Ema {
                alpha: unit("temporal_filter.alpha", alpha, false)?,
                beta: unit("temporal_filter.beta", beta, true)?,
            }
        }
        "taa" => {
            let alpha = param(K, t, "alpha", v.span, &["coverage", "motion", "moving"])?;
            let coverage = param(K, t, "coverage", v.span, &["alpha", "motion", "moving"])?;
            let motion_v = param(K, t, "motion", v.span, &["alpha", "coverage", "moving"])?;
            let moving_v = param(K, t, "moving", v.span, &["alpha", "coverage", "motion"])?;
            let alpha = match alpha {
                None => DEFAULT_ALPHA,
                Some(a) => {
                    let x = number("temporal_filter.alpha", &a)?;
                    if !(MIN_ALPHA..=1.0).contains(&x) {
                        return Err(SpecError::at(
                            "temporal_filter.alpha",
                            a.span,
                            format!(
                                "`temporal_filter.alpha` must be in [0.001, 1], got {}",
                                Num(x)
                            ),
                        ));
                    }
                    x
                }
            };
            let coverage = match coverage {
                None => DEFAULT_TAA_COVERAGE,
                Some(c) => {
                    let x = number("temporal_filter.coverage", &c)?;
                    if !(MIN_TAA_COVERAGE..=0.5).contains(&x) {
                        return Err(SpecError::at(
                            "temporal_filter.coverage",
                            c.span,
                            format!(
                                "`temporal_filter.coverage` must be in [0.15, 0.5] (below 1/9 no arrangement gives every 3×3 window a value under it, and below 0.15 bakes leave windows open), got {}",
                                Num(x)
                            ),
                        ));
                    }
                    x
                }
            };
            let motion = match &motion_v {
                None => [0, 0],
                Some(m) => motion_pair(m)?,
            };
            let moving = match (&moving_v, motion) {
                (None, [0, 0]) => 0.0,
                (None, _) => DEFAULT_MOVING,
                (Some(s), m) => {
                    let x = number("temporal_filter.moving", s)?;
                    if m == [0, 0] && x != 0.0 {
                        return Err(SpecError::at(
                            "temporal_filter.moving",
                            s.span,
                            "`temporal_filter.moving` weighs a moving camera: give its `motion` too (e.g. `motion = [3, 1]`)",
                        ));
                    }
                    if !(0.0..1.0).contains(&x) {
                        return Err(SpecError::at(
                            "temporal_filter.moving",
                            s.span,
                            format!("`temporal_filter.moving` must be in [0, 1), got {}", Num(x)),
                        ));
                    }
                    x
                }
            };
            TemporalFilter::Taa {
                alpha,
                coverage,
                motion,
                moving,
            }
        }
        other => {
            return Err(SpecError::at(
                "temporal_filter.kind",
                v.span,
                format!(
                    "unknown temporal filter \"{}\"; valid: none, box, gauss, ema, taa",
                    Shown(other)
                ),
            ));
        }
    })
}
