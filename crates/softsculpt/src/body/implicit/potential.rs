//! The step's incremental potential G(v⁺), whose gradient is the residual r (`system/`):
//!
//!   G(v⁺) = ½ (v⁺ − v)ᵀ M (v⁺ − v) + E(x + dt v⁺) + dt R(v⁺)                 (J)
//!
//! with E every conservative force's energy at x_t = x + dt v⁺ and R the damping's Rayleigh
//! dissipation function (f_damping = −∂R/∂v⁺). Check: ∂G/∂v⁺ = M (v⁺ − v) + dt ∇E(x_t) +
//! dt ∂R/∂v⁺ = M (v⁺ − v) − dt f = r. Backward Euler's v⁺ is a stationary point of G
//! (Martin et al. 2011, "Example-based elastic materials"; Gast et al. 2015, "Optimization
//! integrator"), and every iterate the line search accepts lowers it (`Implicit::line_search`:
//! an Armijo test on G).
//!
//! **The damping's directions are frozen per line search** ([`Frozen`]): a spring's damping
//! cs ((v_j − v_i)·d) d and a hinge's D w τ (∇θ · v) ∇θ turn with the geometry, so they are not
//! the gradient of any function of v⁺ (`shared/solver-notes.md`). G takes them with d and ∇θ of
//! the line search's start x_t⁰, R = ½ cs ((v_j − v_i)·d⁰)² and ½ D w τ (∇θ⁰ · v)²: then G's
//! slope at the start is exactly δ · r, the line search's s(0), and a small enough step along a
//! descent direction always passes the Armijo test. So each line search has its own G_k (the
//! same but for the damping's directions): an accepted iterate lowers G_k from the one before.
//! Measured before the test was added (the mushroom subdivided once, grabbed, `examples/anytime`):
//! with G's damping on the moving directions, 4 of 955 line searches "raised" G by up to 5e-5 J
//! while G's finite-difference slope disagreed with δ · r by up to 4×; with the spring damping
//! off, 0 of 971 raised it; with the directions frozen, none in the grabs and drops measured
//! (`LineStats`, printed by `examples/anytime`). Wind and face pressures are frozen the same
//! way: −dt f_ext⁰ · v⁺.
//!
//! **Cost.** The springs', hinges' and gas's energies are summed by `System::eval` in its own
//! passes (`System::spring_energy`, `he`, `gas_energy`), so G after an evaluation is one pass
//! over the vertices and one over the springs' frozen directions, no square roots: measured
//! 573 ms of the 19.98 s of 180 budgeted frames of the grab at 5,762 vertices (2.9 %).
//!
//! The terms, each beside the force it is the potential of (the force's formula in `system/`):
//! - springs and bending springs: ½ k (l − L)², damping R = ½ cs ((v_j − v_i) · d)²;
//! - hinges: ½ D w r² (r = θ − θ̄, faded at a crushed face), damping R = ½ D w τ ṙ²;
//! - gas: −nRT ln(V / V₀) + P_ref (V − V₀) (`gas::energy`);
//! - gravity m g y; the constant user forces and the kept load −f · x;
//! - target springs ½ k_t |a − x|², damping R = ½ c_t |v|²; viscous damping R = ½ c m |v|²;
//! - self-contacts ½ k_c (h − d)² where d < h.
//!
//! Not exactly potentials: the hinge fade's Ψ (only at a crushed face: the force is −D w Ψ (θ − θ̄) ∇θ,
//! G's term ½ D w Ψ (θ − θ̄)²), and the box and sphere volume modes (their pressure pushes along
//! the exact volume's gradient). There G's slope is not δ · r and the Armijo test may not pass:
//! the line search then keeps its last halving ([`BACKTRACK_MAX`]) and counts it (`LineStats::rose`).

use super::adjacency::SpringRows;
use super::super::hinges::rate;
use super::super::selfcontact::along;
use super::system::{Frame, System};

/// G's value and its rounding level (J): 16 ε times the magnitudes summed into it. Differences
/// of G below the rounding level say nothing (`shared/solver-notes.md`: at relative residuals
/// below ~1e-5 a step changes G by less than its rounding).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Potential {
    pub value: f64,
    pub noise: f64,
}

/// Sums a potential's terms and the magnitudes they round at.
#[derive(Default)]
struct Sum {
    value: f64,
    scale: f64,
}

impl Sum {
    fn add(&mut self, t: f64) {
        self.value += t;
        self.scale += t.abs();
    }
}

