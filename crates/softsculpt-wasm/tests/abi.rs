//! The page's side of the binding, written from the binding's one table (issue #39 item 3):
//! `web/src/engine/abi.ts` holds the raw exports' TypeScript types (from the `exports!` blocks,
//! `src/abi.rs`), the layout table's slots and the stats block's order (`src/views.rs`) and the
//! delta scope codes (`src/history.rs`) and the JSON reports' interfaces (the `reports!` blocks,
//! `src/report.rs`). The test fails when the committed file is not what the
//! table writes; `UPDATE_ABI=1 cargo test -p softsculpt-wasm --test abi` rewrites it.

use softsculpt_wasm::abi::Export;
use softsculpt_wasm::{exports, reports, LAYOUT_LEN, SCOPES, SLOTS, STATS, STATS_LEN};
use std::fmt::Write;
use std::path::{Path, PathBuf};

fn abi_ts_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../web/src/engine/abi.ts")
}

/// `name_len` → `nameLen`, `BendingRest` → `bendingRest`.
fn camel(s: &str) -> String {
    let mut out = String::new();
    let mut up = false;
    for (k, c) in s.chars().enumerate() {
        if c == '_' {
            up = true;
        } else if k == 0 {
            out.extend(c.to_lowercase());
        } else if up {
            out.extend(c.to_uppercase());
            up = false;
        } else {
            out.push(c);
        }
    }
    out
}

/// A JSDoc comment at `indent` from doc lines (rustdoc's: a leading space each), then `extra`
/// lines; nothing when both are empty.
fn jsdoc(out: &mut String, indent: &str, doc: &[&str], extra: &[String]) {
    let mut lines: Vec<String> = doc.iter().map(|l| l.strip_prefix(' ').unwrap_or(l).replace("*/", "*\\/")).collect();
    while lines.last().is_some_and(|l| l.is_empty()) {
        lines.pop();
    }
    if !extra.is_empty() {
        if !lines.is_empty() {
            lines.push(String::new());
        }
        lines.extend(extra.iter().cloned());
    }
    match lines.len() {
        0 => {}
        1 => writeln!(out, "{indent}/** {} */", lines[0]).unwrap(),
        _ => {
            writeln!(out, "{indent}/**").unwrap();
            for l in &lines {
                writeln!(out, "{indent} *{}{l}", if l.is_empty() { "" } else { " " }).unwrap();
            }
            writeln!(out, "{indent} */").unwrap();
        }
    }
}

fn doc_lines(doc: &str) -> Vec<&str> {
    doc.lines().collect()
}

fn rust_signature(e: &Export) -> String {
    let args: Vec<String> = e.params.iter().map(|p| format!("{}: {}", p.name, p.rust)).collect();
    let ret = if e.ret_rust == "()" { String::new() } else { format!(" -> {}", e.ret_rust) };
    format!("`{}{}({}){ret}`", if e.unsafe_ { "unsafe " } else { "" }, e.name, args.join(", "))
}

/// The text of `web/src/engine/abi.ts`.
fn abi_ts() -> String {
    let mut o = String::new();
    o.push_str(
        "// The page's side of the WebAssembly binding, written from its one table: do not edit. The\n\
         // raw exports' types (the `exports!` blocks of crates/softsculpt-wasm/src, abi.rs), the\n\
         // layout table's slots and the stats block's order (views.rs), the delta scope codes\n\
         // (history.rs), the JSON reports' interfaces (the `reports!` blocks, report.rs). After\n\
         // changing one of those, `UPDATE_ABI=1 cargo test -p softsculpt-wasm\n\
         // --test abi` rewrites this file (crates/softsculpt-wasm/tests/abi.rs). The calls'\n\
         // conventions (status and index, error and result slots, memory): the crate documentation\n\
         // of crates/softsculpt-wasm/src/lib.rs.\n\n",
    );

    o.push_str(
        "/**\n * The engine's raw exports, with wasm-level types: 32-bit integers, pointers and floats are\n \
         * `number` (a u32 above 2^31 arrives negative: `>>> 0`), 64-bit integers `bigint`. Each\n \
         * comment ends with the Rust signature.\n */\nexport interface RawEngine {\n  memory: WebAssembly.Memory;\n",
    );
    for e in exports() {
        jsdoc(&mut o, "  ", e.doc, &[rust_signature(e)]);
        let args: Vec<String> = e.params.iter().map(|p| format!("{}: {}", camel(p.name), p.ts)).collect();
        writeln!(o, "  {}({}): {};", e.name, args.join(", "), e.ret_ts).unwrap();
    }
    o.push_str("}\n\n");

    o.push_str("/** Every raw export and its number of arguments (what `Function.length` says of it), in the table's order. */\n");
    o.push_str("export const EXPORTS: { readonly [name in Exclude<keyof RawEngine, 'memory'>]: number } = {\n");
    for e in exports() {
        writeln!(o, "  {}: {},", e.name, e.params.len()).unwrap();
    }
    o.push_str("};\n\n");

    o.push_str("/** The slots of a body's layout table (`ss_body_views`; crates/softsculpt-wasm/src/views.rs). */\nexport const SLOT = {\n");
    for (k, (name, doc)) in SLOTS.iter().enumerate() {
        jsdoc(&mut o, "  ", &doc_lines(doc), &[]);
        writeln!(o, "  {}: {k},", camel(name)).unwrap();
    }
    writeln!(o, "}} as const;\n/** Length of the layout table (u32). */\nexport const LAYOUT_LEN = {LAYOUT_LEN};\n").unwrap();

    o.push_str("/** A body's statistics as of the last `ss_sync` (the stats block, views.rs). */\nexport interface Stats {\n");
    for s in STATS {
        jsdoc(&mut o, "  ", &doc_lines(s.doc), &[]);
        let ty = if s.width == 1 { "number".to_string() } else { format!("[{}]", vec!["number"; s.width].join(", ")) };
        writeln!(o, "  {}: {ty};", s.name).unwrap();
    }
    writeln!(o, "}}\n/** Length of the stats block (f64). */\nexport const STATS_LEN = {STATS_LEN};\n").unwrap();
    o.push_str("/** The stats block (`STATS_LEN` f64, the layout table's `stats` slot) as `Stats`. */\nexport function readStats(s: ArrayLike<number>): Stats {\n  return {\n");
    let mut at = 0;
    for s in STATS {
        let v: Vec<String> = (at..at + s.width).map(|k| format!("s[{k}]")).collect();
        let v = if s.width == 1 { v[0].clone() } else { format!("[{}]", v.join(", ")) };
        writeln!(o, "    {}: {v},", s.name).unwrap();
        at += s.width;
    }
    o.push_str("  };\n}\n\n");

    o.push_str("/** `ss_delta`'s scope codes (crates/softsculpt-wasm/src/history.rs): what an undo delta keeps. */\nexport const SCOPE = {\n");
    for (k, s) in SCOPES.iter().enumerate() {
        jsdoc(&mut o, "  ", &[s.doc], &[]);
        writeln!(o, "  {}: {k},", s.name).unwrap();
    }
    o.push_str("} as const;\nexport type DeltaScope = keyof typeof SCOPE;\n");

    // The JSON reports calls leave in the result slot.
    for r in reports() {
        o.push('\n');
        jsdoc(&mut o, "", r.doc, &[]);
        writeln!(o, "export interface {} {{", r.name).unwrap();
        for f in r.fields {
            jsdoc(&mut o, "  ", f.doc, &[]);
            writeln!(o, "  {}: {};", f.name, (f.ts)()).unwrap();
        }
        o.push_str("}\n");
    }
    o
}

