//! Freezing and subdividing in the modeler's world, through the World API the page uses (the
//! `modeler` preset: implicit steps of 1/60 s, gravity, ground, gas; the grab as target springs;
//! Freeze under load; Subdivide keeping the load as `web/src/worker/document.ts` does).

use softsculpt::body::{Material, SoftBody, Target};
use softsculpt::mesh::builtin::builtin;
use softsculpt::world::{World, WorldSettings};

/// The page's mushroom: placed on the ground, 1 kg, modeler preset, foot pinned, settled 6 s.
fn page_mushroom() -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let (lo, hi) = softsculpt::mesh::bounds(&mesh.positions);
    let c = [(lo[0] + hi[0]) / 2.0, lo[1], (lo[2] + hi[2]) / 2.0];
    for p in mesh.positions.chunks_exact_mut(3) {
        for d in 0..3 {
            p[d] -= c[d];
        }
    }
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    let n = w.bodies[0].vertex_count();
    for i in 0..n {
        if w.bodies[0].positions()[3 * i + 1] < 0.01 {
            w.bodies[0].set_pinned(i, true).unwrap();
        }
    }
    steps(&mut w, 360);
    w
}

fn steps(w: &mut World, n: usize) {
    for _ in 0..n {
        w.step().unwrap();
    }
}

fn page_freeze(w: &mut World) {
    if w.settings.gravity != 0.0 {
        w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    } else {
        w.bodies[0].freeze()
    }
}

fn page_subdivide(w: &mut World) {
    let before = w.param(0, "gas.ambient").unwrap();
    let finer = w.bodies[0].subdivided().unwrap();
    w.replace_body(0, finer);
    if w.settings.gravity != 0.0 {
        w.set_param(0, "gas.ambient", before).unwrap();
        w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    }
}

fn com_y(w: &World) -> f64 {
    w.stats(0).center_of_mass[1]
}

/// The page's grab: target springs from the vertices within 0.35 m of `p` to p + offset + `pull`.
fn grab(w: &mut World, p: [f64; 3], pull: [f64; 3], omega: f64) {
    let b = &w.bodies[0];
    let x = b.positions();
    let mut t = Vec::new();
    for i in 0..b.vertex_count() {
        let d2: f64 = (0..3).map(|d| (x[3 * i + d] - p[d]).powi(2)).sum();
        let r = 0.35f64;
        if d2 < r * r {
            let q = 1.0 - d2 / (r * r);
            let wgt = q * q;
            let m = b.masses()[i];
            t.push(Target { vertex: i, anchor: [x[3 * i] + pull[0], x[3 * i + 1] + pull[1], x[3 * i + 2] + pull[2]], stiffness: m * wgt * omega * omega, damping: 2.0 * m * wgt * omega });
        }
    }
    w.bodies[0].set_targets(&t).unwrap();
}

fn top(w: &World) -> [f64; 3] {
    let x = w.bodies[0].positions();
    let i = (0..x.len() / 3).max_by(|&a, &b| x[3 * a + 1].total_cmp(&x[3 * b + 1])).unwrap();
    [x[3 * i], x[3 * i + 1], x[3 * i + 2]]
}


fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// A frozen state under load is an exact equilibrium: every free vertex feels its prestress
/// m g ŷ and its weight −m g ŷ (which cancel to rounding, |m g / m − g| ≲ 1e-15 m/s²), springs
/// at rest, the gas at P_ref; supported vertices are pinned or pressed onto the ground. So a
/// vertex may drift by rounding only: ≲ 1e-15 m/s² × (3 s)² ≈ 1e-14 m. Tolerance 1e-9 m.
const HELD: f64 = 1e-9;

/// Subdivide after a Freeze, and Subdivide twice, keep the mushroom standing (they crushed it
/// into a dome: centre of mass 0.95 → 0.31 m, because the subdivided body lost the kept load).
#[test]
fn subdividing_a_frozen_or_subdivided_mushroom_keeps_its_shape() {
    let settled = page_mushroom();
    let h0 = com_y(&settled);
    let mut frozen = settled.clone();
    page_freeze(&mut frozen);
    let mut once = settled.clone();
    page_subdivide(&mut once);
    for (what, mut w) in [("freeze, subdivide", frozen), ("subdivide twice", once)] {
        page_subdivide(&mut w);
        let x0 = w.bodies[0].positions().to_vec();
        steps(&mut w, 180);
        let moved = max_diff(w.bodies[0].positions(), &x0);
        assert!(moved < HELD, "{what}: moved {moved} m in 3 s");
        // Loop subdivision smooths the shape: the centre of mass moves by a fraction of an edge.
        assert!((com_y(&w) - h0).abs() < 0.01, "{what}: centre of mass {h0} -> {}", com_y(&w));
    }
}

/// Freeze while a grab is held (the page ends the stroke first, then freezes under load) keeps
/// the pulled shape (it tipped the mushroom over: volume 2.52 → 1.61 m³), as does freezing with
/// the targets still on and releasing them after.
#[test]
fn freezing_during_a_grab_holds_the_pulled_shape() {
    let settled = page_mushroom();
    let mut w = pull_cap(&settled);
    let v_pulled = w.stats(0).volume;
    assert!(com_y(&w) > com_y(&settled) + 0.05, "the grab lifts the cap");
    let mut released_first = w.clone();
    released_first.bodies[0].clear_targets();
    page_freeze(&mut released_first);
    page_freeze(&mut w);
    w.bodies[0].clear_targets();
    for (what, mut w) in [("release, freeze", released_first), ("freeze, release", w)] {
        let x0 = w.bodies[0].positions().to_vec();
        steps(&mut w, 180);
        let moved = max_diff(w.bodies[0].positions(), &x0);
        assert!(moved < HELD, "{what}: moved {moved} m in 3 s");
        assert!((w.stats(0).volume - v_pulled).abs() < 1e-9, "{what}: volume {v_pulled} -> {}", w.stats(0).volume);
    }
}

/// The page's grab of the cap's top, dragged 0.3 m up and sideways over half a second and held
/// for another half.
fn pull_cap(settled: &World) -> World {
    let p = top(settled);
    let mut w = settled.clone();
    for k in 1..=30 {
        let s = k as f64 / 30.0;
        let mut anchors = settled.clone();
        grab(&mut anchors, p, [0.3 * s, 0.3 * s, 0.0], 600.0);
        w.bodies[0].set_targets(anchors.bodies[0].targets()).unwrap();
        steps(&mut w, 1);
    }
    steps(&mut w, 30);
    w
}