/// Halvings of the line search's step after its slope test, at most, until G passes the
/// Armijo test (`Implicit::line_search`).
pub(crate) const BACKTRACK_MAX: u32 = 12;
/// The Armijo test's constant c: G(λ) ≤ G(0) + c λ s(0) (Nocedal & Wright, 3.1: 1e-4 is usual).
pub(crate) const ARMIJO: f64 = 1e-4;

/// What a line search's G holds fixed from its start (see the module documentation): the
/// springs' directions d⁰ (per CSR entry, as the vertex pass wrote them into `ecoef`, `bcoef`),
/// the hinges' ∇θ⁰ and the wind's and face pressures' forces there.
#[derive(Debug, Clone, Default)]
pub(crate) struct Frozen {
    ed: Vec<[f64; 3]>,
    bd: Vec<[f64; 3]>,
    hg: Vec<[f64; 12]>,
    fext: Option<Vec<f64>>,
}

impl Frozen {
    /// Take them from the system's last evaluation (the line search's start).
    pub fn take(&mut self, sys: &System, fr: &Frame) {
        let dirs = |out: &mut Vec<[f64; 3]>, coef: &[[f64; 5]]| {
            out.clear();
            out.extend(coef.iter().map(|c| [c[2], c[3], c[4]]));
        };
        dirs(&mut self.ed, &sys.ecoef);
        self.bd.clear();
        if sys.bending {
            dirs(&mut self.bd, &sys.bcoef);
        }
        self.hg.clear();
        if sys.hinged {
            self.hg.extend_from_slice(&sys.hg);
        }
        let fext_on = (fr.w.wind_drag > 0.0 && fr.w.wind != [0.0; 3]) || fr.m.face_pressure_active;
        match (&mut self.fext, fext_on) {
            (Some(f), true) => f.copy_from_slice(&sys.fext),
            (f, true) => *f = Some(sys.fext.clone()),
            (f, false) => *f = None,
        }
    }
}

/// How the line searches of a body's steps ended, counted since it was built (for the tests
/// and the benchmarks): searches, those whose G changed by less than its rounding (the slope
/// test alone decided), those halved to pass the Armijo test, and those that still did not
/// pass after [`BACKTRACK_MAX`] halvings.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LineStats {
    pub searches: u64,
    pub unresolved: u64,
    pub backtracked: u64,
    pub rose: u64,
}

impl System {
    /// G at (x_t, v⁺) (see the module documentation), with the damping's directions and the
    /// external forces frozen at the line search's start. The springs', hinges' and gas's
    /// energies are the last evaluation's (`System::eval` sums them in its passes): call it
    /// right after evaluating at (x_t, v⁺).
    pub(crate) fn potential(&self, fr: &Frame, vp: &[f64], xt: &[f64], fz: &Frozen) -> Potential {
        let (p, w, m, dt) = (fr.p, fr.w, fr.m, fr.dt);
        let mut g = Sum::default();
        g.add(self.spring_energy);
        g.add(self.gas_energy);
        let cs = p.spring_damping;
        if cs != 0.0 {
            // R = ½ cs Σ_springs ((v_j − v_i) · d⁰)² = ¼ cs Σ over both rows' entries.
            let mut r = damping_sum(&self.edges, &fz.ed, vp);
            if self.bending {
                r += damping_sum(&self.bends, &fz.bd, vp);
            }
            g.add(dt * 0.25 * cs * r);
        }
        if self.hinged {
            let tau = p.retardation_time();
            let hn = &m.hinges;
            for (h, hv) in hn.v.iter().enumerate() {
                g.add(self.he[h]);
                if let (Some(g0), true) = (fz.hg.get(h), tau != 0.0) {
                    let g0: [[f64; 3]; 4] = std::array::from_fn(|q| [g0[3 * q], g0[3 * q + 1], g0[3 * q + 2]]);
                    let rd = rate(&g0, hv, vp);
                    g.add(dt * 0.5 * p.rigidity * hn.weight[h] * tau * rd * rd);
                }
            }
        }
        let c = p.damping;
        let targets = m.targets.active();
        for i in 0..m.mass.len() {
            let mi = m.mass[i];
            let k3 = 3 * i;
            let (mut kin, mut vv) = (0.0, 0.0);
            for d in 0..3 {
                let dv = vp[k3 + d] - fr.v[k3 + d];
                kin += dv * dv;
                vv += vp[k3 + d] * vp[k3 + d];
            }
            g.add(0.5 * mi * kin);
            g.add(mi * w.gravity * xt[k3 + 1]);
            g.add(dt * 0.5 * c * mi * vv);
            if m.external_active {
                g.add(-(0..3).map(|d| m.external[k3 + d] * xt[k3 + d]).sum::<f64>());
            }
            if let Some(fe) = &fz.fext {
                g.add(-dt * (0..3).map(|d| fe[k3 + d] * vp[k3 + d]).sum::<f64>());
            }
            if targets {
                let (kt, ct) = (m.targets.k[i], m.targets.c[i]);
                if kt != 0.0 || ct != 0.0 {
                    let a = &m.targets.anchor[k3..k3 + 3];
                    let d2: f64 = (0..3).map(|d| (a[d] - xt[k3 + d]).powi(2)).sum();
                    g.add(0.5 * kt * d2 + dt * 0.5 * ct * vv);
                }
            }
        }
        let sc = &m.self_contacts;
        for ct in &sc.list {
            let d = along(ct, xt);
            if d < sc.thickness {
                g.add(0.5 * ct.k * (sc.thickness - d).powi(2));
            }
        }
        Potential { value: g.value, noise: 16.0 * f64::EPSILON * g.scale }
    }
}

