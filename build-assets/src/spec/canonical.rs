//! The canonical text of a spec: the format behind every cache key, written field by field.
//!
//! ```text
//! canonical = field *( ";" field )
//! field     = key "=" value
//! value     = number | word | "[" value *( "," value ) "]" | "{" field' *( "," field' ) "}"
//! field'    = key "=" value
//! ```
//!
//! The fields are the spec's own keys, every default filled in, in a fixed order: `kind`,
//! `dims`, `seed`, `format`, then the kind's fields in the order its family file documents
//! (`spec/vac.rs`, `spec/fast.rs`). Integers are decimal; floating-point numbers are written
//! by [`num`]; words are the spec's spellings (`u16`, `slice`, `gauss`). The texture's name is
//! not part of it: two crates declaring the same texture under different names share an entry.
//!
//! The text is part of the release contract (`tests/canonical.rs` pins one spec of every kind
//! and every FAST filter and sample space, with their keys): changing it re-keys every cache.

/// A floating-point number in canonical text: the shortest decimal that reads back as the same
/// `f64`, without an exponent (Rust's `Display` for `f64`), `-` for negatives; integral values
/// without a fraction (`2`, not `2.0`).
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// Reads canonical text back into a spec (named `T`), by writing it as the TOML it came from:
/// a text that does not read back, or reads back to a different canonical text, was not
/// written by this version (`noisebake cache verify` calls such an entry stale).
pub fn to_spec(text: &str) -> Result<super::TextureSpec, String> {
    let mut toml = String::from("[[texture]]\nname = \"T\"\n");
    for field in split_top(text, ';') {
        let (k, v) = field
            .split_once('=')
            .ok_or_else(|| format!("`{field}` is not key=value"))?;
        // The one canonical word no spec spells: `iterations` left out.
        if (k, v) == ("iterations", "converged") {
            continue;
        }
        toml += &format!("{k} = {}\n", toml_value(v)?);
    }
    super::parse_toml(&toml)
        .map_err(|e| e.render("canonical text", &toml))
        .and_then(|f| {
            f.textures
                .into_iter()
                .next()
                .ok_or_else(|| "no texture".into())
        })
}

/// `s` split at `sep` outside brackets and braces.
fn split_top(s: &str, sep: char) -> Vec<&str> {
    let (mut depth, mut start, mut out) = (0i32, 0, Vec::new());
    for (i, c) in s.char_indices() {
        match c {
            '[' | '{' => depth += 1,
            ']' | '}' => depth -= 1,
            c if c == sep && depth == 0 => {
                out.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    if start < s.len() {
        out.push(&s[start..]);
    }
    out
}

/// A canonical value as TOML: numbers and booleans as they are, words quoted, lists and tables
/// element by element.
fn toml_value(v: &str) -> Result<String, String> {
    if let Some(inner) = v.strip_prefix('[').and_then(|r| r.strip_suffix(']')) {
        let items: Result<Vec<String>, String> =
            split_top(inner, ',').into_iter().map(toml_value).collect();
        return Ok(format!("[{}]", items?.join(", ")));
    }
    if let Some(inner) = v.strip_prefix('{').and_then(|r| r.strip_suffix('}')) {
        let fields: Result<Vec<String>, String> = split_top(inner, ',')
            .into_iter()
            .map(|f| {
                let (k, v) = f
                    .split_once('=')
                    .ok_or_else(|| format!("`{f}` is not key=value"))?;
                Ok(format!("{k} = {}", toml_value(v)?))
            })
            .collect();
        return Ok(format!("{{ {} }}", fields?.join(", ")));
    }
    if v == "true" || v == "false" || v.parse::<f64>().is_ok() {
        return Ok(v.to_string());
    }
    if v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') && !v.is_empty() {
        return Ok(format!("\"{v}\""));
    }
    Err(format!("`{v}` is not a canonical value"))
}
