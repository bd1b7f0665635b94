//! Freezing and subdividing in the modeler's world, through the World API the page uses (the
//! `modeler` preset: implicit steps of 1/60 s, gravity, ground, gas; the grab as target springs;
//! Freeze under load; Subdivide keeping the load as `web/src/worker/document.ts` does).

use softsculpt::body::{FreezeOptions, Material, SoftBody, Target};
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

/// The page's Freeze (F): under load when gravity is on; keeping the tension or not.
fn page_freeze_with(w: &mut World, keep_tension: bool) {
    w.freeze(0, FreezeOptions { under_load: w.settings.gravity != 0.0, keep_tension }).unwrap();
}

fn page_freeze(w: &mut World) {
    page_freeze_with(w, false);
}

/// The page's Subdivide (U): the finer body comes plainly frozen (`ss_subdivide`); the gas
/// reference is put back and it is frozen again as Freeze would.
fn page_subdivide(w: &mut World) {
    let before = w.param(0, "gas.ambient").unwrap();
    w.subdivide(0, FreezeOptions::default()).unwrap();
    w.set_param(0, "gas.ambient", before).unwrap();
    page_freeze(w);
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

/// Built-in `name` standing on y = 0 (not pinned), 1 kg, the modeler preset with `setup`'s
/// changes, settled 3 s (the page's octopus stands on its tentacles this way).
fn page_standing(name: &str, setup: impl FnOnce(&mut WorldSettings)) -> World {
    let mut mesh = builtin(name).unwrap();
    let (lo, _) = softsculpt::mesh::bounds(&mesh.positions);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo[1];
    }
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    setup(&mut w.settings);
    steps(&mut w, 180);
    w
}

/// After a new mesh (`replace` on `w`): some vertex rests on a support, and over 2 s no vertex
/// moves by `held` (m) or more and the height stays within `dh` (m) of `w`'s before.
fn keeps_resting(mut w: World, replace: impl FnOnce(&mut World), held: f64, dh: f64) {
    let h0 = height(&w);
    replace(&mut w);
    let resting = w.resting_vertices(0).unwrap().iter().filter(|&&r| r).count();
    assert!(resting > 0, "the new mesh rests on its support");
    let x0 = w.bodies[0].positions().to_vec();
    steps(&mut w, 120);
    let moved = max_diff(w.bodies[0].positions(), &x0);
    assert!(moved < held, "moved {moved} m in 2 s");
    assert!((height(&w) - h0).abs() < dh, "height {h0} -> {}", height(&w));
}

fn height(w: &World) -> f64 {
    let ys = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]);
    ys.clone().fold(f64::MIN, f64::max) - ys.fold(f64::MAX, f64::min)
}

/// Subdividing a body that stands on the ground keeps it standing: Loop subdivision lifts the
/// vertices that stood on the ground (the octopus's tentacle tips, by 6.4 mm), which are put
/// back on it, so the freeze under load finds its supports (it found none and carried none of
/// the weight: the octopus sagged from 1.76 m to 1.33 m within a second, tentacles splayed).
#[test]
fn a_subdivided_octopus_keeps_standing_on_its_tentacles() {
    // Held as any frozen state under load (HELD: rounding only), and Loop subdivision's
    // smoothing moves a vertex by a fraction of its edges (the tips by 0.1 of one; measured
    // 1.763 → 1.749 m overall): 2 cm, a fifth of an edge of the subdivided octopus (~0.1 m),
    // where the sag was 43 cm.
    keeps_resting(page_standing("octopus", |_| {}), page_subdivide, HELD, 0.02);
}

/// Remeshing under load keeps a resting body on its supports too (a remeshed vertex takes its
/// nearest old vertex's support): the modeler's sphere, settled on the ground with a flattened
/// bottom, remeshed to a finer even mesh, rests on the ground and is held (HELD); the remesher
/// projects onto the old surface, so the height changes by a fraction of an edge (~0.1 m): 2 cm.
#[test]
fn a_remeshed_sphere_keeps_resting_on_the_ground() {
    let remesh = |w: &mut World| {
        let rest = w.bodies[0].rest_lengths();
        let edge = 0.7 * rest.iter().sum::<f64>() / rest.len() as f64;
        w.remesh(0, edge, true).unwrap();
    };
    keeps_resting(page_standing("sphere", |_| {}), remesh, HELD, 0.02);
}

