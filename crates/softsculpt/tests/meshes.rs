//! Loading meshes: welding, checks, volume modes, and errors.

mod common;
use common::*;
use softsculpt::body::{Material, SoftBody, VolumeMode};
use softsculpt::world::WorldSettings;
use softsculpt::error::MeshError;
use softsculpt::mesh::{builtin::icosphere, load_obj};
use std::f64::consts::PI;

/// A UV sphere as exporters write it: a seam column of duplicated vertices (u = 0 and u = 1)
/// and a duplicated pole vertex per segment. Unwelded, it is open along the seam.
fn seamed_uv_sphere(segments: usize, rings: usize) -> String {
    let mut s = String::new();
    let index = |r: usize, k: usize| 1 + r * (segments + 1) + k;
    for r in 0..=rings {
        let phi = PI * r as f64 / rings as f64;
        for k in 0..=segments {
            let th = 2.0 * PI * k as f64 / segments as f64;
            // k = segments repeats k = 0 up to rounding: sin(2π) is not exactly 0.
            s += &format!("v {} {} {}\n", phi.sin() * th.cos(), phi.cos(), phi.sin() * th.sin());
        }
    }
    for r in 0..rings {
        for k in 0..segments {
            let (a, b, c, d) = (index(r, k), index(r, k + 1), index(r + 1, k + 1), index(r + 1, k));
            s += &format!("f {a} {b} {c} {d}\n");
        }
    }
    s
}

#[test]
fn welding_heals_a_seamed_sphere_so_it_holds_gas() {
    let (seg, rings) = (16, 8);
    let loaded = load_obj(seamed_uv_sphere(seg, rings).as_bytes()).unwrap();
    let r = &loaded.report;
    // Duplicates: the seam column (rings − 1 interior rows) and, at each pole, segments + 1
    // copies of one point (segments welded each).
    assert_eq!(r.welded, (rings - 1) + 2 * seg, "{r:?}");
    assert_eq!((r.edges.boundary, r.edges.non_manifold), (0, 0));
    assert!(loaded.mesh.is_closed());
    // Pole quads collapse to triangles: their repeated vertex makes one of the two fan
    // triangles degenerate.
    assert_eq!(r.degenerate_faces, 2 * seg);
    // The faces were wound inward in the file; loading turned them outward.
    assert!(loaded.mesh.volume() > 0.0);
    // It now holds gas: inflating it keeps it closed and finite.
    let mut p = Material { spring_damping: 0.5, damping: 1.0, ..bare() };
    p.set_nrt(2.0);
    let mut w = alone(SoftBody::new(&loaded.mesh, 1.0, p).unwrap(), still());
    let v0 = w.bodies[0].exact_volume();
    run(&mut w, 1e-4, 5000);
    let body = &w.bodies[0];
    assert!(body.is_finite() && body.exact_volume() > v0);
    // Written back in the source's layout: same vertex count and polygons.
    let text = loaded.write_obj(body.positions(), "test");
    let back = softsculpt::mesh::obj::parse(&text).unwrap();
    assert_eq!(back.vertex_count(), (rings + 1) * (seg + 1));
    assert_eq!(back.arities, loaded.source.arities);
}

#[test]
fn an_open_mesh_is_refused_with_gas_and_accepted_without() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n"; // a tetrahedron missing a face
    let loaded = load_obj(text.as_bytes()).unwrap();
    assert_eq!(loaded.report.edges.boundary, 3);
    let mut p = bare();
    p.set_nrt(1.0);
    let err = SoftBody::new(&loaded.mesh, 1.0, p).unwrap_err().to_string();
    assert!(err.contains("3 boundary (open) edges"), "{err}");
    assert!(SoftBody::new(&loaded.mesh, 1.0, bare()).is_ok());
}

