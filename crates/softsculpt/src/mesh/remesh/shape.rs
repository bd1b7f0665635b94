//! A remesh keeps the shape or says why it cannot.
//!
//! The remesher collapses every edge shorter than 4/5 L and then restores the volume along the
//! normals. On a mesh much coarser than L that is not a remesh but a new shape: a 4 × 4 × 10 cm
//! box of 8 vertices remeshed at its mean edge length (7.0 cm) collapsed to 5 vertices, a squat
//! double pyramid 7.8 cm wide and 7.8 cm tall (having lost 76 % of its volume before the
//! correction blew it up again), with no word said. So every result is measured against its
//! input ([`departure`]: how far each surface lies from the other, both ways, and the volume
//! the remesher lost) and, if it does not keep the shape ([`Departure::keeps_shape`]), the
//! remesh is tried again at L/2 and L/4 ([`TRIES`] edge lengths: at a shorter edge the coarse
//! faces are split instead of collapsed), then at L/4 keeping the edges sharper than [`CREASE`]
//! (a box's edges and corners stay where they are; measured: the box is kept exactly there,
//! while plain L/4 still rounds its corners by 1.2 cm). If no try keeps it (or the next edge
//! would make more than [`super::MAX_TRIANGLES`]), the remesh is refused with one error naming
//! how far the surface would move, and nothing changes. A result kept at the first try is
//! exactly what [`super::remesh`] makes: nothing changes for a mesh that was fine.

use super::{check_edge_length, remesh_measured, Surface};
use crate::error::{sig3, MeshError};
use crate::mesh::TriMesh;
use crate::vec3::{add, get, norm, scale, sub, V3};

/// A result keeps the input's shape if no sampled point of either surface lies farther than
/// `SHAPE` × the input's bounding-box diagonal from the other surface, and ...
///
/// Why 5 % of the size (not a fraction of L): a remesh at L rounds every sharp edge off by one
/// triangle, up to about 0.35 L from it ((L/2)·sin 45° for a right angle), which is the
/// resolution asked for and fine on a model many edges across, but the whole model on one a
/// single edge across. Measured at the mean edge length (tests/remesh.rs): icosphere 0.04 %,
/// kangaroo 1.3 %, mushroom 3.4 % (its cap's rim) — these are kept as they were; the octopus
/// 29 % (its thin tentacles collapse; kept at L/4, 4.7 %), the 8-vertex box 39 % (at L/2 still
/// 21 %, 7.2 cm wide instead of 4). 5 % is a change one sees only side by side.
pub const SHAPE: f64 = 0.05;
/// ... the remesher changed the volume by at most `VOLUME` (relative) before its correction.
/// Its correction moves every vertex along its normal to restore the volume, so a large loss is
/// a shape inflated back, not kept. Measured at the mean edge length: icosphere −0.2 %,
/// kangaroo −1.3 %, mushroom −3.5 %, octopus −10 %, box −76 %; a 1 m rod 2 cm thick −98 %
/// (collapsed to a line: the distance alone, 4 mm, would not tell).
pub const VOLUME: f64 = 0.05;
/// Edge lengths tried: L, L/2, L/4; then L/4 once more keeping creases sharper than [`CREASE`]
/// (if no crease angle was asked for).
pub const TRIES: usize = 3;
/// The crease angle (degrees) of the last try: a box's 90° edges are kept, a smooth model's
/// facets (the icosphere's 12°–20°, the kangaroo's) are not.
pub const CREASE: f64 = 60.0;

/// How far a remeshed surface departs from its input.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Departure {
    /// The largest distance from an input vertex or face centroid to the result's surface (m).
    pub input_to_result: f64,
    /// The largest distance from a result vertex or face centroid to the input's surface (m).
    pub result_to_input: f64,
    /// The remesher's relative volume change before its volume correction (V_raw/V₀ − 1; 0 for
    /// an open mesh, which has no volume to keep).
    pub volume_change: f64,
}

impl Departure {
    /// The larger of the two one-sided distances: a Hausdorff distance sampled at vertices and
    /// face centroids (m).
    pub fn distance(&self) -> f64 {
        self.input_to_result.max(self.result_to_input)
    }

    /// Whether the result keeps the shape of an input of bounding-box diagonal `size` (m): see
    /// [`SHAPE`] and [`VOLUME`].
    pub fn keeps_shape(&self, size: f64) -> bool {
        self.distance() <= SHAPE * size && self.volume_change.abs() <= VOLUME
    }
}

/// A remesh that kept the shape: the mesh and how it was made.
#[derive(Debug, Clone)]
pub struct Remeshed {
    pub mesh: TriMesh,
    pub report: RemeshReport,
}

/// How a remesh that kept the shape was made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RemeshReport {
    /// The edge length asked for (m).
    pub requested: f64,
    /// The edge length the result was made at (m): `requested`, or a half or a quarter of it.
    pub edge: f64,
    /// The crease angle used (degrees): the one asked for, or [`CREASE`] if only the last try,
    /// keeping the creases, kept the shape.
    pub crease_deg: Option<f64>,
    /// How many tries it took (1: the edge asked for, as asked).
    pub tries: usize,
    /// The result's departure from the input.
    pub departure: Departure,
}