/// A body resting on a triangle-mesh obstacle (a slab, no ground) and subdivided as the page
/// does keeps resting on it. (The slab is coarse: its reach, a quarter of its 4 m edges, covers
/// every lifted vertex, so this does not exercise a fine mesh's beyond-reach stand-in distance,
/// which `Shape::distance_within` now refuses.)
#[test]
fn a_body_subdivided_on_a_mesh_obstacle_keeps_resting_on_it() {
    // A slab 4 m × 4 m, 0.5 m thick, its top at y = 0.
    let mut slab = softsculpt::mesh::TriMesh { positions: Vec::new(), triangles: Vec::new() };
    for c in 0..8u32 {
        slab.positions.extend([if c & 1 == 0 { -2.0 } else { 2.0 }, if c & 2 == 0 { -0.5 } else { 0.0 }, if c & 4 == 0 { -2.0 } else { 2.0 }]);
    }
    for q in [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]] {
        slab.triangles.push([q[0], q[1], q[2]]);
        slab.triangles.push([q[0], q[2], q[3]]);
    }
    softsculpt::mesh::topology::orient_outward(&mut slab.triangles, &slab.positions).unwrap();
    let w = page_standing("sphere", |s| {
        s.ground = None;
        s.obstacles = vec![softsculpt::world::Obstacle::triangle_mesh(&slab).unwrap()];
    });
    assert!(w.resting_vertices(0).unwrap().iter().any(|&r| r), "settled on the slab");
    // A plain freeze under load on the slab, for comparison: obstacles are not part of the
    // implicit solve (the after-step contact stage), so even that drifts (measured 2.8 cm in
    // 2 s): the subdivided body may drift as much (1.5×), not more; the height as above, 2 cm
    // beside that drift.
    let mut frozen = w.clone();
    page_freeze(&mut frozen);
    let xf = frozen.bodies[0].positions().to_vec();
    steps(&mut frozen, 120);
    let drift = max_diff(frozen.bodies[0].positions(), &xf);
    keeps_resting(w, page_subdivide, 1.5 * drift, 0.02 + drift);
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

