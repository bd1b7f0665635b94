//! The material presets (`params/presets.rs`): each stable with the modeler's implicit steps on
//! every built-in model and after two subdivisions, and the same at either resolution.

mod common;

use softsculpt::mesh::builtin::builtin;
use softsculpt::params::presets::PRESETS;

const MATERIALS: [&str; 5] = ["balloon", "jelly", "clay", "cloth", "stiff_rubber"];

/// Height of the body's top above the ground (m).
fn top(w: &softsculpt::World) -> f64 {
    w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max)
}

/// Every material preset on every built-in model, as loaded and after two subdivisions (16× the
/// faces), 1 s of the modeler's implicit steps (60, a refused one split as the modeler splits
/// it: jelly's hinges on the subdivided mushroom need it once): every step converges, the state stays
/// finite, the volume stays within a factor 2 of the start (the gas presets hold it; cloth has
/// none, so only its height is bounded: it falls onto the ground, no higher than it started),
/// and the two resolutions agree, though at 1 s the bodies still move (up to 1.7 m/s: the gas
/// rounds the mushroom and the octopus, the stiff rubber still bounces), so the two are compared
/// mid-motion. On the sphere (642 and 10,242 vertices): the volume ratio and the height within
/// 15 % (measured ≤ 1.2 % for balloon, jelly and clay; 6.3 % and 8.5 % for the bouncing stiff
/// rubber). On the mushroom and the octopus: the volume ratio within 15 % (measured ≤ 9 %);
/// their heights are not compared: their thin parts carry no bending springs in these presets,
/// and a coarse mesh locks where a fine one buckles (stiff rubber's mushroom stem: upright at
/// 362 vertices, bent at 5,762 after 2 s).
#[test]
fn every_material_preset_is_stable_at_every_resolution() {
    for name in MATERIALS {
        assert!(PRESETS.iter().any(|p| p.name == name && p.is_material()), "{name}");
        for model in ["sphere", "mushroom", "octopus"] {
            let mesh = builtin(model).unwrap();
            let mut results = Vec::new();
            for subdivisions in [0, 2] {
                let mut w = common::on_ground(&mesh, subdivisions, name);
                let (v0, h0) = (w.bodies[0].exact_volume(), top(&w));
                // As the modeler steps (`World::advance`): a step the solver refuses is split
                // (up to dt/8) and first retried with hinges let go; counted, and printed.
                let budget = softsculpt::world::Budget { splits: 3, relax: true, ..softsculpt::world::Budget::converge() };
                let a = w.advance(1.0, &budget).unwrap_or_else(|e| panic!("{name} on {model} ×{subdivisions}: {e}"));
                let b = &w.bodies[0];
                assert!(b.is_finite(), "{name} on {model} ×{subdivisions}");
                let (ratio, height) = (b.exact_volume() / v0, top(&w) / h0);
                println!("{name:>12} {model:>8} ×{subdivisions}: {:>6} vertices, V/V0 {ratio:.3}, top/top0 {height:.3}, max speed {:.3}, split steps {}", b.vertex_count(), b.max_speed(), a.splits);
                if name == "cloth" {
                    assert!(height <= 1.01, "{name} on {model} ×{subdivisions}: rose to {height}× its height");
                } else {
                    assert!((0.5..2.0).contains(&ratio), "{name} on {model} ×{subdivisions}: volume ×{ratio}");
                }
                results.push((ratio, height));
            }
            if name != "cloth" {
                let ((r0, h0), (r2, h2)) = (results[0], results[1]);
                let (volume, height) = if model == "sphere" { (0.15, 0.15) } else { (0.15, f64::INFINITY) };
                assert!((r0 / r2 - 1.0).abs() < volume, "{name} on {model}: volume ratio {r0} vs {r2} after two subdivisions");
                assert!((h0 / h2 - 1.0).abs() < height, "{name} on {model}: height {h0} vs {h2} after two subdivisions");
            }
        }
    }
}

fn load(text: &str) -> Result<softsculpt::scene::SceneRun, softsculpt::scene::SceneError> {
    let mut resolve = |p: &str| -> Result<Vec<u8>, String> { Err(format!("no such file '{p}'")) };
    softsculpt::scene::SceneRun::load(text, &mut resolve)
}