#[test]
fn the_page_side_of_the_binding_is_written_from_the_table() {
    let want = abi_ts();
    if std::env::var_os("UPDATE_ABI").is_some() {
        std::fs::write(abi_ts_path(), &want).unwrap();
    }
    let have = std::fs::read_to_string(abi_ts_path()).unwrap_or_default();
    assert!(have == want, "web/src/engine/abi.ts is stale: run UPDATE_ABI=1 cargo test -p softsculpt-wasm --test abi");
}

/// Every `#[no_mangle]` function of the binding is written in an `exports!` block (so it is in
/// the table): the only `no_mangle` in its sources is the macro's own.
#[test]
fn every_export_is_in_the_table() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    for f in std::fs::read_dir(&src).unwrap() {
        let path = f.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let count = text.lines().filter(|l| l.trim() == "#[no_mangle]").count();
        let allowed = if name == "abi.rs" { 2 } else { 0 };
        assert_eq!(count, allowed, "src/{name} has {count} `#[no_mangle]`: write exports in an `exports!` block (src/abi.rs)");
    }
    let names: Vec<&str> = exports().map(|e| e.name).collect();
    for (k, n) in names.iter().enumerate() {
        assert!(n.starts_with("ss_"), "{n}: the binding's exports are named ss_*");
        assert!(!names[..k].contains(n), "{n} twice");
    }
}

/// The calls the crate documentation's table names (`ss_error_ptr/len` names two).
fn documented_calls() -> Vec<String> {
    let lib = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let mut names = Vec::new();
    for line in lib.lines().filter(|l| l.starts_with("//! | `ss_")) {
        let call = line.split('|').nth(1).unwrap_or("");
        for word in call.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '/')).filter(|w| w.starts_with("ss_")) {
            match word.strip_suffix("_ptr/len") {
                Some(stem) => names.extend([format!("{stem}_ptr"), format!("{stem}_len")]),
                None => names.push(word.to_string()),
            }
        }
    }
    names
}

/// The crate documentation's table of calls names every export, and names only exports.
#[test]
fn the_crate_documentation_names_every_export() {
    let documented = documented_calls();
    let names: Vec<&str> = exports().map(|e| e.name).collect();
    let missing: Vec<&&str> = names.iter().filter(|n| !documented.iter().any(|d| d == *n)).collect();
    assert!(missing.is_empty(), "src/lib.rs's table of calls does not name {missing:?}");
    let stray: Vec<&String> = documented.iter().filter(|d| !names.contains(&d.as_str())).collect();
    assert!(stray.is_empty(), "src/lib.rs's table of calls names {stray:?}, which are no exports");
}

/// The layout table's stats slot holds the whole block, and the block's entries sum to its length.
#[test]
fn the_slots_and_the_stats_block_fit() {
    assert_eq!(SLOTS.len(), LAYOUT_LEN);
    assert_eq!(STATS.iter().map(|s| s.width).sum::<usize>(), STATS_LEN);
    assert_eq!(SLOTS.last().map(|s| s.0), Some("Stats"));
}
