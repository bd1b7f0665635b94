//! Reading a crate's imports from its source, for the tests that keep its modules free of
//! circles (issue #39): `tests/layers.rs` (the core's modules, and the sub-modules of `mesh`) and
//! `crates/softsculpt-wasm/tests/modules.rs` (the binding's modules), which includes this file.
//!
//! What counts as an import: every `crate::` path (in `use` lines and inline), with its groups
//! expanded to each item (`crate::{mesh::{obj, TriMesh}, world}` names `mesh::obj`,
//! `mesh::TriMesh` and `world`), and every `super::` path, resolved from the file's own module to
//! a path from the crate root. A path names a module, or a name a module's file re-exports
//! (`pub use`), which counts as the module it comes from. Only code counts: a file is read up
//! to its `#[cfg(test)]` line (tests may use anything), and `//` comments are skipped (a doc
//! comment may name or link a higher module without depending on it).
#![allow(dead_code)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

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
pub fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !(stem == "mod" || (stem == "lib" && parts.is_empty())) {
        parts.push(stem.to_string());
    }
    parts
}

/// A source file: its path under `src`, its module path and its text.
pub struct Source {
    pub rel: PathBuf,
    pub path: Vec<String>,
    pub text: String,
}

/// Every file under `src`.
pub fn sources(src: &Path) -> Vec<Source> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files
        .into_iter()
        .map(|f| {
            let rel = f.strip_prefix(src).unwrap().to_path_buf();
            let path = module_path(&rel);
            let text = std::fs::read_to_string(&f).unwrap();
            Source { rel, path, text }
        })
        .collect()
}

/// The lines of code of a file (1-based number, text): up to its `#[cfg(test)]` line, each
/// without its `//` comment.
pub fn code_lines(text: &str) -> Vec<(usize, &str)> {
    text.lines()
        .enumerate()
        .take_while(|(_, l)| !l.trim_start().starts_with("#[cfg(test)]"))
        .map(|(i, l)| (i + 1, l.find("//").map_or(l, |c| &l[..c])))
        .collect()
}

