//! Errors of the core, each with a message fit to show a user as it is, and what those messages
//! are made with: the checks that refuse a parameter ([`check_positive`],
//! [`check_non_negative`]) and numbers written to three significant digits ([`sig3`]).

use std::fmt;

/// Why a mesh could not be read or used.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshError {
    /// The OBJ text is malformed at a given 1-based line.
    Parse { line: usize, message: String },
    /// The bytes are not text (binary junk, invalid UTF-8).
    NotText { offset: usize },
    /// No faces at all (an empty file, or only comments).
    Empty(String),
    /// Gas needs a closed, manifold surface.
    NotClosed { boundary_edges: usize, non_manifold_edges: usize },
    /// The surface cannot be oriented consistently (a Möbius-like mesh).
    NonOrientable { edges: usize },
    /// A builtin name that does not exist.
    UnknownBuiltin(String),
    /// A file of another format (PLY, STL, glTF, GLB) is malformed.
    Format { format: &'static str, message: String },
    /// Anything else about the mesh that makes it unusable.
    Invalid(String),
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Parse { line, message } => write!(f, "line {line}: {message}"),
            MeshError::NotText { offset } => {
                write!(f, "not a text OBJ file (binary or invalid UTF-8 data at byte {offset})")
            }
            MeshError::Empty(what) => write!(f, "{what}"),
            MeshError::NotClosed { boundary_edges, non_manifold_edges } => {
                let mut parts = Vec::new();
                if *boundary_edges > 0 {
                    parts.push(format!("{boundary_edges} boundary (open) edges"));
                }
                if *non_manifold_edges > 0 {
                    parts.push(format!("{non_manifold_edges} non-manifold edges (shared by more than two faces)"));
                }
                write!(
                    f,
                    "gas pressure needs a closed manifold surface, but the mesh has {}; \
                     close the holes, or simulate it without gas (gas 0)",
                    parts.join(" and ")
                )
            }
            MeshError::NonOrientable { edges } => write!(
                f,
                "the surface cannot be oriented consistently ({edges} edges join faces of opposite orientation whichever way they are flipped): it is not a closed orientable body"
            ),
            MeshError::UnknownBuiltin(name) => write!(
                f,
                "unknown built-in model '{name}' (available: {})",
                BUILTIN_NAMES.join(", ")
            ),
            MeshError::Format { format, message } => write!(f, "not a valid {format} file: {message}"),
            MeshError::Invalid(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for MeshError {}

/// Why the simulation could not go on or a parameter was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum SimError {
    /// A parameter is outside its valid range (name, message).
    BadParameter { name: &'static str, message: String },
    /// The state became non-finite (an explosion). `step` counts from the body's creation.
    NonFinite { step: u64 },
    /// The volume the gas uses fell to zero or below (the body turned inside out).
    Collapsed { step: u64, volume: f64 },
    /// An implicit step did not reach the tolerance within the Newton iteration cap; the state
    /// is left as it was before the step. `time` (s) is the time at the step's start.
    NotConverged { step: u64, time: f64, iterations: u32, residual: f64, tolerance: f64 },
    /// The caller interrupted an implicit step (`WorldSettings::interrupt`: the page has a
    /// command waiting); the state is left as it was before the step.
    Interrupted { step: u64, time: f64 },
    /// An array passed in has the wrong length.
    Length { what: &'static str, expected: usize, got: usize },
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::BadParameter { name, message } => write!(f, "{name}: {message}"),
            SimError::NonFinite { step } => write!(
                f,
                "the simulation blew up at step {step} (positions or velocities became non-finite); \
                 try a smaller dt, more damping, or another integrator (symplectic or rk4)"
            ),
            SimError::Collapsed { step, volume } => write!(
                f,
                "the body collapsed at step {step} (gas volume {volume:e} m^3 is not positive); \
                 try a smaller dt (or the implicit integrator) or more gas"
            ),
            SimError::NotConverged { step, time, iterations, residual, tolerance } => write!(
                f,
                "the implicit step at t = {} s (step {step}) did not converge: relative residual {residual:.3e} \
                 after {iterations} Newton iterations, tolerance {tolerance:e}; the state is unchanged. \
                 Try a smaller dt (e.g. half), a looser --tolerance, or more --newton-iterations",
                sig3(*time)
            ),
            SimError::Interrupted { step, time } => write!(
                f,
                "the step at t = {} s (step {step}) was interrupted by its caller; the state is unchanged",
                sig3(*time)
            ),
            SimError::Length { what, expected, got } => {
                write!(f, "{what}: expected {expected} values, got {got}")
            }
        }
    }
}

impl std::error::Error for SimError {}

/// The built-in models' names (`mesh::builtin` builds them, as `mesh::builtin::NAMES`): here so
/// that [`MeshError::UnknownBuiltin`]'s message can list them without this module importing the
/// mesh module above it.
pub(crate) const BUILTIN_NAMES: &[&str] = &["sphere", "mushroom", "octopus", "kangaroo"];

pub(crate) fn bad(name: &'static str, message: String) -> SimError {
    SimError::BadParameter { name, message }
}

/// `value` must be finite and ≥ 0.
pub fn check_non_negative(name: &'static str, value: f64) -> Result<(), SimError> {
    if !value.is_finite() {
        return Err(bad(name, format!("must be a finite number, got {value}")));
    }
    if value < 0.0 {
        return Err(bad(name, format!("must not be negative, got {value}")));
    }
    Ok(())
}

/// `value` must be finite and > 0.
pub fn check_positive(name: &'static str, value: f64) -> Result<(), SimError> {
    if !(value.is_finite() && value > 0.0) {
        return Err(bad(name, format!("must be a finite number greater than 0, got {value}")));
    }
    Ok(())
}

/// `x` with three significant digits ("0.250", "12.0", "1.23e-5").
pub fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if !(-4..6).contains(&e) {
        return format!("{x:.2e}");
    }
    if e >= 2 {
        let unit = 10f64.powi(e - 2);
        return format!("{:.0}", (x / unit).round() * unit);
    }
    let decimals = (2 - e) as usize;
    format!("{x:.decimals$}")
}
