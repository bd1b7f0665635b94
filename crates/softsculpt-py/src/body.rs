//! `softsculpt.Body`: one body of a world (`world.bodies[i]`), a view that reads and writes
//! the world it belongs to. Arrays read are copies, (N, 3) float64 (metres, m/s): the world
//! steps its own buffers in place (and replaces them on a restore), so a view of them would
//! change or dangle under the reader; a copy of 40,962 vertices takes ~0.1 ms, against ~100 ms
//! for a step. Arrays written are checked (shape, finite) before anything changes.

use crate::convert::{from_numpy, json_to_py, sim_error, to_numpy};
use crate::world::World;
use numpy::PyArray1;
use numpy::PyArrayMethods;
use pyo3::prelude::*;

#[pyclass(module = "softsculpt._core")]
pub struct Body {
    pub world: Py<World>,
    pub index: usize,
}

impl Body {
    /// Replace the positions (or, with `velocities`, the velocities) by an (N, 3) array,
    /// converted and checked before the world is borrowed for writing.
    fn set_state_part(&self, py: Python<'_>, value: &Bound<'_, PyAny>, velocities: bool) -> PyResult<()> {
        let n = crate::world::read(&self.world, py)?.core.bodies[self.index].vertex_count();
        let new = from_numpy(value, if velocities { "velocities" } else { "positions" }, n)?;
        let mut w = crate::world::write(&self.world, py)?;
        let b = &mut w.core.bodies[self.index];
        let (x, v) = if velocities { (b.positions().to_vec(), new) } else { (new, b.velocities().to_vec()) };
        b.set_state(&x, &v).map_err(sim_error)
    }
}

#[pymethods]
impl Body {
    /// The body's name (the scene's table name, or "body").
    #[getter]
    fn name(&self, py: Python<'_>) -> PyResult<String> {
        Ok(crate::world::read(&self.world, py)?.names[self.index].clone())
    }

    /// Vertex positions (N, 3), metres.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_numpy(py, crate::world::read(&self.world, py)?.core.bodies[self.index].positions())
    }

    #[setter]
    fn set_positions(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_state_part(py, value, false)
    }

    /// Vertex velocities (N, 3), m/s.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_numpy(py, crate::world::read(&self.world, py)?.core.bodies[self.index].velocities())
    }

    #[setter]
    fn set_velocities(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_state_part(py, value, true)
    }

    /// Triangles (F, 3) as vertex indices, counter-clockwise seen from outside.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let w = crate::world::read(&self.world, py)?;
        let flat: Vec<u32> = w.core.bodies[self.index].triangles().iter().flatten().copied().collect();
        let n = flat.len() / 3;
        Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any())
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(crate::world::read(&self.world, py)?.core.bodies[self.index].positions().len() / 3)
    }

    /// The volume the surface encloses (m³); None for an open surface.
    #[getter]
    fn volume(&self, py: Python<'_>) -> PyResult<Option<f64>> {
        let w = crate::world::read(&self.world, py)?;
        let b = &w.core.bodies[self.index];
        Ok(b.is_closed().then(|| b.exact_volume()))
    }

    /// This body's statistics (`World.stats`).
    fn stats(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &crate::world::read(&self.world, py)?.core.stats(self.index).to_json())
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let w = crate::world::read(&self.world, py)?;
        Ok(format!("<softsculpt.Body '{}': {} vertices>", w.names[self.index], w.core.bodies[self.index].positions().len() / 3))
    }
}