/// A scene body's `preset` sets the preset's values except those the body gives itself
/// (`stiffness` here, the gas's `nrt`), `yield`, `flow` and the ellipsoid mode are read, and a
/// bad preset or value is refused naming the line and key.
#[test]
fn scene_bodies_take_presets_and_plasticity() {
    use softsculpt::params::Value;
    let run = load("[[body]]\nmodel = \"sphere\"\npreset = \"clay\"\nstiffness = 123\n\n[[body]]\nmodel = \"sphere\"\npreset = \"clay\"\ngas = { nrt = 7, volume = \"ellipsoid\" }\nflow = 1.5\n").unwrap();
    let w = &run.world;
    assert_eq!(w.param(0, "stiffness").unwrap(), Value::Number(123.0));
    assert_eq!(w.param(0, "damping").unwrap(), Value::Number(4.0));
    assert_eq!(w.param(0, "yield").unwrap(), Value::Number(0.005));
    assert!((w.bodies[0].material.nrt() - 20.0).abs() < 1e-12);
    assert!((w.bodies[1].material.nrt() - 7.0).abs() < 1e-12);
    assert_eq!(w.param(1, "gas.volume").unwrap(), Value::Choice("ellipsoid"));
    assert_eq!(w.param(1, "flow").unwrap(), Value::Number(1.5));
    assert_eq!(w.param(1, "stiffness").unwrap(), Value::Number(300.0));

    // Each cited at the line that sets it (line 3; the body's header is line 1).
    for (body, line, key, says) in [
        ("preset = \"marble\"", 3, "body[0].preset", "unknown preset 'marble'"),
        ("preset = \"modeler\"", 3, "body[0].preset", "a body takes a material preset"),
        ("yield = -0.1", 3, "body[0].yield", "must be 0 or more"),
        ("flow = nan", 3, "body[0].flow", "must be 0 or more"),
    ] {
        let e = load(&format!("[[body]]\nmodel = \"sphere\"\n{body}\n")).map(|_| ()).unwrap_err();
        assert_eq!((e.line, e.key.as_deref()), (Some(line), Some(key)), "{e}");
        assert!(e.to_string().contains(says), "{e}");
    }
}

/// Balloon, jelly and stiff rubber spring back from a press (their hinges, `presets.rs`): the
/// modeler's rooted mushroom (foot pinned), settled, its weight carried by a freeze under load
/// as the modeler applies a preset, then the preset, settled; a dent of 15 cm (cosine profile,
/// 35 cm radius) at its front-most point, let go: 5 s later the point is back within 5 mm
/// (issue #37; measured 0.5 mm balloon, 0.8 mm jelly, 0.1 mm stiff rubber; without hinges the
/// balloon kept 12.6 cm and jelly 14.1 cm: a snapped-through skin is an equilibrium too).
#[test]
fn a_dented_balloon_jelly_or_stiff_rubber_springs_back() {
    for preset in ["balloon", "jelly", "stiff_rubber"] {
        let mut w = common::rooted_mushroom();
        w.step_n(120).unwrap();
        w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
        w.apply_preset(0, preset).unwrap();
        // Jelly is barely damped (0.3 1/s): 10 s to settle before the press.
        w.step_n(600).unwrap();
        let x0 = w.bodies[0].positions().to_vec();
        let (x, c) = common::dented(&x0);
        w.bodies[0].set_state(&x, &vec![0.0; x.len()]).unwrap();
        w.step_n(300).unwrap();
        let left = x0[3 * c + 2] - w.bodies[0].positions()[3 * c + 2];
        assert!(left.abs() < 0.005, "{preset}: a dent of {left} m stayed");
    }
}

#[test]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_mushroom() {
    common::material_takes_the_tools("mushroom", 0);
}

#[test]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_sphere() {
    common::material_takes_the_tools("sphere", 0);
}

#[test]
fn each_material_takes_a_press_and_a_grab_as_named_on_the_octopus() {
    common::material_takes_the_tools("octopus", 0);
}

