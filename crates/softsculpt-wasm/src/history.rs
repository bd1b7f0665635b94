//! Undo deltas and old project files: thin calls over `softsculpt::delta` and
//! `softsculpt::compat`.
//!
//! `ss_mark(w)` remembers a copy of the world as it is now (replacing the last mark);
//! `ss_delta(w, scope)` writes the bytes of the delta that takes the world back to the mark
//! (`Delta::between(mark, world, scope)`, scope 0 none, 1 touched, 2 all) and keeps the mark;
//! `ss_apply_delta(w, ptr, len)` applies delta bytes (world untouched on error, kind `delta`) and
//! writes the inverse delta's bytes (what redoes the change).

use crate::status;
use crate::world::with_world;

/// Remember the world as it is now, for `ss_delta`.
#[no_mangle]
pub extern "C" fn ss_mark(w: u32) -> i32 {
    status(|| {
        with_world(w, |h| {
            h.mark = Some(h.world.clone());
            Ok(())
        })
    })
}
