//! Plasticity ("clay", `body/plastic.rs`): rest lengths flow where the strain exceeds the yield
//! strain, the gas reference follows, the energy removed is accounted for.

mod common;
use common::*;
use softsculpt::body::{Material, SoftBody};
use softsculpt::world::{Integrator, World, WorldSettings};

/// The clay preset's skin and gas on a unit icosphere (162 vertices), elastic until `yield` and
/// `flow` are set.
fn clay_ball() -> SoftBody {
    let mut m = Material { stiffness: 300.0, spring_damping: 0.5, damping: 4.0, ..bare() };
    m.set_nrt(20.0);
    sphere_body(2, 1.0, m)
}

/// The vertices of the caps y > 0.9 (pushed) and y < −0.8 (pinned).
fn cap(b: &SoftBody) -> (Vec<usize>, Vec<usize>) {
    let y = |i: usize| b.positions()[3 * i + 1];
    ((0..b.vertex_count()).filter(|&i| y(i) > 0.9).collect(), (0..b.vertex_count()).filter(|&i| y(i) < -0.8).collect())
}

/// Distance between the mean heights of the two caps (m).
fn cap_height(b: &SoftBody, cap: &(Vec<usize>, Vec<usize>)) -> f64 {
    let mean = |c: &[usize]| c.iter().map(|&i| b.positions()[3 * i + 1]).sum::<f64>() / c.len() as f64;
    mean(&cap.0) - mean(&cap.1)
}

/// Squeeze the caps together with `force` N on each (no net force) for `seconds`, then let go
/// for `settle` seconds; returns the gap under the squeeze.
fn push(w: &mut World, cap: &(Vec<usize>, Vec<usize>), force: f64, seconds: f64, settle: f64) -> f64 {
    let dt = w.settings.dt;
    let mut f = vec![0.0; 3 * w.bodies[0].vertex_count()];
    for &i in &cap.0 {
        f[3 * i + 1] = -force / cap.0.len() as f64;
    }
    for &i in &cap.1 {
        w.bodies[0].set_pinned(i, true).unwrap();
    }
    w.bodies[0].set_user_forces(&f).unwrap();
    w.step_n((seconds / dt).round() as u64).unwrap();
    let pushed = cap_height(&w.bodies[0], cap);
    f.fill(0.0);
    w.bodies[0].set_user_forces(&f).unwrap();
    w.step_n((settle / dt).round() as u64).unwrap();
    pushed
}

