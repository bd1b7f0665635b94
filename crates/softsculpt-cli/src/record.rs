//! What a run was, recorded with its results so a file of statistics describes itself: the
//! command line, the engine's version, every world and body parameter by its table id
//! (`World::param_values`: the table's ids), and each input file with the
//! SHA-256 of its bytes (what `sha256sum` prints). `simulate --stats` puts it in its first row
//! (step 0) under `"run"`, `run` in `summary.json` under `"run"` (docs/records.md).

use serde_json::{json, Map, Value};
use sha2::{Digest, Sha256};
use softsculpt::params::Scope;
use softsculpt::world::World;
use std::path::Path;

/// The SHA-256 of `bytes`, as lowercase hex.
pub fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// An input as recorded: its name, and for a file the SHA-256 of its contents (none for
/// `builtin:NAME`, which the version names).
pub fn input(name: &str) -> Value {
    if name.starts_with("builtin:") {
        return json!({ "name": name });
    }
    match crate::input::read_file(Path::new(name), name) {
        Ok(bytes) => json!({ "name": name, "sha256": sha256(&bytes), "bytes": bytes.len() }),
        Err(_) => json!({ "name": name }),
    }
}

/// The parameters of `scope` for body `body` of `world`, by table id (null where a parameter
/// has no value, such as the ground's without a ground).
pub fn parameters(world: &World, body: usize, scope: Scope) -> Map<String, Value> {
    world.param_values(body, &[scope]).into_iter().map(|(id, v)| (id.to_string(), v.and_then(|v| serde_json::to_value(v).ok()).unwrap_or(Value::Null))).collect()
}

/// The record of a run of `world` whose bodies are `names` (by index), read from `inputs`.
pub fn run(world: &World, names: &[String], inputs: Vec<Value>) -> Value {
    let bodies: Map<String, Value> = names.iter().enumerate().map(|(k, n)| (n.clone(), Value::Object(parameters(world, k, Scope::Body)))).collect();
    json!({
        "command": std::env::args().collect::<Vec<_>>(),
        "version": env!("CARGO_PKG_VERSION"),
        "inputs": inputs,
        "world": Value::Object(parameters(world, 0, Scope::World)),
        "bodies": Value::Object(bodies),
    })
}
