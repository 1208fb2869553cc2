//! Reading spec files: `[[texture]]` tables with byte spans, so errors point at file, line and key.

use super::{Span, Spanned, SpecError, Table, TextureSpec, Value, from_table};
use toml::de::{DeTable, DeValue};

/// A parsed spec file.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecFile {
    /// Every texture, in file order.
    pub textures: Vec<TextureSpec>,
    /// `cache_dir` named at the top of the file, if any (relative to the file).
    pub cache_dir: Option<String>,
}

fn span(r: std::ops::Range<usize>) -> Option<Span> {
    Some(Span {
        start: r.start,
        end: r.end,
    })
}

fn convert(v: &toml::Spanned<DeValue<'_>>) -> Result<Spanned<Value>, SpecError> {
    let value = match v.get_ref() {
        DeValue::String(s) => Value::Str(s.to_string()),
        DeValue::Integer(i) => {
            let digits = i.as_str().replace('_', "");
            let (neg, body) = match digits.strip_prefix('-') {
                Some(b) => (true, b.to_string()),
                None => (false, digits.trim_start_matches('+').to_string()),
            };
            let body = body
                .trim_start_matches("0x")
                .trim_start_matches("0o")
                .trim_start_matches("0b");
            let x = i64::from_str_radix(body, i.radix()).map_err(|_| SpecError {
                message: format!("integer `{}` is out of range", i.as_str()),
                key: None,
                span: span(v.span()),
            })?;
            Value::Int(if neg { -x } else { x })
        }
        DeValue::Float(f) => {
            let s = f.as_str().replace('_', "");
            let x = match s.trim_start_matches('+') {
                "inf" => f64::INFINITY,
                "-inf" => f64::NEG_INFINITY,
                "nan" | "-nan" => f64::NAN,
                t => t.parse().map_err(|_| SpecError {
                    message: format!("bad float `{s}`"),
                    key: None,
                    span: span(v.span()),
                })?,
            };
            Value::Float(x)
        }
        DeValue::Boolean(b) => Value::Bool(*b),
        DeValue::Datetime(_) => {
            return Err(SpecError {
                message: "dates are not spec values".into(),
                key: None,
                span: span(v.span()),
            });
        }
        DeValue::Array(a) => Value::Array(a.iter().map(convert).collect::<Result<_, _>>()?),
        DeValue::Table(t) => Value::Table(convert_table(t)?),
    };
    Ok(Spanned {
        value,
        span: span(v.span()),
    })
}

fn convert_table(t: &DeTable<'_>) -> Result<Table, SpecError> {
    let mut out: Table = t
        .iter()
        .map(|(k, v)| {
            Ok((
                Spanned {
                    value: k.get_ref().to_string(),
                    span: span(k.span()),
                },
                convert(v)?,
            ))
        })
        .collect::<Result<_, SpecError>>()?;
    out.sort_by_key(|(k, _)| k.span.map_or(0, |s| s.start));
    Ok(out)
}

/// Parses one TOML value (`1.9`, `[0, 1]`, `{ axes = [2], sigma = 1.9 }`, `"u16"`), as the
/// CLI's `--key value` flags take them; the TOML error (a duplicate key, an integer out of
/// range, an unclosed table) when `text` is not one TOML value.
pub fn parse_value(text: &str) -> Result<Value, String> {
    let line = format!("v = {text}");
    let doc = DeTable::parse(&line).map_err(|e| e.message().to_string())?;
    let top = convert_table(doc.get_ref()).map_err(|e| e.message)?;
    match top.as_slice() {
        [(k, v)] if k.value == "v" => Ok(v.value.clone()),
        _ => Err("not one value".to_string()),
    }
}

/// The top-level `cache_dir` of a spec file's text, without validating its textures (the
/// macro's way to find a committed cache; the build script reports the file's errors).
pub fn read_cache_dir(text: &str) -> Option<String> {
    let doc = DeTable::parse(text).ok()?;
    match doc.get_ref().get("cache_dir")?.get_ref() {
        DeValue::String(s) => Some(s.to_string()),
        _ => None,
    }
}

/// Parses and validates a spec file's text. Errors carry byte spans into `text`; use
/// [`SpecError::render`] to show them with file, line and column.
pub fn parse_toml(text: &str) -> Result<SpecFile, SpecError> {
    let doc = DeTable::parse(text).map_err(|e| SpecError {
        message: format!("invalid TOML: {}", e.message()),
        key: None,
        span: e.span().and_then(span),
    })?;
    let top = convert_table(doc.get_ref())?;
    let mut textures = Vec::new();
    let mut cache_dir = None;
    for (k, v) in &top {
        match (k.value.as_str(), &v.value) {
            ("texture", Value::Array(items)) => {
                for item in items {
                    let Value::Table(t) = &item.value else {
                        return Err(SpecError::at(
                            "texture",
                            item.span,
                            "`texture` entries must be tables ([[texture]])",
                        ));
                    };
                    let spec = from_table(t, None)?;
                    if textures.iter().any(|s: &TextureSpec| s.name == spec.name) {
                        let at = t
                            .iter()
                            .find(|(k, _)| k.value == "name")
                            .and_then(|(_, v)| v.span);
                        return Err(SpecError::at(
                            "name",
                            at,
                            format!("duplicate texture name `{}`", spec.name),
                        ));
                    }
                    textures.push(spec);
                }
            }
            ("cache_dir", Value::Str(s)) => cache_dir = Some(s.clone()),
            (key @ ("cache_dir" | "texture"), other) => {
                let want = if key == "texture" {
                    "an array of tables ([[texture]])"
                } else {
                    "a string (a directory relative to this file)"
                };
                return Err(SpecError::at(
                    key,
                    v.span,
                    format!("`{key}` must be {want}, got {}", other.type_name()),
                ));
            }
            (key, _) => {
                let hint = super::closest(key, &["texture", "cache_dir"])
                    .map(|c| format!(" (did you mean `{c}`?)"))
                    .unwrap_or_default();
                return Err(SpecError::at(
                    key,
                    k.span,
                    format!(
                        "unknown top-level key `{key}`{hint}; a spec file holds [[texture]] tables and an optional cache_dir = \"…\""
                    ),
                ));
            }
        }
    }
    Ok(SpecFile {
        textures,
        cache_dir,
    })
}
