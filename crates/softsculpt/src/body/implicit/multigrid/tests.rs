//! The V-cycle preconditioner checked against block Jacobi and its coarse matrices against the
//! Galerkin product (`super`).

use super::super::Implicit;
use super::*;
use crate::body::{Material, SoftBody};
use crate::mesh::builtin::icosphere;
use crate::settings::{Ground, Integrator, WorldSettings};
use super::super::system::Frame;

/// One tight implicit step of a swirled, inflated sphere (2,562 vertices in two chunks of the
/// vertex passes, the standard workload's ω dt ≈ 27 per spring, far
/// outside explicit stability), once preconditioned by the V-cycle and once by block Jacobi.
/// Both solve the same backward-Euler equations to ‖r‖_{M⁻¹} ≤ 1e-12 ‖r_0‖_{M⁻¹}; with
/// A ⪰ M the velocity error of each is ≤ ‖r‖_{M⁻¹}/√m ≈ 1e-12 ‖r_0‖_{M⁻¹}/√m, ~1e-10 of the
/// velocities here: they must agree to 1e-8 relative. And the V-cycle must need fewer
/// conjugate-gradient iterations (that is its point).
#[test]
fn the_multigrid_preconditioner_reaches_the_same_step_in_fewer_iterations() {
    let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, ..Material::default() };
    p.set_nrt(2.0);
    let mut body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
    let n = body.model.mass.len();
    for i in 0..n {
        let x = &body.state.x[3 * i..3 * i + 3];
        let (vx, vy, vz) = (-x[1], x[0] + 0.3 * x[2], 0.5 * x[0] * x[1]);
        body.state.v[3 * i..3 * i + 3].copy_from_slice(&[vx, vy, vz]);
    }
    let w = WorldSettings { integrator: Integrator::Implicit, tolerance: 1e-12, gravity: 9.81, ..WorldSettings::default() };
    let run = |from: usize, th: &Threads| {
        let mut s = body.state.clone();
        let mut imp = Implicit::new(&body.model);
        imp.mg = Multigrid::new(&imp.sys, n, from);
        assert_eq!(imp.mg.levels.is_empty(), from > n);
        let it = imp.step(th, &p, &w, &body.model, &mut s, 1.0 / 60.0).unwrap();
        (s.v, it.linear)
    };
    let one = Threads::single();
    let (vm, itm) = run(0, &one);
    let (vj, itj) = run(usize::MAX, &one);
    // The cycle's coarse levels run on the calling thread and its fine passes in fixed
    // chunks: two threads give the same bits.
    assert_eq!(run(0, &Threads::new(2).unwrap()).0, vm);
    let scale = vj.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let err = vm.iter().zip(&vj).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(err <= 1e-8 * scale, "max |Δv| = {err:e} of {scale}");
    assert!(2 * itm < itj, "V-cycle {itm} vs block Jacobi {itj} CG iterations");
}

/// The implicit scratch of `body` with the V-cycle at any size, its system evaluated at
/// v⁺ = v (the ground's held vertices from the state, their v⁺_y prescribed) with dt = 1/60 s
/// and the coarse levels assembled from it.
fn assembled(body: &SoftBody, p: &Material, w: &WorldSettings) -> Implicit {
    let m = &body.model;
    let mut imp = Implicit::new(m);
    imp.mg = Multigrid::new(&imp.sys, m.mass.len(), 0);
    let fr = Frame { p, w, m, x: &body.state.x, v: &body.state.v, dt: 1.0 / 60.0, relax: crate::Relaxed::No };
    imp.sys.ground.find(m, w.ground.as_ref(), fr.x, fr.v, fr.dt);
    imp.vp.copy_from_slice(fr.v);
    imp.sys.ground.prescribe(&mut imp.vp);
    imp.eval(&Threads::single(), &fr).unwrap();
    imp.mg.assemble(&imp.sys, m, &imp.xt);
    imp
}