/// A balloon: the unit icosphere (642 vertices) inflated by 30 J of gas with the modeler's
/// material and implicit steps, without gravity, settled.
fn balloon() -> World {
    let body = SoftBody::new(&softsculpt::mesh::builtin::icosphere(3, 1.0), 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    // No hinges: what these tests compare is the skin's tension, and hinges carry a dent by
    // bending whatever the tension (with the modeler's D = 0.05 J a plain freeze caved in 1.24×
    // as deep as the live balloon instead of 2.3×).
    w.set_param(0, "rigidity", softsculpt::params::Value::Number(0.0)).unwrap();
    w.settings.gravity = 0.0;
    w.settings.ground = None;
    steps(&mut w, 600);
    w
}

/// Squeeze: `force` (N) spread over the vertices within 0.3 m of the top, pushing down, and
/// the same over the bottom, pushing up; settle 4 s; how much the top-to-bottom distance shrank (m).
fn squeeze_depth(w: &World, force: f64) -> f64 {
    let mut w = w.clone();
    let x = w.bodies[0].positions().to_vec();
    let n = x.len() / 3;
    let (top, bottom) = (
        (0..n).max_by(|&a, &b| x[3 * a + 1].total_cmp(&x[3 * b + 1])).unwrap(),
        (0..n).min_by(|&a, &b| x[3 * a + 1].total_cmp(&x[3 * b + 1])).unwrap(),
    );
    let near = |c: usize| -> Vec<usize> { (0..n).filter(|&i| (0..3).map(|d| (x[3 * i + d] - x[3 * c + d]).powi(2)).sum::<f64>() < 0.09).collect() };
    let mut f = vec![0.0; 3 * n];
    for (c, sign) in [(top, -1.0), (bottom, 1.0)] {
        let patch = near(c);
        for &i in &patch {
            f[3 * i + 1] += sign * force / patch.len() as f64;
        }
    }
    let gap = |w: &World| w.bodies[0].positions()[3 * top + 1] - w.bodies[0].positions()[3 * bottom + 1];
    let g0 = gap(&w);
    w.bodies[0].set_user_forces(&f).unwrap();
    steps(&mut w, 240);
    g0 - gap(&w)
}

/// The page's press: target springs (ω = 200 1/s) on the vertices within 0.35 m of vertex `c`,
/// anchored `depth` × weight inward along −n (n: the outward direction at c, given).
fn press(w: &mut World, c: usize, n: [f64; 3], depth: f64) {
    let b = &w.bodies[0];
    let x = b.positions();
    let omega: f64 = 200.0;
    let mut t = Vec::new();
    for i in 0..b.vertex_count() {
        let d2: f64 = (0..3).map(|d| (x[3 * i + d] - x[3 * c + d]).powi(2)).sum();
        let r = 0.35f64;
        if d2 < r * r {
            let q = 1.0 - d2 / (r * r);
            let wgt = q * q;
            let m = b.masses()[i];
            t.push(Target { vertex: i, anchor: [0, 1, 2].map(|d| x[3 * i + d] - depth * wgt * n[d]), stiffness: m * wgt * omega * omega, damping: 2.0 * m * wgt * omega });
        }
    }
    w.bodies[0].set_targets(&t).unwrap();
}

/// The page's press (depth 0.15 m) held for 1 s on the cap's surface point in direction `dir`
/// from the cap's centre (the vertices above 1 m): (displacement of the pressed vertex, of the
/// point opposite it across the cap's axis, of the cap's centre), m.
fn press_cap(w: &World, dir: [f64; 3]) -> (f64, f64, f64) {
    let mut w = w.clone();
    let x = w.bodies[0].positions().to_vec();
    let n = x.len() / 3;
    let cap: Vec<usize> = (0..n).filter(|&i| x[3 * i + 1] > 1.0).collect();
    let centre = |x: &[f64]| -> [f64; 3] { let mut c = [0.0; 3]; for &i in &cap { for d in 0..3 { c[d] += x[3 * i + d] / cap.len() as f64; } } c };
    let c0 = centre(&x);
    // The cap's surface point in direction `dir` from its centre.
    let toward = |dir: [f64; 3]| *cap.iter().max_by(|&&a, &&b| {
        let s = |i: usize| (0..3).map(|d| (x[3 * i + d] - c0[d]) * dir[d]).sum::<f64>();
        s(a).total_cmp(&s(b))
    }).unwrap();
    let near = toward(dir);
    let far = toward([-dir[0], dir[1], -dir[2]]);
    let nn = { let v = [0, 1, 2].map(|d| x[3 * near + d] - c0[d]); let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt(); v.map(|a| a / l) };
    press(&mut w, near, nn, 0.15);
    steps(&mut w, 60);
    let y = w.bodies[0].positions();
    let dist = |a: &[f64], b: &[f64]| (0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>().sqrt();
    (dist(&y[3 * near..3 * near + 3], &x[3 * near..3 * near + 3]), dist(&y[3 * far..3 * far + 3], &x[3 * far..3 * far + 3]), dist(&centre(y), &c0))
}

/// The tension-keeping freeze leaves the gas pressing (P − P_ref = P > 0) and an equilibrium:
/// its residual is below 1e-10 N (the solve stops at 1e-12 of the load, ~1 N), which on a
/// vertex of ≥ 1/5762 kg is ≤ 5.8e-7 m/s², so within 1 s no vertex may reach 1e-6 m/s (the
/// bound asked for).
/// Checked on a balloon without gravity, on the page's mushroom under load, on the mushroom
/// frozen while pulled by a grab, and on the mushroom subdivided keeping the tension (1,442
/// vertices; at 5,762 a solve stopped at 1e-12 of the load left 6e-12 N, the implicit step's
/// rounding floor, and Newton, iterating on rounding, failed to converge two steps later).
#[test]
fn a_tension_keeping_freeze_holds_the_shape_with_the_gas_still_pressing() {
    let kt = FreezeOptions { under_load: true, keep_tension: true };
    let settled = page_mushroom();
    let mut pulled = pull_cap(&settled);
    pulled.bodies[0].clear_targets();
    let mut finer = settled.clone();
    finer.subdivide(0, kt).unwrap();
    for (what, mut w) in [("balloon", balloon()), ("mushroom", settled), ("pulled mushroom", pulled), ("mushroom subdivided keeping the tension", finer)] {
        let r = w.freeze(0, kt).unwrap();
        let b = &w.bodies[0];
        assert!(b.pressure() > b.gas_reference().ambient_pressure + 1.0, "{what}: the gas still presses: P {} P_ref {}", b.pressure(), b.gas_reference().ambient_pressure);
        assert!(r.residual < 1e-10 && r.clamped == 0, "{what}: {r:?}");
        let mut vmax: f64 = 0.0;
        for _ in 0..60 {
            w.step().unwrap();
            vmax = vmax.max(w.bodies[0].max_speed());
        }
        eprintln!("{what}: {} vertices, {r:?}, max speed over 1 s {vmax:e} m/s", w.bodies[0].vertex_count());
        assert!(vmax < 1e-6, "{what}: max speed {vmax} m/s");
    }
}

/// An inflated balloon frozen keeping the tension answers a squeeze (1 N on 0.3 m patches at
/// top and bottom) as before the freeze; frozen plainly its slack skin caves in about twice as
/// deep. On a sphere the least-energy tensions are the uniform stretch the gas made, up to the
/// icosphere's ±10 % edge-length spread; measured agreement 1e-4, tolerance 2 %.
#[test]
fn a_balloon_frozen_keeping_tension_answers_a_push_as_before_the_freeze() {
    let before = balloon();
    let mut kept = before.clone();
    kept.freeze(0, FreezeOptions { under_load: false, keep_tension: true }).unwrap();
    let mut plain = before.clone();
    plain.freeze(0, FreezeOptions::default()).unwrap();
    let (d0, dk, dp) = (squeeze_depth(&before, 1.0), squeeze_depth(&kept, 1.0), squeeze_depth(&plain, 1.0));
    eprintln!("squeeze depth: before the freeze {d0:.5} m, keeping the tension {dk:.5} m, plain {dp:.5} m");
    assert!((dk - d0).abs() < 0.02 * d0, "keep tension {dk} vs before {d0}");
    assert!(dp > 1.8 * d0, "plain {dp} vs before {d0}");
}

/// A press on the cap of the mushroom frozen under load keeping the tension dents it as before
/// the freeze: the pressed point goes in more than twice as far as the cap's centre moves, and
/// every displacement is within 5 % of the unfrozen mushroom's. The least-energy tensions are
/// not the ones gas and weight made, only as close as the shape allows: measured 1e-4 apart
/// for a press on the cap's shoulder, 2.3 % on its top.
#[test]
fn a_press_on_the_frozen_mushrooms_cap_dents_it_as_before_the_freeze() {
    let settled = page_mushroom();
    let mut kept = settled.clone();
    kept.freeze(0, FreezeOptions { under_load: true, keep_tension: true }).unwrap();
    for dir in [[0.5, 0.85, 0.0], [0.0, 1.0, 0.0]] {
        let (p0, f0, c0) = press_cap(&settled, dir);
        let (p, f, c) = press_cap(&kept, dir);
        eprintln!("press toward {dir:?}: before (pressed {p0:.4}, far {f0:.4}, centre {c0:.4}) m, frozen keeping tension ({p:.4}, {f:.4}, {c:.4}) m");
        assert!(p > 2.0 * c, "a dent, not a swing: pressed {p}, cap centre {c}");
        for (a, b) in [(p, p0), (f, f0), (c, c0)] {
            assert!((a - b).abs() < 0.05 * p0, "{a} vs {b} before the freeze");
        }
    }
}

/// The equilibrium a tension-keeping freeze makes is stable: nudged by a 1 cm/s velocity field,
/// the mushroom (settled, or pulled by a grab) comes back. The nudge moves it ~ v / c ≈ 7 mm
/// (c = 1.5 1/s), decaying as e^(−c t): after 3 s ~0.1 mm is left; tolerance 1 mm (an unstable
/// freeze moved it 0.25 m: the least-energy tensions from a slack skin, see docs/model.md).
#[test]
fn a_nudged_mushroom_frozen_keeping_tension_comes_back() {
    let settled = page_mushroom();
    let mut pulled = pull_cap(&settled);
    pulled.bodies[0].clear_targets();
    for (what, mut w) in [("settled", settled), ("pulled", pulled)] {
        w.freeze(0, FreezeOptions { under_load: true, keep_tension: true }).unwrap();
        let x0 = w.bodies[0].positions().to_vec();
        let v: Vec<f64> = x0.chunks_exact(3).enumerate().flat_map(|(i, p)| if w.bodies[0].is_pinned(i) { [0.0; 3] } else { [0.01 * (3.0 * p[0]).sin(), -0.01, 0.01 * (2.0 * p[2]).cos()] }).collect();
        w.bodies[0].set_state(&x0, &v).unwrap();
        steps(&mut w, 180);
        let moved = max_diff(w.bodies[0].positions(), &x0);
        assert!(moved < 1e-3, "{what}: {moved} m from the frozen shape 3 s after the nudge");
    }
}

/// An open surface has no enclosed volume (a flat sheet: exactly 0 by the divergence theorem), so
/// freezing it must not make that its gas reference volume V₀ (a V₀ that is not positive is refused
/// everywhere else). Before: Freeze set V₀ := V = 0, and then Subdivide (the
/// page's hint for a coarse import), setting the gas reference back, and opening the saved
/// project all failed ("gas reference: must be finite with a positive volume"). Now a body
/// without a positive volume keeps the reference a new body gets (1 m³; unused without gas).
#[test]
fn an_open_sheet_can_be_frozen_subdivided_saved_and_opened_again() {
    let n = 8;
    let mut obj = String::new();
    for i in 0..=n {
        for j in 0..=n {
            obj += &format!("v {} 0.5 {}\n", 2.0 * i as f64 / n as f64 - 1.0, 2.0 * j as f64 / n as f64 - 1.0);
        }
    }
    let v = |i: usize, j: usize| i * (n + 1) + j + 1;
    for i in 0..n {
        for j in 0..n {
            obj += &format!("f {} {} {}\nf {} {} {}\n", v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i + 1, j));
        }
    }
    let mesh = softsculpt::mesh::load_obj(obj.as_bytes()).unwrap().mesh;
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    // As the page imports it: the modeler's preset without its gas (skipped on an open surface).
    assert_eq!(w.apply_preset_scaled(0, "modeler", 1.0).unwrap(), ["gas.nrt"]);
    steps(&mut w, 30);
    let plain = FreezeOptions { under_load: false, keep_tension: false };
    let load = FreezeOptions { under_load: true, keep_tension: false };
    w.freeze(0, plain).unwrap();
    let gas = w.bodies[0].gas_reference();
    assert!(gas.reference_volume > 0.0, "{gas:?}");
    // The page sets the reference back after a freeze (`document.ts`): the same value is taken.
    w.bodies[0].set_gas_reference(gas).unwrap();
    w.subdivide(0, load).unwrap();
    assert_eq!(w.bodies[0].vertex_count(), (2 * n + 1) * (2 * n + 1));
    w.freeze(0, load).unwrap();
    steps(&mut w, 30);
    // Saved and opened again: the same world, stepping to the same bits.
    let bytes = w.snapshot();
    let mut again = World::restore(&bytes).unwrap();
    steps(&mut w, 10);
    steps(&mut again, 10);
    assert_eq!(w.bodies[0].positions(), again.bodies[0].positions());
    assert!(w.bodies[0].positions().iter().all(|x| x.is_finite()));
    // A project saved before the fix (V0 = 0 after the freeze: the gas pairs [P_ref, V0] =
    // [0, 1] written as [0, 0], checksum redone) opens, and steps to the same bits (V0 enters
    // only the gas energy, and there is no gas).
    let mut old = bytes.clone();
    let (one, zero) = (1.0f64.to_le_bytes(), 0.0f64.to_le_bytes());
    let pair: Vec<u8> = zero.iter().chain(&one).copied().collect();
    let mut patched = 0;
    for k in 21..old.len() - 16 {
        if old[k..k + 16] == pair[..] {
            old[k + 8..k + 16].copy_from_slice(&zero);
            patched += 1;
        }
    }
    assert!(patched >= 2, "the body's and the frozen state's gas references: {patched}");
    let crc = crc32fast::hash(&old[21..]).to_le_bytes();
    old[17..21].copy_from_slice(&crc);
    let mut opened = World::restore(&old).unwrap();
    assert_eq!(opened.bodies[0].gas_reference().reference_volume, 1.0);
    let mut again = World::restore(&bytes).unwrap();
    steps(&mut opened, 10);
    steps(&mut again, 10);
    assert_eq!(opened.bodies[0].positions(), again.bodies[0].positions());
}
