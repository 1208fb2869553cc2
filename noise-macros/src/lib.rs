//! `noise_texture!`: declare a baked noise texture inline. Re-exported by `noisebake` (feature
//! `macros`); see [`noise_texture!`] for the grammar.
//!
//! This crate is a thin front end: it turns tokens into a `build_assets` spec table (keeping
//! each token's span for errors), and `build_assets` validates, caches and generates exactly as
//! for a build script, in the same cache directory.

use build_assets::cache::{HEADER, Locator, Source};
use build_assets::codegen;
use build_assets::spec::{self, Span, Spanned, Table, Value};
use proc_macro2::{Span as PSpan, TokenStream};
use quote::quote;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::{Ident, Token, Visibility, braced, bracketed};

/// The path an expansion names the facade by when the input does not say `crate = …`.
const DEFAULT_CRATE: &str = "::noisebake";

/// Parsed input: `(crate = path;)? vis NAME = kind { key: value, … }`.
struct Input {
    /// The path the expansion names the facade by (`::noisebake` unless `crate = …` says).
    krate: String,
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
        // `Ident::parse_any`: a bare word may be a Rust keyword (`kind: box`, `type: ...`).
        let lit: syn::Lit = if input.peek(Ident::peek_any) && !input.peek(syn::LitBool) {
            let id: Ident = Ident::parse_any(input)?;
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
        let krate = if input.peek(Token![crate]) && input.peek2(Token![=]) {
            input.parse::<Token![crate]>()?;
            input.parse::<Token![=]>()?;
            let path: syn::Path = input.parse()?;
            input.parse::<Token![;]>().map_err(|e| {
                syn::Error::new(
                    e.span(),
                    "expected `;` after the crate path: `noise_texture!(crate = my::noisebake; NAME = kind { … })`",
                )
            })?;
            quote!(#path).to_string().replace(' ', "")
        } else {
            DEFAULT_CRATE.to_string()
        };
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
            krate,
            vis,
            name,
            kind,
            table,
            spans: ctx.spans,
        })
    }
}

/// Declares a baked noise texture as a `static` typed view over bytes generated at compile time.
///
/// # Grammar
///
/// ```text
/// noise_texture!( (crate = PATH ;)? VISIBILITY? NAME = KIND { KEY: VALUE, … } ;? )
///
/// VALUE := number | -number | "string" | identifier | true | false
///        | [ VALUE, … ]                 (arrays, e.g. dims: [64, 64, 16])
///        | { KEY: VALUE, … }            (tables, e.g. spatial_filter: { kind: box, size: 5 })
/// ```
///
/// `NAME` is the item's name (the spec's `name`), `KIND` the spec's `kind`, and the keys are the
/// spec keys of that kind (the table on the `noisebake` crate's front page). `=` is accepted in
/// place of `:`; a bare identifier is a string (`format: u16` is `format = "u16"`). The item
/// is `VISIBILITY static NAME: Mask2<…> | Mask3<…> | Mask4<…>` (or `SamplerTile<…>`), its
/// texel type following `format`.
///
/// The expansion names its types through `::noisebake`. A crate that renames the dependency
/// (`nb = { package = "noisebake", … }`) or re-exports it (a plugin of its own that wraps
/// noisebake) says where the facade is with a leading `crate = PATH;`, as serde's and Bevy's
/// derives take `crate = "…"`: `noise_texture!(crate = ::my_plugin::noisebake; DITHER = blue2d { … })`.
///
/// # Examples
///
/// ```ignore
/// use noisebake::noise_texture;
///
/// // A 64×64 blue-noise dither mask, 8-bit.
/// noise_texture!(pub DITHER = blue2d { dims: [64, 64], seed: 1, sigma: 1.9 });
/// // Spatiotemporal blue noise with flat per-frame histograms.
/// noise_texture!(STBN = stbn { dims: [64, 64, 16], seed: 7, format: u16, histogram: slice });
/// // FAST for a 5×5 box filter and a plain exponential moving average (no history
/// // rejection: beta 0, also the default when `temporal_filter` is left out).
/// noise_texture!(pub(crate) FAST = fast {
///     dims: [32, 32, 16],
///     spatial_filter: { kind: box, size: 5 },
///     temporal_filter: { kind: ema, alpha: 0.1, beta: 0 },
/// });
///
/// let v: u8 = DITHER.get(x, y);
/// let k3 = STBN.get_k_unit(x, y, frame, 3);
/// ```
///
/// # Errors and messages
///
/// An invalid spec is a compile error at the offending token (the key, or its value), and the
/// item is still declared with zeroed bytes so uses of it add no errors of their own. The macro
/// shares the cache with build scripts (see the `noisebake` front page, "The cache and offline
/// builds"); when it generates a texture or replaces a corrupt entry it says so on stderr, with
/// the time taken. A generation never costs a second compile; Cargo shows the line again on
/// fresh builds until the crate next compiles (it replays what a compile printed), and a compile
/// that finds the texture in the cache prints nothing. Under rust-analyzer a cache miss gives a
/// placeholder instead of a long generation.
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
        krate,
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
            let ph: TokenStream = fallback_placeholder(&table, &name.to_string(), &vis_s, &krate)
                .parse()
                .unwrap_or_default();
            return quote!(#err #ph);
        }
    };
    let fail = |msg: String| {
        let err = syn::Error::new(name.span(), format!("noisebake: {msg}")).to_compile_error();
        let ph: TokenStream = codegen::placeholder(&s, &vis_s, &krate)
            .parse()
            .unwrap_or_default();
        quote!(#err #ph)
    };
    let mut cache = match Locator::for_macro().resolve() {
        Ok(c) => c,
        Err(e) => return fail(e.to_string()),
    };
    let analyzer = std::env::var_os("RUST_ANALYZER_INTERNALS_DO_NOT_USE").is_some();
    let entry = if analyzer {
        cache.lookup(&s)
    } else {
        // Said at once on stderr, which cargo shows for a proc macro that runs long.
        let mut announce = |line: &str| eprintln!("noisebake: {line}");
        match build_assets::bake::obtain(
            &mut cache,
            &s,
            build_assets::generate::estimate::ANNOUNCE_SECONDS,
            &mut announce,
            &mut |_, _| {},
        ) {
            Ok(e) => Some(e),
            Err(e) => return fail(e.to_string()),
        }
    };
    // Proc macros have no warning channel on stable Rust; stderr reaches the user through
    // cargo. Said once, when it happens: a later build hits the cache and prints nothing.
    for w in &cache.warnings {
        eprintln!("warning: noisebake: {w}");
    }
    let code = match entry {
        None => codegen::placeholder(&s, &vis_s, &krate),
        Some(entry) => {
            let Some(path) = entry.path else {
                return fail(format!(
                    "texture `{}` was generated but no cache directory could store it, and the macro embeds the stored file; make the cache directory writable or set NOISEBAKE_CACHE_DIR",
                    s.name
                ));
            };
            if entry.source == Source::Generated {
                let what = format!("{} {:?}", s.kind.name(), s.dims);
                let dir = path.parent().unwrap_or(&cache.dir);
                eprintln!(
                    "warning: {}",
                    build_assets::bake::announce(&s.name, &what, entry.seconds, dir)
                );
            }
            codegen::item(&s, &vis_s, &path.display().to_string(), HEADER, &krate)
        }
    };
    code.parse().unwrap_or_else(|e| {
        syn::Error::new(name.span(), format!("noisebake generated bad code: {e}"))
            .to_compile_error()
    })
}

