//! Several bodies: contact between soft bodies.

mod common;
use common::*;
use softsculpt::body::Material;
use softsculpt::world::mesh_obstacle::MeshShape;
use softsculpt::world::{ContactSettings, Ground, World, WorldSettings};
use softsculpt::TriMesh;

/// A world of `bodies` with contact thickness `thickness` (m), stepping by `dt` (s).
fn world(bodies: Vec<softsculpt::SoftBody>, settings: WorldSettings, thickness: f64, dt: f64) -> World {
    World::new(bodies, WorldSettings { contact: ContactSettings { thickness, ..ContactSettings::default() }, dt, ..settings })
}

fn balloon(dy: f64, v: f64) -> softsculpt::SoftBody {
    let mut p = Material { spring_damping: 0.2, damping: 1.0, ..bare() };
    p.set_nrt(20.0);
    let mut b = sphere_body(2, 1.0, p);
    let x: Vec<f64> = b.positions().chunks_exact(3).flat_map(|q| [q[0] + 0.1 * dy.signum(), q[1] + dy, q[2]]).collect();
    let vel: Vec<f64> = (0..x.len()).map(|k| if k % 3 == 1 { v } else { 0.0 }).collect();
    b.set_state(&x, &vel).unwrap();
    b
}

/// Generalised winding number of point p with respect to a closed mesh: 1 inside, 0 outside.
fn winding(p: [f64; 3], x: &[f64], tris: &[[u32; 3]]) -> f64 {
    let mut total = 0.0;
    for t in tris {
        let v: Vec<[f64; 3]> = t.iter().map(|&i| [x[3 * i as usize] - p[0], x[3 * i as usize + 1] - p[1], x[3 * i as usize + 2] - p[2]]).collect();
        let l: Vec<f64> = v.iter().map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()).collect();
        let det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) - v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) + v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let div = l[0] * l[1] * l[2] + dot(v[0], v[1]) * l[2] + dot(v[1], v[2]) * l[0] + dot(v[2], v[0]) * l[1];
        total += 2.0 * det.atan2(div);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Two balloons dropped on each other onto the ground (the upper one lands off-centre and rolls
/// off): the total energy never rises above its start (tolerance: the symplectic step's own
/// energy error, well below 1e-2 J here, against a start of ~40 J), both come to rest, and no
/// vertex of one ends inside the other.
#[test]
fn two_balloons_dropped_on_each_other_rest_without_interpenetrating() {
    let mut world = world(vec![balloon(0.0, 0.0), balloon(2.4, -2.0)], WorldSettings { gravity: 9.81, ground: Some(Ground::at(-1.2)), ..still() }, 0.1, 5e-4);
    let e0 = world.total_energy();
    let mut worst = f64::NEG_INFINITY;
    for step in 0..32000 {
        world.step().unwrap();
        if step % 20 == 0 {
            worst = worst.max(world.total_energy() - e0);
        }
    }
    assert!(worst < 1e-2, "energy rose by {worst} J");
    for b in &world.bodies {
        assert!(b.max_speed() < 0.05, "resting: {}", b.max_speed());
    }
    let (a, b) = (&world.bodies[0], &world.bodies[1]);
    for (p, q) in [(a, b), (b, a)] {
        for v in p.positions().chunks_exact(3) {
            let w = winding([v[0], v[1], v[2]], q.positions(), q.triangles());
            assert!(w < 0.5, "a vertex is inside the other balloon (winding {w})");
        }
    }
    // Momentum exchange is exact: nothing but gravity, damping and the ground acts from outside.
}

/// Contact impulses conserve momentum: two balloons colliding in free space (no gravity, no
/// ground, no damping) keep their total momentum.
#[test]
fn a_collision_between_bodies_conserves_momentum() {
    let make = |dx: f64, vx: f64| {
        let mut p = Material { spring_damping: 0.2, ..bare() };
        p.set_nrt(20.0);
        let mut b = sphere_body(2, 1.0, p);
        let x: Vec<f64> = b.positions().chunks_exact(3).flat_map(|q| [q[0] + dx, q[1] + 0.3 * dx.signum(), q[2]]).collect();
        let v: Vec<f64> = (0..x.len()).map(|k| if k % 3 == 0 { vx } else { 0.0 }).collect();
        b.set_state(&x, &v).unwrap();
        b
    };
    let mut world = world(vec![make(-1.3, 2.0), make(1.3, -1.0)], still(), 0.01, 5e-4);
    let total = |w: &World| (0..w.bodies.len()).fold([0.0; 3], |acc, b| { let m = w.stats(b).momentum; [acc[0] + m[0], acc[1] + m[1], acc[2] + m[2]] });
    let p0 = total(&world);
    for _ in 0..3000 {
        world.step().unwrap();
    }
    let p1 = total(&world);
    // They met (the first one slowed down) and the total is unchanged up to rounding.
    assert!(world.stats(0).momentum[0] < 1.5, "{:?}", world.stats(0).momentum);
    for d in 0..3 {
        assert!((p1[d] - p0[d]).abs() < 1e-9, "{p0:?} -> {p1:?}");
    }
}

/// A gasless sphere on the ground crushed by a weight on its top: the top skin comes down onto
/// the bottom skin. Without self-collision it passes through and reaches the ground; with it, it
/// stops on the bottom skin, at least half the contact thickness above it (the contact stage
/// corrects penetration only, so the gap settles between 0 and the thickness; 0.5 leaves room
/// for the skin's sag between vertices).
#[test]
fn self_collision_keeps_a_crushed_sphere_from_passing_through_itself() {
    let run = |self_collision: bool| {
        let p = Material { spring_damping: 0.05, damping: 2.0, self_collision, ..bare() };
        let mut b = sphere_body(3, 1.0, p);
        let top: Vec<usize> = (0..b.vertex_count()).filter(|&i| b.positions()[3 * i + 1] > 0.7).collect();
        let mut f = vec![0.0; 3 * b.vertex_count()];
        for &i in &top {
            f[3 * i + 1] = -40.0 / top.len() as f64;
        }
        b.set_user_forces(&f).unwrap();
        let mut world = world(vec![b], WorldSettings { gravity: 9.81, ground: Some(Ground::at(-1.0)), ..still() }, 0.03, 5e-4);
        for _ in 0..2000 {
            world.step().unwrap();
        }
        let x = world.bodies[0].positions();
        let pole = (0..x.len() / 3).max_by(|&a, &b| world.bodies[0].frozen_positions()[3 * a + 1].total_cmp(&world.bodies[0].frozen_positions()[3 * b + 1])).unwrap();
        let on_ground = top.iter().filter(|&&i| x[3 * i + 1] < -1.0 + 0.015).count();
        eprintln!("self {self_collision}: pole y {}, {on_ground} of {} top vertices on the ground, lowest {}", x[3 * pole + 1], top.len(), top.iter().map(|&i| x[3 * i + 1]).fold(f64::INFINITY, f64::min));
        top.iter().map(|&i| x[3 * i + 1]).fold(f64::INFINITY, f64::min)
    };
    let (without, with) = (run(false), run(true));
    eprintln!("lowest top vertex: without self-collision {without}, with {with}");
    assert!(without < -0.99, "without self-collision the top reaches the ground: {without}");
    assert!(with > -1.0 + 0.5 * 0.03, "with self-collision the top stays on the bottom skin: {with}");
}

/// A firm balloon thrown at 20 m/s at another moves 2 cm per 1 ms step, twice the contact
/// thickness, so a vertex can go from outside the contact band to behind a face in one step:
/// vertex–face contact catches it up to one triangle radius deep and puts it back. Checked every
/// 5 steps: the thrown one never comes out through the far side (its centre of mass stays
/// behind the other's), and no vertex is ever more than 1 mm (a tenth of the thickness) inside
/// the other balloon (measured: 3e-5 m with vertex–face contact alone, 8e-4 m with the
/// edge–edge corrections on top). (A softer balloon, nRT = 20 J, is crushed flat by such
/// a hit — its volume goes through zero, which the step reports as a collapse.)
#[test]
fn a_fast_body_does_not_pass_through_another() {
    let make = |dx: f64, vx: f64| {
        let mut p = Material { spring_damping: 0.2, damping: 0.5, ..bare() };
        p.set_nrt(100.0);
        let mut b = sphere_body(2, 1.0, p);
        let x: Vec<f64> = b.positions().chunks_exact(3).flat_map(|q| [q[0] + dx, q[1], q[2]]).collect();
        let v: Vec<f64> = (0..x.len()).map(|k| if k % 3 == 0 { vx } else { 0.0 }).collect();
        b.set_state(&x, &v).unwrap();
        b
    };
    let mut world = world(vec![make(-2.5, 20.0), make(0.0, 0.0)], still(), 0.01, 1e-3);
    let mut deepest: f64 = 0.0;
    for step in 0..600 {
        world.step().unwrap();
        if step % 5 == 0 {
            let (a, b) = (&world.bodies[0], &world.bodies[1]);
            assert!(world.stats(0).center_of_mass[0] < world.stats(1).center_of_mass[0], "passed through at step {step}");
            for (p, q) in [(a, b), (b, a)] {
                let surface = MeshShape::new(&TriMesh { positions: q.positions().to_vec(), triangles: q.triangles().to_vec() }).unwrap();
                for v in p.positions().chunks_exact(3) {
                    if winding([v[0], v[1], v[2]], q.positions(), q.triangles()) > 0.5 {
                        let depth = surface.closest([v[0], v[1], v[2]], 1.0).map_or(1.0, |c| c.0.abs());
                        deepest = deepest.max(depth);
                    }
                }
            }
        }
    }
    eprintln!("deepest vertex inside the other balloon: {deepest} m");
    assert!(deepest < 1e-3, "a vertex went {deepest} m into the other balloon");
    // The hit passed momentum on: the second balloon moves away.
    assert!(world.stats(1).momentum[0] > 5.0, "{:?}", world.stats(1).momentum);
}

/// Two cubes meeting edge to edge, crosswise: A's top edge runs along x, B's bottom edge along z,
/// and no vertex of either is anywhere near a face of the other where they meet — vertex–face
/// contact alone lets B's edge cut through A's (measured: 0.47 m deep). Edge–edge contact stops
/// the crossing: B's edge never gets below A's — measured between the edges' midpoints, which
/// sit a little off the contact point as the edges tilt, so within 1 mm (a tenth of the
/// thickness; measured 0.17 mm) — and B is stopped (momentum −3 → −0.8 kg·m/s).
#[test]
fn edge_to_edge_crossing_is_stopped() {
    use softsculpt::TriMesh;
    let cube = |angle_axis: usize, center_y: f64| {
        let mut positions = Vec::new();
        for k in 0..8 {
            let p = [if k & 1 == 0 { -0.5 } else { 0.5 }, if k & 2 == 0 { -0.5 } else { 0.5 }, if k & 4 == 0 { -0.5 } else { 0.5 }];
            let (c, s) = (std::f64::consts::FRAC_PI_4.cos(), std::f64::consts::FRAC_PI_4.sin());
            // 45° about x (A: an edge along x on top) or about z (B: an edge along z below).
            let q = if angle_axis == 0 { [p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]] } else { [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]] };
            positions.extend_from_slice(&[q[0], q[1] + center_y, q[2]]);
        }
        let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let triangles = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        let mut p = Material { stiffness: 2000.0, spring_damping: 0.5, ..bare() };
        p.set_nrt(50.0);
        softsculpt::SoftBody::new(&TriMesh { positions, triangles }, 1.0, p).unwrap()
    };
    // The top edge of A (the two vertices with the largest y) and the bottom edge of B.
    let extreme = |b: &softsculpt::SoftBody, top: bool| {
        let mut idx: Vec<usize> = (0..8).collect();
        idx.sort_by(|&i, &j| b.positions()[3 * i + 1].total_cmp(&b.positions()[3 * j + 1]));
        if top { [idx[7], idx[6]] } else { [idx[0], idx[1]] }
    };
    let run = |edges: bool| {
        let (a, b) = (cube(0, 0.0), cube(2, 2.0 * 0.5f64.sqrt() + 0.1));
        let (ea, eb) = (extreme(&a, true), extreme(&b, false));
        let mut b = b;
        b.set_uniform_velocity([0.0, -3.0, 0.0]).unwrap();
        let mut world = world(vec![a, b], still(), 0.01, 5e-4);
        world.settings.contact.edge_contact = edges;
        let mut lowest_gap = f64::INFINITY;
        for _ in 0..400 {
            world.step().unwrap();
            let (xa, xb) = (world.bodies[0].positions(), world.bodies[1].positions());
            let y = |x: &[f64], e: [usize; 2]| 0.5 * (x[3 * e[0] + 1] + x[3 * e[1] + 1]);
            lowest_gap = lowest_gap.min(y(xb, eb) - y(xa, ea));
        }
        (lowest_gap, world.stats(1).momentum[1])
    };
    let (without, _) = run(false);
    let (with, momentum) = run(true);
    eprintln!("lowest gap between the edges: without edge contact {without} m, with {with} m; B's momentum {momentum}");
    assert!(without < -0.1, "vertex–face alone lets the edges cross: {without}");
    assert!(with > -1e-3, "the edges crossed by {with} m");
    assert!(momentum > -3.0 * 0.5, "B was stopped: momentum {momentum}");
}
