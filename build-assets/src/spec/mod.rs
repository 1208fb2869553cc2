//! The texture spec: one texture, its kind and parameters, validated and with defaults filled in.
//!
//! Both front ends (TOML files via [`parse_toml`], the `noise_texture!` macro via [`from_table`])
//! produce a [`Table`] of spanned values; [`from_table`] is the one validator, so a key means the
//! same thing everywhere and every error names the key (and points at it when a span is known).

pub mod canonical;
mod error;
pub mod fast;
pub mod sampler;
mod toml_file;
pub mod vac;
mod value;

pub use crate::encoding::{Format, Scalar};
pub use error::{Num, Shown, SpecError, closest};
pub use toml_file::{SpecFile, parse_toml, parse_value, read_cache_dir};
pub use vac::{Group, VacParams, splat_footprint};
pub use value::{Span, Spanned, Table, Value};

use fast::FastParams;
use sampler::SamplerParams;

/// Most texels a texture may have (64 Mi): void and cluster needs about
/// [`WORK_BYTES_PER_TEXEL`] bytes of working memory per texel.
pub const MAX_TEXELS: u64 = 1 << 26;
/// Working memory of void and cluster per texel (texel record, queue entries, ranks, copies).
pub const WORK_BYTES_PER_TEXEL: u64 = 64;
/// Most footprint updates one generation may perform (texels × kernel entries), so a huge σ on a
/// large mask is an error instead of an hours-long build.
pub const MAX_SPLAT_WORK: u64 = 1 << 38;

/// How ranks become values: over the whole volume, or within each 2D slice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Histogram {
    /// Rank over the whole volume (the paper's choice): slices are flat only on average.
    Volume,
    /// Re-rank within each 2D (x, y) slice: every slice holds every value exactly once.
    Slice,
}

/// What to generate, with every parameter explicit.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// 2D void and cluster (Ulichney 1993): one group, x and y.
    Blue2d(VacParams),
    /// Spatiotemporal blue noise, 2D×1D (Wolfe et al. 2022, eq. 3): x and y, then t.
    Stbn(VacParams),
    /// Void and cluster with any axis grouping (STBN App. B, eq. 15).
    Vac(VacParams),
    /// Independent uniform white noise per texel.
    White,
    /// An independent 2D blue-noise mask per slice (baseline: white over time); the params'
    /// one group is each slice's.
    Independent2d(VacParams),
    /// One 2D blue-noise mask animated by adding `t · φ` (golden ratio) mod 1 (STBN §4.2).
    Golden(VacParams),
    /// A filter-adapted mask (FAST, Donnelly et al. 2024).
    Fast(FastParams),
    /// A sampler tile: per pixel and pair of dimensions, the block of Owen-scrambled Sobol
    /// points it takes, arranged so the errors are blue under a filter; `dims` is the tile,
    /// stored as one 16-bit layer of keys per sample dimension.
    Sampler(SamplerParams),
}

impl Kind {
    /// The `kind` key's value.
    pub fn name(&self) -> &'static str {
        match self {
            Kind::Blue2d(_) => "blue2d",
            Kind::Stbn(_) => "stbn",
            Kind::Vac(_) => "vac",
            Kind::White => "white",
            Kind::Independent2d(_) => "independent2d",
            Kind::Golden(_) => "golden",
            Kind::Fast(_) => "fast",
            Kind::Sampler(_) => "sampler",
        }
    }
}

impl Kind {
    /// The void-and-cluster axis groups this kind ranks with (STBN App. B): `{x, y}` for the 2D
    /// kinds (each 2D mask of the baselines), `{x, y} × {t}` for STBN, the spec's groups for `vac`,
    /// none for white noise. The generator and the spec's work check both read it.
    pub fn groups(&self) -> Vec<Group> {
        self.vac().map_or_else(Vec::new, |p| p.groups.clone())
    }

