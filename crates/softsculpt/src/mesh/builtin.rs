//! Built-in models, defined once here and used by the CLI (`builtin:NAME`), tests, benches and
//! the web modeler. All are closed, manifold and wound outward (checked by tests).

use super::TriMesh;
use crate::error::MeshError;
use crate::vec3::{add, normalize, scale, sub, V3};
use std::collections::HashMap;
use std::f64::consts::PI;

/// Names accepted by [`builtin`] (listed in `error.rs`, whose message for an unknown name lists
/// them too).
pub const NAMES: &[&str] = crate::error::BUILTIN_NAMES;

/// A built-in model by name.
pub fn builtin(name: &str) -> Result<TriMesh, MeshError> {
    match name {
        "sphere" => Ok(icosphere(3, 1.0)),
        "mushroom" => Ok(mushroom()),
        "octopus" => Ok(octopus()),
        "kangaroo" => kangaroo(),
        _ => Err(MeshError::UnknownBuiltin(name.to_string())),
    }
}

/// Icosphere of `radius` (m): the regular icosahedron refined `level` times by edge midpoints
/// pushed to the sphere. `10·4^level + 2` vertices. The vertex and face order is exactly that of
/// `shared/bench/gen_icosphere.py` (the reference workload), so results compare bit for bit.
pub fn icosphere(level: u32, radius: f64) -> TriMesh {
    let t = (1.0 + 5.0f64.sqrt()) / 2.0;
    let raw: [V3; 12] = [
        [-1.0, t, 0.0], [1.0, t, 0.0], [-1.0, -t, 0.0], [1.0, -t, 0.0],
        [0.0, -1.0, t], [0.0, 1.0, t], [0.0, -1.0, -t], [0.0, 1.0, -t],
        [t, 0.0, -1.0], [t, 0.0, 1.0], [-t, 0.0, -1.0], [-t, 0.0, 1.0],
    ];
    let mut verts: Vec<V3> = raw.iter().map(|&v| unit(v)).collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
        [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
        [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
        [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ];
    for _ in 0..level {
        let mut cache: HashMap<(u32, u32), u32> = HashMap::with_capacity(faces.len() * 2);
        let mut out = Vec::with_capacity(faces.len() * 4);
        let mut mid = |a: u32, b: u32, verts: &mut Vec<V3>| -> u32 {
            let key = if a < b { (a, b) } else { (b, a) };
            *cache.entry(key).or_insert_with(|| {
                let (pa, pb) = (verts[a as usize], verts[b as usize]);
                verts.push(unit([(pa[0] + pb[0]) * 0.5, (pa[1] + pb[1]) * 0.5, (pa[2] + pb[2]) * 0.5]));
                (verts.len() - 1) as u32
            })
        };
        for &[a, b, c] in &faces {
            let ab = mid(a, b, &mut verts);
            let bc = mid(b, c, &mut verts);
            let ca = mid(c, a, &mut verts);
            out.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = out;
    }
    TriMesh { positions: verts.iter().flat_map(|v| scale(*v, radius)).collect(), triangles: faces }
}

/// Same arithmetic as the Python reference: divide by the norm (not multiply by its inverse).
fn unit(v: V3) -> V3 {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

/// A closed surface of revolution about +y: `profile` lists (radius, height) from the bottom pole
/// to the top pole (poles excluded), `segments` around.
fn revolve(bottom: f64, profile: &[(f64, f64)], top: f64, segments: u32) -> TriMesh {
    let mut p = vec![0.0, bottom, 0.0];
    for &(r, y) in profile {
        for s in 0..segments {
            let a = 2.0 * PI * s as f64 / segments as f64;
            p.extend_from_slice(&[r * a.cos(), y, -r * a.sin()]);
        }
    }
    p.extend_from_slice(&[0.0, top, 0.0]);
    let ring = |k: usize, s: u32| 1 + k as u32 * segments + s % segments;
    let top_index = (p.len() / 3 - 1) as u32;
    let mut t = Vec::new();
    for s in 0..segments {
        t.push([0, ring(0, s + 1), ring(0, s)]);
    }
    for k in 0..profile.len() - 1 {
        for s in 0..segments {
            let (a, b, c, d) = (ring(k, s), ring(k, s + 1), ring(k + 1, s + 1), ring(k + 1, s));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    let last = profile.len() - 1;
    for s in 0..segments {
        t.push([top_index, ring(last, s), ring(last, s + 1)]);
    }
    let mut m = TriMesh { positions: p, triangles: t };
    orient(&mut m);
    m
}

/// Flip every face if the (closed) mesh has negative volume.
fn orient(m: &mut TriMesh) {
    if m.volume() < 0.0 {
        for t in &mut m.triangles {
            t.swap(1, 2);
        }
    }
}

/// The paper's Fig. 2 mushroom: a stem (radius ~0.25 m, 0.8 m tall) under a domed cap (radius
/// 1 m), as one closed surface of revolution with 24 segments, standing on a flat foot at
/// y = 0. 362 vertices.
pub fn mushroom() -> TriMesh {
    let mut profile = vec![(0.30, 0.0), (0.31, 0.06), (0.27, 0.25), (0.25, 0.45), (0.26, 0.65), (0.30, 0.80)];
    // Underside of the cap, flaring out to the rim.
    profile.extend_from_slice(&[(0.50, 0.88), (0.75, 0.92), (0.95, 0.95), (1.05, 1.02)]);
    // The dome, from the rim to near the top.
    for k in 1..6 {
        let a = (k as f64) / 6.0 * (PI / 2.0);
        profile.push((1.05 * a.cos(), 1.02 + 0.65 * a.sin()));
    }
    revolve(0.0, &profile, 1.70, 24)
}

/// The paper's Fig. 7 kangaroo (its 316 vertices, 628 faces; ours 321 and 638), seen from
/// its left side facing +x, standing on its hind foot and tail: made with our own sketch tool
/// from the outline `data/kangaroo_outline.txt` by
/// `softsculpt sketch crates/softsculpt/src/mesh/data/kangaroo_outline.txt --edge 0.12 --out crates/softsculpt/src/mesh/data/kangaroo.obj`
/// (the default gas, inflated to rest), stored as that OBJ file.
pub fn kangaroo() -> Result<TriMesh, MeshError> {
    Ok(super::load_obj(include_bytes!("data/kangaroo.obj"))?.mesh)
}

/// The paper's Fig. 6 octopus: a round head with eight tapering tentacles, about 300 vertices.
/// Built as a UV-sphere head whose eight lower quads (every other one around a ring) are extruded
/// into square tubes that curl outward and down, each closed by a tip vertex.
pub fn octopus() -> TriMesh {
    const SEG: u32 = 16; // around the head
    const RINGS: u32 = 9; // latitude rings between the poles
    const R: f64 = 0.6; // head radius (m)
    let centre = [0.0, 1.0, 0.0];
    let mut p: Vec<V3> = vec![add(centre, [0.0, -R, 0.0])];
    for k in 1..=RINGS {
        let phi = PI * (1.0 - k as f64 / (RINGS + 1) as f64); // from bottom (π) to top (0)
        for s in 0..SEG {
            let a = 2.0 * PI * s as f64 / SEG as f64;
            let (r, y) = (R * phi.sin(), R * phi.cos());
            // A slightly taller, mantle-like head.
            let y = if y > 0.0 { y * 1.3 } else { y };
            p.push(add(centre, [r * a.cos(), y, -r * a.sin()]));
        }
    }
    p.push(add(centre, [0.0, 1.3 * R, 0.0]));
    let ring = |k: u32, s: u32| 1 + k * SEG + s % SEG;
    let top = (p.len() - 1) as u32;
    let mut t: Vec<[u32; 3]> = Vec::new();
    for s in 0..SEG {
        t.push([0, ring(0, s), ring(0, s + 1)]);
        t.push([top, ring(RINGS - 1, s + 1), ring(RINGS - 1, s)]);
    }
    // Quads between ring 1 and ring 2 (just below the equator of the lower half) at even s
    // become tentacles.
    const ARM_RING: u32 = 1;
    let mut arm_quads = Vec::new();
    for k in 0..RINGS - 1 {
        for s in 0..SEG {
            let q = [ring(k, s), ring(k, s + 1), ring(k + 1, s + 1), ring(k + 1, s)];
            if k == ARM_RING && s % 2 == 0 {
                arm_quads.push(q);
            } else {
                t.push([q[0], q[2], q[1]]);
                t.push([q[0], q[3], q[2]]);
            }
        }
    }
    const SECTIONS: usize = 5; // rings per tentacle
    for q in arm_quads {
        let corners: Vec<V3> = q.iter().map(|&i| p[i as usize]).collect();
        let base = scale(add(add(corners[0], corners[1]), add(corners[2], corners[3])), 0.25);
        let outward = normalize([base[0], 0.0, base[2]]);
        let mut prev = q;
        let mut centre_pt = base;
        for j in 1..=SECTIONS {
            let s = j as f64 / SECTIONS as f64;
            // Out, then down: the tentacle curls toward the ground.
            let dir = normalize(add(scale(outward, 0.9 * (1.0 - s) + 0.25), [0.0, -1.0, 0.0]));
            centre_pt = add(centre_pt, scale(dir, 0.22));
            let taper = 1.0 - 0.7 * s;
            let mut next = [0u32; 4];
            for c in 0..4 {
                let off = scale(sub(corners[c], base), taper);
                p.push(add(centre_pt, off));
                next[c] = (p.len() - 1) as u32;
            }
            for c in 0..4 {
                let (a, b) = (prev[c], prev[(c + 1) % 4]);
                let (a2, b2) = (next[c], next[(c + 1) % 4]);
                t.push([a, b2, b]);
                t.push([a, a2, b2]);
            }
            prev = next;
        }
        let tip_dir = normalize(add(scale(outward, 0.25), [0.0, -1.0, 0.0]));
        p.push(add(centre_pt, scale(tip_dir, 0.12)));
        let tip = (p.len() - 1) as u32;
        for c in 0..4 {
            t.push([tip, prev[(c + 1) % 4], prev[c]]);
        }
    }
    let mut m = TriMesh { positions: p.iter().flatten().copied().collect(), triangles: t };
    orient(&mut m);
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_is_closed_manifold_consistent_and_outward() {
        for name in NAMES {
            let m = builtin(name).unwrap();
            let c = m.edge_counts();
            assert_eq!((c.boundary, c.non_manifold, c.inconsistent), (0, 0, 0), "{name}: {c:?}");
            assert!(m.volume() > 0.0, "{name}");
            // Euler characteristic of a sphere-like surface: V − E + F = 2.
            assert_eq!(m.vertex_count() as i64 - c.edges as i64 + m.triangles.len() as i64, 2, "{name}");
        }
    }

    #[test]
    fn icosphere_counts_match_the_reference_workload() {
        for level in 0..5 {
            let m = icosphere(level, 1.0);
            assert_eq!(m.vertex_count(), 10 * 4usize.pow(level) + 2);
            assert_eq!(m.triangles.len(), 20 * 4usize.pow(level));
        }
    }

    #[test]
    fn the_kangaroo_is_about_the_papers_size() {
        let m = kangaroo().unwrap();
        assert!((300..=330).contains(&m.vertex_count()) && (600..=660).contains(&m.triangles.len()), "{} {}", m.vertex_count(), m.triangles.len());
    }

    #[test]
    fn octopus_has_about_three_hundred_vertices() {
        let n = octopus().vertex_count();
        assert!((250..=350).contains(&n), "{n}");
    }
}