/// Σ over the CSR entries of `rows` of ((v_o − v_i) · d⁰)², d⁰ the entry's frozen direction.
fn damping_sum(rows: &SpringRows, dirs: &[[f64; 3]], vp: &[f64]) -> f64 {
    let mut sum = 0.0;
    for i in 0..rows.start.len() - 1 {
        for kk in rows.start[i] as usize..rows.start[i + 1] as usize {
            let (o, d) = (3 * rows.other[kk] as usize, dirs[kk]);
            let dvn = (vp[o] - vp[3 * i]) * d[0] + (vp[o + 1] - vp[3 * i + 1]) * d[1] + (vp[o + 2] - vp[3 * i + 2]) * d[2];
            sum += dvn * dvn;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::super::system::Frame;
    use super::super::{Implicit, Relaxed};
    use crate::body::{Material, SoftBody, Target};
    use crate::mesh::builtin::{builtin, icosphere};
    use crate::par::Threads;
    use crate::world::{Budget, Ground, World, WorldSettings};

    const FRAME: f64 = 1.0 / 60.0;

    /// The modeler's 642-vertex sphere (springs with damping, hinges with their damping, gas,
    /// gravity) in a 1 m/s wind, four vertices pulled by target
    /// springs, after 10 steps: every term of G moving (no face crushed: `hinges::bend`'s fade).
    fn moving_sphere() -> World {
        let body = SoftBody::new(&icosphere(3, 1.0), 1.0, Material::default()).unwrap();
        let mut w = World::single(body, WorldSettings { wind: [1.0, 0.0, 0.3], ..WorldSettings::default() });
        w.apply_preset(0, "modeler").unwrap();
        w.settings.wind_drag = 0.5;
        let x = w.bodies[0].positions().to_vec();
        let grab: Vec<Target> = (0..4).map(|i| Target { vertex: i, anchor: [x[3 * i] + 0.3, x[3 * i + 1] + 0.2, x[3 * i + 2]], stiffness: 200.0, damping: 1.0 }).collect();
        w.bodies[0].set_targets(&grab).unwrap();
        for _ in 0..10 {
            w.step().unwrap();
        }
        w
    }

    /// ∂G/∂v⁺ = r: along a direction δ, the central difference (G(v⁺ + hδ) − G(v⁺ − hδ)) / 2h
    /// against the residual's slope δ · r, at an iterate away from the solution (v⁺ = v + a
    /// perturbation, so r is not small), with the damping's directions frozen there.
    /// Tolerance: the central difference errs by h² |G'''| / 6 + (G's rounding) / h; at h = 1e-4
    /// (δ of 0.1 m/s per coordinate: x_t moves 1.7e-7 m) the first is ~1e-8 of the slope, the
    /// second ~1e-14 J / 1e-4 against a slope of ~1e-2 J: 1e-6 relative holds both with room,
    /// and a missing or wrong term (a force without its energy) is off by far more (the
    /// springs' damping on moving directions was 4× off, `potential.rs`).
    #[test]
    fn the_residual_is_the_gradient_of_the_step_potential() {
        let w = moving_sphere();
        let b = &w.bodies[0];
        let th = Threads::single();
        let fr = Frame { p: &b.material, w: &w.settings, m: &b.model, x: &b.state.x, v: &b.state.v, dt: FRAME, relax: Relaxed::No };
        let mut im = Implicit::new(&b.model);
        let n = b.state.v.len();
        let wiggle: Vec<f64> = (0..n).map(|k| 0.05 * ((k as f64) * 1.7).sin()).collect();
        for k in 0..n {
            im.vp[k] = b.state.v[k] + wiggle[k];
        }
        im.eval(&th, &fr).unwrap();
        
        assert!(im.sys.hinged && !im.sys.crushed && b.model.targets.active(), "hinges, none faded (the fade is not a potential), and targets");
        im.frozen.take(&im.sys, &fr);
        let delta: Vec<f64> = (0..n).map(|k| 0.1 * ((k as f64) * 0.37 + 1.0).cos()).collect();
        let slope: f64 = delta.iter().zip(&im.r).map(|(d, r)| d * r).sum();
        let h = 1e-4;
        let v0 = im.vp.clone();
        let mut g_at = |sign: f64| {
            for ((vp, v), d) in im.vp.iter_mut().zip(&v0).zip(&delta) {
                *vp = v + sign * h * d;
            }
            im.eval(&th, &fr).unwrap();
            im.sys.potential(&fr, &im.vp, &im.xt, &im.frozen).value
        };
        let fd = (g_at(1.0) - g_at(-1.0)) / (2.0 * h);
        assert!(slope.abs() > 1e-4, "a slope worth testing: {slope:e}");
        assert!((fd - slope).abs() <= 1e-6 * slope.abs(), "dG/dλ {fd:e} against δ · r {slope:e}");
    }

    /// Every line search that changes G by more than its rounding ends lower, by the Armijo
    /// margin (the test in `Implicit::line_search`, made where a deadline may stop the solve):
    /// through the modeler's mushroom on the ground grabbed hard (0.8 m aside and 0.4 m up over
    /// 0.5 s at ω = 600 1/s, held, let go) and a drop of the sphere, each under a budget whose
    /// deadline never passes (every step converged) and one whose every deadline has passed (the
    /// anytime step at its most truncated). None needed more than the halvings allowed
    /// (`rose`). Without a deadline the test is not made: the trace stays empty.
    #[test]
    fn accepted_iterates_never_raise_the_step_potential() {
        let mut mesh = builtin("mushroom").unwrap();
        let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
        mesh.positions.chunks_exact_mut(3).for_each(|p| p[1] -= lo);
        let mut dropped = icosphere(3, 0.5);
        dropped.positions.chunks_exact_mut(3).for_each(|p| p[1] += 1.2);
        fn never() -> f64 {
            0.0
        }
        fn late() -> f64 {
            use std::sync::atomic::{AtomicU64, Ordering};
            static T: AtomicU64 = AtomicU64::new(0);
            T.fetch_add(1, Ordering::Relaxed) as f64
        }
        for (name, mesh, grab) in [("mushroom", mesh, true), ("sphere", dropped, false)] {
            for (label, budget) in [("converge", Budget { splits: 3, relax: true, ..Budget::converge() }), ("never late", Budget::real_time(0.012, never)), ("late", Budget::real_time(0.012, late))] {
                let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
                let mut w = World::single(body, WorldSettings { ground: Some(Ground::at(0.0)), ..WorldSettings::default() });
                w.apply_preset(0, "modeler").unwrap();
                let x0 = w.bodies[0].positions().to_vec();
                let top = (0..x0.len() / 3).max_by(|&a, &b| x0[3 * a + 1].total_cmp(&x0[3 * b + 1])).unwrap();
                let k = w.bodies[0].masses()[top] * 600.0f64.powi(2);
                for f in 0..90 {
                    if grab && f < 45 {
                        let s = (f as f64 / 30.0).min(1.0);
                        let t = Target { vertex: top, anchor: [x0[3 * top] + 0.8 * s, x0[3 * top + 1] + 0.4 * s, x0[3 * top + 2]], stiffness: k, damping: 0.0 };
                        w.bodies[0].set_targets(&[t]).unwrap();
                    } else if f == 45 {
                        w.bodies[0].set_targets(&[]).unwrap();
                    }
                    w.advance(FRAME, &budget).unwrap();
                    assert!(w.bodies[0].positions().iter().all(|x| x.is_finite()));
                }
                let im = w.bodies[0].work.implicit.as_ref().unwrap();
                if label == "converge" {
                    assert!(im.trace.is_empty() && im.lines.searches > 50, "{name}: {:?}", im.lines);
                    continue;
                }
                assert!(im.trace.len() > 50, "{name} {label}: {} line searches resolved", im.trace.len());
                for (i, &(g0, g1, noise)) in im.trace.iter().enumerate() {
                    assert!(g1 < g0 + noise, "{name} {label}: line search {i} raised G from {g0} to {g1} (rounding {noise:e})");
                }
                assert_eq!(im.lines.rose, 0, "{name} {label}: {:?}", im.lines);
            }
        }
    }
}
