//! The spec-key table on the facade's front page (`src/lib.rs`, "kind | what | dims | keys
//! (defaults)") against the parser, so the two cannot drift apart:
//! - every key the parser accepts for a kind is named in that kind's row, and every key the
//!   row names is accepted;
//! - every value the parser accepts for a string-valued key (and for a filter's `kind`) is
//!   named in the row, as `"value"` or `` `value` ``;
//! - every default the row writes as a TOML value changes nothing when written out.
//!
//! What the parser accepts is read from its own error messages: an unknown key lists the valid
//! keys, and an unknown value lists the valid values.

use build_assets::spec::parse_toml;

/// Keys every kind has; the front page documents them apart from the table.
const COMMON: &[&str] = &["name", "kind", "dims", "seed", "format"];

/// The table's rows: `(kind, keys cell)`.
fn rows() -> Vec<(String, String)> {
    let src = include_str!("../src/lib.rs");
    let mut rows = Vec::new();
    let mut inside = false;
    for line in src.lines() {
        let Some(l) = line.strip_prefix("//! ") else {
            inside = false;
            continue;
        };
        if l.starts_with("| kind | what | dims | keys (defaults) |") {
            inside = true;
            continue;
        }
        if !inside || l.starts_with("| ---") {
            continue;
        }
        if !l.starts_with('|') {
            inside = false;
            continue;
        }
        // `\|` inside a cell is an escaped bar, not a column.
        let cells: Vec<String> = l
            .replace("\\|", "\u{1}")
            .split('|')
            .map(|c| c.trim().replace('\u{1}', "|"))
            .collect();
        let kind = cells[1].trim_matches('`').to_string();
        rows.push((kind, cells[4].clone()));
    }
    rows
}

/// The dims a kind's probe spec uses.
fn dims(kind: &str) -> &'static str {
    match kind {
        "blue2d" | "sampler" => "[16, 16]",
        _ => "[16, 16, 2]",
    }
}

/// The canonical text of `kind` with `extra` lines, or the parser's error.
fn parse(kind: &str, extra: &str) -> Result<String, String> {
    let text = format!(
        "[[texture]]\nname = \"T\"\nkind = \"{kind}\"\ndims = {}\n{extra}\n",
        dims(kind)
    );
    parse_toml(&text)
        .map(|f| f.textures[0].canonical())
        .map_err(|e| e.message)
}

/// The keys a cell names: its backticked plain words outside parentheses (values are quoted,
/// contain spaces, or sit in a key's parenthesis).
fn named_keys(cell: &str) -> Vec<String> {
    let (mut keys, mut depth) = (Vec::new(), 0i32);
    for (i, piece) in cell.split('`').enumerate() {
        if i % 2 == 0 {
            depth += piece.matches('(').count() as i32 - piece.matches(')').count() as i32;
        } else if depth == 0
            && !piece.is_empty()
            && piece.chars().all(|c| c.is_ascii_lowercase() || c == '_')
        {
            keys.push(piece.to_string());
        }
    }
    keys
}

fn is_key_word(w: &str) -> bool {
    !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase() || c == '_')
}

/// The values an error message lists: after `valid: ` (comma-separated), or else every quoted
/// word but the probe's.
fn listed_values(message: &str, probe: &str) -> Vec<String> {
    if let Some(rest) = message.split("valid: ").nth(1) {
        return rest
            .split(", ")
            .map(|v| v.trim_end_matches(['.', ')']).to_string())
            .collect();
    }
    message
        .split('"')
        .skip(1)
        .step_by(2)
        .filter(|v| *v != probe)
        .map(str::to_string)
        .collect()
}

fn names(cell: &str, value: &str) -> bool {
    cell.contains(&format!("\"{value}\"")) || cell.contains(&format!("`{value}`"))
}

#[test]
fn the_table_has_a_row_for_every_kind() {
    let kinds: Vec<String> = rows().into_iter().map(|r| r.0).collect();
    for k in build_assets::spec::KINDS {
        assert!(
            kinds.iter().any(|r| r == k),
            "no row for kind `{k}` in src/lib.rs"
        );
    }
}

