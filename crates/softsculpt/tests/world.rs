//! Several bodies: contact between soft bodies.

mod common;
use common::*;
use softsculpt::body::{Ground, Params};
use softsculpt::world::World;

fn balloon(dy: f64, v: f64) -> softsculpt::SoftBody {
    let mut p = Params { gravity: 9.81, spring_damping: 0.2, damping: 1.0, ground: Some(Ground::at(-1.2)), ..bare() };
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
    let mut world = World::new(vec![balloon(0.0, 0.0), balloon(2.4, -2.0)], 0.1);
    let e0 = world.total_energy();
    let mut worst = f64::NEG_INFINITY;
    for step in 0..32000 {
        world.step(5e-4).unwrap();
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
        let mut p = Params { spring_damping: 0.2, ..bare() };
        p.set_nrt(20.0);
        let mut b = sphere_body(2, 1.0, p);
        let x: Vec<f64> = b.positions().chunks_exact(3).flat_map(|q| [q[0] + dx, q[1] + 0.3 * dx.signum(), q[2]]).collect();
        let v: Vec<f64> = (0..x.len()).map(|k| if k % 3 == 0 { vx } else { 0.0 }).collect();
        b.set_state(&x, &v).unwrap();
        b
    };
    let mut world = World::new(vec![make(-1.3, 2.0), make(1.3, -1.0)], 0.01);
    let total = |w: &World| w.bodies.iter().fold([0.0; 3], |acc, b| { let m = b.stats().momentum; [acc[0] + m[0], acc[1] + m[1], acc[2] + m[2]] });
    let p0 = total(&world);
    for _ in 0..3000 {
        world.step(5e-4).unwrap();
    }
    let p1 = total(&world);
    // They met (the first one slowed down) and the total is unchanged up to rounding.
    assert!(world.bodies[0].stats().momentum[0] < 1.5, "{:?}", world.bodies[0].stats().momentum);
    for d in 0..3 {
        assert!((p1[d] - p0[d]).abs() < 1e-9, "{p0:?} -> {p1:?}");
    }
}
