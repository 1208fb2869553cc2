//! `noise_texture!`: declare a baked noise texture inline.
//!
//! ```ignore
//! noisebake::noise_texture!(pub STBN = stbn { dims: [64, 64, 16], seed: 7, format: u16 });
//! ```
//!
//! Visibility, item name, kind, then the spec keys of `../shared/DESIGN.md` as `key: value`
//! (arrays `[…]`, nested tables `{ … }`, identifiers and strings both accepted for string values).
//! This crate is a thin front end: it turns tokens into a `build_assets` spec table (keeping each
//! token's span for errors), and `build_assets` validates, caches and generates exactly as for a
//! build script, sharing the same cache directory.

use build_assets::cache::{Cache, HEADER, target_dir};
use build_assets::codegen;
use build_assets::spec::{self, Span, Spanned, Table, Value};
use proc_macro2::{Span as PSpan, TokenStream};
use quote::quote;
use std::path::PathBuf;
use syn::parse::{Parse, ParseStream};
use syn::{Ident, Token, Visibility, braced, bracketed};

/// Parsed input: `vis NAME = kind { key: value, … }`.
struct Input {
    vis: Visibility,
    name: Ident,
    kind: Ident,
    table: Table,
    spans: Vec<PSpan>,
}

struct Ctx {
    spans: Vec<PSpan>,
}

impl Ctx {
    fn span(&mut self, s: PSpan) -> Option<Span> {
        self.spans.push(s);
        Some(Span {
            start: self.spans.len() - 1,
            end: self.spans.len(),
        })
    }

    fn value(&mut self, input: ParseStream) -> syn::Result<Spanned<Value>> {
        if input.peek(syn::token::Bracket) {
            let content;
            let b = bracketed!(content in input);
            let mut items = Vec::new();
            while !content.is_empty() {
                items.push(self.value(&content)?);
                if !content.is_empty() {
                    content.parse::<Token![,]>()?;
                }
            }
            return Ok(Spanned {
                value: Value::Array(items),
                span: self.span(b.span.join()),
            });
        }
        if input.peek(syn::token::Brace) {
            let content;
            let b = braced!(content in input);
            let t = self.table(&content)?;
            return Ok(Spanned {
                value: Value::Table(t),
                span: self.span(b.span.join()),
            });
        }
        let neg = input.peek(Token![-]);
        if neg {
            input.parse::<Token![-]>()?;
        }
        let sign = if neg { -1.0 } else { 1.0 };
        let lit: syn::Lit = if input.peek(Ident) {
            let id: Ident = input.parse()?;
            let v = match id.to_string().as_str() {
                "true" => Value::Bool(true),
                "false" => Value::Bool(false),
                s => Value::Str(s.to_string()),
            };
            return Ok(Spanned {
                value: v,
                span: self.span(id.span()),
            });
        } else {
            input.parse()?
        };
        let span = lit.span();
        let v = match &lit {
            syn::Lit::Int(i) => match i.base10_parse::<i64>() {
                Ok(x) => Value::Int(if neg { -x } else { x }),
                Err(_) => return Err(syn::Error::new(span, "integer out of range")),
            },
            syn::Lit::Float(f) => Value::Float(sign * f.base10_parse::<f64>()?),
            syn::Lit::Str(s) => Value::Str(s.value()),
            syn::Lit::Bool(b) => Value::Bool(b.value),
            _ => {
                return Err(syn::Error::new(
                    span,
                    "expected a number, string, identifier, [array] or { table }",
                ));
            }
        };
        Ok(Spanned {
            value: v,
            span: self.span(span),
        })
    }

    fn table(&mut self, input: ParseStream) -> syn::Result<Table> {
        let mut t = Table::new();
        while !input.is_empty() {
            let key: Ident = if input.peek(Token![type]) {
                let k: Token![type] = input.parse()?;
                Ident::new("type", k.span)
            } else {
                input.parse()?
            };
            if !input.peek(Token![:]) && input.peek(Token![=]) {
                input.parse::<Token![=]>()?;
            } else {
                input.parse::<Token![:]>()?;
            }
            let ks = self.span(key.span());
            let v = self.value(input)?;
            t.push((
                Spanned {
                    value: key.to_string(),
                    span: ks,
                },
                v,
            ));
            if !input.is_empty() {
                input.parse::<Token![,]>()?;
            }
        }
        Ok(t)
    }
}

impl Parse for Input {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let vis: Visibility = input.parse()?;
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let kind: Ident = input.parse()?;
        let content;
        braced!(content in input);
        let mut ctx = Ctx { spans: Vec::new() };
        let table = ctx.table(&content)?;
        if !input.is_empty() {
            input.parse::<Token![;]>()?;
        }
        Ok(Input {
            vis,
            name,
            kind,
            table,
            spans: ctx.spans,
        })
    }
}

