//! Undo deltas: applying one takes the world back exactly (bit for bit, as its snapshot shows),
//! applying the inverse takes it forward again; a brush stroke's delta holds only what the stroke
//! touched; bad or foreign deltas are refused with the world left as it was. And version-1
//! project files of the modeler open as a world that continues where they were saved.

use proptest::prelude::*;
use softsculpt::compat::project_v1;
use softsculpt::delta::{Delta, DeltaError, StateScope};
use softsculpt::mesh::builtin::icosphere;
use softsculpt::world::{Ground, World, WorldSettings};
use softsculpt::{Material, SoftBody};

fn balloon(level: u32) -> World {
    let mut m = Material::default();
    m.set_nrt(5.0);
    m.bending_stiffness = 20.0;
    m.damping = 0.5;
    let body = SoftBody::new(&icosphere(level, 0.5), 1.0, m).unwrap();
    World::single(body, WorldSettings { ground: Some(Ground::at(-0.6)), ..WorldSettings::default() })
}

/// One modeling operation, as the modeler does them.
#[derive(Debug, Clone)]
enum Op {
    Steps(u64),
    Inflate { center: usize, factor: f64 },
    Mass { vertex: usize, mass: f64 },
    Pin(usize),
    Freeze,
    FreezeUnderLoad,
    Reset,
    Gas(f64),
    Stiffness(f64),
    Rigidity(f64),
    Gravity(f64),
    Integrator(&'static str),
    Target { vertex: usize, k: f64 },
    Subdivide,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (1u64..20).prop_map(Op::Steps),
        (0usize..42, 0.8f64..1.3).prop_map(|(center, factor)| Op::Inflate { center, factor }),
        (0usize..42, 0.001f64..0.1).prop_map(|(vertex, mass)| Op::Mass { vertex, mass }),
        (0usize..42).prop_map(Op::Pin),
        Just(Op::Freeze),
        Just(Op::FreezeUnderLoad),
        Just(Op::Reset),
        (0.0f64..20.0).prop_map(Op::Gas),
        (50.0f64..500.0).prop_map(Op::Stiffness),
        (0.0f64..0.5).prop_map(Op::Rigidity),
        (0.0f64..12.0).prop_map(Op::Gravity),
        prop::sample::select(vec!["implicit", "symplectic", "rk4"]).prop_map(Op::Integrator),
        (0usize..42, 10.0f64..1000.0).prop_map(|(vertex, k)| Op::Target { vertex, k }),
        Just(Op::Subdivide),
    ]
}

/// Vertices within 0.3 m of vertex `c` get `factor`, the others 1: a brush dab.
fn dab(b: &SoftBody, c: usize, factor: f64) -> Vec<f64> {
    let x = b.positions();
    (0..b.vertex_count())
        .map(|i| {
            let d2: f64 = (0..3).map(|k| (x[3 * i + k] - x[3 * c + k]).powi(2)).sum();
            if d2 < 0.09 { factor } else { 1.0 }
        })
        .collect()
}

