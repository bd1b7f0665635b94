//! Helpers shared by the physics tests.
#![allow(dead_code)]

use softsculpt::body::{Material, SoftBody, Target};
use softsculpt::mesh::builtin::{builtin, icosphere};
use softsculpt::world::{Integrator, World, WorldSettings};

/// A material with no damping and no gas: add what a test needs.
pub fn bare() -> Material {
    Material { stiffness: 100.0, spring_damping: 0.0, damping: 0.0, ..Material::default() }
}

/// A world with no gravity, symplectic Euler, nothing else: add what a test needs.
pub fn still() -> WorldSettings {
    WorldSettings { gravity: 0.0, integrator: Integrator::Symplectic, ..WorldSettings::default() }
}

pub fn sphere_body(level: u32, mass: f64, material: Material) -> SoftBody {
    SoftBody::new(&icosphere(level, 1.0), mass, material).unwrap()
}

pub fn model_body(name: &str, mass: f64, material: Material) -> SoftBody {
    SoftBody::new(&builtin(name).unwrap(), mass, material).unwrap()
}

/// A lone body in a world with `settings`.
pub fn alone(body: SoftBody, settings: WorldSettings) -> World {
    World::single(body, settings)
}

/// A smooth, deterministic, non-uniform velocity field (m/s) that excites many modes.
pub fn swirl(body: &mut SoftBody, amplitude: f64) {
    let x = body.positions().to_vec();
    let v: Vec<f64> = x
        .chunks_exact(3)
        .flat_map(|p| {
            [
                amplitude * (2.0 * p[1]).sin(),
                amplitude * (3.0 * p[2] + 0.5).cos() * 0.5,
                amplitude * (1.5 * p[0]).sin() * p[1],
            ]
        })
        .collect();
    body.set_state(&x, &v).unwrap();
}

/// `steps` steps of `dt` seconds.
pub fn run(world: &mut World, dt: f64, steps: usize) {
    world.settings.dt = dt;
    for _ in 0..steps {
        world.step().unwrap();
    }
}

pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// The modeler's mushroom as it opens, not yet settled: standing on the ground (y = 0), its foot
/// pinned (the vertices within 1 cm of the ground), the `modeler` preset.
pub fn rooted_mushroom() -> World {
    rooted_mushroom_subdivided(0)
}

/// [`rooted_mushroom`] subdivided `subdivisions` times before its foot is pinned.
pub fn rooted_mushroom_subdivided(subdivisions: u32) -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo;
    }
    let mut body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    for _ in 0..subdivisions {
        body = body.subdivided().unwrap();
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    for i in 0..w.bodies[0].vertex_count() {
        if w.bodies[0].positions()[3 * i + 1] < 0.01 {
            w.bodies[0].set_pinned(i, true).unwrap();
        }
    }
    w
}

/// A press's dent in positions `x0` (flat xyz): the front-most vertex (largest z) and those
/// within 35 cm of it pushed back along −z by 15 cm × ½ (1 + cos(π d / 0.35)), the modeler's
/// default press (a cosine profile). Returns the dented positions and the front-most vertex.
pub fn dented(x0: &[f64]) -> (Vec<f64>, usize) {
    let n = x0.len() / 3;
    let c = (0..n).max_by(|&a, &b| x0[3 * a + 2].total_cmp(&x0[3 * b + 2])).unwrap();
    let mut x = x0.to_vec();
    for i in 0..n {
        let d = (0..3).map(|k| (x0[3 * i + k] - x0[3 * c + k]).powi(2)).sum::<f64>().sqrt();
        if d < 0.35 {
            x[3 * i + 2] -= 0.15 * 0.5 * (1.0 + (std::f64::consts::PI * d / 0.35).cos());
        }
    }
    (x, c)
}

