//! The table as TypeScript (`web/src/engine/params.ts`, written and checked by a test as
//! `docs/parameters.md` is): the ids as a string-literal type, so the page's calls that name a
//! parameter (`World.setParam`, the worker's `setParam` command) are checked by `tsc`; the rows
//! (id, scope, unit, default, range) as a const array; and R, the gas constant nRT divides by.

use super::{Scope, Value, GAS_CONSTANT, TABLE};

/// A number as TypeScript writes it (`null` for an unbounded end of a range).
fn number(x: f64) -> String {
    if x.is_finite() { format!("{x}") } else { "null".into() }
}

fn value(v: &Value) -> String {
    match v {
        Value::Number(x) => number(*x),
        Value::Vector(v) => format!("[{}, {}, {}]", number(v[0]), number(v[1]), number(v[2])),
        Value::Choice(c) => format!("'{c}'"),
        Value::Flag(b) => b.to_string(),
    }
}

fn scope(s: Scope) -> &'static str {
    match s {
        Scope::Body => "body",
        Scope::World => "world",
        Scope::Scene => "scene",
        Scope::Obstacle => "obstacle",
    }
}

/// `  | 'a'\n  | 'b'` for the ids of the parameters `keep` keeps.
fn union(keep: impl Fn(Scope) -> bool) -> String {
    TABLE.iter().filter(|p| keep(p.scope)).map(|p| format!("\n  | '{}'", p.id)).collect()
}

/// The text of `web/src/engine/params.ts`.
pub fn typescript() -> String {
    let mut out = String::from(
        "// The engine's parameter table (ids, scopes, units, defaults, ranges) for the page's types.\n\
         // Generated from crates/softsculpt/src/params/table.rs: do not edit. A test fails when it is\n\
         // stale; regenerate it with `UPDATE_DOCS=1 cargo test -p softsculpt --release --test parameters`.\n\n",
    );
    out.push_str(&format!("/** Ideal gas constant R (J/(mol·K)): gas as nRT (J) is n = nRT / (R T) mol. */\nexport const GAS_CONSTANT = {GAS_CONSTANT};\n\n"));
    out.push_str(&format!("/** A body's parameter (each body has its own). */\nexport type BodyParamId ={};\n\n", union(|s| s == Scope::Body)));
    out.push_str(&format!("/** A world's parameter (every body shares it). */\nexport type WorldParamId ={};\n\n", union(|s| s == Scope::World)));
    out.push_str(&format!("/** Every parameter of the table (scene and obstacle ones exist only in scene files). */\nexport type ParamId = BodyParamId | WorldParamId{};\n\n", union(|s| s != Scope::Body && s != Scope::World)));
    out.push_str(
        "/** A row of the table: valid numbers (each component of a vector) are min ≤ v ≤ max (min < v when minOpen; null: unbounded). */\n\
         export interface ParamRow {\n  id: ParamId;\n  scope: 'body' | 'world' | 'scene' | 'obstacle';\n  unit: string;\n  \
         default: number | boolean | string | readonly [number, number, number];\n  min: number | null;\n  max: number | null;\n  minOpen: boolean;\n}\n\n",
    );
    out.push_str("/** The table's rows, in its order. */\nexport const PARAMS = [\n");
    for p in TABLE {
        out.push_str(&format!(
            "  {{ id: '{}', scope: '{}', unit: '{}', default: {}, min: {}, max: {}, minOpen: {} }},\n",
            p.id,
            scope(p.scope),
            p.unit,
            value(&p.default),
            number(p.range.min),
            number(p.range.max),
            p.range.min_open
        ));
    }
    out.push_str("] as const satisfies readonly ParamRow[];\n");
    out
}