fn run(w: &mut World, op: &Op) {
    let b = &mut w.bodies[0];
    let n = b.vertex_count();
    match *op {
        Op::Steps(k) => {
            let _ = w.step_n(k);
        }
        Op::Inflate { center, factor } => {
            let f = dab(b, center % n, factor);
            b.scale_rest_lengths_by_vertex(&f).unwrap();
        }
        Op::Mass { vertex, mass } => b.set_vertex_mass(vertex % n, mass).unwrap(),
        Op::Pin(v) => b.set_pinned(v % n, true).unwrap(),
        Op::Freeze => b.freeze(),
        Op::FreezeUnderLoad => {
            w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
        }
        Op::Reset => b.reset(),
        Op::Gas(nrt) => {
            let t = b.material.temperature;
            b.set_gas(nrt / (softsculpt::GAS_CONSTANT * t), t).unwrap();
        }
        Op::Stiffness(k) => w.set_param(0, "stiffness", softsculpt::params::Value::Number(k)).unwrap(),
        Op::Rigidity(b) => w.set_param(0, "rigidity", softsculpt::params::Value::Number(b)).unwrap(),
        Op::Gravity(g) => w.set_param(0, "gravity", softsculpt::params::Value::Number(g)).unwrap(),
        Op::Integrator(name) => w.set_param(0, "integrator", softsculpt::params::choice("integrator", name).unwrap()).unwrap(),
        Op::Target { vertex, k } => {
            let anchor = [0.0, 1.0, 0.0];
            b.set_targets(&[softsculpt::body::Target { vertex: vertex % n, anchor, stiffness: k, damping: 0.1 }]).unwrap()
        }
        Op::Subdivide => {
            if n < 200 {
                w.bodies[0] = w.bodies[0].subdivided().unwrap();
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Undo then redo of any operation after any history: the snapshots (every field a world
    /// keeps, bit for bit) are the ones before and after the operation. Scope `All` keeps the
    /// whole state, so equality is exact.
    #[test]
    fn undo_and_redo_restore_the_world_exactly(history in prop::collection::vec(op(), 0..6), last in op()) {
        let mut w = balloon(1);
        for o in &history {
            run(&mut w, o);
        }
        let before = w.clone();
        run(&mut w, &last);
        let after_bytes = w.snapshot();
        let undo = Delta::between(&before, &w, StateScope::All);
        let undo = Delta::from_bytes(&undo.to_bytes()).unwrap();
        let redo = undo.apply(&mut w).unwrap();
        prop_assert!(w.snapshot() == before.snapshot(), "undo of {last:?} did not restore the world");
        let again = redo.apply(&mut w).unwrap();
        prop_assert!(w.snapshot() == after_bytes, "redo of {last:?} did not restore the world");
        // And the undo made from the redo is the same undo again.
        again.apply(&mut w).unwrap();
        prop_assert!(w.snapshot() == before.snapshot());
    }
}

/// A brush stroke (inflating the rest lengths under a 0.3 m brush) undone with `Touched`:
/// every rest length (edge and bending springs) and the touched vertices' (the ends of a
/// changed spring) positions and velocities are as before; every
/// other vertex keeps moving from where it is (its position is the after-stroke one).
#[test]
fn undoing_a_brush_stroke_restores_what_it_touched_only() {
    let mut w = balloon(3);
    w.step_n(50).unwrap();
    let before = w.clone();
    let f = dab(&w.bodies[0], 0, 1.2);
    w.bodies[0].scale_rest_lengths_by_vertex(&f).unwrap();
    w.step_n(20).unwrap();
    let after = w.clone();
    let undo = Delta::between(&before, &after, StateScope::Touched);
    undo.apply(&mut w).unwrap();
    let (b0, b1, b) = (&before.bodies[0], &after.bodies[0], &w.bodies[0]);
    assert_eq!(b.rest_lengths(), b0.rest_lengths());
    assert_eq!(b.bending_rest_lengths(), b0.bending_rest_lengths());
    let (si, sj) = b.spring_ends();
    let mut touched = vec![false; b.vertex_count()];
    for k in 0..si.len() {
        if b0.rest_lengths()[k] != b1.rest_lengths()[k] {
            touched[si[k] as usize] = true;
            touched[sj[k] as usize] = true;
        }
    }
    let (bi, bj) = b.bending_ends();
    for k in 0..bi.len() {
        if b0.bending_rest_lengths()[k] != b1.bending_rest_lengths()[k] {
            touched[bi[k] as usize] = true;
            touched[bj[k] as usize] = true;
        }
    }
    let t = touched.iter().filter(|&&t| t).count();
    assert!(t > 0 && t < b.vertex_count() / 2, "{t} touched vertices");
    for i in 0..b.vertex_count() {
        let want = if touched[i] { b0 } else { b1 };
        assert_eq!(&b.positions()[3 * i..3 * i + 3], &want.positions()[3 * i..3 * i + 3], "vertex {i}");
        assert_eq!(&b.velocities()[3 * i..3 * i + 3], &want.velocities()[3 * i..3 * i + 3], "vertex {i}");
    }
    // The clock is the after-stroke one (undo does not rewind time for a stroke).
    assert_eq!(w.time(), after.time());
}

/// What a stroke's delta weighs: a 0.3 m dab on a 0.5 m balloon of 10,242 vertices touches
/// about (0.3/0.5)²/4 ≈ 9 % of the surface (a spherical cap of chord 0.3 m: area fraction
/// (1 − cos θ)/2 with sin(θ/2) = 0.3), each touched vertex costing its ~3 springs, ~3 bending
/// springs and its x and v (about 12 values of 12 bytes: 150 B), against a snapshot's ~700 B
/// per vertex: the delta must be under a quarter of the snapshot.
#[test]
fn a_brush_strokes_delta_holds_only_the_touched_region() {
    let mut w = balloon(5);
    let before = w.clone();
    let f = dab(&w.bodies[0], 0, 1.1);
    w.bodies[0].scale_rest_lengths_by_vertex(&f).unwrap();
    w.step_n(3).unwrap();
    let delta = Delta::between(&before, &w, StateScope::Touched).to_bytes().len();
    let snap = w.snapshot().len();
    assert!(delta * 4 < snap, "delta {delta} B vs snapshot {snap} B");
    // A parameter change holds nothing of the meshes at all.
    let before = w.clone();
    w.set_param(0, "stiffness", softsculpt::params::Value::Number(321.0)).unwrap();
    let p = Delta::between(&before, &w, StateScope::None).to_bytes().len();
    assert!(p < 200, "a parameter change weighs {p} B");
}

/// A subdivision changes the structure: the delta holds the whole earlier world and undo brings
/// the coarse mesh back; redo the fine one.
#[test]
fn undoing_a_subdivision_brings_the_coarse_mesh_back() {
    let mut w = balloon(1);
    let before = w.clone();
    w.bodies[0] = w.bodies[0].subdivided().unwrap();
    let fine = w.snapshot();
    let undo = Delta::between(&before, &w, StateScope::All);
    assert!(undo.is_whole());
    let redo = undo.apply(&mut w).unwrap();
    assert_eq!(w.bodies[0].vertex_count(), 42);
    assert!(w.snapshot() == before.snapshot());
    redo.apply(&mut w).unwrap();
    assert!(w.snapshot() == fine);
}

/// A whole delta (`Delta::whole`, the modeler's material presets) takes a world back to the mark
/// whatever happened after it: the change and the steps since (positions, clock) — not only what
/// the operation itself changed, as `between` does — and its inverse forward again, bit for bit.
#[test]
fn a_whole_delta_undoes_what_the_steps_since_made_of_a_change() {
    let mut w = balloon(2);
    w.step_n(5).unwrap();
    let mark = w.clone();
    w.set_param(0, "stiffness", softsculpt::params::Value::Number(3.0)).unwrap();
    let undo = Delta::whole(&mark);
    let only_the_change = Delta::between(&mark, &w, StateScope::All);
    w.step_n(40).unwrap();
    let later = w.snapshot();
    // `between`, taken right after the change, brings the stiffness back but leaves the shape the
    // 40 steps made; the whole delta brings back the world as it was.
    let mut partial = w.clone();
    only_the_change.apply(&mut partial).unwrap();
    assert!(partial.bodies[0].positions() != mark.bodies[0].positions());
    let redo = undo.apply(&mut w).unwrap();
    assert!(w.snapshot() == mark.snapshot());
    redo.apply(&mut w).unwrap();
    assert!(w.snapshot() == later);
}

/// Nothing changed: an empty delta, which changes nothing.
#[test]
fn a_delta_of_nothing_is_empty() {
    let w = balloon(1);
    assert!(Delta::between(&w, &w, StateScope::All).is_empty());
}

/// A parameter change of the rigidity (a material field outside the version-1 material) is in
/// the delta even with scope `None`: undo brings the earlier value back, redo the new one.
#[test]
fn undoing_a_rigidity_change_brings_the_earlier_value_back() {
    let mut w = balloon(1);
    w.set_param(0, "rigidity", softsculpt::params::Value::Number(0.1)).unwrap();
    let before = w.clone();
    w.set_param(0, "rigidity", softsculpt::params::Value::Number(0.3)).unwrap();
    let undo = Delta::between(&before, &w, StateScope::None);
    assert!(!undo.is_empty() && !undo.is_whole());
    let undo = Delta::from_bytes(&undo.to_bytes()).unwrap();
    let redo = undo.apply(&mut w).unwrap();
    assert_eq!(w.bodies[0].material.rigidity, 0.1);
    assert!(w.snapshot() == before.snapshot());
    redo.apply(&mut w).unwrap();
    assert_eq!(w.bodies[0].material.rigidity, 0.3);
}

/// Bad bytes and deltas of another model are refused, naming why, and the world is untouched.
#[test]
fn foreign_or_damaged_deltas_are_refused_and_change_nothing() {
    let mut w = balloon(1);
    let before = w.clone();
    w.bodies[0].scale_rest_lengths(1.1).unwrap();
    let bytes = Delta::between(&before, &w, StateScope::All).to_bytes();
    let msg = |e: DeltaError| e.to_string();
    assert!(msg(Delta::from_bytes(b"hello").err().unwrap()).contains("SSDLT"));
    let mut flipped = bytes.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 1;
    assert!(msg(Delta::from_bytes(&flipped).err().unwrap()).contains("checksum"));
    assert!(Delta::from_bytes(&bytes[..bytes.len() - 3]).is_err());
    let mut newer = bytes.clone();
    newer[5] = 9;
    assert!(msg(Delta::from_bytes(&newer).err().unwrap()).contains("version 9"));
    // A balloon's delta on another mesh (fewer springs than the delta's indices reach).
    let mut other = World::single(SoftBody::new(&icosphere(0, 0.5), 1.0, Material::default()).unwrap(), WorldSettings::default());
    let snap = other.snapshot();
    let e = Delta::from_bytes(&bytes).unwrap().apply(&mut other).err().unwrap();
    assert!(matches!(e, DeltaError::DoesNotFit(_)), "{e}");
    assert!(other.snapshot() == snap);
    // Made for a body of the same size but another mesh (its triangles flipped): refused too.
    let mut flipped = balloon(1);
    let tris: Vec<[u32; 3]> = flipped.bodies[0].triangles().iter().map(|t| [t[0], t[2], t[1]]).collect();
    let x = flipped.bodies[0].positions().to_vec();
    flipped.bodies[0] = SoftBody::new(&softsculpt::TriMesh { positions: x, triangles: tris }, 1.0, Material::default()).unwrap();
    let snap = flipped.snapshot();
    let e = Delta::from_bytes(&bytes).unwrap().apply(&mut flipped).err().unwrap();
    assert!(matches!(e, DeltaError::DoesNotFit(_)), "{e}");
    assert!(flipped.snapshot() == snap);
    // Made for two bodies, applied to one.
    let mut two = balloon(1);
    two.add_body(SoftBody::new(&icosphere(1, 0.2), 1.0, Material::default()).unwrap());
    let two_before = two.clone();
    two.bodies[1].scale_rest_lengths(1.1).unwrap();
    let e = Delta::between(&two_before, &two, StateScope::All).apply(&mut w).err().unwrap();
    assert!(e.to_string().contains("2 bodies"), "{e}");
}

// ----- version-1 project files -------------------------------------------------------------

/// A version-1 project file as the modeler wrote it (web/src/project.ts before snapshots), for
/// body 0 of `w` with the page's parameter names and `ui`.
fn project_v1_text(w: &World) -> String {
    let b = &w.bodies[0];
    let g = b.gas_reference();
    let fg = b.frozen_gas_reference();
    let s = &w.settings;
    let pinned: Vec<u8> = (0..b.vertex_count()).map(|i| b.is_pinned(i) as u8).collect();
    let tris: Vec<u32> = b.triangles().iter().flatten().copied().collect();
    let m = &b.material;
    serde_json::json!({
        "format": "softsculpt-project", "version": 1, "name": "ball.obj",
        "body": {
            "triangles": tris, "pinned": pinned,
            "gas": [g.ambient_pressure, g.reference_volume], "frozenGas": [fg.ambient_pressure, fg.reference_volume],
            "params": {
                "stiffness": m.stiffness, "springDamping": m.spring_damping, "bendingStiffness": m.bending_stiffness,
                "damping": m.damping, "gravity": s.gravity, "gasAmount": m.gas_amount, "temperature": m.temperature,
                "volumeMode": 1, "windX": 0.5, "windY": 0, "windZ": 0, "windDrag": s.wind_drag,
                "groundOn": 1, "groundHeight": -0.6, "friction": 0.3, "integrator": 2, "selfCollision": 0
            },
            "positions": b.positions(), "velocities": b.velocities(), "restLengths": b.rest_lengths(),
            "masses": b.masses(), "frozenPositions": b.frozen_positions(), "frozenRestLengths": b.frozen_rest_lengths(),
            "prestress": b.prestress(), "frozenPrestress": b.frozen_prestress(),
            "bendingRestLengths": b.bending_rest_lengths(), "frozenBendingRestLengths": b.frozen_bending_rest_lengths()
        },
        "ui": { "dt": 0.0005, "substeps": 33, "realTime": true, "playing": false, "model": "ball.obj", "brush": { "radius": 0.2 } }
    })
    .to_string()
}

/// A saved version-1 project opens as a world in the saved state (shape, rest lengths, masses,
/// pins, gas references, parameters by their old names, dt from the page's settings) and steps
/// on exactly as the saved body does (same bits after 30 steps).
#[test]
fn a_version_1_project_opens_where_it_was_saved() {
    let mut w = balloon(2);
    w.settings.wind = [0.5, 0.0, 0.0];
    w.settings.ground = Some(Ground { height: -0.6, friction: 0.3, restitution: 0.0 });
    w.settings.integrator = softsculpt::Integrator::Rk4;
    w.settings.dt = 0.0005;
    w.bodies[0].material.volume_mode = softsculpt::VolumeMode::Box;
    w.step_n(40).unwrap();
    w.bodies[0].set_pinned(3, true).unwrap();
    let f = dab(&w.bodies[0], 5, 1.2);
    w.bodies[0].scale_rest_lengths_by_vertex(&f).unwrap();
    w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    w.step_n(10).unwrap();
    let text = project_v1_text(&w);
    let (mut opened, meta) = project_v1(text.as_bytes()).unwrap();
    assert_eq!(meta.name, "ball.obj");
    assert_eq!(meta.ui["brush"]["radius"], 0.2);
    let (a, b) = (&opened.bodies[0], &w.bodies[0]);
    assert_eq!(a.positions(), b.positions());
    assert_eq!(a.rest_lengths(), b.rest_lengths());
    assert_eq!(a.bending_rest_lengths(), b.bending_rest_lengths());
    assert_eq!(a.masses(), b.masses());
    assert!(a.is_pinned(3));
    assert_eq!(a.material, b.material);
    assert_eq!(opened.settings.dt, 0.0005);
    assert_eq!(opened.settings.integrator, softsculpt::Integrator::Rk4);
    assert_eq!(opened.settings.ground, w.settings.ground);
    opened.step_n(30).unwrap();
    w.step_n(30).unwrap();
    assert_eq!(opened.bodies[0].positions(), w.bodies[0].positions());
}

/// Broken or foreign project files get one message naming the problem.
#[test]
fn broken_version_1_projects_are_refused_naming_the_problem() {
    let err = |t: &str| project_v1(t.as_bytes()).err().unwrap();
    assert!(err("{ not json").contains("not JSON"));
    assert!(err(r#"{"format": "other"}"#).contains("not a SoftSculpt project"));
    assert!(err(r#"{"format": "softsculpt-project", "version": 7}"#).contains("version 7"));
    let good = project_v1_text(&balloon(1));
    let truncated = &good[..good.len() / 2];
    assert!(err(truncated).contains("not JSON"));
    let mut j: serde_json::Value = serde_json::from_str(&good).unwrap();
    j["body"]["masses"].as_array_mut().unwrap().pop();
    let e = err(&j.to_string());
    assert!(e.contains("pinned") || e.contains("mass"), "{e}");
    let mut j: serde_json::Value = serde_json::from_str(&good).unwrap();
    j["body"]["restLengths"].as_array_mut().unwrap().pop();
    assert!(err(&j.to_string()).contains("rest lengths"));
    let mut j: serde_json::Value = serde_json::from_str(&good).unwrap();
    j["body"]["params"]["integrator"] = serde_json::json!(9);
    assert!(err(&j.to_string()).contains("integrator"));
}