/// A world as the modeler makes one (its preset: implicit at 1/60 s, gravity, ground at 0)
/// for `mesh` subdivided `subdivisions` times, the body set on the ground, then the material
/// `preset`.
pub fn on_ground(mesh: &softsculpt::TriMesh, subdivisions: u32, preset: &str) -> World {
    let mut body = SoftBody::new(mesh, 1.0, Material::default()).unwrap();
    for _ in 0..subdivisions {
        body = body.subdivided().unwrap();
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.apply_preset(0, preset).unwrap();
    let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|p| [p[0], p[1] - lowest + 1e-3, p[2]]).collect();
    let v = vec![0.0; x.len()];
    w.bodies[0].set_state(&x, &v).unwrap();
    w
}

/// Σ m_i |v_i| (kg·m/s): the scale a momentum error is measured against.
pub fn momentum_scale(b: &SoftBody) -> f64 {
    b.velocities().chunks_exact(3).zip(b.masses()).map(|(v, m)| m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).sum()
}

/// The modeler's 642-vertex sphere (`modeler` preset, implicit steps at tolerance 1e-3, no
/// gravity) and its hard pull: the targets at step s, the top pulled 2 m aside and 1 m up over
/// 24 steps (0.4 s) and a band round the equator 2 m the other way, at ω = 600 1/s (k_t = m ω²).
pub fn pulled_sphere() -> (World, impl Fn(usize) -> Vec<Target>) {
    let body = sphere_body(2, 1.0, Material::default());
    let mut a = alone(body, WorldSettings { integrator: Integrator::Implicit, tolerance: 1e-3, ..still() });
    a.apply_preset(0, "modeler").unwrap();
    let n = a.bodies[0].vertex_count();
    let k = (1.0 / n as f64) * 600.0f64.powi(2);
    let x0 = a.bodies[0].positions().to_vec();
    let top: Vec<usize> = (0..n).filter(|&i| x0[3 * i + 1] > 0.8).collect();
    let band: Vec<usize> = (0..n).filter(|&i| x0[3 * i + 1].abs() < 0.3 && x0[3 * i] > 0.8).collect();
    let pull = move |s: usize| {
        let t = (s as f64 / 24.0).min(1.0);
        let at = |i: usize, d: [f64; 3]| Target { vertex: i, anchor: [x0[3 * i] + t * d[0], x0[3 * i + 1] + t * d[1], x0[3 * i + 2]], stiffness: k, damping: 0.0 };
        top.iter().map(|&i| at(i, [2.0, 1.0, 0.0])).chain(band.iter().map(|&i| at(i, [-2.0, 0.0, 0.0]))).collect()
    };
    (a, pull)
}

/// How the page steps (`World::advance`: a step that does not finish is split, or retried with
/// crushed hinges let go).
pub fn page_budget() -> softsculpt::world::Budget {
    softsculpt::world::Budget { splits: 3, relax: true, ..softsculpt::world::Budget::converge() }
}

