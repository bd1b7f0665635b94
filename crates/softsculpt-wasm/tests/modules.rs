//! No circles between the binding's modules (issue #39). The order they stand in, lowest first:
//!
//! 0. `lib`: the crate root: the error and result slots, `Fail`, and the small helpers every call
//!    uses (`status`, `index`, `bytes`, `text`).
//!    `abi`: the `exports!` macro every module writes its calls with, and the table's types; it
//!    imports nothing of the crate.
//! 1. `views`: what the binding keeps beside a body for the page (`BodyViews`, the layout table).
//! 2. `handle`: the table of world handles (`Handle`: a world, its bodies' views, the mark, the
//!    open scene's record `SceneInfo`), `with_world`, and the calls that make and free worlds.
//! 3. `world`: the calls on a world and its bodies (the views' calls among them), and the core's
//!    errors as `Fail`.
//! 4. `scene`, `history`, `import`: scene files, marks and deltas, mesh files of any format.
//!
//! Before, `world` held the handle table and imported `views` (`BodyViews`) and `scene`
//! (`SceneInfo`), which imported `world` back for `with_world`: two circles. The test reads the
//! `crate::` and `super::` paths of every file (`softsculpt/tests/support/imports.rs`, shared
//! with the core's `tests/layers.rs`) and fails on any circle, naming the imports that make it.

#[path = "../../softsculpt/tests/support/imports.rs"]
mod imports;

use imports::{circles, sources, Level};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

#[test]
fn the_binding_modules_import_each_other_without_circles() {
    let files = sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    let level = Level::new(&files, &[], "lib");
    let arrows = level.arrows();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (_, from, to, _) in &arrows {
        // A name that is no module is one the crate root defines itself (`crate::status`).
        let to = if to.starts_with('?') { "lib" } else { to };
        if to != from {
            edges.entry(from.clone()).or_default().insert(to.to_string());
        }
    }
    for m in ["handle", "views", "world", "scene", "history", "import"] {
        assert!(level.modules.iter().any(|x| x == m), "module `{m}` not found in {:?}", level.modules);
    }
    assert!(edges.get("world").is_some_and(|e| e.contains("handle")), "the scan found no import of `handle` by `world`: {edges:?}");
    let found = circles(&edges);
    let said: Vec<String> = found
        .iter()
        .map(|c| {
            let lines: Vec<String> = arrows
                .iter()
                .filter(|(_, from, to, _)| c.contains(from) && c.contains(to))
                .map(|(s, from, to, i)| format!("  src/{}:{}: `{from}` imports `{to}`: {}", s.rel.display(), i.line, i.text))
                .collect();
            format!("circle {}:\n{}", c.join(" ↔ "), lines.join("\n"))
        })
        .collect();
    assert!(found.is_empty(), "the binding's modules import each other in a circle (see tests/modules.rs):\n{}", said.join("\n"));
}

/// The circle finder finds circles of any length, and only those.
#[test]
fn circles_are_found() {
    let graph = |arrows: &[(&str, &str)]| {
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in arrows {
            g.entry(a.to_string()).or_default().insert(b.to_string());
        }
        g
    };
    assert!(circles(&graph(&[("world", "views"), ("world", "lib"), ("views", "lib")])).is_empty());
    assert_eq!(circles(&graph(&[("world", "views"), ("views", "world"), ("scene", "lib")])), [["views", "world"]]);
    assert_eq!(circles(&graph(&[("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")])), [["a", "b", "c"]]);
}
