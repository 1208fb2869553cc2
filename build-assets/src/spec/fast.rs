//! The keys of the `fast` kind: sample space, distribution, filters, combination.

use super::{Fields, Span, Spanned, SpecError, Value, number, type_error};
use crate::fast::{
    Combine, Distribution, FastParams, Filter, SampleSpace, Start, TemporalFilter,
    space::SAMPLE_SPACES,
};
use crate::spec::{Format, Scalar, closest};

/// The EMA's blend weight when a spec leaves it out (FAST §7 uses 0.1).
const DEFAULT_ALPHA: f64 = 0.1;

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
                    "unknown `sample_space` \"{s}\"{hint}; valid: {}",
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
                            "`distribution` must be \"uniform\", \"tent\" or \"gauss\", got \"{s}\""
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
                    format!("`combine.separate` is a weight in [0, 1], got {w}"),
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
        Some((other, span)) => {
            return Err(SpecError::at(
                "start",
                span,
                format!("`start` must be \"random\" or \"ign\", got \"{other}\""),
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
    // No refusal by work: a long bake is announced with its estimate (`crate::estimate`) and
    // shows progress; memory is bounded by the texel limit every kind shares.
    Ok(params)
}

/// The entries of a nested table.
type Entries<'a> = &'a [(Spanned<String>, Spanned<Value>)];

/// Reads the `kind` of a filter table and checks that only `allowed` other keys appear.
fn filter_table<'a>(key: &str, v: &'a Spanned<Value>) -> Result<(&'a str, Entries<'a>), SpecError> {
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
fn param(
    key: &str,
    t: &[(Spanned<String>, Spanned<Value>)],
    name: &str,
    span: Option<Span>,
    allowed_extra: &[&str],
) -> Result<Option<Spanned<Value>>, SpecError> {
    for (k, _) in t {
        if k.value != "kind" && k.value != name && !allowed_extra.contains(&k.value.as_str()) {
            return Err(SpecError::at(
                format!("{key}.{}", k.value),
                k.span.or(span),
                format!(
                    "unknown key `{}` in `{key}`; expected `kind` and `{name}`",
                    k.value
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
            format!("`{key}` must be in (0, {max}], got {x}"),
        ));
    }
    Ok(x)
}

fn count(
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

fn spatial_filter(v: &Spanned<Value>) -> Result<Filter, SpecError> {
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
        other => {
            return Err(SpecError::at(
                "spatial_filter.kind",
                v.span,
                format!("unknown spatial filter \"{other}\"; valid: none, box, gauss, binomial"),
            ));
        }
    })
}

fn temporal_filter(v: &Spanned<Value>) -> Result<TemporalFilter, SpecError> {
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
                        x > 0.0 && x <= 1.0
                    };
                    if !ok {
                        let range = if zero { "[0, 1]" } else { "(0, 1]" };
                        return Err(SpecError::at(
                            key,
                            v.span,
                            format!("`{key}` must be in {range}, got {x}"),
                        ));
                    }
                    Ok(x)
                };
            TemporalFilter::Ema {
                alpha: unit("temporal_filter.alpha", alpha, false)?,
                beta: unit("temporal_filter.beta", beta, true)?,
            }
        }
        other => {
            return Err(SpecError::at(
                "temporal_filter.kind",
                v.span,
                format!("unknown temporal filter \"{other}\"; valid: none, box, gauss, ema"),
            ));
        }
    })
}