/// The modeler's `model` (the rooted mushroom, or the sphere or octopus set on the ground)
/// subdivided `subdivisions` times, settled 2 s, frozen under load and given the material
/// `preset` with the gas's push kept (what the page's material switch does), then `overrides`
/// (parameter id, value), settled 1 s.
pub fn with_material(preset: &str, model: &str, subdivisions: u32, overrides: &[(&str, f64)]) -> World {
    use softsculpt::body::{FreezeOptions, GasReference};
    let mut w: World = if model == "mushroom" { rooted_mushroom_subdivided(subdivisions) } else { on_ground(&builtin(model).unwrap(), subdivisions, "modeler") };
    w.advance(2.0, &page_budget()).unwrap();
    w.freeze(0, FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    let push = w.stats(0).pressure - w.bodies[0].gas_reference().ambient_pressure;
    w.apply_preset(0, preset).unwrap();
    for &(id, v) in overrides {
        w.set_param(0, id, softsculpt::params::Value::Number(v)).unwrap();
    }
    let gas = GasReference { ambient_pressure: (w.stats(0).pressure - push).max(0.0), ..w.bodies[0].gas_reference() };
    w.bodies[0].set_gas_reference(gas).unwrap();
    w.advance(1.0, &page_budget()).unwrap();
    w
}

/// The modeler's brush of radius `r` (m) centred on vertex `c` of positions `x` (flat xyz): each
/// vertex within `r` with its weight (1 − (d/r)²)² (`web/src/tools/brush.ts`).
pub fn brush_at(x: &[f64], c: usize, r: f64) -> Vec<(usize, f64)> {
    (0..x.len() / 3)
        .filter_map(|i| {
            let d = (0..3).map(|k| (x[3 * i + k] - x[3 * c + k]).powi(2)).sum::<f64>().sqrt();
            (d < r).then(|| (i, (1.0 - d * d / (r * r)).powi(2)))
        })
        .collect()
}

/// How a material takes the modeler's press or grab (issue #37, `examples/clay.rs`,
/// `tests/presets.rs`): the change of the body's depth at the brush's centre — the distance from
/// the front-most vertex (largest z) to the back-most — under the tool, 5 s and 10 s after
/// release (m; < 0 shallower).
pub struct ToolRun {
    pub vertices: usize,
    pub held: f64,
    pub at5: f64,
    pub at10: f64,
}

/// The modeler's `model` with the material `preset` ([`with_material`]); then the modeler's
/// default press (15 cm at the centre of
/// a 35 cm brush, weight (1 − (d/r)²)², target springs of ω = 600 1/s, pressed in over 0.25 s
/// and held to 1.5 s) or grab (the brush's vertices on target springs of m w ω², moved 0.4 m out
/// along z over 0.5 s, held to 1.5 s), let go, stepped as the page steps (`World::advance`:
/// split or relaxed where a step does not finish). The depth is measured between two vertices so
/// that what the body does as a whole (an unrooted body slides and tips under the tool) does not
/// count.
pub fn press_or_pull(preset: &str, model: &str, pull: bool, subdivisions: u32, overrides: &[(&str, f64)]) -> ToolRun {
    let (mut w, budget) = (with_material(preset, model, subdivisions, overrides), page_budget());
    let x0 = w.bodies[0].positions().to_vec();
    let m = w.bodies[0].masses().to_vec();
    let n = m.len();
    let c = (0..n).max_by(|&p, &q| x0[3 * p + 2].total_cmp(&x0[3 * q + 2])).unwrap();
    let b = (0..n).min_by(|&p, &q| x0[3 * p + 2].total_cmp(&x0[3 * q + 2])).unwrap();
    let brush = brush_at(&x0, c, 0.35);
    let omega: f64 = 600.0;
    let frame = 1.0 / 60.0;
    let span = |x: &[f64]| (0..3).map(|k| (x[3 * c + k] - x[3 * b + k]).powi(2)).sum::<f64>().sqrt();
    let span0 = span(&x0);
    let shift = |w: &World| span(w.bodies[0].positions()) - span0;
    for f in 0..90 {
        let t = (f + 1) as f64 * frame;
        let targets: Vec<Target> = brush
            .iter()
            .map(|&(i, wt)| {
                let (dz, k) = if pull { (0.4 * (t / 0.5).min(1.0), wt) } else { (-0.15 * wt * (t / 0.25).min(1.0), 1.0) };
                Target { vertex: i, anchor: [x0[3 * i], x0[3 * i + 1], x0[3 * i + 2] + dz], stiffness: m[i] * k * omega * omega, damping: 2.0 * m[i] * k * omega }
            })
            .collect();
        w.bodies[0].set_targets(&targets).unwrap();
        w.advance(frame, &budget).unwrap();
    }
    let held = shift(&w);
    w.bodies[0].clear_targets();
    w.advance(5.0, &budget).unwrap();
    let at5 = shift(&w);
    w.advance(5.0, &budget).unwrap();
    ToolRun { vertices: n, held, at5, at10: shift(&w) }
}

/// A held inflate's bulge (`inflated`): its height (m) and the largest angle between
/// neighbouring faces' normals within twice the brush radius of its centre before and after
/// (rad), against the smooth bound ([`bulge_bound`]).
pub struct Bulge {
    pub vertices: usize,
    pub height: f64,
    pub before: f64,
    pub after: f64,
    pub bound: f64,
}

/// Each interior edge (i < j) whose two faces' centroids both lie within `radius` of `centre`:
/// the angle (rad) between the two faces' normals and the distance between their centroids (m).
pub fn neighbour_faces(x: &[f64], tris: &[[u32; 3]], centre: [f64; 3], radius: f64) -> Vec<((u32, u32), f64, f64)> {
    use std::collections::HashMap;
    let p = |i: u32| [x[3 * i as usize], x[3 * i as usize + 1], x[3 * i as usize + 2]];
    let face = |t: &[u32; 3]| {
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        ([n[0] / l, n[1] / l, n[2] / l], [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0])
    };
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (f, t) in tris.iter().enumerate() {
        for k in 0..3 {
            let (i, j) = (t[k], t[(k + 1) % 3]);
            by_edge.entry((i.min(j), i.max(j))).or_default().push(f);
        }
    }
    let dist = |a: [f64; 3], b: [f64; 3]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    let mut out = Vec::new();
    for (&edge, faces) in by_edge.iter().filter(|(_, f)| f.len() == 2) {
        let ((n1, c1), (n2, c2)) = (face(&tris[faces[0]]), face(&tris[faces[1]]));
        if dist(c1, centre) < radius && dist(c2, centre) < radius {
            let cos = (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]).clamp(-1.0, 1.0);
            out.push((edge, cos.acos(), dist(c1, c2)));
        }
    }
    out
}

