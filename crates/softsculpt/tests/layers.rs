//! No circles between the core's modules (issue #39): they form layers, and a module imports
//! only from its own layer or the ones below it. Lowest first:
//!
//! 0. `vec3`, `geometry`, `hash`, `error`, `par`: leaf utilities (vector arithmetic, closest
//!    points, hashing, the error types with their messages and checks, threads), which know
//!    nothing of meshes, bodies or worlds.
//! 1. `mesh`, `params`: plain data built on the utilities: a triangle mesh and its formats; the
//!    parameter table (defaults, units, ranges, the presets' values) that everything above reads.
//! 2. `obstacles`: rigid shapes (spheres, boxes, capsules, triangle meshes) made from meshes,
//!    with the table's default friction.
//! 3. `settings`: what a world imposes on every body (gravity, wind, ground, obstacles,
//!    integrator, dt, contacts): it holds obstacles and takes its defaults from the table.
//! 4. `body`: a soft body, stepped with the settings it is handed.
//! 5. `world`: the unit of simulation, which owns bodies and settings and runs the step.
//! 6. `scene`, `snapshot`, `snapshot_v3`…`snapshot_v7`, `delta`, `workload`, `sketch`,
//!    `compat`, and the crate root `lib`: they build, save, load, compare or drive whole
//!    worlds.
//!
//! Modules of one layer may import each other (`snapshot` and its `snapshot_vN` readers do both
//! ways, as do `snapshot` and `delta`).
//!
//! What counts as an import: every `crate::<module>` path (in `use` lines and inline), every
//! `crate::{…}` group, every `super::` path that climbs to the crate root, and `crate::Name`
//! where the crate root re-exports `Name` from a module (`lib.rs`'s `pub use`). Only code
//! counts: a file is read up to its `#[cfg(test)]` line (tests may use anything), and `//`
//! comments are skipped (a doc comment may name or link a higher module without depending on
//! it).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The layers, lowest first (see the module documentation for why each is where it is).
const LAYERS: &[&[&str]] = &[
    &["vec3", "geometry", "hash", "error", "par"],
    &["mesh", "params"],
    &["obstacles"],
    &["settings"],
    &["body"],
    &["world"],
    &["scene", "snapshot", "snapshot_v3", "snapshot_v4", "snapshot_v5", "snapshot_v6", "snapshot_v7", "delta", "workload", "sketch", "compat", "lib"],
];

fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, in a fixed order.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// A file's module path under `src`: `world/ground.rs` → [world, ground], `world/mod.rs` →
/// [world], `lib.rs` → [] (the crate root).
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !(stem == "mod" || (stem == "lib" && parts.is_empty())) {
        parts.push(stem.to_string());
    }
    parts
}

/// The top-level module a file belongs to (`lib` for the crate root).
fn top_module(path: &[String]) -> &str {
    path.first().map_or("lib", String::as_str)
}

/// The lines of code of a file (1-based number, text): up to its `#[cfg(test)]` line, each
/// without its `//` comment.
fn code_lines(text: &str) -> Vec<(usize, &str)> {
    text.lines()
        .enumerate()
        .take_while(|(_, l)| !l.trim_start().starts_with("#[cfg(test)]"))
        .map(|(i, l)| (i + 1, l.find("//").map_or(l, |c| &l[..c])))
        .collect()
}

/// Names the crate root re-exports, by the module they come from (`pub use body::{Material, …}`
/// → Material: body).
fn root_names(lib: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for (_, line) in code_lines(lib) {
        let Some(rest) = line.trim().strip_prefix("pub use ") else { continue };
        let Some((module, items)) = rest.split_once("::") else { continue };
        for item in items.trim_end_matches(';').trim_matches(|c| c == '{' || c == '}').split(',') {
            let name = item.rsplit(" as ").next().unwrap().rsplit("::").next().unwrap().trim();
            if !name.is_empty() {
                names.insert(name.to_string(), module.trim().to_string());
            }
        }
    }
    names
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

fn ident(s: &str) -> &str {
    &s[..s.find(|c: char| !is_ident(c)).unwrap_or(s.len())]
}

/// The first name of each item of the group `s` opens (`{a::b, c}` → a, c), or of the path `s`
/// starts with, with its offset in `s`.
fn first_names(s: &str) -> Vec<(usize, &str)> {
    let Some(group) = s.strip_prefix('{') else { return vec![(0, ident(s))] };
    let mut names = Vec::new();
    let (mut depth, mut start) = (0, 0);
    let mut item = |from: usize, to: usize| {
        let t = &group[from..to];
        let skip = t.len() - t.trim_start().len();
        names.push((1 + from + skip, ident(&t[skip..])));
    };
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                item(start, i);
                break;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                item(start, i);
                start = i + 1;
            }
            _ => {}
        }
    }
    names.into_iter().filter(|(_, n)| !n.is_empty() && *n != "self").collect()
}

/// One import of a top-level module from another file: where, what, and the line that says it.
#[derive(Debug, PartialEq)]
struct Import {
    line: usize,
    /// The top-level module imported, or `?Name` for a root name it could not place.
    module: String,
    text: String,
}