#[test]
fn non_manifold_edges_are_reported_and_refused_with_gas() {
    // Two tetrahedra sharing an edge through three faces on it: a fin makes it non-manifold.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 2 5\n";
    let loaded = load_obj(text.as_bytes()).unwrap();
    assert!(loaded.report.edges.non_manifold >= 1);
    let mut p = bare();
    p.set_nrt(1.0);
    let err = SoftBody::new(&loaded.mesh, 1.0, p).unwrap_err();
    assert!(matches!(err, softsculpt::body::BodyError::Mesh(MeshError::NotClosed { .. })));
}

#[test]
fn inconsistent_faces_are_reoriented_outward() {
    let text = String::from_utf8(icosphere(1, 1.0).to_obj("x")).unwrap();
    // Flip the first face's winding in the text.
    let text: String = text
        .lines()
        .scan(false, |flipped, line| {
            let mut out = line.to_string();
            if line.starts_with("f ") && !*flipped {
                let w: Vec<&str> = line.split_whitespace().collect();
                out = format!("f {} {} {}", w[1], w[3], w[2]);
                *flipped = true;
            }
            Some(out + "\n")
        })
        .collect();
    let loaded = load_obj(text.as_bytes()).unwrap();
    assert_eq!(loaded.report.flipped_faces, 1);
    assert_eq!(loaded.mesh.edge_counts().inconsistent, 0);
    assert!((loaded.mesh.volume() - icosphere(1, 1.0).volume()).abs() < 1e-12);
}

#[test]
fn box_and_sphere_modes_report_the_bounding_volumes() {
    let mesh = icosphere(3, 1.0);
    let (lo, hi) = mesh.bounds();
    let boxed = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    let mut w = alone(SoftBody::new(&mesh, 1.0, Material { volume_mode: VolumeMode::Box, ..bare() }).unwrap(), still());
    assert_eq!(w.bodies[0].volume(), boxed);
    assert_eq!(w.stats(0).volume, boxed);
    let body = &mut w.bodies[0];
    body.material.volume_mode = VolumeMode::Sphere;
    // Every vertex is at distance 1 from the centroid (0 up to rounding): 4/3 π.
    assert!((body.volume() - 4.0 / 3.0 * PI).abs() < 1e-12);
    body.material.volume_mode = VolumeMode::Exact;
    assert!(body.volume() < 4.0 / 3.0 * PI && body.volume() > 0.98 * 4.0 / 3.0 * PI);
}

#[test]
fn an_explosion_is_reported_with_its_step() {
    let mut p = Material { stiffness: 1e6, ..bare() };
    p.set_nrt(2.0);
    let mut body = sphere_body(2, 1.0, p);
    swirl(&mut body, 1.0);
    let mut w = alone(body, WorldSettings { dt: 1e-2, ..still() });
    let mut err = None;
    for _ in 0..10000 {
        if let Err(e) = w.step() {
            err = Some(e);
            break;
        }
    }
    let msg = err.expect("dt = 1e-2 with k = 1e6 must blow up").to_string();
    assert!(msg.contains("at step") && msg.contains("smaller dt"), "{msg}");
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let mut w = alone(sphere_body(1, 1.0, bare()), still());
    w.settings.dt = 0.0;
    assert!(w.step().unwrap_err().to_string().starts_with("dt:"));
    w.settings.dt = f64::NAN;
    assert!(w.step().is_err());
    w.settings.dt = 1e-3;
    w.bodies[0].material.stiffness = f64::NAN;
    assert!(w.step().unwrap_err().to_string().starts_with("stiffness:"));
    w.bodies[0].material.stiffness = 1.0;
    w.bodies[0].material.gas_amount = -1.0;
    assert!(w.step().unwrap_err().to_string().starts_with("gas.amount:"));
    assert!(SoftBody::new(&icosphere(1, 1.0), 0.0, bare()).is_err());
    let body = &mut w.bodies[0];
    assert!(body.set_vertex_mass(10_000, 1.0).is_err());
    assert!(body.set_user_forces(&[1.0]).is_err());
}