    /// The void-and-cluster parameters of this kind, `None` outside that family.
    pub fn vac(&self) -> Option<&VacParams> {
        match self {
            Kind::Blue2d(p)
            | Kind::Stbn(p)
            | Kind::Vac(p)
            | Kind::Independent2d(p)
            | Kind::Golden(p) => Some(p),
            Kind::White | Kind::Fast(_) | Kind::Sampler(_) => None,
        }
    }
}

/// Every kind the `kind` key accepts.
pub const KINDS: &[&str] = &[
    "blue2d",
    "stbn",
    "vac",
    "fast",
    "sampler",
    "white",
    "independent2d",
    "golden",
];
/// Kinds the design names that a later release will add.
pub const PLANNED_KINDS: &[&str] = &["ign", "r2", "plus", "bayer"];

/// One texture: a name, a kind with its parameters, dims, seed and storage format.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureSpec {
    /// The Rust item name.
    pub name: String,
    /// What to generate.
    pub kind: Kind,
    /// Sizes: x, y, then further axes.
    pub dims: Vec<usize>,
    /// Seed of every random choice.
    pub seed: u64,
    /// Storage format.
    pub format: Format,
}

impl TextureSpec {
    /// The dims of the stored texture: `dims` itself, except for a sampler tile, whose
    /// `[W, H]` holds one layer of keys per sample dimension (`[W, H, sample_dims]`).
    pub fn storage_dims(&self) -> Vec<usize> {
        let mut dims = self.dims.clone();
        if let Kind::Sampler(p) = &self.kind {
            dims.push(p.sample_dims as usize);
        }
        dims
    }

    /// Total texel count of the stored texture.
    pub fn texels(&self) -> usize {
        self.storage_dims().iter().product()
    }

    /// Size of the encoded texture in bytes.
    pub fn byte_len(&self) -> usize {
        self.texels() * self.format.texel_bytes()
    }

    /// The canonical text: one line, field by field, every default filled in (the format is
    /// documented in [`canonical`](mod@canonical)). Two specs generate the same bytes exactly when
    /// their canonical texts are equal; the cache key hashes it, KTX2 files and generated items
    /// carry it.
    pub fn canonical(&self) -> String {
        let dims: Vec<String> = self.dims.iter().map(|d| d.to_string()).collect();
        let head = format!(
            "kind={};dims=[{}];seed={};format={}",
            self.kind.name(),
            dims.join(","),
            self.seed,
            self.format
        );
        let own = match &self.kind {
            Kind::Fast(p) => p.canonical(),
            Kind::Sampler(p) => p.canonical(),
            k => vac::canonical(k).unwrap_or_default(),
        };
        if own.is_empty() {
            head
        } else {
            format!("{head};{own}")
        }
    }
}

/// The longest texture name: the build writes `NAME.bin` and a temporary file beside it, and
/// file names stop at 255 bytes on common file systems.
pub const MAX_NAME: usize = 200;

/// Checks that `name` can be a Rust item name.
pub fn check_identifier(name: &str) -> Result<(), String> {
    const KEYWORDS: &[&str] = &[
        "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum",
        "extern", "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod",
        "move", "mut", "pub", "ref", "return", "self", "Self", "static", "struct", "super",
        "trait", "true", "type", "unsafe", "use", "where", "while", "abstract", "become", "box",
        "do", "final", "macro", "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
    ];
    if name.len() > MAX_NAME {
        return Err(format!(
            "the texture name is {} characters long; at most {MAX_NAME} fit a file name (the build writes `NAME.bin`)",
            name.len()
        ));
    }
    let mut chars = name.chars();
    let ok_start = matches!(chars.next(), Some(c) if c == '_' || c.is_ascii_alphabetic());
    if !ok_start || !chars.all(|c| c == '_' || c.is_ascii_alphanumeric()) || name == "_" {
        return Err(format!("`{name}` is not a valid Rust identifier"));
    }
    if KEYWORDS.contains(&name) {
        return Err(format!(
            "`{name}` is a Rust keyword and cannot name a texture"
        ));
    }
    Ok(())
}