/// Every top-level module the code of the file at module path `path` imports (itself included):
/// `crate::m…`, `crate::{m…, …}`, `crate::Name` re-exported by the root, and `super::` paths
/// that climb to the root.
fn imports(path: &[String], text: &str, modules: &[String], roots: &BTreeMap<String, String>) -> Vec<Import> {
    let lines = code_lines(text);
    // The code as one string (a `use crate::{…}` group may span lines), with each line's start.
    let mut code = String::new();
    let mut starts = Vec::new();
    for (n, l) in &lines {
        starts.push((code.len(), *n));
        code.push_str(l);
        code.push('\n');
    }
    let line_at = |offset: usize| starts[starts.partition_point(|&(s, _)| s <= offset) - 1].1;
    let place = |name: &str| {
        if modules.iter().any(|m| m == name) {
            name.to_string()
        } else {
            roots.get(name).cloned().unwrap_or_else(|| format!("?{name}"))
        }
    };
    let mut found = Vec::new();
    let mut push = |at: usize, names: Vec<(usize, &str)>| {
        for (offset, name) in names {
            let line = line_at(at + offset);
            let text = text.lines().nth(line - 1).unwrap().trim().to_string();
            found.push(Import { line, module: place(name), text });
        }
    };
    let starts_path = |at: usize| code[..at].chars().next_back().is_none_or(|c| !(is_ident(c) || c == '$' || c == ':'));
    for (at, _) in code.match_indices("crate::") {
        if starts_path(at) {
            let from = at + "crate::".len();
            push(from, first_names(&code[from..]));
        }
    }
    for (at, _) in code.match_indices("super::") {
        if !starts_path(at) {
            continue;
        }
        let (mut from, mut depth) = (at, path.len());
        while code[from..].starts_with("super::") {
            from += "super::".len();
            depth = depth.saturating_sub(1);
        }
        if depth == 0 {
            push(from, first_names(&code[from..]));
        }
    }
    found.sort_by_key(|i| i.line);
    found
}

/// Every file under `src` with its module path and text.
fn sources(src: &Path) -> Vec<(PathBuf, Vec<String>, String)> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files
        .into_iter()
        .map(|f| {
            let rel = f.strip_prefix(src).unwrap().to_path_buf();
            let path = module_path(&rel);
            let text = std::fs::read_to_string(&f).unwrap();
            (rel, path, text)
        })
        .collect()
}

#[test]
fn no_module_imports_one_above_it() {
    let src = src();
    let files = sources(&src);
    let mut modules: Vec<String> = files.iter().filter_map(|(_, p, _)| p.first().cloned()).collect();
    modules.sort();
    modules.dedup();
    let roots = root_names(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    let mut problems: Vec<String> = modules.iter().filter(|m| layer(m).is_none()).map(|m| format!("module `{m}` has no layer: add it to LAYERS in tests/layers.rs")).collect();
    let mut checked = 0;
    for (rel, path, text) in &files {
        let from = top_module(path);
        let Some(own) = layer(from) else { continue };
        for i in imports(path, text, &modules, &roots) {
            if i.module == from {
                continue;
            }
            checked += 1;
            match layer(i.module.trim_start_matches('?')) {
                Some(l) if l <= own => {}
                Some(l) => problems.push(format!(
                    "src/{}:{}: `{from}` (layer {own}) imports `{}` (layer {l}): {}",
                    rel.display(),
                    i.line,
                    i.module,
                    i.text
                )),
                None => problems.push(format!("src/{}:{}: `{from}` imports `{}`, which has no layer: {}", rel.display(), i.line, i.module, i.text)),
            }
        }
    }
    assert!(checked > 0, "no imports between modules found under {}", src.display());
    assert!(problems.is_empty(), "{} imports from a higher layer (see tests/layers.rs):\n{}", problems.len(), problems.join("\n"));
}

/// The scan reads what the compiler would: paths in `use` lines and inline, groups across
/// lines, `super::` up to the root, root re-exports; not comments, not tests, not paths that
/// merely end in `crate::`-like text.
#[test]
fn the_scan_reads_every_kind_of_import_but_not_comments_or_tests() {
    let modules: Vec<String> = ["body", "mesh", "world", "settings", "error"].map(String::from).to_vec();
    let roots = root_names("pub use body::{Material, SoftBody};\npub use world::{World as W, Advance};\n");
    assert_eq!(roots.get("SoftBody").map(String::as_str), Some("body"));
    assert_eq!(roots.get("W").map(String::as_str), Some("world"));
    let text = "\
//! Stepped by a [`crate::world::World`].
use crate::settings::WorldSettings;
use crate::{
    mesh::TriMesh,
    SoftBody,
};
use super::super::error::SimError;
use super::sibling;
fn f() -> f64 { crate::world::sig3(1.0); $crate::mesh::x(); my_crate::world::y(); 0.0 } // crate::body
pub(crate) fn g(_: &crate::Unknown) {}
#[cfg(test)]
mod tests {
    use crate::world::World;
}
";
    let path = ["body".to_string(), "implicit".to_string()];
    let got: Vec<(usize, String)> = imports(&path, text, &modules, &roots).into_iter().map(|i| (i.line, i.module)).collect();
    let want = [(2, "settings"), (4, "mesh"), (5, "body"), (7, "error"), (9, "world"), (10, "?Unknown")];
    assert_eq!(got, want.map(|(l, m)| (l, m.to_string())).to_vec());
    assert_eq!(module_path(Path::new("world/mod.rs")), ["world"]);
    assert_eq!(module_path(Path::new("body/implicit/ground.rs")), ["body", "implicit", "ground"]);
    assert!(module_path(Path::new("lib.rs")).is_empty());
}