/// The placeholder item of an invalid spec: the view type the spec most likely meant (its `dims`
/// and `format` when those parse, else a 1×1 u8 mask), zero bytes, `dead_code` allowed.
fn fallback_placeholder(table: &spec::Table, name: &str, vis: &str, krate: &str) -> String {
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
        codegen::placeholder(&s, vis, krate)
    )
}

/// The grammar on its own: token streams in, the parsed input out, with no cache and no
/// generation (the expansion is tested through `tests/ui` and the workspace's pipeline tests).
#[cfg(test)]
mod tests {
    use super::*;

    fn parse(tokens: TokenStream) -> syn::Result<Input> {
        syn::parse2::<Input>(tokens)
    }

    fn keys(t: &Table) -> Vec<(&str, &Value)> {
        t.iter()
            .map(|(k, v)| (k.value.as_str(), &v.value))
            .collect()
    }

    #[test]
    fn the_facade_is_noisebake_unless_the_input_names_another() {
        let i = parse(quote!(pub D = blue2d { dims: [64, 64] })).unwrap();
        assert_eq!(i.krate, "::noisebake");
        let i = parse(quote!(crate = ::my_plugin::noisebake; pub D = blue2d { dims: [64, 64] }))
            .unwrap();
        assert_eq!(i.krate, "::my_plugin::noisebake");
        assert_eq!(i.name, "D");
        assert_eq!(i.kind, "blue2d");
        let i = parse(quote!(crate = nb; D = white { dims: [4, 4] };)).unwrap();
        assert_eq!(i.krate, "nb");
        let i =
            parse(quote!(crate = crate::reexports::noisebake; D = white { dims: [4, 4] })).unwrap();
        assert_eq!(i.krate, "crate::reexports::noisebake");
    }

    #[test]
    fn a_crate_path_needs_its_semicolon_and_a_path() {
        let e = parse(quote!(crate = nb D = white { dims: [4, 4] }))
            .err()
            .expect("missing `;` is an error");
        assert!(
            e.to_string().contains("expected `;` after the crate path"),
            "{e}"
        );
        assert!(parse(quote!(crate = ; D = white { dims: [4, 4] })).is_err());
        assert!(parse(quote!(crate = "nb"; D = white { dims: [4, 4] })).is_err());
    }

    #[test]
    fn values_keys_and_visibility_parse_as_the_grammar_says() {
        let i = parse(quote!(pub(crate) F = fast {
            dims: [32, 32, 16],
            format = u16,
            spatial_filter: { kind: box, size: 5 },
            sigma: -1.5,
            histogram: "slice",
            wrap: true,
        }))
        .unwrap();
        let vis = &i.vis;
        assert_eq!(quote!(#vis).to_string(), "pub (crate)");
        let k = keys(&i.table);
        assert_eq!(k[0].0, "dims");
        assert!(matches!(k[0].1, Value::Array(a) if a.len() == 3));
        assert_eq!(k[1], ("format", &Value::Str("u16".into())));
        assert!(matches!(k[2].1, Value::Table(t) if t.len() == 2));
        assert_eq!(k[3], ("sigma", &Value::Float(-1.5)));
        assert_eq!(k[4], ("histogram", &Value::Str("slice".into())));
        assert_eq!(k[5], ("wrap", &Value::Bool(true)));
        // Every key and value has a span the errors can point at.
        assert!(
            i.table
                .iter()
                .all(|(k, v)| k.span.is_some() && v.span.is_some())
        );
    }

    #[test]
    fn malformed_input_is_an_error_not_a_panic() {
        for bad in [
            quote!(D = blue2d),
            quote!(D blue2d { dims: [4, 4] }),
            quote!(D = blue2d { dims: [4, 4] } extra),
            quote!(D = blue2d { dims: 'c' }),
            quote!(
                D = blue2d {
                    dims: 99999999999999999999
                }
            ),
        ] {
            assert!(parse(bad.clone()).is_err(), "{bad}");
        }
    }
}
