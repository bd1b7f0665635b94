//! Values, arrays and errors between the core and Python.
//!
//! - A parameter's value is a float (numbers), a tuple of three floats (vectors), a str (a
//!   choice: the integrator, the volume mode) or a bool (flags), by the table's default's kind.
//! - Per-vertex arrays are numpy float64 arrays of shape (N, 3) (metres, m/s); arrays given in
//!   are converted with `numpy.asarray(a, dtype=float64)` and refused, before anything changes,
//!   unless their shape is (N, 3) and every entry is finite.
//! - Errors: a parameter outside its range, a bad mesh or scene, a wrong array: `ValueError`
//!   with the message the CLI prints; a failed step: `softsculpt.SimulationError`.

use crate::SimulationError;
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};
use softsculpt::params::{self, ParamError, Value};
use softsculpt::{SimError, StepError};

/// A parameter's value as a Python object.
pub fn value_to_py(py: Python<'_>, v: Value) -> PyResult<Py<PyAny>> {
    Ok(match v {
        Value::Number(x) => x.into_pyobject(py)?.into_any().unbind(),
        Value::Vector(a) => PyTuple::new(py, a)?.into_any().unbind(),
        Value::Choice(s) => PyString::new(py, s).into_any().unbind(),
        Value::Flag(b) => PyBool::new(py, b).to_owned().into_any().unbind(),
    })
}

/// A Python object as a value of parameter `id` (its kind is its default's): a TypeError
/// naming the parameter if it is of another kind; the range is the core's check.
pub fn py_to_value(id: &str, obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    let p = params::find(id).map_err(param_error)?;
    let kind_error = |want: &str| PyTypeError::new_err(format!("{id}: expected {want}, got {}", obj.get_type().name().map(|n| n.to_string()).unwrap_or_default()));
    Ok(match p.default {
        Value::Flag(_) => Value::Flag(obj.cast::<PyBool>().map_err(|_| kind_error("True or False"))?.is_true()),
        Value::Choice(_) => {
            let name: String = obj.extract().map_err(|_| kind_error(&format!("a name, one of {}", p.choices().join(", "))))?;
            params::choice(id, &name).map_err(param_error)?
        }
        Value::Number(_) => {
            if obj.is_instance_of::<PyBool>() {
                return Err(kind_error("a number"));
            }
            Value::Number(obj.extract::<f64>().map_err(|_| kind_error("a number"))?)
        }
        Value::Vector(_) => Value::Vector(obj.extract::<[f64; 3]>().map_err(|_| kind_error("three numbers (x, y, z)"))?),
    })
}

/// A JSON value (the core's statistics rows) as Python objects: objects as dicts, arrays as
/// lists, numbers as int or float.
pub fn json_to_py(py: Python<'_>, v: &serde_json::Value) -> PyResult<Py<PyAny>> {
    use serde_json::Value as J;
    Ok(match v {
        J::Null => py.None(),
        J::Bool(b) => PyBool::new(py, *b).to_owned().into_any().unbind(),
        J::Number(n) => match n.as_u64() {
            Some(u) => u.into_pyobject(py)?.into_any().unbind(),
            None => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any().unbind(),
        },
        J::String(s) => PyString::new(py, s).into_any().unbind(),
        J::Array(a) => PyList::new(py, a.iter().map(|x| json_to_py(py, x)).collect::<PyResult<Vec<_>>>()?)?.into_any().unbind(),
        J::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, json_to_py(py, x)?)?;
            }
            d.into_any().unbind()
        }
    })
}

/// Flat xyz as a new (N, 3) float64 array (a copy: the world keeps stepping its own).
pub fn to_numpy<'py>(py: Python<'py>, flat: &[f64]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_slice(py, flat).reshape([flat.len() / 3, 3])?.into_any())
}

/// An (N, 3) array-like of finite numbers as flat xyz; `what` and `n` for the message.
pub fn from_numpy(obj: &Bound<'_, PyAny>, what: &str, n: usize) -> PyResult<Vec<f64>> {
    let np = obj.py().import("numpy")?;
    let a = np.call_method1("ascontiguousarray", (obj, "float64")).map_err(|e| PyValueError::new_err(format!("{what}: not an array of numbers ({e})")))?;
    let a = a.cast_into::<numpy::PyArrayDyn<f64>>().map_err(|_| PyValueError::new_err(format!("{what}: not an array of numbers")))?;
    let shape = a.shape().to_vec();
    if shape != [n, 3] {
        return Err(PyValueError::new_err(format!("{what}: expected shape ({n}, 3), got {shape:?}")));
    }
    let flat: Vec<f64> = a.readonly().as_slice()?.to_vec();
    if let Some(k) = flat.iter().position(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!("{what}: row {} is not finite ({:?})", k / 3, &flat[3 * (k / 3)..3 * (k / 3) + 3])));
    }
    Ok(flat)
}

pub fn param_error(e: ParamError) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A core error: a bad value is a ValueError; anything that happened while stepping a
/// SimulationError.
pub fn sim_error(e: SimError) -> PyErr {
    match e {
        SimError::BadParameter { .. } | SimError::Length { .. } => PyValueError::new_err(e.to_string()),
        _ => SimulationError::new_err(e.to_string()),
    }
}

/// A failed step: the CLI's message ("at t s: why", with the scene line of an event).
pub fn step_error(e: StepError) -> PyErr {
    match &e.error {
        SimError::BadParameter { .. } | SimError::Length { .. } => PyValueError::new_err(softsculpt::scene::run::scene_error(&e).to_string()),
        _ => SimulationError::new_err(softsculpt::scene::run::scene_error(&e).to_string()),
    }
}