#[test]
fn every_key_the_parser_accepts_is_in_its_row_and_back() {
    for (kind, cell) in rows() {
        let msg = parse(&kind, "zz_not_a_key = 1").expect_err("an unknown key is an error");
        let valid = msg
            .split("valid keys here: ")
            .nth(1)
            .unwrap_or_else(|| panic!("{kind}: no key list in {msg:?}"));
        let accepted: Vec<&str> = valid.split(", ").collect();
        let named = named_keys(&cell);
        for k in &accepted {
            assert!(
                COMMON.contains(k) || named.iter().any(|n| n == k),
                "kind `{kind}`: the parser accepts `{k}` but the front page's row does not name it"
            );
        }
        for n in &named {
            assert!(
                accepted.contains(&n.as_str()),
                "kind `{kind}`: the row names `{n}`, which the parser does not accept"
            );
        }
    }
}

#[test]
fn every_value_the_parser_accepts_is_in_its_row() {
    const PROBE: &str = "zz_not_a_value";
    let mut checked = 0;
    for (kind, cell) in rows() {
        for key in named_keys(&cell) {
            let mut probes = vec![format!("{key} = \"{PROBE}\"")];
            if key.ends_with("_filter") {
                probes.push(format!("{key} = {{ kind = \"{PROBE}\" }}"));
            }
            for probe in probes {
                let Err(msg) = parse(&kind, &probe) else {
                    continue;
                };
                if !msg.contains(PROBE) {
                    continue; // not a string-valued key: a type error
                }
                for v in listed_values(&msg, PROBE) {
                    checked += 1;
                    assert!(
                        names(&cell, &v),
                        "kind `{kind}`: `{key}` accepts \"{v}\" (parser: {msg:?}) but the front page's row does not name it"
                    );
                }
            }
        }
    }
    assert!(
        checked > 20,
        "only {checked} values checked: the probes found too few"
    );
}

#[test]
fn every_default_written_out_changes_nothing() {
    let mut checked = 0;
    for (kind, cell) in rows() {
        let bare = parse(&kind, "").unwrap_or_else(|e| panic!("{kind}: {e}"));
        // "`key` (default…": the first item of the parenthesis, when it is a TOML value.
        for part in cell.split("`").collect::<Vec<_>>().windows(2) {
            let (key, after) = (part[0], part[1]);
            if !is_key_word(key) {
                continue;
            }
            let Some(paren) = after.strip_prefix(" (") else {
                continue;
            };
            let first = paren.split([';', ',', ')']).next().unwrap_or("").trim();
            if first.is_empty() {
                continue;
            }
            // A bare number or boolean, or a backticked value right after the parenthesis.
            let value = if first.parse::<f64>().is_ok() || first == "true" || first == "false" {
                first.to_string()
            } else {
                continue;
            };
            let with = parse(&kind, &format!("{key} = {value}")).unwrap_or_else(|e| {
                panic!("{kind}: `{key} = {value}` (its documented default): {e}")
            });
            assert_eq!(
                with, bare,
                "kind `{kind}`: `{key} = {value}` is documented as the default"
            );
            checked += 1;
        }
        // Backticked defaults: "`key` (`value`".
        for (i, piece) in cell.split(" (`").enumerate().skip(1) {
            let before = cell.split(" (`").nth(i - 1).unwrap_or("");
            let Some(key) = before.rsplit('`').nth(1) else {
                continue;
            };
            if !is_key_word(key) {
                continue;
            }
            let Some(value) = piece.split('`').next() else {
                continue;
            };
            let Ok(with) = parse(&kind, &format!("{key} = {value}")) else {
                continue; // not a TOML value as written (e.g. `all`)
            };
            assert_eq!(
                with, bare,
                "kind `{kind}`: `{key} = {value}` is documented as the default"
            );
            checked += 1;
        }
    }
    assert!(checked > 12, "only {checked} defaults checked");
}
