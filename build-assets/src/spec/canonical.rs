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