/// The narrowest void-and-cluster σ accepted, in texels (or frames). Below it the energy a
/// texel splats on its nearest neighbour is under e^-2 of its own, void and cluster no longer
/// sees clusters, and the mask's low-frequency power climbs toward white noise's (the spec
/// tests measure both sides of the bound).
pub const MIN_SIGMA: f64 = 0.5;

/// Reads the keys of one texture table, remembering which were used.
struct Fields<'a> {
    table: &'a Table,
    used: Vec<bool>,
    allowed: Vec<&'static str>,
}

impl<'a> Fields<'a> {
    fn get(&mut self, key: &'static str) -> Option<&'a Spanned<Value>> {
        self.allowed.push(key);
        let i = self.table.iter().position(|(k, _)| k.value == key)?;
        self.used[i] = true;
        Some(&self.table[i].1)
    }

    fn f64(&mut self, key: &'static str, default: f64) -> Result<(f64, Option<Span>), SpecError> {
        match self.get(key) {
            None => Ok((default, None)),
            Some(v) => Ok((number(key, v)?, v.span)),
        }
    }

    fn positive(&mut self, key: &'static str, default: f64, max: f64) -> Result<f64, SpecError> {
        let (x, span) = self.f64(key, default)?;
        if !(x > 0.0 && x <= max) {
            return Err(SpecError::at(
                key,
                span,
                format!("`{key}` must be a number in (0, {max}], got {}", Num(x)),
            ));
        }
        Ok(x)
    }

    /// A void-and-cluster σ: positive, at most 100, and at least [`MIN_SIGMA`].
    fn sigma(&mut self, key: &'static str, default: f64) -> Result<f64, SpecError> {
        let x = self.positive(key, default, 100.0)?;
        if x < MIN_SIGMA {
            let span = self.get(key).and_then(|v| v.span);
            return Err(SpecError::at(
                key,
                span,
                format!(
                    "`{key}` = {x:?} is below {MIN_SIGMA}: a Gaussian this narrow gives the nearest neighbour less than e^-2 of a texel's energy, so void and cluster cannot see clusters and bakes white noise; use {MIN_SIGMA} or more (1.5 to 2 is usual)"
                ),
            ));
        }
        Ok(x)
    }

    fn density(&mut self) -> Result<f64, SpecError> {
        let (x, span) = self.f64("initial_density", vac::DEFAULT_DENSITY)?;
        if !(x > 0.0 && x <= 0.5) {
            return Err(SpecError::at(
                "initial_density",
                span,
                format!("`initial_density` must be in (0, 0.5], got {}", Num(x)),
            ));
        }
        Ok(x)
    }

    fn string(&mut self, key: &'static str) -> Result<Option<(&'a str, Option<Span>)>, SpecError> {
        match self.get(key) {
            None => Ok(None),
            Some(Spanned {
                value: Value::Str(s),
                span,
            }) => Ok(Some((s.as_str(), *span))),
            Some(v) => Err(type_error(key, "a string", v)),
        }
    }

    fn histogram(&mut self) -> Result<Histogram, SpecError> {
        match self.string("histogram")? {
            None | Some(("volume", _)) => Ok(Histogram::Volume),
            Some(("slice", _)) => Ok(Histogram::Slice),
            Some((other, span)) => Err(SpecError::at(
                "histogram",
                span,
                format!(
                    "`histogram` must be \"volume\" or \"slice\", got \"{}\"",
                    Shown(other)
                ),
            )),
        }
    }

    fn finish(self, texture: &str) -> Result<(), SpecError> {
        for (i, (k, _)) in self.table.iter().enumerate() {
            if !self.used[i] {
                if self.allowed.contains(&k.value.as_str()) {
                    return Err(SpecError::at(
                        k.value.clone(),
                        k.span,
                        format!("texture `{texture}`: key `{}` is given twice", k.value),
                    ));
                }
                let hint = closest(&k.value, &self.allowed)
                    .map(|c| format!(" (did you mean `{c}`?)"))
                    .unwrap_or_default();
                let mut allowed = self.allowed.clone();
                allowed.sort_unstable();
                allowed.dedup();
                return Err(SpecError::at(
                    k.value.clone(),
                    k.span,
                    format!(
                        "texture `{texture}`: unknown key `{}`{hint}; valid keys here: {}",
                        Shown(&k.value),
                        allowed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }
}

pub(super) fn type_error(key: &str, want: &str, v: &Spanned<Value>) -> SpecError {
    SpecError::at(
        key,
        v.span,
        format!("`{key}` must be {want}, got {}", v.value.type_name()),
    )
}

fn number(key: &str, v: &Spanned<Value>) -> Result<f64, SpecError> {
    let x = match v.value {
        Value::Int(i) => i as f64,
        Value::Float(f) => f,
        _ => return Err(type_error(key, "a number", v)),
    };
    if !x.is_finite() {
        return Err(SpecError::at(
            key,
            v.span,
            format!("`{key}` must be finite, got {}", Num(x)),
        ));
    }
    Ok(x)
}

fn integer(key: &str, v: &Spanned<Value>) -> Result<i64, SpecError> {
    match v.value {
        Value::Int(i) => Ok(i),
        _ => Err(type_error(key, "an integer", v)),
    }
}

/// Validates one texture table. `name` overrides a missing `name` key (the macro and the CLI
/// give the name outside the table).
pub fn from_table(table: &Table, name: Option<&str>) -> Result<TextureSpec, SpecError> {
    let mut f = Fields {
        table,
        used: vec![false; table.len()],
        allowed: Vec::new(),
    };
    let name = match (f.string("name")?, name) {
        (Some((n, span)), _) => {
            check_identifier(n).map_err(|m| SpecError::at("name", span, m))?;
            n.to_string()
        }
        (None, Some(n)) => n.to_string(),
        (None, None) => return Err(SpecError::msg("a texture needs a `name` key")),
    };
    let (kind_name, kind_span) = f
        .string("kind")?
        .ok_or_else(|| SpecError::msg(format!("texture `{name}` needs a `kind` key")))?;
    let dims_v = f
        .get("dims")
        .ok_or_else(|| SpecError::msg(format!("texture `{name}` needs a `dims` key")))?;
    let dims = parse_dims(dims_v)?;
    let seed = match f.get("seed") {
        None => 0,
        Some(v) => u64::try_from(integer("seed", v)?)
            .map_err(|_| SpecError::at("seed", v.span, "`seed` must be a non-negative integer"))?,
    };
    let format_span = f.get("format").and_then(|v| v.span);
    let format = match f.string("format")? {
        // A sampler tile stores 16-bit keys; every other kind defaults to 8 bits.
        None if kind_name == "sampler" => Format::U16,
        None => Format::U8,
        Some((s, span)) => Format::parse(s).ok_or_else(|| {
            SpecError::at(
                "format",
                span,
                format!(
                    "`format` must be u8, u16, f32 or a vector form like u8x3, got \"{}\"",
                    Shown(s)
                ),
            )
        })?,
    };
    let want_dims = |lo: usize, hi: usize| -> Result<(), SpecError> {
        if dims.len() < lo || dims.len() > hi {
            let want = if lo == hi {
                format!("{lo}")
            } else {
                format!("{lo} to {hi}")
            };
            return Err(SpecError::at(
                "dims",
                dims_v.span,
                format!("kind `{kind_name}` takes {want} dims, got {}", dims.len()),
            ));
        }
        Ok(())
    };
    let kind = match kind_name {
        name if vac::KINDS.contains(&name) => vac::parse(name, &mut f, &dims, &want_dims)?,
        "fast" => {
            want_dims(2, 3)?;
            Kind::Fast(fast::parse(&mut f, &dims, format, format_span)?)
        }
        "sampler" => {
            want_dims(2, 2)?;
            let pixels = dims[0].saturating_mul(dims[1]);
            if pixels > sampler::MAX_PIXELS {
                return Err(SpecError::at(
                    "dims",
                    dims_v.span,
                    format!(
                        "a sampler tile of {dims:?} has {pixels} pixels; the limit is {} (256×256: the optimiser holds every pixel's errors on its training integrands)",
                        sampler::MAX_PIXELS
                    ),
                ));
            }
            if format != Format::U16 {
                return Err(SpecError::at(
                    "format",
                    format_span,
                    format!(
                        "kind `sampler` stores 16-bit keys; `format` must be u16 (the default), got {format}"
                    ),
                ));
            }
            Kind::Sampler(sampler::parse(&mut f)?)
        }
        other => {
            let msg = if PLANNED_KINDS.contains(&other) {
                format!("kind `{other}` is not available in this version of noisebake yet")
            } else if other == "taa" {
                // A TAA mask is a FAST mask made for TAA's history: say where that lives rather
                // than suggesting the nearest spelling (`vac`).
                "`taa` is a temporal filter, not a kind: a mask for TAA is `kind = \"fast\"` with `temporal_filter = { kind = \"taa\", coverage = 0.25 }` (also `alpha`, `motion`, `moving`)".to_string()
            } else {
                let hint = closest(other, KINDS)
                    .map(|c| format!(" (did you mean `{c}`?)"))
                    .unwrap_or_default();
                format!(
                    "unknown kind `{}`{hint}; valid kinds: {}",
                    Shown(other),
                    KINDS.join(", ")
                )
            };
            return Err(SpecError::at("kind", kind_span, msg));
        }
    };
    if format.channels != 1 && !matches!(kind, Kind::Fast(_)) {
        return Err(SpecError::at(
            "format",
            f.get("format").and_then(|v| v.span),
            format!(
                "kind `{kind_name}` makes scalar masks; `format` must be u8, u16 or f32, got {format}"
            ),
        ));
    }
    f.finish(&name)?;
    let spec = TextureSpec {
        name,
        kind,
        dims,
        seed,
        format,
    };
    check_work(&spec, dims_v.span)?;
    Ok(spec)
}

fn parse_dims(v: &Spanned<Value>) -> Result<Vec<usize>, SpecError> {
    let Value::Array(items) = &v.value else {
        return Err(type_error("dims", "an array of sizes like [64, 64, 16]", v));
    };
    if items.is_empty() {
        return Err(SpecError::at("dims", v.span, "`dims` is empty"));
    }
    let mut dims = Vec::with_capacity(items.len());
    let mut texels: u64 = 1;
    for (i, x) in items.iter().enumerate() {
        let d = integer("dims", x)?;
        if d <= 0 {
            return Err(SpecError::at(
                "dims",
                x.span,
                format!("`dims[{i}]` must be at least 1, got {d}"),
            ));
        }
        texels = texels.saturating_mul(d as u64);
        dims.push(d as usize);
    }
    if texels > MAX_TEXELS {
        let gib = texels as f64 * WORK_BYTES_PER_TEXEL as f64 / (1u64 << 30) as f64;
        return Err(SpecError::at(
            "dims",
            v.span,
            format!(
                "`dims` {dims:?} make {texels} texels, which would need about {gib:.1} GiB of working memory; the limit is {MAX_TEXELS} texels ({} GiB)",
                (MAX_TEXELS * WORK_BYTES_PER_TEXEL) >> 30
            ),
        ));
    }
    Ok(dims)
}

/// Rejects parameter combinations whose generation would take unreasonably long.
fn check_work(spec: &TextureSpec, span: Option<Span>) -> Result<(), SpecError> {
    let n = spec.texels() as u64;
    let fp = splat_footprint(spec);
    if n.saturating_mul(fp) > MAX_SPLAT_WORK {
        return Err(SpecError::at(
            "dims",
            span,
            format!(
                "texture `{}`: σ this large on {n} texels means {fp} energy updates per texel ({} in all, limit {MAX_SPLAT_WORK}); use a smaller σ or smaller dims",
                spec.name,
                n.saturating_mul(fp)
            ),
        ));
    }
    Ok(())
}
