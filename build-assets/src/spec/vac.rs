//! The keys of the void-and-cluster family: `blue2d`, `stbn`, `vac`, `independent2d`,
//! `golden` and `white` (parsing, defaults, validation), and the axis groups they share.

use super::{Fields, Kind, Spanned, SpecError, TextureSpec, Value, integer, type_error};

/// The default truncation of the Gaussian: offsets whose weight is below this are dropped.
/// At σ = 1.9 this keeps a disc of radius 7.4 (≈ 170 texels in 2D).
pub const DEFAULT_CUTOFF: f64 = 5e-4;

/// A set of axes that share one Gaussian (STBN App. B); the other axes must match exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Indices of the axes in the group (0 = x, fastest in memory).
    pub axes: Vec<usize>,
    /// Standard deviation of the Gaussian, in texels.
    pub sigma: f64,
}

/// The default σ of `blue2d` (Ulichney's).
pub const BLUE2D_SIGMA: f64 = 1.5;
/// The default σ of every other void-and-cluster Gaussian (STBN's).
pub const DEFAULT_SIGMA: f64 = 1.9;
/// The default `initial_density`.
pub const DEFAULT_DENSITY: f64 = 0.1;

/// The parameters of the void-and-cluster family, as [`FastParams`](super::FastParams) are
/// FAST's: one algorithm (STBN App. B) whose kinds are presets of its axis groups.
#[derive(Clone, Debug, PartialEq)]
pub struct VacParams {
    /// The axes that share one Gaussian, each group with its σ: x and y for `blue2d` (σ
    /// [`BLUE2D_SIGMA`] by default), `independent2d` and `golden` (each slice's 2D mask, σ
    /// [`DEFAULT_SIGMA`]); x and y, then t for `stbn` (`sigma_xy`, `sigma_t`); as given for
    /// `vac` (by default every axis in one group, σ [`DEFAULT_SIGMA`]).
    pub groups: Vec<Group>,
    /// Per axis of the groups: whether it wraps (`vac`'s `toroidal`; every axis for the
    /// others).
    pub toroidal: Vec<bool>,
    /// Density of the initial pattern ([`DEFAULT_DENSITY`]).
    pub initial_density: f64,
    /// How ranks become values (`stbn`, `vac`; the 2D kinds rank their one plane,
    /// [`Histogram::Volume`](super::Histogram::Volume)).
    pub histogram: super::Histogram,
}

impl VacParams {
    /// A 2D mask's parameters (`blue2d`, `independent2d`, `golden`): x and y with σ `sigma`.
    pub fn plane(sigma: f64, initial_density: f64) -> VacParams {
        VacParams {
            groups: vec![Group {
                axes: vec![0, 1],
                sigma,
            }],
            toroidal: vec![true; 2],
            initial_density,
            histogram: super::Histogram::Volume,
        }
    }

    /// STBN's parameters: x and y with σ `sigma_xy`, t with σ `sigma_t`.
    pub fn stbn(
        sigma_xy: f64,
        sigma_t: f64,
        initial_density: f64,
        histogram: super::Histogram,
    ) -> VacParams {
        VacParams {
            groups: vec![
                Group {
                    axes: vec![0, 1],
                    sigma: sigma_xy,
                },
                Group {
                    axes: vec![2],
                    sigma: sigma_t,
                },
            ],
            toroidal: vec![true; 3],
            initial_density,
            histogram,
        }
    }
}

/// The kinds this file parses.
pub const KINDS: &[&str] = &["blue2d", "stbn", "vac", "white", "independent2d", "golden"];