/// The same at a finer resolution: clay on the rooted mushroom subdivided twice (5,762
/// vertices) keeps the press and the pull as it does at 362 (the hinges' yield is a curvature,
/// the same at any resolution: `body/plastic.rs`). Measured 85 % and 88 % at a yield strain of
/// 1 % (82 % and 87 % at 362 vertices; 91 % and 96 % there at the preset's 0.5 %); bounds as
/// above.
#[test]
fn clay_keeps_a_press_and_a_grab_on_the_subdivided_mushroom() {
    for pull in [false, true] {
        let r = common::press_or_pull("clay", "mushroom", pull, 2, &[]);
        println!("clay mushroom ×2 pull {pull}: held {:+.4} m, after 5 s {:+.4} m, after 10 s {:+.4} m", r.held, r.at5, r.at10);
        assert!(r.held.abs() > 0.02 && r.at5 / r.held >= 0.7, "kept {} m of {} m", r.at5, r.held);
        assert!((r.at10 - r.at5).abs() < (0.02 * r.held.abs()).max(1e-3), "crept from {} m to {} m", r.at5, r.at10);
    }
}

/// The modeler's rooted mushroom with clay (`common::with_material`), its cap's rim — the
/// front-most vertex and those within 35 cm, weight (1 − (d/r)²)² — grabbed by the modeler's
/// target springs (m w ω², ω = 600 1/s, critically damped) and pulled 0.4 m straight down over
/// 0.5 s, held to 1 s, let go, stepped as the page steps. Returns the rim's fall (m, < 0 down)
/// at release, 5 s and 10 s after.
fn rim_pulled_down() -> (f64, f64, f64) {
    use softsculpt::body::Target;
    let (mut w, budget) = (common::with_material("clay", "mushroom", 0, &[]), common::page_budget());
    let x0 = w.bodies[0].positions().to_vec();
    let m = w.bodies[0].masses().to_vec();
    let n = m.len();
    let c = (0..n).max_by(|&p, &q| x0[3 * p + 2].total_cmp(&x0[3 * q + 2])).unwrap();
    let brush = common::brush_at(&x0, c, 0.35);
    let (omega, frame): (f64, f64) = (600.0, 1.0 / 60.0);
    for f in 0..60 {
        let down = 0.4 * ((f + 1) as f64 * frame / 0.5).min(1.0);
        let targets: Vec<Target> = brush
            .iter()
            .map(|&(i, wt)| Target { vertex: i, anchor: [x0[3 * i], x0[3 * i + 1] - down, x0[3 * i + 2]], stiffness: m[i] * wt * omega * omega, damping: 2.0 * m[i] * wt * omega })
            .collect();
        w.bodies[0].set_targets(&targets).unwrap();
        w.advance(frame, &budget).unwrap();
    }
    let fall = |w: &softsculpt::World| w.bodies[0].positions()[3 * c + 1] - x0[3 * c + 1];
    let held = fall(&w);
    w.bodies[0].clear_targets();
    w.advance(5.0, &budget).unwrap();
    let at5 = fall(&w);
    w.advance(5.0, &budget).unwrap();
    (held, at5, fall(&w))
}

/// Issue #37: clay keeps a rim pulled down (`rim_pulled_down`: the mushroom's cap pulled 0.4 m
/// down at its rim for 1 s). Bounds: ≥ 70 % of the pull kept 5 s after release (the issue's
/// bound, as for the press and the grab above; measured 77 %, 62 % with the yield strain at
/// 1 %, whose hinges sprang back by up to their yield angle each: `params/presets.rs`, `clay`),
/// and no creep after: from 5 s to 10 s less than 2 % of the pull or 1 mm (c = 4 1/s leaves
/// e^(−20) of any motion by then; measured < 0.1 mm).
#[test]
fn clay_keeps_a_rim_pulled_down_on_the_mushroom() {
    let (held, at5, at10) = rim_pulled_down();
    println!("clay mushroom rim pulled down: held {held:+.4} m, after 5 s {at5:+.4} m ({:.0} %), after 10 s {at10:+.4} m", 100.0 * at5 / held);
    assert!(held < -0.3, "the pull moved the rim only {held} m");
    assert!(at5 / held >= 0.7, "clay kept {at5} m of the rim's {held} m pull");
    assert!((at10 - at5).abs() < (0.02 * held.abs()).max(1e-3), "crept from {at5} m to {at10} m");
}