/// The coarse matrix is the Galerkin product of the fine one the cycle works on: for any
/// coarse vector x₁ (six unknowns per node of level 1), A₁ x₁ = Pᵀ F A F P x₁, F zeroing
/// the ground-held vertices' y components (the fine product's rows and the cycle's vectors
/// are 0 there, `ground.rs`). On a jittered sphere (compressed and stretched springs,
/// bending springs, bent hinges, damping, one pinned vertex) whose bottom rests on the ground. Both sides
/// sum the same products of the same coefficients in other orders: they agree to rounding,
/// ~1e-15 of the largest term per entry times the ~100 terms an entry sums; 1e-11 of
/// max |A₁ x₁| leaves room for that. A coarse matrix that counts the held vertices' y
/// stiffness misses by O(1) of it on the bottom's nodes.
#[test]
fn the_coarse_matrix_is_the_galerkin_product_of_the_fine_one_with_the_ground_holding_vertices() {
    let mut p = Material { stiffness: 300.0, spring_damping: 0.5, bending_stiffness: 50.0, rigidity: 0.05, ..Material::default() };
    p.set_nrt(2.0);
    let mut body = SoftBody::new(&icosphere(3, 1.0), 1.0, p.clone()).unwrap();
    let n = body.model.mass.len();
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for x in body.state.x.iter_mut() {
        *x += 0.02 * rnd();
    }
    for v in body.state.v.iter_mut() {
        *v = 0.1 * rnd();
    }
    body.set_pinned(7, true).unwrap();
    let w = WorldSettings { integrator: Integrator::Implicit, gravity: 9.81, ground: Some(Ground::at(-0.85)), ..WorldSettings::default() };
    let th = Threads::single();
    let imp = assembled(&body, &p, &w);
    let m = &body.model;
    assert!(imp.sys.ground.list.len() >= 10, "{} held", imp.sys.ground.list.len());
    let l1 = &imp.mg.levels[0];
    let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
    for _ in 0..3 {
        let x1: Vec<[f64; 6]> = (0..l1.s.n).map(|_| std::array::from_fn(|_| rnd())).collect();
        // u = F P x₁ on the free vertices; q = A u.
        let mut u = vec![0.0; 3 * n];
        for i in 0..n {
            if m.inv_mass[i] != 0.0 {
                let xp = &x1[l1.s.parent[i] as usize];
                let wv = cross(&[xp[3], xp[4], xp[5]], &l1.off[i]);
                for d in 0..3 {
                    u[3 * i + d] = xp[d] + wv[d];
                }
            }
        }
        imp.sys.ground.filter(&mut u);
        let mut q = vec![0.0; 3 * n];
        imp.sys.product(&th, m, &u, 0.0, &mut q, &mut slots);
        // Pᵀ q against A₁ x₁.
        let mut ptq = vec![[0.0; 6]; l1.s.n];
        for i in 0..n {
            let qi = [q[3 * i], q[3 * i + 1], q[3 * i + 2]];
            let wv = cross(&l1.off[i], &qi);
            let acc = &mut ptq[l1.s.parent[i] as usize];
            for d in 0..3 {
                acc[d] += qi[d];
                acc[3 + d] += wv[d];
            }
        }
        let mut scale = 0.0f64;
        let mut err = 0.0f64;
        for c in 0..l1.s.n {
            let mut y = [0.0; 6];
            for e in l1.s.start[c] as usize..l1.s.start[c + 1] as usize {
                let t = mul6(&l1.a[e], &x1[l1.s.col[e] as usize]);
                for d in 0..6 {
                    y[d] += t[d];
                }
            }
            for d in 0..6 {
                scale = scale.max(y[d].abs());
                err = err.max((y[d] - ptq[c][d]).abs());
            }
        }
        assert!(err <= 1e-11 * scale, "max |A₁x₁ − PᵀFAFPx₁| = {err:e} of {scale:e}");
    }
}

/// The coarse sweeps and residuals dispatched at run time (AVX2 where the CPU has it) give
/// the same bits as the plain code: the second compilation only widens the encoding (no FMA
/// contraction, no reordered sums), so any difference at all is a fault. Forward and backward
/// sweeps then a residual, on every coarse level of an assembled 2,562-vertex hierarchy.
#[test]
fn the_dispatched_coarse_sweeps_give_the_same_bits_as_the_plain_ones() {
    let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, bending_stiffness: 100.0, ..Material::default() };
    p.set_nrt(2.0);
    let body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
    let w = WorldSettings { integrator: Integrator::Implicit, ..WorldSettings::default() };
    let mut imp = assembled(&body, &p, &w);
    assert!(imp.mg.levels.len() >= 2);
    for (l, lv) in imp.mg.levels.iter_mut().enumerate() {
        for (c, b) in lv.b.iter_mut().enumerate() {
            *b = std::array::from_fn(|d| ((7 * c + 3 * d + l) % 11) as f64 - 5.0);
        }
        lv.x.fill([0.0; 6]);
        let mut plain = lv.clone();
        for forward in [true, false] {
            Multigrid::sweep(lv, forward);
            Multigrid::sweep_plain(&mut plain, forward);
        }
        Multigrid::residual(lv);
        Multigrid::residual_plain(&mut plain);
        let bits = |v: &[[f64; 6]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&lv.x), bits(&plain.x), "level {l}: sweeps differ");
        assert_eq!(bits(&lv.r), bits(&plain.r), "level {l}: residuals differ");
    }
}