/// Reads the keys of the void-and-cluster kind `kind` (one of [`KINDS`]) for a texture of
/// `dims`; `want_dims` checks the dimension count the kind takes.
pub(super) fn parse(
    kind: &str,
    f: &mut Fields<'_>,
    dims: &[usize],
    want_dims: &dyn Fn(usize, usize) -> Result<(), SpecError>,
) -> Result<Kind, SpecError> {
    Ok(match kind {
        "blue2d" => {
            want_dims(2, 2)?;
            Kind::Blue2d(VacParams::plane(
                f.sigma("sigma", BLUE2D_SIGMA)?,
                f.density()?,
            ))
        }
        "stbn" => {
            want_dims(3, 3)?;
            Kind::Stbn(VacParams::stbn(
                f.sigma("sigma_xy", DEFAULT_SIGMA)?,
                f.sigma("sigma_t", DEFAULT_SIGMA)?,
                f.density()?,
                f.histogram()?,
            ))
        }
        "vac" => {
            want_dims(1, 4)?;
            let groups = match f.get("groups") {
                None => vec![Group {
                    axes: (0..dims.len()).collect(),
                    sigma: DEFAULT_SIGMA,
                }],
                Some(v) => parse_groups(v, dims.len())?,
            };
            let toroidal = match f.get("toroidal") {
                None => vec![true; dims.len()],
                Some(Spanned {
                    value: Value::Bool(b),
                    ..
                }) => vec![*b; dims.len()],
                Some(
                    v @ Spanned {
                        value: Value::Array(a),
                        ..
                    },
                ) => {
                    let t = a
                        .iter()
                        .map(|x| match x.value {
                            Value::Bool(b) => Ok(b),
                            _ => Err(type_error(
                                "toroidal",
                                "a boolean or an array of booleans",
                                x,
                            )),
                        })
                        .collect::<Result<Vec<_>, _>>()?;
                    if t.len() != dims.len() {
                        return Err(SpecError::at(
                            "toroidal",
                            v.span,
                            format!("`toroidal` has {} entries for {} dims", t.len(), dims.len()),
                        ));
                    }
                    t
                }
                Some(v) => {
                    return Err(type_error(
                        "toroidal",
                        "a boolean or an array of booleans",
                        v,
                    ));
                }
            };
            Kind::Vac(VacParams {
                groups,
                toroidal,
                initial_density: f.density()?,
                histogram: f.histogram()?,
            })
        }
        "white" => {
            want_dims(1, 4)?;
            Kind::White
        }
        "independent2d" => {
            want_dims(2, 4)?;
            Kind::Independent2d(VacParams::plane(
                f.sigma("sigma", DEFAULT_SIGMA)?,
                f.density()?,
            ))
        }
        "golden" => {
            want_dims(3, 3)?;
            Kind::Golden(VacParams::plane(
                f.sigma("sigma", DEFAULT_SIGMA)?,
                f.density()?,
            ))
        }
        other => {
            return Err(SpecError::msg(format!(
                "kind `{other}` is not of the void-and-cluster family"
            )));
        }
    })
}

