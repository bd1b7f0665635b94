//! The integrators, on the state (x, v) with a(x, v) from the force stages.

use super::forces::{accelerations, evaluate, symplectic, Fault};
use super::parforces::ParForces;
use super::implicit::{Implicit, SolverIterations};
use super::{Material, Model, State, Work};
use crate::par::{Out, Threads};
use crate::settings::{Integrator, WorldSettings};

/// a(x, v) into `a` (m/s²); `x` and `v` are only read.
#[allow(clippy::too_many_arguments)]
fn eval(th: &Threads, par: &mut ParForces, p: &Material, w: &WorldSettings, m: &Model, x: &mut [f64], v: &mut [f64], rare: &mut [f64], a: &mut [f64]) -> Result<(), Fault> {
    let ao = Out::new(a);
    evaluate(th, par, p, w, m, x, v, rare, |vr, f, fa, _, v| {
        // SAFETY: every chunk writes its own vertices only.
        let a = unsafe { ao.range(3 * vr.start..3 * vr.end) };
        accelerations(p, w, m, vr, f, fa, v, a);
    })
}

fn ensure(buf: &mut Vec<f64>, n: usize) {
    if buf.len() != n {
        *buf = vec![0.0; n];
    }
}

/// One step of `dt` (s). The state is left untouched if a force evaluation fails (and by the
/// implicit integrator if it does not converge).
pub(crate) fn step(p: &Material, world: &WorldSettings, m: &Model, s: &mut State, w: &mut Work, dt: f64, threads: &Threads) -> Result<(), Fault> {
    let n = s.x.len();
    w.iterations = SolverIterations::default();
    if world.integrator == Integrator::Implicit {
        // Backward Euler (`implicit/`): its scratch is built on the first implicit step.
        if !w.implicit.as_ref().is_some_and(|i| i.fits(m)) {
            w.implicit = Some(Box::new(Implicit::new(m)));
        }
        let solver = w.implicit.as_mut().expect("built above");
        w.iterations = solver.step(threads, p, world, m, s, dt)?;
        return Ok(());
    }
    // The explicit stages in chunks of vertices (`parforces.rs`), partition built once.
    if !w.par.as_ref().is_some_and(|q| q.fits(m)) {
        w.par = Some(Box::new(ParForces::new(m)));
    }
    let Work { f, xs, vs, a, par, .. } = w;
    let par = par.as_deref_mut().expect("built above");
    let th = threads;
    let w = world;
    match w.integrator {
        Integrator::Implicit => unreachable!("handled above"),
        Integrator::Symplectic => {
            // v' = v + dt a(x, v); x' = x + dt v', fused into the force stages' second pass.
            evaluate(th, par, p, w, m, &mut s.x, &mut s.v, f, |vr, f, fa, x, v| symplectic(p, w, m, vr, f, fa, dt, x, v))?;
        }
        Integrator::Euler => {
            // x' = x + dt v; v' = v + dt a(x, v)
            ensure(&mut a[0], n);
            eval(th, par, p, w, m, &mut s.x, &mut s.v, f, &mut a[0])?;
            for k in 0..n {
                s.x[k] += dt * s.v[k];
                s.v[k] += dt * a[0][k];
            }
        }
        Integrator::Midpoint => {
            // a1 = a(x, v); (xm, vm) = (x + dt/2 v, v + dt/2 a1); a2 = a(xm, vm)
            // x' = x + dt vm; v' = v + dt a2
            ensure(&mut a[0], n);
            ensure(&mut a[1], n);
            ensure(xs, n);
            ensure(vs, n);
            eval(th, par, p, w, m, &mut s.x, &mut s.v, f, &mut a[0])?;
            let h = 0.5 * dt;
            for k in 0..n {
                xs[k] = s.x[k] + h * s.v[k];
                vs[k] = s.v[k] + h * a[0][k];
            }
            eval(th, par, p, w, m, xs, vs, f, &mut a[1])?;
            for k in 0..n {
                s.x[k] += dt * vs[k];
                s.v[k] += dt * a[1][k];
            }
        }
        Integrator::Rk4 => {
            // Classic RK4 on y = (x, v), y' = (v, a(x, v)). With a1..a4 the stage accelerations,
            // the stage velocities are v, v + h/2 a1, v + h/2 a2, v + h a3, and
            //   x' = x + h v + h²/6 (a1 + a2 + a3)
            //   v' = v + h/6 (a1 + 2 a2 + 2 a3 + a4)
            for b in a.iter_mut() {
                ensure(b, n);
            }
            ensure(xs, n);
            ensure(vs, n);
            let h = dt;
            eval(th, par, p, w, m, &mut s.x, &mut s.v, f, &mut a[0])?;
            for k in 0..n {
                xs[k] = s.x[k] + 0.5 * h * s.v[k];
                vs[k] = s.v[k] + 0.5 * h * a[0][k];
            }
            eval(th, par, p, w, m, xs, vs, f, &mut a[1])?;
            for k in 0..n {
                // x3 = x + h/2 (v + h/2 a1)
                xs[k] = s.x[k] + 0.5 * h * (s.v[k] + 0.5 * h * a[0][k]);
                vs[k] = s.v[k] + 0.5 * h * a[1][k];
            }
            eval(th, par, p, w, m, xs, vs, f, &mut a[2])?;
            for k in 0..n {
                // x4 = x + h (v + h/2 a2)
                xs[k] = s.x[k] + h * (s.v[k] + 0.5 * h * a[1][k]);
                vs[k] = s.v[k] + h * a[2][k];
            }
            eval(th, par, p, w, m, xs, vs, f, &mut a[3])?;
            for k in 0..n {
                s.x[k] += h * s.v[k] + h * h / 6.0 * (a[0][k] + a[1][k] + a[2][k]);
                s.v[k] += h / 6.0 * (a[0][k] + 2.0 * a[1][k] + 2.0 * a[2][k] + a[3][k]);
            }
        }
    }
    Ok(())
}