/// Largest |l/L − 1| over the edge springs.
fn max_strain(b: &SoftBody) -> f64 {
    let (i, j) = b.spring_ends();
    let x = b.positions();
    (0..i.len())
        .map(|e| {
            let (a, c) = (3 * i[e] as usize, 3 * j[e] as usize);
            let l = ((x[c] - x[a]).powi(2) + (x[c + 1] - x[a + 1]).powi(2) + (x[c + 2] - x[a + 2]).powi(2)).sqrt();
            (l / b.rest_lengths()[e] - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

fn settings(integrator: Integrator) -> WorldSettings {
    let dt = if integrator == Integrator::Implicit { 1.0 / 60.0 } else { 1e-3 };
    WorldSettings { integrator, dt, tolerance: 1e-6, ..still() }
}

/// An inflated clay ball at rest: its elastic equilibrium under the gas, then frozen.
fn resting(integrator: Integrator) -> World {
    let mut w = alone(clay_ball(), settings(integrator));
    w.step_n((3.0 / w.settings.dt) as u64).unwrap();
    w
}

/// Both integrators the modeler and the CLI use.
const INTEGRATORS: [Integrator; 2] = [Integrator::Symplectic, Integrator::Implicit];

/// A plastic copy of the resting ball: yield strain `y`, flow rate `flow` (1/s).
fn plastic(w: &World, y: f64, flow: f64) -> World {
    let mut w = w.clone();
    w.set_param(0, "yield", softsculpt::params::Value::Number(y)).unwrap();
    w.set_param(0, "flow", softsculpt::params::Value::Number(flow)).unwrap();
    w
}

/// Below the yield strain the stage does nothing: a 5 N push on the top cap (bottom pinned)
/// for 1 s, strain staying below the 5 % yield strain, leaves every rest length bit for bit as
/// it was, so the ball springs back to its elastic equilibrium. Tolerance: what 3 s of settling
/// leaves, 1e-4 m (the damping c = 4 1/s leaves e^(−12) of a 0.3 m dent, 2e-6 m, and symplectic
/// Euler's slow modes a little more).
#[test]
fn below_the_yield_strain_a_push_springs_back_fully() {
    for integrator in INTEGRATORS {
        let rest = resting(integrator);
        let c = cap(&rest.bodies[0]);
        let gap0 = cap_height(&rest.bodies[0], &c);
        let mut w = plastic(&rest, 0.05, 2.0);
        let rest_lengths = w.bodies[0].rest_lengths().to_vec();
        let pushed = push(&mut w, &c, 5.0, 1.0, 3.0);
        assert!(gap0 - pushed > 0.2, "{integrator:?}: the push should dent the ball, by {}", gap0 - pushed);
        assert_eq!(w.bodies[0].rest_lengths(), &rest_lengths[..], "{integrator:?}: nothing may flow below the yield strain");
        assert_eq!(w.bodies[0].plastic_dissipation(), 0.0);
        let left = gap0 - cap_height(&w.bodies[0], &c);
        assert!(left.abs() < 1e-4, "{integrator:?}: a dent of {left} m stayed");
    }
}

/// Beyond the yield strain (0.1 %, below the gas's own 0.56 % at rest, so the skin has relaxed
/// to nearly slack before the push) the same push leaves a dent, and a longer push a deeper one:
/// the flow takes 1/φ = 0.5 s, so a 0.2 s push flows a part of what a 1 s push flows. Measured:
/// 0.45 m and 0.62 m (symplectic), 0.34 m and 0.60 m (implicit); bounds: more than 5 cm after 0.2 s
/// (the elastic run above leaves < 0.1 mm) and 20 % more after 1 s.
#[test]
fn beyond_the_yield_strain_the_dent_stays_and_grows_with_the_push() {
    for integrator in INTEGRATORS {
        let rest = resting(integrator);
        let c = cap(&rest.bodies[0]);
        let relaxed = {
            let mut w = plastic(&rest, 0.001, 2.0);
            w.step_n((3.0 / w.settings.dt) as u64).unwrap();
            w
        };
        let gap0 = cap_height(&relaxed.bodies[0], &c);
        let dent = |seconds: f64| {
            let mut w = relaxed.clone();
            push(&mut w, &c, 5.0, seconds, 3.0);
            gap0 - cap_height(&w.bodies[0], &c)
        };
        let (short, long) = (dent(0.2), dent(1.0));
        println!("{integrator:?}: dent after 0.2 s {short} m, after 1 s {long} m");
        assert!(short > 0.05, "{integrator:?}: a 0.2 s push left {short} m");
        assert!(long > 1.2 * short, "{integrator:?}: a 1 s push left {long} m, a 0.2 s one {short} m");
    }
}

/// A ball at rest whose gas strains the skin (0.56 %) beyond the yield strain (0.3 %): the
/// rest lengths flow until every strain is the yield strain, and the gas reference follows
/// (`plastic.rs`), so the ball only evens out its tension and stops. Were the reference fixed,
/// the gas would keep stretching the relaxed skin: at equilibrium the strain of a sphere goes as
/// P R / L ∝ R⁻³, so it would grow until (ε0/ε_y)^(1/3) = 1.23 × its radius, ×1.87 its volume.
/// Measured: volume +0.05 %, largest displacement 2.0, 2.3, 2.5 mm after 2, 4, 8 s (the
/// strains' last approach to the yield strain). Bounds: volume within 0.1 %, displacement
/// within 5 mm, and from 4 s to 8 s less than 10 % of what came before (it settles, it does not
/// creep).
#[test]
fn a_plastic_body_at_rest_under_its_gas_does_not_creep() {
    for integrator in INTEGRATORS {
        let rest = resting(integrator);
        let (v0, x0) = (rest.bodies[0].exact_volume(), rest.bodies[0].positions().to_vec());
        let mut w = plastic(&rest, 0.003, 2.0);
        w.step_n((4.0 / w.settings.dt) as u64).unwrap();
        let x4 = w.bodies[0].positions().to_vec();
        w.step_n((4.0 / w.settings.dt) as u64).unwrap();
        let b = &w.bodies[0];
        let (moved4, later) = (max_abs_diff(&x4, &x0), max_abs_diff(b.positions(), &x4));
        assert!(b.plastic_dissipation() != 0.0, "{integrator:?}: the skin should have flowed");
        assert!(max_strain(b) < 0.0031, "{integrator:?}: strain {} should be at the yield strain", max_strain(b));
        assert!((b.exact_volume() / v0 - 1.0).abs() < 1e-3, "{integrator:?}: volume {} from {v0}", b.exact_volume());
        assert!(moved4 < 5e-3 && later < 0.1 * moved4, "{integrator:?}: moved {moved4} m in 4 s, then {later} m");
    }
}

/// Largest |E(t) + D(t) − E(0)| over `steps` steps of 1e-4 s of symplectic Euler (E: kinetic
/// + elastic + gas energy, D: the plastic dissipation), and D at the end.
fn energy_balance(mut body: SoftBody, y: f64, flow: f64, steps: usize) -> (f64, f64) {
    body.material.yield_strain = y;
    body.material.flow_rate = flow;
    swirl(&mut body, 2.0);
    let mut w = alone(body, WorldSettings { dt: 1e-4, ..still() });
    let e0 = w.stats(0).total_energy;
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        w.step().unwrap();
        let s = w.stats(0);
        worst = worst.max((s.total_energy + s.plastic_dissipation - e0).abs());
    }
    (worst, w.bodies[0].plastic_dissipation())
}

/// The energy the plastic stage removes is accounted for: with no damping, kinetic + elastic
/// (+ gas) energy plus the plastic dissipation stays what it was, up to the integrator's own
/// error. That error is measured on the same run with plasticity off (symplectic Euler's energy
/// oscillates by O(dt) without drifting); the stage itself is exact at fixed positions
/// (½k[(l−L)² − (l−L')²] is the integral of k (l − L) dL along the flow), so the plastic run may
/// only show the same kind of error: bound 3× the elastic run's plus 1e-3 of the dissipation
/// (the stage acts at the step's end, the statistics see the integrator's half-step offset).
/// The dissipation must be a sizable part of the energy for the test to mean anything.
/// With hinges (D = 0.5 J, a plate 21 cm thick on k = 100 N/m, yield curvature 0.19 1/m at
/// ε_y = 2 %) their rest angles flow too, and their released bending energy is in the
/// dissipation as well: the same bound.
#[test]
fn the_energy_removed_is_the_plastic_dissipation() {
    for (nrt, rigidity) in [(0.0, 0.0), (5.0, 0.0), (5.0, 0.5)] {
        let mut m = Material { rigidity, ..bare() };
        m.set_nrt(nrt);
        let body = sphere_body(2, 1.0, m);
        let e0 = {
            let mut b = body.clone();
            swirl(&mut b, 2.0);
            alone(b, still()).stats(0).kinetic_energy
        };
        let hinges = body.hinge_rest_angles().to_vec();
        let (elastic, none) = energy_balance(body.clone(), 0.0, 0.0, 10_000);
        let (plastic, dissipated) = energy_balance(body.clone(), 0.02, 5.0, 10_000);
        if rigidity > 0.0 {
            let mut flowed = body;
            flowed.material.yield_strain = 0.02;
            flowed.material.flow_rate = 5.0;
            swirl(&mut flowed, 2.0);
            let mut w = alone(flowed, WorldSettings { dt: 1e-4, ..still() });
            w.step_n(10_000).unwrap();
            let moved = w.bodies[0].hinge_rest_angles().iter().zip(&hinges).filter(|(a, b)| a != b).count();
            assert!(moved > hinges.len() / 10, "only {moved} of {} hinges flowed", hinges.len());
        }
        println!("nRT {nrt}, D {rigidity}: kinetic {e0} J, elastic run error {elastic} J, plastic run error {plastic} J, dissipated {dissipated} J");
        assert_eq!(none, 0.0);
        assert!(dissipated > 0.1 * e0, "nRT {nrt}, D {rigidity}: only {dissipated} J of {e0} J flowed");
        assert!(plastic < 3.0 * elastic + 1e-3 * dissipated, "nRT {nrt}, D {rigidity}: energy off by {plastic} J (elastic run {elastic} J)");
    }
}

/// A plastic world continues exactly from its snapshot (version 3 keeps the yield strain, the
/// flow rate, the dissipation and the ellipsoid mode; the flowing rest lengths and the gas
/// reference are in the version-1 part), and an undo delta taken over steps that flowed puts
/// the rest lengths, gas reference, dissipation and parameters back bit for bit.
#[test]
fn snapshots_and_undo_keep_the_plastic_state() {
    use softsculpt::delta::{Delta, StateScope};
    use softsculpt::params::Value;
    let mut w = plastic(&resting(Integrator::Symplectic), 0.001, 2.0);
    w.set_param(0, "gas.volume", Value::Choice("ellipsoid")).unwrap();
    w.step_n(200).unwrap();
    let mut restored = World::restore(&w.snapshot()).unwrap();
    assert_eq!(restored.param(0, "yield").unwrap(), Value::Number(0.001));
    assert_eq!(restored.param(0, "gas.volume").unwrap(), Value::Choice("ellipsoid"));
    let before = w.clone();
    w.step_n(200).unwrap();
    restored.step_n(200).unwrap();
    let (a, b) = (&w.bodies[0], &restored.bodies[0]);
    assert_eq!(a.positions(), b.positions());
    assert_eq!(a.rest_lengths(), b.rest_lengths());
    assert_eq!(a.gas_reference(), b.gas_reference());
    assert_eq!(a.plastic_dissipation(), b.plastic_dissipation());
    assert_ne!(a.rest_lengths(), before.bodies[0].rest_lengths(), "the steps should have flowed");

    let undo = Delta::between(&before, &w, StateScope::All);
    let redo = undo.apply(&mut w).unwrap();
    let (a, b) = (&w.bodies[0], &before.bodies[0]);
    assert_eq!(a.rest_lengths(), b.rest_lengths());
    assert_eq!(a.bending_rest_lengths(), b.bending_rest_lengths());
    assert_eq!(a.gas_reference(), b.gas_reference());
    assert_eq!(a.plastic_dissipation(), b.plastic_dissipation());
    assert_eq!(a.positions(), b.positions());
    redo.apply(&mut w).unwrap();
    assert_eq!(w.bodies[0].rest_lengths(), restored.bodies[0].rest_lengths());

    // A parameter change alone (scope none): the yield strain and flow rate come back.
    let mark = w.clone();
    w.set_param(0, "yield", Value::Number(0.05)).unwrap();
    w.set_param(0, "flow", Value::Number(0.0)).unwrap();
    Delta::between(&mark, &w, StateScope::None).apply(&mut w).unwrap();
    assert_eq!(w.bodies[0].material.yield_strain, 0.001);
    assert_eq!(w.bodies[0].material.flow_rate, 2.0);
}

/// A call of `step_n` that fails leaves the world as it was, rest lengths included.
#[test]
fn a_rolled_back_call_restores_the_rest_lengths() {
    let mut m = Material { stiffness: 1e6, ..bare() };
    m.set_nrt(2.0);
    let mut body = sphere_body(2, 1.0, m);
    swirl(&mut body, 1.0);
    let mut w = plastic(&alone(body, WorldSettings { dt: 1e-2, ..still() }), 0.0, 50.0);
    let before = w.clone();
    assert!(w.step_n(1000).is_err(), "k = 1e6 at dt = 1e-2 must blow up");
    assert_eq!(w.bodies[0].rest_lengths(), before.bodies[0].rest_lengths());
    assert_eq!(w.bodies[0].gas_reference(), before.bodies[0].gas_reference());
    assert_eq!(w.bodies[0].positions(), before.bodies[0].positions());
}

/// Negative or non-finite yield strains and flow rates are refused naming the parameter, by id
/// and on the material (a step checks it), and nothing changes.
#[test]
fn bad_yield_and_flow_are_refused() {
    use softsculpt::params::Value;
    let mut w = alone(clay_ball(), still());
    for id in ["yield", "flow"] {
        for bad in [-0.1, f64::NAN, f64::INFINITY] {
            let e = w.set_param(0, id, Value::Number(bad)).unwrap_err().to_string();
            assert!(e.starts_with(id) && e.contains("≥ 0"), "{e}");
        }
        assert_eq!(w.param(0, id).unwrap(), Value::Number(0.0));
    }
    w.bodies[0].material.flow_rate = -1.0;
    let e = w.step().unwrap_err().to_string();
    assert!(e.starts_with("flow") && e.contains("≥ 0"), "{e}");
}

/// The modeler's clay mushroom (the `modeler` world, settled on the ground, frozen under load,
/// then `clay` with the gas's push kept — what the page's material switch does), pulled by a
/// mirrored grab: target springs of ω = 600 1/s on the vertices within 0.35 m of the cap's rim
/// on both sides, their anchors moved 0.42 m up and 0.42 m out over 0.5 s and held 1 s, then let
/// go for 2 s. Returns the least volume under the pull and the volume at the end (m³); checks
/// after every step that the flow never raised P_ref past P (the gas never sucks).
fn pulled_clay_mushroom(plastic: bool) -> (f64, f64) {
    use softsculpt::body::{FreezeOptions, GasReference, Target};
    let mut mesh = softsculpt::mesh::builtin::builtin("mushroom").unwrap();
    let (lo, hi) = softsculpt::mesh::bounds(&mesh.positions);
    let centre = [(lo[0] + hi[0]) / 2.0, lo[1], (lo[2] + hi[2]) / 2.0];
    for p in mesh.positions.chunks_exact_mut(3) {
        (0..3).for_each(|d| p[d] -= centre[d]);
    }
    let mut w = alone(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.step_n(180).unwrap();
    w.freeze(0, FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    let push = w.stats(0).pressure - w.bodies[0].gas_reference().ambient_pressure;
    w.apply_preset(0, "clay").unwrap();
    let gas = GasReference { ambient_pressure: (w.stats(0).pressure - push).max(0.0), ..w.bodies[0].gas_reference() };
    w.bodies[0].set_gas_reference(gas).unwrap();
    if !plastic {
        w.set_param(0, "flow", softsculpt::params::Value::Number(0.0)).unwrap();
    }
    let (x, m) = (w.bodies[0].positions().to_vec(), w.bodies[0].masses().to_vec());
    let n = m.len();
    println!("volume before the pull: {} m³", w.bodies[0].exact_volume());
    let rim = (0..n).max_by(|&a, &b| (x[3 * a] + x[3 * a + 1]).total_cmp(&(x[3 * b] + x[3 * b + 1]))).unwrap();
    let grabbed: Vec<(usize, f64, f64)> = [1.0, -1.0]
        .iter()
        .flat_map(|&side| {
            let (x, rim) = (&x, rim);
            (0..n).filter_map(move |i| {
                let d = ((x[3 * i] - side * x[3 * rim]).powi(2) + (x[3 * i + 1] - x[3 * rim + 1]).powi(2) + (x[3 * i + 2] - x[3 * rim + 2]).powi(2)).sqrt();
                (d < 0.35).then(|| (i, (1.0 - d * d / (0.35 * 0.35)).powi(2), side))
            })
        })
        .collect();
    let omega: f64 = 600.0;
    let budget = softsculpt::world::Budget { splits: 3, relax: true, ..softsculpt::world::Budget::converge() };
    let (mut least, mut ambient) = (f64::INFINITY, w.bodies[0].gas_reference().ambient_pressure);
    for step in 0..270 {
        if step < 90 {
            let f = ((step + 1) as f64 / 30.0).min(1.0) * 0.42;
            let targets: Vec<Target> = grabbed
                .iter()
                .map(|&(i, wt, side)| Target { vertex: i, anchor: [x[3 * i] + side * f, x[3 * i + 1] + f, x[3 * i + 2]], stiffness: m[i] * wt * omega * omega, damping: 2.0 * m[i] * wt * omega })
                .collect();
            w.bodies[0].set_targets(&targets).unwrap();
        } else if step == 90 {
            w.bodies[0].clear_targets();
        }
        // As the page steps: a step that does not finish is split or retried with crushed hinges
        // let go (`World::advance`).
        w.advance(w.settings.dt, &budget).unwrap();
        let (p, now) = (w.stats(0).pressure, w.bodies[0].gas_reference().ambient_pressure);
        // Rounding of P_ref's update: a few ulps of P.
        assert!(now <= ambient.max(p * (1.0 + 1e-12)), "step {step}: P_ref rose to {now} Pa past the gas's {p} Pa");
        ambient = now;
        if step < 90 {
            least = least.min(w.bodies[0].exact_volume());
        }
    }
    (least, w.bodies[0].exact_volume())
}

/// A hard, mirrored pull on the modeler's clay mushroom leaves the pulled shape and the gas in
/// it: the flow credits P_ref only with the gas's share of the stretched springs' tension, and
/// never past P (`body/plastic.rs`, "The gas's share"). Crediting it with every flow (before)
/// ran P_ref to thousands of Pa and crushed the body (0.3 % of its volume; the step then failed).
/// Bounds: the clay body may keep what the pull did — down to the least volume the same pull
/// gives the elastic body (measured 1.98 of 2.46 m³; 1.53 before clay had hinges) — less 10 %
/// for a plastic body pulled a little differently (it yields as it is pulled); measured 2.34 m³
/// at the end (1.78 without hinges).
#[test]
fn a_pulled_clay_body_keeps_its_gas_and_the_pulled_shape() {
    let (elastic_least, _) = pulled_clay_mushroom(false);
    let (_, clay_end) = pulled_clay_mushroom(true);
    println!("least volume under the pull, elastic: {elastic_least} m³; clay after it: {clay_end} m³");
    assert!(clay_end >= 0.9 * elastic_least, "the clay body lost more than the pull took: {clay_end} m³ against {elastic_least} m³");
}

/// The clay ball (#37): the clay preset on a unit ball of 642 vertices, its bottom cap
/// pinned, no gravity, implicit steps of 1/60 s; the vertices within 0.6 m of its top pressed
/// down (target springs of ω = 600 1/s, anchors 0.6 m × (1 − (d/0.6)²)² below where they were)
/// for 1 s, let go. Returns the dent at the top under the press and 5 s and 10 s after release.
fn pressed_clay_ball(rigidity: f64) -> (f64, f64, f64) {
    use softsculpt::body::Target;
    let mut w = alone(sphere_body(3, 1.0, bare()), WorldSettings { integrator: Integrator::Implicit, dt: 1.0 / 60.0, tolerance: 1e-6, ..still() });
    w.apply_preset(0, "clay").unwrap();
    for (id, v) in [("rigidity", rigidity), ("gas.nrt", 8.0), ("yield", 0.02)] {
        w.set_param(0, id, softsculpt::params::Value::Number(v)).unwrap();
    }
    let n = w.bodies[0].vertex_count();
    for i in 0..n {
        if w.bodies[0].positions()[3 * i + 1] < -0.9 {
            w.bodies[0].set_pinned(i, true).unwrap();
        }
    }
    w.step_n(120).unwrap();
    let (x0, m) = (w.bodies[0].positions().to_vec(), w.bodies[0].masses().to_vec());
    let top = (0..n).max_by(|&a, &b| x0[3 * a + 1].total_cmp(&x0[3 * b + 1])).unwrap();
    let omega: f64 = 600.0;
    let targets: Vec<Target> = (0..n)
        .filter_map(|i| {
            let d = (0..3).map(|k| (x0[3 * i + k] - x0[3 * top + k]).powi(2)).sum::<f64>().sqrt();
            let anchor = [x0[3 * i], x0[3 * i + 1] - 0.6 * (1.0 - d * d / 0.36).powi(2), x0[3 * i + 2]];
            (d < 0.6).then(|| Target { vertex: i, anchor, stiffness: m[i] * omega * omega, damping: 2.0 * m[i] * omega })
        })
        .collect();
    w.bodies[0].set_targets(&targets).unwrap();
    w.step_n(60).unwrap();
    let dent = |w: &World| x0[3 * top + 1] - w.bodies[0].positions()[3 * top + 1];
    let held = dent(&w);
    w.bodies[0].clear_targets();
    w.step_n(300).unwrap();
    let at5 = dent(&w);
    w.step_n(300).unwrap();
    (held, at5, dent(&w))
}

/// A potter's dent is a bending change (`body/plastic.rs`, "Bending"): pressed 0.6 m deep for
/// 1 s, the clay ball keeps its dent with its hinges' rest angles flowing, and without hinges
/// it springs back (the inverted cap is nearly isometric, so hardly a spring passed the yield
/// strain; the issue measured all of it back). Measured: kept 0.xx of 0.yy m with hinges, 0.zz
/// m without. Bounds: the goal, ≥ 70 % kept 5 s after release, and no creep after:
/// from 5 s to 10 s less than 1 % of the dent (the flow has stopped once every hinge is within
/// its yield angle; the damped body has settled: c = 4 1/s leaves e^(−20) of any motion).
#[test]
fn a_pressed_clay_ball_keeps_its_dent_by_its_hinges() {
    let (held, at5, at10) = pressed_clay_ball(softsculpt::params::presets::CLAY_RIGIDITY);
    let (held0, at5_0, _) = pressed_clay_ball(0.0);
    println!("with hinges: pressed {held} m, {at5} m after 5 s, {at10} m after 10 s; without: pressed {held0} m, {at5_0} m after 5 s");
    assert!(held > 0.4, "the press should go deep: {held} m");
    assert!(at5 >= 0.7 * held, "kept {at5} m of {held} m");
    assert!((at10 - at5).abs() < 0.01 * held, "crept from {at5} m to {at10} m");
    assert!(at5_0 < at5, "without hinges {at5_0} m, with {at5} m");
}

/// The hinges' flowed rest angles are state like the rest lengths: a snapshot keeps them
/// (version 7) and the restored world continues bit for bit; an undo delta over steps that
/// flowed them puts them back, and its redo brings them again; a rollback of a failed call puts
/// them back too (`PlasticState`); a reset returns them to the frozen shape's.
#[test]
fn flowed_hinge_rest_angles_are_kept_by_snapshots_undo_and_rollback() {
    use softsculpt::delta::{Delta, StateScope};
    let mut m = Material { rigidity: 0.5, yield_strain: 0.02, flow_rate: 5.0, ..bare() };
    m.set_nrt(5.0);
    let mut body = sphere_body(2, 1.0, m);
    let frozen = body.hinge_rest_angles().to_vec();
    swirl(&mut body, 2.0);
    let mut w = alone(body, WorldSettings { dt: 1e-4, ..still() });
    w.step_n(2000).unwrap();
    let before = w.clone();
    w.step_n(2000).unwrap();
    assert_ne!(w.bodies[0].hinge_rest_angles(), before.bodies[0].hinge_rest_angles(), "the steps should have flowed the hinges");
    let mut restored = World::restore(&w.snapshot()).unwrap();
    assert_eq!(restored.bodies[0].hinge_rest_angles(), w.bodies[0].hinge_rest_angles());
    let after = w.clone();
    w.step_n(500).unwrap();
    restored.step_n(500).unwrap();
    assert_eq!(w.bodies[0].positions(), restored.bodies[0].positions());
    assert_eq!(w.bodies[0].hinge_rest_angles(), restored.bodies[0].hinge_rest_angles());

    let mut u = after.clone();
    let undo = Delta::between(&before, &u, StateScope::All);
    let redo = undo.apply(&mut u).unwrap();
    assert_eq!(u.bodies[0].hinge_rest_angles(), before.bodies[0].hinge_rest_angles());
    redo.apply(&mut u).unwrap();
    assert_eq!(u.bodies[0].hinge_rest_angles(), after.bodies[0].hinge_rest_angles());

    // A call that fails (k = 1e6 at this dt blows up) is rolled back whole.
    let mut r = after.clone();
    r.set_param(0, "stiffness", softsculpt::params::Value::Number(1e6)).unwrap();
    let mark = r.bodies[0].hinge_rest_angles().to_vec();
    assert!(r.step_n(1000).is_err());
    assert_eq!(r.bodies[0].hinge_rest_angles(), &mark[..]);

    let mut reset = after.clone();
    reset.bodies[0].reset();
    assert_eq!(reset.bodies[0].hinge_rest_angles(), &frozen[..]);
}