/// A square sheet of `n` × `n` cells, `side` m wide, level at height `y`, centred on the y axis.
fn sheet(n: usize, side: f64, y: f64) -> softsculpt::TriMesh {
    let h = side / n as f64;
    let positions = (0..=n).flat_map(|j| (0..=n).flat_map(move |i| [i as f64 * h - side / 2.0, y, j as f64 * h - side / 2.0])).collect();
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let triangles = (0..n).flat_map(|j| (0..n).flat_map(move |i| [[at(i, j), at(i, j + 1), at(i + 1, j)], [at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]])).collect();
    softsculpt::TriMesh { positions, triangles }
}

/// Cloth drapes (issue #37, item 1): a 2 m square sheet (20 × 20 cells, the cloth preset in the
/// world of a scene: symplectic Euler at 2e-4 s) let fall from 0.2 m above a 1 m square table (a
/// box whose top is at 0.5 m) comes to hang over it (measured: the corners 0.79 m below the middle, 8 cm/s, 4 % strain): after 6 s its middle rests on the table
/// (within 5 cm of its top: the contact thickness and the sag between vertices), its corners
/// hang far below (more than 0.3 m lower: its flaps reach 0.5–0.7 m past the table's edges; a
/// sheet that kept its shape would hold them level), it has nearly stopped (below 0.2 m/s: the
/// cloth's damping, c = 1 1/s, leaves e^(−6) of its fall's 3 m/s), and its weave barely
/// stretches (every edge within 10 % of its rest length: k = 400 N/m under 1 kg).
///
/// Not with the implicit integrator (the modeler's): there the obstacle is met only after each
/// 1/60 s step (the ground is inside the solve, `implicit/ground.rs`; obstacles are not), and
/// vertices near the table's edges end up under it, hooking the sheet — measured an edge
/// stretched 70 % and a vertex jittering at 2.3 m/s (over a ball: 227 %, 17 m/s). Left for
/// the obstacles to join the solve as the ground did.
#[test]
fn cloth_drapes_over_a_table() {
    use softsculpt::world::{Budget, Ground, Integrator, Obstacle};
    // A scene's world: explicit steps, gravity, the ground out of the way.
    let settings = softsculpt::WorldSettings { integrator: Integrator::Symplectic, dt: 2e-4, tolerance: 1e-3, gravity: 9.81, ground: Some(Ground::at(-2.0)), obstacles: vec![Obstacle::aabb([0.0, 0.0, 0.0], [0.5, 0.5, 0.5])], ..softsculpt::WorldSettings::default() };
    let mut body = softsculpt::SoftBody::new(&sheet(20, 2.0, 0.7), 1.0, softsculpt::Material::default()).unwrap();
    body.material.set_nrt(0.0);
    let mut w = softsculpt::World::single(body, settings);
    w.apply_preset(0, "cloth").unwrap();
    w.advance(6.0, &Budget { splits: 3, relax: true, ..Budget::converge() }).unwrap();
    let b = &w.bodies[0];
    let x = b.positions();
    let (middle, corner) = (x[3 * (10 * 21 + 10) + 1], x[1]);
    let stretch = {
        let (i, j) = b.spring_ends();
        (0..i.len())
            .map(|e| {
                let (p, q) = (3 * i[e] as usize, 3 * j[e] as usize);
                (((x[q] - x[p]).powi(2) + (x[q + 1] - x[p + 1]).powi(2) + (x[q + 2] - x[p + 2]).powi(2)).sqrt() / b.rest_lengths()[e] - 1.0).abs()
            })
            .fold(0.0, f64::max)
    };
    println!("cloth over the table: middle at {middle} m, a corner at {corner} m, largest speed {} m/s, largest strain {stretch}", b.max_speed());
    assert!((middle - 0.5).abs() < 0.05, "the middle is at {middle} m, the table's top at 0.5 m");
    assert!(middle - corner > 0.3, "the corners hang only {} m below the middle", middle - corner);
    assert!(b.max_speed() < 0.2, "still moving at {} m/s", b.max_speed());
    assert!(stretch < 0.1, "an edge stretched by {stretch}");
}