impl RemeshReport {
    /// Whether the shape could be kept only at a shorter edge or by keeping creases.
    pub fn shortened(&self) -> bool {
        self.tries > 1
    }
}

/// How far `result` departs from `input` (see [`Departure`]); `raw_volume` is the result's
/// volume before any volume correction (`result.volume()` if there was none).
pub fn departure(input: &TriMesh, result: &TriMesh, raw_volume: f64) -> Departure {
    let one_way = |from: &TriMesh, to: &TriMesh| -> f64 {
        if to.triangles.is_empty() {
            return f64::INFINITY;
        }
        let surface = Surface::new(&to.positions, &to.triangles);
        // A sample the search cannot place (no triangle found, or NaN) counts as infinitely far:
        // a result the check cannot measure does not keep the shape.
        samples(from).map(|p| surface.distance(p)).fold(0.0, |a, d| if d.is_nan() { f64::INFINITY } else { a.max(d) })
    };
    let v0 = input.volume();
    let closed = input.edge_counts().boundary == 0;
    Departure {
        input_to_result: one_way(input, result),
        result_to_input: one_way(result, input),
        volume_change: if closed && v0 != 0.0 { raw_volume / v0 - 1.0 } else { 0.0 },
    }
}

/// A mesh's vertices and its faces' centroids.
fn samples(m: &TriMesh) -> impl Iterator<Item = V3> + '_ {
    let vertices = (0..m.vertex_count()).map(|i| get(&m.positions, i));
    let centroids = m.triangles.iter().map(|t| {
        let p = |i: u32| get(&m.positions, i as usize);
        scale(add(add(p(t[0]), p(t[1])), p(t[2])), 1.0 / 3.0)
    });
    vertices.chain(centroids)
}

/// [`super::remesh`] that keeps the shape: remesh at `edge`; if the result does not keep the
/// shape ([`Departure::keeps_shape`]), try again at half the edge, up to [`TRIES`] edge lengths,
/// then (without `crease_deg`) at the shortest keeping creases sharper than [`CREASE`]; refuse if
/// none keeps it. A result kept at the first try is exactly `remesh(mesh, edge, crease_deg)`.
pub fn remesh_keeping_shape(mesh: &TriMesh, edge: f64, crease_deg: Option<f64>) -> Result<Remeshed, MeshError> {
    // (The edge asked for is checked by the first try's remesh: `check_edge_length`.)
    let (lo, hi) = mesh.bounds();
    let size = norm(sub(hi, lo));
    let mut plan: Vec<(f64, Option<f64>)> = (0..TRIES).map(|k| (edge * 0.5f64.powi(k as i32), crease_deg)).collect();
    if crease_deg.is_none() {
        plan.push((plan[TRIES - 1].0, Some(CREASE)));
    }
    // Every try that did not keep the shape: (edge, departure).
    let mut missed: Vec<(f64, Departure)> = Vec::new();
    let mut stopped = String::new();
    for (k, &(at, crease)) in plan.iter().enumerate() {
        if k > 0 {
            if let Err(e) = check_edge_length(mesh, at) {
                stopped = format!(" (a shorter edge is refused: {e})");
                break;
            }
        }
        let (out, raw_volume) = remesh_measured(mesh, at, crease)?;
        let d = departure(mesh, &out, raw_volume);
        if d.keeps_shape(size) {
            return Ok(Remeshed { mesh: out, report: RemeshReport { requested: edge, edge: at, crease_deg: crease, tries: k + 1, departure: d } });
        }
        missed.push((at, d));
    }
    Err(refusal(size, &missed, &stopped))
}

/// The one error of a remesh that no try kept: how far the surface would move at the edge asked
/// for, and at the shortest tried.
fn refusal(size: f64, missed: &[(f64, Departure)], stopped: &str) -> MeshError {
    let says = |d: &Departure| {
        let volume = if d.volume_change.abs() > VOLUME { format!(", {:+.0} % of its volume before the remesher's correction", 100.0 * d.volume_change) } else { String::new() };
        format!("{} m ({:.0} % of the model's size{volume})", sig3(d.distance()), 100.0 * d.distance() / size)
    };
    let (edge, first) = missed[0];
    let shortest = match missed.last() {
        Some((e, d)) if missed.len() > 1 => format!("; at {} m, the last try, still {}", sig3(*e), says(d)),
        _ => String::new(),
    };
    MeshError::Invalid(format!(
        "remeshing at edge length {} m would change the shape: the surface would move by up to {}{shortest}{stopped}; a remesh may move it by at most {:.0} % of the model's size and change its volume by at most {:.0} %. The mesh is too coarse for remeshing: Subdivide it first, or remesh at a shorter edge",
        sig3(edge),
        says(&first),
        100.0 * SHAPE,
        100.0 * VOLUME,
    ))
}
