//! The neutral value tree both front ends produce: the TOML reader and the `noise_texture!`
//! macro turn their input into [`Value`]s with [`Span`]s, and one validator turns those into a
//! [`TextureSpec`](super::TextureSpec), so both ways in accept exactly the same keys.

/// Where a value came from: a byte range in a TOML file, or (from the macro) an index into the
/// macro's own table of token spans. `None` for values made in code (CLI flags, defaults).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// Start (byte offset or token index).
    pub start: usize,
    /// End (exclusive).
    pub end: usize,
}

/// A value with the place it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where it came from.
    pub span: Option<Span>,
}

impl<T> Spanned<T> {
    /// A value with no source location.
    pub fn bare(value: T) -> Self {
        Self { value, span: None }
    }
}

/// A spec value: TOML's data model, minus dates.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// An integer.
    Int(i64),
    /// A float.
    Float(f64),
    /// A string (or, from the macro, a bare identifier such as `u16`).
    Str(String),
    /// A boolean.
    Bool(bool),
    /// An array.
    Array(Vec<Spanned<Value>>),
    /// A table, keys in source order.
    Table(Table),
}

/// A table: keys in source order, each with its span.
pub type Table = Vec<(Spanned<String>, Spanned<Value>)>;

impl Value {
    /// The name of the value's type, for error messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            Value::Int(_) => "an integer",
            Value::Float(_) => "a float",
            Value::Str(_) => "a string",
            Value::Bool(_) => "a boolean",
            Value::Array(_) => "an array",
            Value::Table(_) => "a table",
        }
    }
}
