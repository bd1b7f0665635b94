//! Undo deltas and old project files: thin calls over `softsculpt::delta` and
//! `softsculpt::compat`.
//!
//! `ss_mark(w)` remembers a copy of the world as it is now (replacing the last mark);
//! `ss_delta(w, scope)` writes the bytes of the delta that takes the world back to the mark
//! (`Delta::between(mark, world, scope)`, scope 0 none, 1 touched, 2 all; 3 whole: `Delta::whole(mark)`) and keeps the mark;
//! `ss_apply_delta(w, ptr, len)` applies delta bytes (world untouched on error, kind `delta`) and
//! writes the inverse delta's bytes (what redoes the change).
//!
//! `ss_open_project_v1(w, ptr, len)`: a version-1 project file of the modeler (a body's arrays as
//! JSON) becomes the world (`softsculpt::compat::project_v1`: a one-body world); the result is
//! `{"name": …, "ui": {…}}` as the file had them. On error (kind `project`, the core's message)
//! the world is untouched. Like `ss_clear`, it forgets an open scene.

use crate::abi::exports;
use crate::handle::with_world;
use crate::{bytes, set_result, status, Fail};
use softsculpt::delta::{Delta, DeltaError, StateScope};

fn delta_fail(e: DeltaError) -> Fail {
    Fail::new("delta", e.to_string())
}

/// One scope of `ss_delta`: its code is its index in [`SCOPES`], its name the page's
/// (`DeltaScope`, written from this list into `web/src/engine/abi.ts` by `tests/abi.rs`).
#[derive(Debug)]
pub struct DeltaScopeCode {
    pub name: &'static str,
    /// What of the state the delta keeps (`Delta::between`); `None`: the whole world as it was
    /// at the mark (`Delta::whole`).
    pub keeps: Option<StateScope>,
    pub doc: &'static str,
}

/// `ss_delta`'s scopes, by code.
pub const SCOPES: [DeltaScopeCode; 4] = [
    DeltaScopeCode { name: "none", keeps: Some(StateScope::None), doc: "Positions and velocities are not kept." },
    DeltaScopeCode { name: "touched", keeps: Some(StateScope::Touched), doc: "The state of the vertices whose state changed." },
    DeltaScopeCode { name: "all", keeps: Some(StateScope::All), doc: "The state of every vertex." },
    DeltaScopeCode { name: "whole", keeps: None, doc: "The world as it was at the mark, whatever the steps since did." },
];

exports! {
    /// Remember the world as it is now, for `ss_delta`.
    pub fn ss_mark(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                h.mark = Some(h.world.clone());
                Ok(())
            })
        })
    }

    /// The bytes of the delta that takes the world back to the mark, in the result (scope 0 none:
    /// positions and velocities are not kept, 1 touched: of the vertices whose state changed, 2 all,
    /// 3 whole: the world as it was at the mark, whatever happens after — `Delta::whole`).
    pub fn ss_delta(w: u32, scope: u32) -> i32 {
        status(|| {
            let scope = match SCOPES.get(scope as usize) {
                Some(s) => s.keeps,
                None => {
                    let codes: Vec<String> = SCOPES.iter().enumerate().map(|(k, s)| format!("{k} ({})", s.name)).collect();
                    let (last, rest) = codes.split_last().expect("scopes");
                    return Err(Fail::usage(format!("scope {scope} is not {} or {last}", rest.join(", "))));
                }
            };
            with_world(w, |h| {
                let mark = h
                    .mark
                    .as_ref()
                    .ok_or_else(|| Fail::usage("there is no mark (call ss_mark first)"))?;
                let delta = match scope {
                    Some(scope) => Delta::between(mark, &h.world, scope),
                    None => Delta::whole(mark),
                };
                set_result(delta.to_bytes());
                Ok(())
            })
        })
    }

    /// Apply delta bytes; the result holds the inverse delta's bytes. On error (kind `delta`) the
    /// world is untouched. Every body's views change.
    ///
    /// # Safety
    /// `ptr` must point to `len` readable bytes.
    pub unsafe fn ss_apply_delta(w: u32, ptr: *const u8, len: usize) -> i32 {
        status(|| {
            let delta = Delta::from_bytes(bytes(ptr, len)).map_err(delta_fail)?;
            with_world(w, |h| {
                let inverse = delta.apply(&mut h.world).map_err(delta_fail)?;
                h.rebuild_views();
                set_result(inverse.to_bytes());
                Ok(())
            })
        })
    }

    /// A version-1 project file becomes the world; result `{name, ui}`.
    ///
    /// # Safety
    /// `ptr` must point to `len` readable bytes.
    pub unsafe fn ss_open_project_v1(w: u32, ptr: *const u8, len: usize) -> i32 {
        status(|| {
            let (world, meta) =
                softsculpt::compat::project_v1(bytes(ptr, len)).map_err(|m| Fail::new("project", m))?;
            with_world(w, |h| {
                set_result(
                    serde_json::json!({ "name": meta.name, "ui": meta.ui })
                        .to_string()
                        .into_bytes(),
                );
                h.world = world;
                h.scene = None;
                h.rebuild_views();
                Ok(())
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error() -> String {
        let e = crate::ERROR.with(|e| e.borrow().clone());
        String::from_utf8(e).unwrap()
    }

    #[test]
    fn a_scope_code_outside_the_table_is_refused_naming_every_code() {
        let w = crate::handle::ss_world_new() as u32;
        assert_eq!(ss_mark(w), 0);
        for (code, _) in SCOPES.iter().enumerate() {
            assert_eq!(ss_delta(w, code as u32), 0, "{}", error());
        }
        assert_eq!(ss_delta(w, 4), -1);
        assert!(error().contains("scope 4 is not 0 (none), 1 (touched), 2 (all) or 3 (whole)"), "{}", error());
        crate::handle::ss_world_free(w);
    }
}
