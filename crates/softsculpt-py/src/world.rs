//! `softsculpt.World`: a world of soft bodies, made from a scene file or a mesh, stepped in
//! place. Stepping releases the GIL (other Python threads run) and checks for Ctrl+C every
//! [`STEPS_PER_CHECK`] steps; a failed step raises `SimulationError` and rolls the world back to
//! the start of its batch of steps (the core's `World::step_n`). While a world steps, another
//! thread that reads or changes it gets a RuntimeError ("the world is stepping"), not a wait.

use crate::body::Body;
use crate::convert::{from_numpy, json_to_py, param_error, py_to_value, sim_error, step_error, value_to_py};
use crate::files::{disk_resolver, load_mesh};
use numpy::PyArrayMethods;
use pyo3::exceptions::{PyIndexError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use softsculpt::mesh::{LoadedMesh, ObjData};
use softsculpt::params::{self, Scope};
use softsculpt::scene::SceneRun;
use softsculpt::world::{Budget, World as Core, WorldSettings};
use softsculpt::{Material, SoftBody};
use std::path::{Path, PathBuf};

/// Steps between checks for Ctrl+C (and between releases of the GIL).
const STEPS_PER_CHECK: u64 = 16;

#[pyclass(module = "softsculpt._core")]
pub struct World {
    pub core: Core,
    /// Each body's name (the scene's, or "body").
    pub names: Vec<String>,
    /// Each body's source mesh (for OBJ in the file's vertex order), absent after a restore.
    pub meshes: Vec<Option<LoadedMesh>>,
    /// The scene's run length (s); None for a world made from a mesh.
    pub duration: Option<f64>,
}

/// Read and build the scene at `path` as `softsculpt run` does: its text, the run, and the
/// files it named with their bytes. Errors are the CLI's ("PATH: line L: key: why").
pub fn load_scene(path: &Path) -> PyResult<(String, SceneRun, Vec<(String, Vec<u8>)>)> {
    let bytes = crate::files::read_file(path)?;
    let shown = path.display();
    let text = String::from_utf8(bytes).map_err(|_| PyValueError::new_err(format!("{shown}: not UTF-8 text")))?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut files = Vec::new();
    let run = SceneRun::load(&text, &mut disk_resolver(&dir, &mut files)).map_err(|e| PyValueError::new_err(format!("{shown}: {e}")))?;
    Ok((text, run, files))
}

impl World {
    /// A world on every core, as the CLI's default (`threads` sets fewer).
    fn wrap(mut core: Core, names: Vec<String>, meshes: Vec<Option<LoadedMesh>>, duration: Option<f64>) -> World {
        let _ = core.set_threads(0); // (0 is always valid: one per core)
        World { core, names, meshes, duration }
    }

    fn of_scene(run: SceneRun) -> World {
        World::wrap(run.world, run.names, run.meshes.into_iter().map(Some).collect(), Some(run.duration))
    }

    pub fn body_index(&self, body: isize) -> PyResult<usize> {
        let n = self.core.bodies.len() as isize;
        let i = if body < 0 { body + n } else { body };
        if !(0..n).contains(&i) {
            return Err(PyIndexError::new_err(format!("there is no body {body} (the world has {n})")));
        }
        Ok(i as usize)
    }

    /// `n` steps, `STEPS_PER_CHECK` at a time under [`Core::advance`] without the GIL.
    fn step_released(&mut self, py: Python<'_>, n: u64) -> PyResult<()> {
        let mut left = n;
        while left > 0 {
            let k = left.min(STEPS_PER_CHECK);
            let core = &mut self.core;
            let frame = k as f64 * core.settings.dt;
            py.detach(|| core.advance(frame, &Budget::converge())).map_err(step_error)?;
            left -= k;
            py.check_signals()?;
        }
        Ok(())
    }
}

/// `world.borrow()` / `borrow_mut()` without the panic: a RuntimeError while another thread
/// steps the world (stepping releases the GIL and holds it mutably borrowed).
pub fn read<'py>(w: &'py Py<World>, py: Python<'py>) -> PyResult<PyRef<'py, World>> {
    w.bind(py).try_borrow().map_err(|_| stepping())
}

pub fn write<'py>(w: &'py Py<World>, py: Python<'py>) -> PyResult<PyRefMut<'py, World>> {
    w.bind(py).try_borrow_mut().map_err(|_| stepping())
}

fn stepping() -> PyErr {
    pyo3::exceptions::PyRuntimeError::new_err("the world is stepping in another thread: read or change it between steps")
}

/// A mesh given as arrays: vertices (N, 3) and triangles (F, 3) of vertex indices.
fn mesh_of_arrays(vertices: &Bound<'_, PyAny>, triangles: &Bound<'_, PyAny>) -> PyResult<LoadedMesh> {
    let np = vertices.py().import("numpy")?;
    let n = np.call_method1("shape", (vertices,))?.extract::<Vec<usize>>()?;
    let positions = from_numpy(vertices, "vertices", n.first().copied().unwrap_or(0))?;
    let t = np.call_method1("asarray", (triangles,))?;
    let shape: Vec<usize> = t.getattr("shape")?.extract()?;
    if shape.len() != 2 || shape[1] != 3 {
        return Err(PyValueError::new_err(format!("triangles: expected shape (F, 3), got {shape:?}")));
    }
    // Integers only (a float index is refused, not rounded), read as one int64 buffer.
    let kind: String = t.getattr("dtype")?.getattr("kind")?.extract()?;
    if kind != "i" && kind != "u" {
        return Err(PyValueError::new_err("triangles: not whole numbers"));
    }
    let t = np.call_method1("ascontiguousarray", (t, "int64"))?.cast_into::<numpy::PyArrayDyn<i64>>().map_err(|_| PyValueError::new_err("triangles: not whole numbers"))?;
    let ro = t.readonly();
    let flat = ro.as_slice()?;
    let nv = positions.len() / 3;
    let indices = flat
        .iter()
        .map(|&i| if (0..nv as i64).contains(&i) { Ok(i as u32) } else { Err(PyValueError::new_err(format!("triangles: vertex index {i} is not one of the {nv} vertices"))) })
        .collect::<PyResult<Vec<u32>>>()?;
    let source = ObjData { positions, arities: vec![3; indices.len() / 3], indices };
    softsculpt::mesh::prepare(source).map_err(|e| PyValueError::new_err(format!("mesh: {e}")))
}

/// A keyword's parameter id: the id itself, or with its first '_' read as '.' (`gas_amount`
/// for `gas.amount`, `ground_height` for `ground.height`).
fn param_id(key: &str) -> String {
    if params::find(key).is_ok() {
        return key.to_string();
    }
    key.replacen('_', ".", 1)
}

#[pymethods]
impl World {
    /// Build the world a scene file describes (docs/scenes.md); its meshes are read relative to
    /// the scene's folder. Steps fire the scene's events on time.
    #[staticmethod]
    fn from_scene(path: PathBuf) -> PyResult<World> {
        Ok(World::of_scene(load_scene(&path)?.1))
    }

    /// Build a scene from its text and the files it names (`{name: bytes}`, as
    /// `softsculpt.scene_files` reads them).
    #[staticmethod]
    #[pyo3(signature = (text, files=None))]
    fn from_scene_text(text: &str, files: Option<&Bound<'_, PyDict>>) -> PyResult<World> {
        let mut resolve = |name: &str| -> Result<Vec<u8>, String> {
            let item = files.map(|f| f.get_item(name)).transpose().map_err(|e| e.to_string())?.flatten();
            item.ok_or_else(|| "not among the files given".to_string())?.extract::<Vec<u8>>().map_err(|_| "not bytes".to_string())
        };
        let run = SceneRun::load(text, &mut resolve).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(World::of_scene(run))
    }

    /// A one-body world from a mesh: a path (OBJ, PLY, STL, glTF, GLB), `builtin:NAME`, or
    /// arrays `vertices` (N, 3) and `triangles` (F, 3). `preset` applies a material preset
    /// first; every other keyword sets a parameter by its table id (docs/parameters.md;
    /// `gas_amount` may stand for `gas.amount`), checked by the table.
    #[staticmethod]
    #[pyo3(signature = (mesh, triangles=None, *, preset=None, up=None, **params))]
    fn from_mesh(
        mesh: &Bound<'_, PyAny>,
        triangles: Option<&Bound<'_, PyAny>>,
        preset: Option<&str>,
        up: Option<&str>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<World> {
        let mut loaded = match triangles {
            Some(t) => mesh_of_arrays(mesh, t)?,
            None => {
                let path: PathBuf = mesh.extract().map_err(|_| PyTypeError::new_err("mesh: a path or 'builtin:NAME', or vertices with triangles"))?;
                load_mesh(&path.to_string_lossy())?
            }
        };
        if let Some(up) = up {
            let axis = softsculpt::mesh::UpAxis::from_name(up).ok_or_else(|| PyValueError::new_err(format!("up: unknown up axis '{up}' (use y or z)")))?;
            loaded.set_up_axis(axis);
        }
        let body = SoftBody::new(&loaded.mesh, params::MASS.number(), Material::default()).map_err(|e| PyValueError::new_err(format!("mesh: {e}")))?;
        let mut w = World::wrap(Core::single(body, WorldSettings::default()), vec!["body".into()], vec![Some(loaded)], None);
        if let Some(name) = preset {
            w.core.apply_preset(0, name).map_err(param_error)?;
        }
        let mut ids = Vec::new();
        if let Some(params) = params {
            let mut given: Vec<(String, Bound<'_, PyAny>)> = params.iter().map(|(k, v)| Ok((param_id(&k.extract::<String>()?), v))).collect::<PyResult<_>>()?;
            // `ground` before `ground.height` and the other ground keys (they need a ground).
            given.sort_by_key(|(id, _)| id != "ground");
            for (id, v) in given {
                w.set_param(&id, &v, 0)?;
                ids.push(id);
            }
        }
        // A preset carries what it needs to run, as `simulate --preset` (the CLI's note).
        if let Some(name) = preset {
            let was = w.core.settings.integrator;
            if !ids.iter().any(|id| id == "integrator" || id == "dt") {
                if let Some(limit) = w.core.implicit_if_unstable() {
                    let note = format!("preset {name}: {} is stable only below ~{limit:.1e} s for this model, not at dt {} s; the implicit integrator steps it (give integrator= or dt= to choose)", was.name(), w.core.settings.dt);
                    pyo3::PyErr::warn(mesh.py(), &mesh.py().get_type::<pyo3::exceptions::PyUserWarning>(), &std::ffi::CString::new(note).unwrap_or_default(), 1)?;
                }
            }
        }
        Ok(w)
    }

    /// The standard benchmark workload at icosphere `level` (`softsculpt bench`'s, defined in
    /// the core's `workload`): for measuring the binding against the CLI.
    #[staticmethod]
    fn workload(level: u32) -> PyResult<World> {
        if level > 9 {
            return Err(PyValueError::new_err(format!("level {level} is too large (at most 9: 2,621,442 vertices)")));
        }
        Ok(World::wrap(softsculpt::workload::world(level), vec!["body".into()], vec![None], None))
    }

    /// A world from `snapshot()`'s bytes (the modeler's and the CLI's snapshot format).
    #[staticmethod]
    fn restore(data: &[u8]) -> PyResult<World> {
        let core = Core::restore(data).map_err(|e| PyValueError::new_err(format!("snapshot: {e}")))?;
        let n = core.bodies.len();
        let names = if n == 1 { vec!["body".to_string()] } else { (0..n).map(|i| format!("body{i}")).collect() };
        Ok(World::wrap(core, names, vec![None; n], None))
    }

    /// The whole state as bytes (positions, velocities, materials, settings, clock, pending
    /// events): `World.restore` of them steps exactly as this world would.
    fn snapshot<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.core.snapshot())
    }

    /// Pickling: the snapshot, the names and the run's length.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>, Vec<String>, Option<f64>))> {
        let me = slf.try_borrow().map_err(|_| stepping())?;
        let rebuild = slf.get_type().getattr("_unpickle")?;
        Ok((rebuild, (me.snapshot(slf.py()), me.names.clone(), me.duration)))
    }

    #[staticmethod]
    fn _unpickle(data: &[u8], names: Vec<String>, duration: Option<f64>) -> PyResult<World> {
        let mut w = World::restore(data)?;
        if names.len() == w.names.len() {
            w.names = names;
        }
        w.duration = duration;
        Ok(w)
    }

    /// Take `n` steps of dt (events fire on time). Returns the world's step count.
    #[pyo3(signature = (n=1))]
    fn step(&mut self, py: Python<'_>, n: u64) -> PyResult<u64> {
        self.step_released(py, n)?;
        Ok(self.core.steps())
    }

    /// Advance by `seconds` of simulated time: the nearest whole number of steps (at least
    /// one), as `World::advance` in the core takes a frame. Returns the simulated time.
    fn advance(&mut self, py: Python<'_>, seconds: f64) -> PyResult<f64> {
        if !(seconds.is_finite() && seconds > 0.0) {
            return Err(PyValueError::new_err(format!("seconds: must be greater than 0, got {seconds}")));
        }
        let n = ((seconds / self.core.settings.dt).round() as u64).max(1);
        self.step_released(py, n)?;
        Ok(self.core.time())
    }

    /// Play a scene to its end (`duration`), as `softsculpt run` does (`SceneRun::run`: until
    /// the time is within half a step of it). Returns the steps taken.
    fn run(&mut self, py: Python<'_>) -> PyResult<u64> {
        let duration = self.duration.ok_or_else(|| PyValueError::new_err("run: this world has no scene duration (use step or advance)"))?;
        let before = self.core.steps();
        while self.core.time() < duration - 0.5 * self.core.settings.dt {
            // (dt may change at an event: a step at a time, as SceneRun::run.)
            self.step_released(py, 1)?;
        }
        Ok(self.core.steps() - before)
    }

    /// The bodies, in the world's order.
    #[getter]
    fn bodies(slf: &Bound<'_, Self>) -> PyResult<Vec<Body>> {
        let n = slf.try_borrow().map_err(|_| stepping())?.core.bodies.len();
        Ok((0..n).map(|index| Body { world: slf.clone().unbind(), index }).collect())
    }

    #[getter]
    fn names(&self) -> Vec<String> {
        self.names.clone()
    }

    /// Simulated time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.core.time()
    }

    /// Steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.core.steps()
    }

    /// The time step (s); set it with `set_param("dt", …)`.
    #[getter]
    fn dt(&self) -> f64 {
        self.core.settings.dt
    }

    /// The scene's run length (s), None for a world made from a mesh.
    #[getter]
    fn duration(&self) -> Option<f64> {
        self.duration
    }

    /// Threads the force stages and the implicit solver use: every core unless set (0: every
    /// core). A sweep runs each world on one.
    #[getter]
    fn threads(&self) -> usize {
        self.core.threads()
    }

    #[setter]
    fn set_threads(&mut self, n: usize) -> PyResult<()> {
        softsculpt::par::check_threads(n as u64).map_err(|e| PyValueError::new_err(format!("threads: {e}")))?;
        self.core.set_threads(n).map_err(|e| PyValueError::new_err(format!("threads: {e}")))
    }

    /// The value of parameter `id` (docs/parameters.md); body parameters are body `body`'s.
    #[pyo3(signature = (id, body=0))]
    fn param(&self, py: Python<'_>, id: &str, body: isize) -> PyResult<Py<PyAny>> {
        let i = self.body_index(body)?;
        value_to_py(py, self.core.param(i, id).map_err(param_error)?)
    }

    /// Set parameter `id`, checked by the table (ValueError with its range and unit).
    #[pyo3(signature = (id, value, body=0))]
    pub fn set_param(&mut self, id: &str, value: &Bound<'_, PyAny>, body: isize) -> PyResult<()> {
        let i = self.body_index(body)?;
        let v = py_to_value(id, value)?;
        self.core.set_param(i, id, v).map_err(param_error)
    }

    /// Every world and body parameter (body `body`'s) by its table id.
    #[pyo3(signature = (body=0))]
    fn params<'py>(&self, py: Python<'py>, body: isize) -> PyResult<Bound<'py, PyDict>> {
        let i = self.body_index(body)?;
        let d = PyDict::new(py);
        for (id, v) in self.core.param_values(i, &[Scope::World, Scope::Body]) {
            d.set_item(id, match v {
                Some(v) => value_to_py(py, v)?,
                None => py.None(),
            })?;
        }
        Ok(d)
    }

    /// Apply a material preset (docs/parameters.md) to body `body`.
    #[pyo3(signature = (name, body=0))]
    fn apply_preset(&mut self, name: &str, body: isize) -> PyResult<()> {
        let i = self.body_index(body)?;
        self.core.apply_preset(i, name).map_err(param_error)
    }

    /// Body `body`'s statistics: the keys of `softsculpt simulate --stats` (docs/records.md).
    #[pyo3(signature = (body=0))]
    fn stats(&self, py: Python<'_>, body: isize) -> PyResult<Py<PyAny>> {
        let i = self.body_index(body)?;
        json_to_py(py, &self.core.stats(i).to_json())
    }

    /// Body `body`'s current shape as OBJ text (the source file's vertex order and polygons
    /// when it came from one).
    #[pyo3(signature = (body=0, header=""))]
    fn obj(&self, body: isize, header: &str) -> PyResult<String> {
        let i = self.body_index(body)?;
        let b = &self.core.bodies[i];
        let bytes = match &self.meshes[i] {
            Some(m) => m.write_obj(b.positions(), header),
            None => softsculpt::TriMesh { positions: b.positions().to_vec(), triangles: b.triangles().to_vec() }.to_obj(header),
        };
        String::from_utf8(bytes).map_err(|e| sim_error(softsculpt::SimError::BadParameter { name: "obj", message: e.to_string() }))
    }

    fn __repr__(&self) -> String {
        let vertices: usize = self.core.bodies.iter().map(|b| b.positions().len() / 3).sum();
        format!("<softsculpt.World: {} bodies ({}), {vertices} vertices, t = {} s after {} steps>", self.names.len(), self.names.join(", "), self.core.time(), self.core.steps())
    }
}

/// The parameter table (docs/parameters.md) as a list of dicts: id, scope, unit, default,
/// range and help.
#[pyfunction]
pub fn parameters(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let table: serde_json::Value = serde_json::from_str(&params::table_json()).map_err(|e| PyValueError::new_err(e.to_string()))?;
    json_to_py(py, &table)
}
