//! Sketch a silhouette, get a balloon (as in Teddy, Igarashi et al. 1999, but inflated by the
//! engine's own gas): a closed outline in the xy plane becomes a pillow ([`pillow`]) that the
//! gas inflates to rest.
//!
//! Edge length: given, or L = √(A / [`CELLS`]) from the outline's area A, so a sketch of any size
//! has about the same number of triangles (each side ≈ CELLS / (√3/4) ≈ 350 triangles).
//!
//! Inflation: the pillow is a body with the modeler's material (the `modeler` preset: springs
//! and bending springs at rest in the pillow's shape, damping, implicit steps of 1/60 s), no
//! gravity and no ground, filled with gas nRT (J) and stepped until it is at rest (largest
//! speed below [`REST_SPEED`] for [`REST_STEPS`] steps) or [`MAX_STEPS`] steps have passed.
//! Default gas: the amount whose pressure on the pillow stretches its skin by about
//! [`DEFAULT_STRAIN`]: a membrane of spring stiffness k has a tension T ≈ (√3/2)·k·ε per unit
//! length (an equilateral spring network), and a bulge of radius r holds P = 2T/r (Laplace); so
//! nRT = P·V with r the outline's inradius-like d_max and V the pillow's volume.

pub mod outline;
pub mod pillow;

pub use outline::Outline;

use crate::error::MeshError;
use crate::mesh::TriMesh;
use crate::{SoftBody, World};

/// Triangles per side ∝ CELLS: L = √(A / CELLS).
pub const CELLS: f64 = 150.0;
/// Default stretch of the skin by the gas (fraction).
pub const DEFAULT_STRAIN: f64 = 0.02;
/// At rest: every vertex slower than this (m/s) ...
pub const REST_SPEED: f64 = 1e-4;
/// ... for this many steps in a row.
pub const REST_STEPS: u32 = 30;
/// Most steps of inflation (20 s at 1/60 s).
pub const MAX_STEPS: u32 = 1200;

/// What a sketch made.
#[derive(Debug, Clone)]
pub struct Sketched {
    /// The inflated body at rest (closed, outward).
    pub mesh: TriMesh,
    /// The flat pillow it was inflated from.
    pub pillow: TriMesh,
    /// Edge length used (m), gas used (J), steps taken, and whether it came to rest.
    pub edge: f64,
    pub nrt: f64,
    pub steps: u32,
    pub at_rest: bool,
}

/// The default edge length for an outline (m).
pub fn default_edge(outline: &Outline) -> f64 {
    (outline.area() / CELLS).sqrt()
}

/// The pillow of an outline at edge length `edge` (m): checked, resampled, triangulated.
pub fn build_pillow(outline: &Outline, edge: f64) -> Result<TriMesh, MeshError> {
    if !(edge.is_finite() && edge > 0.0) {
        return Err(MeshError::Invalid(format!("edge length must be a positive number of metres, got {edge}")));
    }
    let size = outline.perimeter();
    if edge > 0.25 * size {
        return Err(MeshError::Invalid(format!("edge length {edge} m is too long for an outline of perimeter {size:.4} m (at most a quarter of it)")));
    }
    let estimate = 2.0 * outline.area() / (3f64.sqrt() / 4.0 * edge * edge);
    if estimate > crate::mesh::remesh::MAX_TRIANGLES {
        return Err(MeshError::Invalid(format!("edge length {edge} m would make about {:.1} M triangles: use a longer edge", estimate / 1e6)));
    }
    // Resampling drops close points; if that made the polygon cross itself, keep every point.
    let resampled = Outline::new(&outline.resampled(edge)).map(|o| o.points).unwrap_or_else(|_| outline.points.clone());
    let flat = pillow::pillow(&resampled, edge)?;
    // Lifting stretches the triangles near the rim (the profile is steep there): remeshed at
    // the same edge length, the skin is regular everywhere (see mesh::remesh).
    crate::mesh::remesh::remesh(&flat, edge, None)
}

/// Sketch: the pillow of `outline`, inflated to rest by gas `nrt` (J; `None`: the default).
pub fn sketch(outline: &Outline, edge: Option<f64>, nrt: Option<f64>) -> Result<Sketched, MeshError> {
    let edge = edge.unwrap_or_else(|| default_edge(outline));
    let pillow = build_pillow(outline, edge)?;
    let bad = |e: String| MeshError::Invalid(e);
    let body = SoftBody::new(&pillow, crate::params::table::MASS.number(), Default::default()).map_err(|e| bad(e.to_string()))?;
    let mut world = World::single(body, Default::default());
    world.apply_preset(0, "modeler").map_err(|e| bad(e.to_string()))?;
    world.set_param(0, "gravity", crate::params::Value::Number(0.0)).map_err(|e| bad(e.to_string()))?;
    world.set_param(0, "ground", crate::params::Value::Flag(false)).map_err(|e| bad(e.to_string()))?;
    // The flat pillow is a construction, not a rest shape to bend back to: hinges at rest in it
    // would hold its creased rim against the gas. The balloon gets them at its own shape when
    // the modeler loads it (its frozen shape).
    world.set_param(0, "rigidity", crate::params::Value::Number(0.0)).map_err(|e| bad(e.to_string()))?;
    let nrt = match nrt {
        Some(v) if v.is_finite() && v > 0.0 => v,
        Some(v) => return Err(bad(format!("gas nRT must be a positive number of joules, got {v}"))),
        None => default_nrt(&pillow, world.bodies[0].material.stiffness),
    };
    world.set_param(0, "gas.nrt", crate::params::Value::Number(nrt)).map_err(|e| bad(e.to_string()))?;
    let (mut steps, mut calm) = (0u32, 0u32);
    while steps < MAX_STEPS && calm < REST_STEPS {
        world.step().map_err(|e| bad(format!("inflating the pillow: {e}")))?;
        steps += 1;
        calm = if world.bodies[0].max_speed() < REST_SPEED { calm + 1 } else { 0 };
    }
    let mesh = world.bodies[0].to_mesh();
    Ok(Sketched { mesh, pillow, edge, nrt, steps, at_rest: calm >= REST_STEPS })
}

/// The default gas (J): see the module's notes. d_max from the pillow's thickness: its half
/// height is LIFT·d_max.
pub fn default_nrt(pillow: &TriMesh, stiffness: f64) -> f64 {
    let (lo, hi) = pillow.bounds();
    let dmax = 0.5 * (hi[2] - lo[2]) / pillow::LIFT;
    let tension = 3f64.sqrt() / 2.0 * stiffness * DEFAULT_STRAIN;
    2.0 * tension / dmax * pillow.volume()
}

/// The inflated body of an outline given as flat `x y` pairs (m): what the modeler's sketch tool
/// calls. `edge` ≤ 0 takes the default edge length; the default gas.
pub fn sketch_points(xy: &[f64], edge: f64) -> Result<TriMesh, MeshError> {
    let points: Vec<[f64; 2]> = xy.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    if points.iter().flatten().any(|v| !v.is_finite()) {
        return Err(MeshError::Invalid("the outline has non-finite coordinates".into()));
    }
    Ok(sketch(&Outline::new(&points)?, (edge > 0.0).then_some(edge), None)?.mesh)
}
