//! The `softsculpt` Python package's native module, `softsculpt._core` (PyO3): a thin binding
//! of the core's [`softsculpt::World`]. Everything it does is the core's (stepping, parameters
//! by the table's ids and checks, snapshots, statistics); this crate converts values and errors
//! and reads files. The Python side (`python/softsculpt/`) re-exports it and adds the sweeps.
//!
//! Files: `world.rs` the `World` class; `body.rs` the `Body` view of one body; `convert.rs`
//! values, arrays and errors; `files.rs` reading meshes and scenes with the CLI's limits.

use pyo3::prelude::*;

mod body;
mod convert;
mod files;
mod world;

// (Named by its full module path, so that it pickles: Dask and multiprocessing carry it.)
pyo3::create_exception!(
    softsculpt._core,
    SimulationError,
    pyo3::exceptions::PyRuntimeError,
    "A step failed (the body blew up, collapsed, or the implicit solve did not converge); the world is rolled back to the start of the failing batch of steps (at most 16 steps earlier: the message says the time)."
);

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    m.add_class::<world::World>()?;
    m.add_class::<body::Body>()?;
    m.add_function(wrap_pyfunction!(world::parameters, m)?)?;
    m.add_function(wrap_pyfunction!(files::scene_files, m)?)?;
    Ok(())
}
