//! Stepping with rollback: a failed `World::step_n` leaves the whole world as it was before the
//! call — states, clock, fired events and their effects, loads.

use softsculpt::scene::SceneRun;
use softsculpt::world::World;

/// A balloon under explicit Euler whose events freeze it (0.03 s), push it (0.04 s on, a load),
/// turn the wind on (0.05 s) and then pump in a thousand times its gas (0.08 s): it blows up a
/// few steps later.
const SCENE: &str = r#"
[world]
dt = 0.001
duration = 1.0
integrator = "euler"
gravity = 0.0

[[body]]
name = "balloon"
model = "sphere"
stiffness = 100.0
spring_damping = 0.1
gas = { nrt = 20.0 }

[[event]]
time = 0.03
action = "freeze"
under_load = false

[[event]]
time = 0.04
action = "force"
region = { all = true }
force = [0.0, 1.0, 0.0]

[[event]]
time = 0.05
action = "set_wind"
wind = [3.0, 0.0, 0.0]

[[event]]
time = 0.08
action = "set_gas"
nrt = 2e7
"#;

fn world() -> World {
    let mut resolve = |p: &str| Err(format!("no file {p}"));
    SceneRun::load(SCENE, &mut resolve).unwrap_or_else(|e| panic!("{e}")).world
}

/// Everything a step can change, as bits: states, rest lengths, frozen shape, gas, user forces
/// (the loads' effect), material, wind, clock, pending events.
fn fingerprint(w: &World) -> Vec<u64> {
    let b = &w.bodies[0];
    let mut out: Vec<u64> = [b.positions(), b.velocities(), b.rest_lengths(), b.frozen_positions(), b.frozen_rest_lengths()]
        .iter()
        .flat_map(|a| a.iter().map(|x| x.to_bits()))
        .collect();
    let g = b.gas_reference();
    out.extend([g.ambient_pressure, g.reference_volume, b.material.gas_amount, b.material.temperature].map(f64::to_bits));
    out.extend(w.settings.wind.map(f64::to_bits));
    out.extend([w.steps(), w.time().to_bits(), w.pending_events() as u64]);
    out
}

#[test]
fn a_blow_up_mid_scene_rolls_back_the_clock_the_fired_events_and_their_effects() {
    let mut w = world();
    w.step_n(20).unwrap();
    let before = fingerprint(&w);
    assert_eq!(w.pending_events(), 4);

    let err = w.step_n(500).expect_err("a thousand times the gas under explicit Euler blows up");
    let msg = err.to_string();
    eprintln!("{msg}");
    // It failed after the gas event (0.08 s) and within the call's 0.5 s.
    assert!(err.time > 0.08 && err.time < 0.52, "failed at {} s", err.time);
    // The message names the simulated time with three significant digits, and the time the
    // world went back to (0.02 s, written "0.0200").
    assert!(msg.starts_with(&format!("at t = {} s: ", softsculpt::world::sig3(err.time))), "{msg}");
    assert!(msg.contains("rolled back to t = 0.0200 s"), "{msg}");
    // Everything is back, bit for bit: the freeze, the load, the wind and the gas undone, the
    // events pending again, the clock at step 20.
    assert_eq!(fingerprint(&w), before);
    assert_eq!(w.steps(), 20);

    // And the world steps on from there exactly as a fresh run does.
    let mut fresh = world();
    fresh.step_n(20).unwrap();
    w.step_n(40).unwrap();
    fresh.step_n(40).unwrap();
    assert_eq!(fingerprint(&w), fingerprint(&fresh));
}

#[test]
fn a_failing_call_without_events_rolls_back_positions_velocities_and_clock() {
    let mut w = world();
    w.set_events(Vec::new());
    w.step_n(10).unwrap();
    let before = fingerprint(&w);
    w.settings.dt = 0.5; // far beyond the stability limit of explicit Euler
    let err = w.step_n(200).expect_err("dt = 0.5 s blows up");
    assert!(err.rolled_back_to == Some(0.01), "{err:?}");
    assert_eq!(fingerprint(&w), before);
}

#[test]
fn three_significant_digits() {
    use softsculpt::world::sig3;
    assert_eq!(sig3(0.25), "0.250");
    assert_eq!(sig3(12.0), "12.0");
    assert_eq!(sig3(1234.5), "1230");
    assert_eq!(sig3(0.000123456), "0.000123");
    assert_eq!(sig3(0.0), "0");
}
