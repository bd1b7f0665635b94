//! The pillow: two copies of a quality triangulation of the outline, stitched along it.
//!
//! The outline is triangulated by a constrained Delaunay triangulation refined (Ruppert/Chew, as
//! `spade` implements it) to angles of at least [`MIN_ANGLE_DEG`] and areas of at most an
//! equilateral triangle of side L. The top copy keeps the winding (normals +z), the bottom one
//! is reversed (normals −z); the outline's vertices are shared, so the result is closed. Each
//! inner vertex is lifted to z = ±[`LIFT`] · √(d (2 d_max − d)), d its distance to the outline
//! (d_max the largest): a circle's outline so becomes a sphere flattened to LIFT of its height,
//! so the body starts with a volume for its gas and the skin has the material it inflates into.

use super::outline::dist;
use crate::error::MeshError;
use crate::mesh::TriMesh;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

/// Smallest angle the refinement aims for (degrees; Ruppert's algorithm terminates below ~20.7°
/// in theory; spade's off-centre refinement reaches 30° in practice, bounded by a vertex limit).
pub const MIN_ANGLE_DEG: f64 = 28.0;
/// Initial half-thickness as a fraction of a circle's (see the module's notes). Flatter starts
/// (0.5) are pulled thicker by the gas, drawing the rim in (silhouettes 4.5 % small, measured on
/// a star and a crescent); rounder ones (1.0) stretch outward (+7 %); 0.8 stays within 2 %.
pub const LIFT: f64 = 0.8;

/// The pillow of a closed polygon (counter-clockwise, points at about spacing `edge`).
pub fn pillow(boundary: &[[f64; 2]], edge: f64) -> Result<TriMesh, MeshError> {
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
    let mut handles = Vec::with_capacity(boundary.len());
    for p in boundary {
        let h = cdt.insert(Point2::new(p[0], p[1])).map_err(|e| MeshError::Invalid(format!("cannot triangulate the outline: {e:?}")))?;
        handles.push(h);
    }
    for i in 0..handles.len() {
        let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
        if a != b && !cdt.can_add_constraint(a, b) {
            return Err(MeshError::Invalid("the outline crosses itself (found while triangulating)".into()));
        }
        cdt.add_constraint(a, b);
    }
    let max_area = 3f64.sqrt() / 4.0 * edge * edge;
    let params = RefinementParameters::<f64>::new()
        .exclude_outer_faces(true)
        .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE_DEG))
        .with_max_allowed_area(max_area)
        .with_min_required_area(1e-3 * max_area);
    let result = cdt.refine(params);
    let excluded: std::collections::HashSet<_> = result.excluded_faces.into_iter().collect();

    // Vertices: index in the CDT → 2D point; on the outline if on a constraint edge.
    let n = cdt.num_vertices();
    let mut xy = vec![[0.0; 2]; n];
    for v in cdt.vertices() {
        let p = v.position();
        xy[v.fix().index()] = [p.x, p.y];
    }
    let mut on_border = vec![false; n];
    for e in cdt.undirected_edges() {
        if e.is_constraint_edge() {
            for v in e.vertices() {
                on_border[v.fix().index()] = true;
            }
        }
    }
    let mut tris2: Vec<[usize; 3]> = Vec::new();
    for f in cdt.inner_faces() {
        if excluded.contains(&f.fix()) {
            continue;
        }
        let v = f.vertices();
        tris2.push([v[0].fix().index(), v[1].fix().index(), v[2].fix().index()]);
    }
    if tris2.is_empty() {
        return Err(MeshError::Invalid("the outline has no inside to triangulate".into()));
    }
    split_chords(&mut tris2, &mut xy, &mut on_border);
    let n = xy.len();

    // Distance of each vertex to the outline (the refined border: constraint edges).
    let border_edges: Vec<[usize; 2]> = cdt.undirected_edges().filter(|e| e.is_constraint_edge()).map(|e| { let v = e.vertices(); [v[0].fix().index(), v[1].fix().index()] }).collect();
    let d: Vec<f64> = (0..n).map(|i| if on_border[i] { 0.0 } else { border_edges.iter().map(|e| segment_distance(xy[i], xy[e[0]], xy[e[1]])).fold(f64::INFINITY, f64::min) }).collect();
    let dmax = d.iter().copied().fold(0.0, f64::max);

    // Top copy: every used vertex; bottom copy: the inner ones again.
    let mut used = vec![false; n];
    for t in &tris2 {
        for &v in t {
            used[v] = true;
        }
    }
    let mut top = vec![u32::MAX; n];
    let mut bottom = vec![u32::MAX; n];
    let mut positions = Vec::new();
    for i in 0..n {
        if used[i] {
            top[i] = (positions.len() / 3) as u32;
            let z = LIFT * (d[i] * (2.0 * dmax - d[i])).max(0.0).sqrt();
            positions.extend_from_slice(&[xy[i][0], xy[i][1], z]);
        }
    }
    for i in 0..n {
        if used[i] {
            bottom[i] = if on_border[i] {
                top[i]
            } else {
                let k = (positions.len() / 3) as u32;
                positions.extend_from_slice(&[xy[i][0], xy[i][1], -positions[3 * top[i] as usize + 2]]);
                k
            };
        }
    }
    let mut triangles = Vec::with_capacity(2 * tris2.len());
    for t in &tris2 {
        // spade's faces are counter-clockwise in the plane: normal +z.
        triangles.push([top[t[0]], top[t[1]], top[t[2]]]);
        triangles.push([bottom[t[0]], bottom[t[2]], bottom[t[1]]]);
    }
    let mesh = TriMesh { positions, triangles };
    if !mesh.is_closed() {
        let c = mesh.edge_counts();
        return Err(MeshError::Invalid(format!("the pillow is not closed ({} open, {} non-manifold edges): is the outline a simple polygon?", c.boundary, c.non_manifold)));
    }
    Ok(mesh)
}

/// An inner edge between two outline vertices (a chord) would join the two copies in four faces:
/// split each at its midpoint (an inner vertex), its two triangles into four.
fn split_chords(tris: &mut Vec<[usize; 3]>, xy: &mut Vec<[f64; 2]>, on_border: &mut Vec<bool>) {
    let key = |a: usize, b: usize| (a.min(b), a.max(b));
    let mut count: std::collections::HashMap<(usize, usize), usize> = std::collections::HashMap::new();
    for t in tris.iter() {
        for k in 0..3 {
            *count.entry(key(t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    let mut chords: Vec<(usize, usize)> = count.into_iter().filter(|&((a, b), c)| c == 2 && on_border[a] && on_border[b]).map(|(e, _)| e).collect();
    chords.sort_unstable(); // the same mesh every run
    for (a, b) in chords {
        let m = xy.len();
        xy.push([0.5 * (xy[a][0] + xy[b][0]), 0.5 * (xy[a][1] + xy[b][1])]);
        on_border.push(false);
        let mut added = Vec::new();
        for t in tris.iter_mut() {
            if t.contains(&a) && t.contains(&b) {
                // Replace one corner at a time, in place: the winding stays.
                added.push(t.map(|v| if v == a { m } else { v }));
                *t = t.map(|v| if v == b { m } else { v });
            }
        }
        tris.extend(added);
    }
}

fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (ab, ap) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if l2 > 0.0 { ((ap[0] * ab[0] + ap[1] * ab[1]) / l2).clamp(0.0, 1.0) } else { 0.0 };
    dist(p, [a[0] + t * ab[0], a[1] + t * ab[1]])
}