pub(super) fn parse_groups(v: &Spanned<Value>, ndims: usize) -> Result<Vec<Group>, SpecError> {
    let Value::Array(items) = &v.value else {
        return Err(type_error(
            "groups",
            "an array of { axes = [...], sigma = ... } tables",
            v,
        ));
    };
    let mut seen = vec![false; ndims];
    let mut groups = Vec::new();
    for (gi, g) in items.iter().enumerate() {
        let Value::Table(t) = &g.value else {
            return Err(type_error(
                &format!("groups[{gi}]"),
                "a table { axes = [...], sigma = ... }",
                g,
            ));
        };
        let mut f = Fields {
            table: t,
            used: vec![false; t.len()],
            allowed: Vec::new(),
        };
        let key = format!("groups[{gi}].axes");
        let axes_v = f
            .get("axes")
            .ok_or_else(|| SpecError::at(&key, g.span, format!("`{key}` is missing")))?;
        let Value::Array(ax) = &axes_v.value else {
            return Err(type_error(&key, "an array of axis indices", axes_v));
        };
        if ax.is_empty() {
            return Err(SpecError::at(
                &key,
                axes_v.span,
                format!("`{key}` is empty"),
            ));
        }
        let mut axes = Vec::new();
        for a in ax {
            let i = integer(&key, a)?;
            if i < 0 || i as usize >= ndims {
                return Err(SpecError::at(
                    &key,
                    a.span,
                    format!("`{key}`: axis {i} does not exist (dims has {ndims} axes)"),
                ));
            }
            if seen[i as usize] {
                return Err(SpecError::at(
                    &key,
                    a.span,
                    format!("`{key}`: axis {i} is listed twice"),
                ));
            }
            seen[i as usize] = true;
            axes.push(i as usize);
        }
        let sigma = f.sigma("sigma", DEFAULT_SIGMA).map_err(|mut e| {
            e.key = Some(format!("groups[{gi}].sigma"));
            e.message = format!("groups[{gi}]: {}", e.message);
            e
        })?;
        f.finish(&format!("groups[{gi}]"))?;
        groups.push(Group { axes, sigma });
    }
    if let Some(missing) = seen.iter().position(|s| !s) {
        return Err(SpecError::at(
            "groups",
            v.span,
            format!("`groups`: axis {missing} is missing from every group"),
        ));
    }
    Ok(groups)
}

/// Texels whose energy one void-and-cluster placement updates (the truncated Gaussians of
/// every axis group, summed); at least 1.
pub fn splat_footprint(spec: &TextureSpec) -> u64 {
    let group_work = |axes: &[usize], sigma: f64| -> u64 {
        let r = (-2.0 * sigma * sigma * DEFAULT_CUTOFF.ln()).sqrt() as u64;
        axes.iter()
            .map(|&a| (2 * r + 1).min(spec.dims[a] as u64))
            .product()
    };
    spec.kind
        .groups()
        .iter()
        .map(|g| group_work(&g.axes, g.sigma))
        .sum::<u64>()
        .max(1)
}

/// The canonical text of a void-and-cluster kind's own fields, field by field: `sigma`,
/// `initial_density` (`blue2d`, `independent2d`, `golden`); `sigma_xy`, `sigma_t`,
/// `initial_density`, `histogram` (`stbn`); `groups` (`[{axes=[…],sigma=…},…]`), `toroidal`
/// (one `true`/`false` per axis), `initial_density`, `histogram` (`vac`); nothing (`white`).
/// `None` for other kinds.
pub(super) fn canonical(kind: &Kind) -> Option<String> {
    use super::canonical::num;
    let h = |h: &super::Histogram| match h {
        super::Histogram::Slice => "slice",
        super::Histogram::Volume => "volume",
    };
    Some(match kind {
        Kind::Blue2d(p) | Kind::Independent2d(p) | Kind::Golden(p) => format!(
            "sigma={};initial_density={}",
            num(p.groups[0].sigma),
            num(p.initial_density)
        ),
        Kind::Stbn(p) => format!(
            "sigma_xy={};sigma_t={};initial_density={};histogram={}",
            num(p.groups[0].sigma),
            num(p.groups[1].sigma),
            num(p.initial_density),
            h(&p.histogram)
        ),
        Kind::Vac(VacParams {
            groups,
            toroidal,
            initial_density,
            histogram,
        }) => {
            let g: Vec<String> = groups
                .iter()
                .map(|g| {
                    let axes: Vec<String> = g.axes.iter().map(usize::to_string).collect();
                    format!("{{axes=[{}],sigma={}}}", axes.join(","), num(g.sigma))
                })
                .collect();
            let t: Vec<&str> = toroidal
                .iter()
                .map(|&b| if b { "true" } else { "false" })
                .collect();
            format!(
                "groups=[{}];toroidal=[{}];initial_density={};histogram={}",
                g.join(","),
                t.join(","),
                num(*initial_density),
                h(histogram)
            )
        }
        Kind::White => String::new(),
        Kind::Fast(_) | Kind::Sampler(_) => return None,
    })
}