/// The cache directory the macro shares with build scripts: `NOISEBAKE_CACHE_DIR`, else the
/// workspace target dir's `noisebake-cache` (`CARGO_TARGET_DIR`, else `target/` beside the
/// outermost `Cargo.lock` above the crate).
fn cache() -> Cache {
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    let root = manifest
        .ancestors()
        .filter(|d| d.join("Cargo.lock").exists())
        .last()
        .unwrap_or(&manifest)
        .to_path_buf();
    let target = target_dir(None).unwrap_or_else(|| root.join("target"));
    Cache::locate(None, None, &target).with_default_dir(target.join("noisebake-cache"))
}

/// Declares a baked noise texture: `noise_texture!(pub NAME = kind { key: value, … });`
#[proc_macro]
pub fn noise_texture(tokens: proc_macro::TokenStream) -> proc_macro::TokenStream {
    let input = match syn::parse::<Input>(tokens) {
        Ok(i) => i,
        Err(e) => return e.to_compile_error().into(),
    };
    expand(input).into()
}

fn expand(input: Input) -> TokenStream {
    let Input {
        vis,
        name,
        kind,
        mut table,
        spans,
    } = input;
    let vis_s = quote!(#vis).to_string();
    let vis_s = if vis_s.is_empty() {
        String::new()
    } else {
        format!("{vis_s} ")
    };
    let kind_span = spans.len();
    let mut spans = spans;
    spans.push(kind.span());
    table.insert(
        0,
        (
            Spanned::bare("kind".into()),
            Spanned {
                value: Value::Str(kind.to_string()),
                span: Some(Span {
                    start: kind_span,
                    end: kind_span + 1,
                }),
            },
        ),
    );
    if let Err(m) = spec::check_identifier(&name.to_string()) {
        return syn::Error::new(name.span(), m).to_compile_error();
    }
    let s = match spec::from_table(&table, Some(&name.to_string())) {
        Ok(s) => s,
        Err(e) => {
            let at = e
                .span
                .and_then(|s| spans.get(s.start).copied())
                .unwrap_or(name.span());
            let err = syn::Error::new(at, e.message).to_compile_error();
            // A typed placeholder so code using the texture does not add errors of its own.
            let ph: TokenStream = fallback_placeholder(&table, &name.to_string(), &vis_s)
                .parse()
                .unwrap_or_default();
            return quote!(#err #ph);
        }
    };
    let mut cache = cache();
    let code = if std::env::var_os("RUST_ANALYZER_INTERNALS_DO_NOT_USE").is_some()
        && cache.read(&s).ok().flatten().is_none()
    {
        codegen::placeholder(&s, &vis_s, "::noisebake")
    } else {
        match cache.get(&s, &mut |_, _| {}) {
            Ok(entry) => codegen::item(
                &s,
                &vis_s,
                &entry.path.display().to_string(),
                HEADER,
                "::noisebake",
            ),
            Err(e) => {
                let err =
                    syn::Error::new(name.span(), format!("noisebake: {e}")).to_compile_error();
                let ph: TokenStream = codegen::placeholder(&s, &vis_s, "::noisebake")
                    .parse()
                    .unwrap_or_default();
                return quote!(#err #ph);
            }
        }
    };
    code.parse().unwrap_or_else(|e| {
        syn::Error::new(name.span(), format!("noisebake generated bad code: {e}"))
            .to_compile_error()
    })
}

/// The placeholder item of an invalid spec: the view type the spec most likely meant (its `dims`
/// and `format` when those parse, else a 1×1 u8 mask), zero bytes, `dead_code` allowed.
fn fallback_placeholder(table: &spec::Table, name: &str, vis: &str) -> String {
    let dims = table
        .iter()
        .find(|(k, _)| k.value == "dims")
        .and_then(|(_, v)| match &v.value {
            Value::Array(items) if (1..=4).contains(&items.len()) => items
                .iter()
                .map(|x| match x.value {
                    Value::Int(i) if (1..=1 << 20).contains(&i) => Some(i as usize),
                    _ => None,
                })
                .collect::<Option<Vec<usize>>>(),
            _ => None,
        })
        .filter(|d| d.iter().product::<usize>() <= 1 << 20)
        .unwrap_or_else(|| vec![1, 1]);
    let format = table
        .iter()
        .find(|(k, _)| k.value == "format")
        .and_then(|(_, v)| match &v.value {
            Value::Str(f) => spec::Format::parse(f),
            _ => None,
        })
        .unwrap_or(spec::Format::U8);
    let s = build_assets::TextureSpec {
        name: name.to_string(),
        kind: spec::Kind::White,
        dims,
        seed: 0,
        format,
    };
    format!(
        "#[allow(dead_code)] {}",
        codegen::placeholder(&s, vis, "::noisebake")
    )
}