/// Largest angle (rad) between the normals of two faces sharing an edge, over faces whose
/// centroid lies within `radius` of `centre`, and the largest distance between such neighbours'
/// centroids (m).
pub fn normal_jumps(x: &[f64], tris: &[[u32; 3]], centre: [f64; 3], radius: f64) -> (f64, f64) {
    neighbour_faces(x, tris, centre, radius).into_iter().fold((0.0f64, 0.0f64), |(a, s), (_, angle, spacing)| (a.max(angle), s.max(spacing)))
}

/// The largest angle between neighbouring faces' normals a smooth bulge allows: a bump of height
/// H shaped as the brush's weight, H (1 − (d/r)²)², on a surface whose own neighbouring normals
/// differ by at most `rest` (rad), has a profile curvature of at most |f''| = 8 H / r² (at its
/// rim; 4 H / r² at its top), so neighbouring faces whose centroids are at most s apart turn by
/// at most rest + s 8 H / r² more; twice that, for a bulge whose shape is the gas's and the
/// membrane's, not exactly the weight's. A ridge — springs grown with no falloff across the
/// brush's edge — folds the surface by far more than that at one edge.
pub fn bulge_bound(rest: f64, spacing: f64, height: f64, r: f64) -> f64 {
    2.0 * (rest + spacing * 8.0 * height / (r * r))
}