/// Names a module's file re-exports, by the sub-module they come from (`pub use body::{Material,
/// …}` → Material: body).
pub fn root_names(text: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for (_, line) in code_lines(text) {
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

fn skip_ws(s: &str, i: usize) -> usize {
    i + (s[i..].len() - s[i..].trim_start().len())
}

/// The paths a `use` tree (or an inline path) at the start of `s` names, each with the offset in
/// `s` of the item that names it: `a::b(…)` → [a, b]; `a::{b, c::{self, d as e}}` → [a, b],
/// [a, c], [a, c, d]; `{a, b}` → [a], [b]; `a::B as C` → [a, B].
fn use_tree(s: &str) -> Vec<(usize, Vec<String>)> {
    let mut out = Vec::new();
    tree(s, 0, &mut Vec::new(), &mut out);
    out
}

/// One tree at `s[i..]` (after `prefix`), its paths into `out`; returns where it ends.
fn tree(s: &str, i: usize, prefix: &mut Vec<String>, out: &mut Vec<(usize, Vec<String>)>) -> usize {
    let depth = prefix.len();
    let start = skip_ws(s, i);
    let mut i = start;
    let mut named = false;
    loop {
        if s[i..].starts_with('{') {
            i += 1;
            loop {
                i = skip_ws(s, i);
                if i >= s.len() || s[i..].starts_with('}') {
                    i = (i + 1).min(s.len());
                    break;
                }
                i = skip_ws(s, tree(s, i, prefix, out));
                if s[i..].starts_with(',') {
                    i += 1;
                } else {
                    i = if s[i..].starts_with('}') { i + 1 } else { s.len() };
                    break;
                }
            }
            prefix.truncate(depth);
            return i;
        }
        let id = ident(&s[i..]);
        if id.is_empty() {
            i += usize::from(s[i..].starts_with('*'));
            break;
        }
        i += id.len();
        named = true;
        if id != "self" {
            prefix.push(id.to_string());
        }
        if s[i..].starts_with("::") {
            i += 2;
        } else {
            break;
        }
    }
    // `… as Name`: the path is what it names.
    let after = skip_ws(s, i);
    if named && s[after..].starts_with("as ") {
        let j = skip_ws(s, after + 3);
        i = j + ident(&s[j..]).len();
    }
    if named && !prefix.is_empty() {
        out.push((start, prefix.clone()));
    }
    prefix.truncate(depth);
    i
}

/// One import in a file: where, the path it names from the crate root, and the line that says it.
#[derive(Debug, PartialEq)]
pub struct Import {
    pub line: usize,
    pub path: Vec<String>,
    pub text: String,
}

/// Every path the code of the file at module path `path` names from the crate root: `crate::…`
/// paths and groups, and `super::` paths resolved from the file's module.
pub fn imports(path: &[String], text: &str) -> Vec<Import> {
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
    let mut found = Vec::new();
    let mut push = |at: usize, base: &[String], paths: Vec<(usize, Vec<String>)>| {
        for (offset, p) in paths {
            let line = line_at(at + offset);
            let text = text.lines().nth(line - 1).unwrap().trim().to_string();
            found.push(Import { line, path: base.iter().cloned().chain(p).collect(), text });
        }
    };
    let starts_path = |at: usize| code[..at].chars().next_back().is_none_or(|c| !(is_ident(c) || c == '$' || c == ':'));
    for (at, _) in code.match_indices("crate::") {
        if starts_path(at) {
            let from = at + "crate::".len();
            push(from, &[], use_tree(&code[from..]));
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
        push(from, &path[..depth], use_tree(&code[from..]));
    }
    found.sort_by_key(|i| i.line);
    found
}

/// The module directly under `parent` that the import path `import` names: a module of
/// `modules`, or the module a name `roots` (the parent's re-exports) comes from, or `?Name` for a
/// name it cannot place (one the parent's own file defines). `None` for a path not under
/// `parent`.
pub fn module_under(parent: &[String], import: &[String], modules: &[String], roots: &BTreeMap<String, String>) -> Option<String> {
    let name = import.strip_prefix(parent)?.first()?;
    Some(if modules.contains(name) {
        name.clone()
    } else {
        roots.get(name).cloned().unwrap_or_else(|| format!("?{name}"))
    })
}

/// The modules directly under `parent` (the crate root: `&[]`), each file with the module it
/// belongs to (`root` for the parent's own file), and the names the parent's file re-exports.
pub struct Level<'a> {
    pub parent: Vec<String>,
    pub root: &'a str,
    pub modules: Vec<String>,
    pub roots: BTreeMap<String, String>,
    pub files: Vec<(&'a Source, String)>,
}

impl<'a> Level<'a> {
    pub fn new(sources: &'a [Source], parent: &[&str], root: &'a str) -> Self {
        let parent: Vec<String> = parent.iter().map(|s| s.to_string()).collect();
        let mut files = Vec::new();
        let mut roots = BTreeMap::new();
        for s in sources {
            let Some(rest) = s.path.strip_prefix(parent.as_slice()) else { continue };
            match rest.first() {
                Some(m) => files.push((s, m.clone())),
                None => {
                    roots = root_names(&s.text);
                    files.push((s, root.to_string()));
                }
            }
        }
        let mut modules: Vec<String> = files.iter().map(|(_, m)| m.clone()).filter(|m| m != root).collect();
        modules.sort();
        modules.dedup();
        Level { parent, root, modules, roots, files }
    }

    /// Every import of another module of this level: (file, its module, the module imported,
    /// the import).
    pub fn arrows(&self) -> Vec<(&'a Source, String, String, Import)> {
        let mut out = Vec::new();
        for (s, from) in &self.files {
            for i in imports(&s.path, &s.text) {
                let Some(to) = module_under(&self.parent, &i.path, &self.modules, &self.roots) else { continue };
                if &to != from {
                    out.push((*s, from.clone(), to, i));
                }
            }
        }
        out
    }

    /// What breaks the layers (lowest first): a module with no layer, an import of a module in
    /// a higher layer, or of a name that cannot be placed. Panics if no import was found at all.
    pub fn layer_problems(&self, layers: &[&[&str]], list: &str) -> Vec<String> {
        let layer = |m: &str| layers.iter().position(|l| l.contains(&m));
        let mut problems: Vec<String> = self
            .modules
            .iter()
            .chain([&self.root.to_string()])
            .filter(|m| layer(m).is_none())
            .map(|m| format!("module `{m}` has no layer: add it to {list}"))
            .collect();
        let arrows = self.arrows();
        assert!(!arrows.is_empty(), "no imports between the modules under {:?} found", self.parent);
        for (s, from, to, i) in arrows {
            let Some(own) = layer(&from) else { continue };
            match layer(to.trim_start_matches('?')) {
                Some(l) if l <= own => {}
                Some(l) => problems.push(format!("src/{}:{}: `{from}` (layer {own}) imports `{to}` (layer {l}): {}", s.rel.display(), i.line, i.text)),
                None => problems.push(format!("src/{}:{}: `{from}` imports `{to}`, which has no layer: {}", s.rel.display(), i.line, i.text)),
            }
        }
        problems
    }
}

/// The circles of a graph (its strongly connected components with more than one node), each
/// sorted, in a fixed order.
pub fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.keys().chain(edges.values().flatten()).collect();
    let reach = |from: &String| {
        let mut seen = BTreeSet::new();
        let mut todo = vec![from];
        while let Some(n) = todo.pop() {
            for m in edges.get(n).into_iter().flatten() {
                if seen.insert(m) {
                    todo.push(m);
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&String, BTreeSet<&String>> = nodes.iter().map(|&n| (n, reach(n))).collect();
    let mut out: Vec<Vec<String>> = Vec::new();
    for &n in &nodes {
        let mut c: Vec<String> = nodes.iter().filter(|&&m| m != n && reached[n].contains(m) && reached[m].contains(n)).map(|m| (*m).clone()).collect();
        if c.is_empty() {
            continue;
        }
        c.push(n.clone());
        c.sort();
        if !out.contains(&c) {
            out.push(c);
        }
    }
    out
}
