//! Replay refused steps: restore each world snapshot named on the command line and take one
//! step, printing its Newton and linear iterations or the error. The snapshots come from
//! `web/bench/repro/` (the document's engine calls wrapped to save the world before each).
//!
//!   cargo run --release -p softsculpt --example replay -- /tmp/fail-*.bin
//!
//! With `RELAX=1` the step is taken as the modeler's last split takes it (`World::step_n_with`,
//! the relaxed retry on), and the line says what it let go of.
use softsculpt::world::World;

fn main() {
    for path in std::env::args().skip(1) {
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) => {
                eprintln!("{path}: {e}");
                continue;
            }
        };
        let mut w = match World::restore(&bytes) {
            Ok(w) => w,
            Err(e) => {
                eprintln!("{path}: not a world snapshot: {e}");
                continue;
            }
        };
        let relax = std::env::var("RELAX").is_ok_and(|v| v == "1");
        match w.step_n_with(1, None, relax) {
            Ok(()) => println!("{path}: {:?}", w.bodies[0].solver_iterations()),
            Err(e) => println!("{path}: refused: {e}"),
        }
    }
}