/// The modeler's `model` with the material `preset` ([`with_material`]); then the modeler's
/// inflate brush
/// held at its front-most vertex for `seconds` (radius 0.35 m, weight (1 − (d/r)²)², each frame
/// every rest length × the mean of its ends' 1 + rate w dt, rate 0.3 1/s: `tools/brush.ts`
/// `inflateFactor`), then 2 s to settle.
pub fn inflated(preset: &str, model: &str, seconds: f64, subdivisions: u32) -> Bulge {
    let (mut w, budget) = (with_material(preset, model, subdivisions, &[]), page_budget());
    let x0 = w.bodies[0].positions().to_vec();
    let n = x0.len() / 3;
    let c = (0..n).max_by(|&p, &q| x0[3 * p + 2].total_cmp(&x0[3 * q + 2])).unwrap();
    let centre = [x0[3 * c], x0[3 * c + 1], x0[3 * c + 2]];
    let r = 0.35;
    let (frame, rate) = (1.0 / 60.0, 0.3);
    let weights: Vec<f64> = (0..n)
        .map(|i| {
            let d = (0..3).map(|k| (x0[3 * i + k] - centre[k]).powi(2)).sum::<f64>().sqrt();
            if d < r { (1.0 - d * d / (r * r)).powi(2) } else { 0.0 }
        })
        .collect();
    let tris = w.bodies[0].triangles().to_vec();
    let (before, spacing) = normal_jumps(&x0, &tris, centre, 2.0 * r);
    for _ in 0..(seconds / frame).round() as usize {
        let f: Vec<f64> = weights.iter().map(|wt| 1.0 + rate * wt * frame).collect();
        w.bodies[0].scale_rest_lengths_by_vertex(&f).unwrap();
        w.advance(frame, &budget).unwrap();
    }
    w.advance(2.0, &budget).unwrap();
    let x = w.bodies[0].positions();
    // The bulge's height: the centre's move along its outward direction (+z here).
    let height = x[3 * c + 2] - x0[3 * c + 2];
    let (after, _) = normal_jumps(x, &tris, [x[3 * c], x[3 * c + 1], x[3 * c + 2]], 2.0 * r);
    Bulge { vertices: n, height, before, after, bound: bulge_bound(before, spacing, height.max(0.0), r) }
}

/// Issue #37, item 1: each material takes the modeler's default press and grab as its name says
/// (`common::press_or_pull`: the rooted mushroom, the sphere and the octopus as the modeler
/// opens them, settled, the preset applied as the page's material switch does, the press or the
/// grab held 1.5 s, let go; the change of the body's depth at the brush), at `subdivisions`
/// loop subdivisions of the model (`tests/presets.rs` at 0, `tests/presets_fine.rs` at 2).
/// - balloon, jelly, stiff rubber: back within 5 mm 5 s after release (the bound;
///   measured ≤ 0.5 mm except jelly's swaying mushroom cap, 3.7 mm after the grab);
/// - clay: keeps ≥ 70 % of what the tool did 5 s after release (the bound; measured
///   91–112 % of the press, 96 % and 102 % of the pull on the mushroom and the octopus), and no
///   creep after that: from 5 s to 10 s less than 2 % of what the tool did or 1 mm (measured
///   < 0.1 mm; its damping, c = 4 1/s, leaves e^(−20) of any motion by then). Where the grab
///   barely changes the depth (the sphere slides along the ground, 8 mm), only the creep is
///   bounded.
pub fn material_takes_the_tools(model: &str, subdivisions: u32) {
    for pull in [false, true] {
        let tool = if pull { "grab" } else { "press" };
        for preset in ["balloon", "jelly", "stiff_rubber"] {
            let r = press_or_pull(preset, model, pull, subdivisions, &[]);
            println!("{preset} {model} ×{subdivisions} {tool}: held {:+.4} m, after 5 s {:+.4} m", r.held, r.at5);
            assert!(r.held.abs() > 0.005 || pull, "{preset} on {model}: the {tool} did nothing ({} m)", r.held);
            assert!(r.at5.abs() < 0.005, "{preset} on {model}: {} m of the {tool}'s {} m left after 5 s", r.at5, r.held);
        }
        let r = press_or_pull("clay", model, pull, subdivisions, &[]);
        println!("clay {model} ×{subdivisions} {tool}: held {:+.4} m, after 5 s {:+.4} m, after 10 s {:+.4} m", r.held, r.at5, r.at10);
        if r.held.abs() > 0.02 {
            assert!(r.at5 / r.held >= 0.7, "clay on {model}: kept {} m of the {tool}'s {} m", r.at5, r.held);
        }
        assert!((r.at10 - r.at5).abs() < (0.02 * r.held.abs()).max(1e-3), "clay on {model}: crept from {} m to {} m after the {tool}", r.at5, r.at10);
    }
}
