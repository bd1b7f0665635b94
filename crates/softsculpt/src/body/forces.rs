//! The force stages: everything that turns a state (x, v) into accelerations.

use super::{external, gas, Material, Model};
use super::parforces::{Coefficients, ParForces};
use crate::error::SimError;
use crate::par::{Out, Threads};
use crate::settings::WorldSettings;

/// A failure inside a step, before the step number is known.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Fault {
    NonFinite,
    Collapsed(f64),
    /// The implicit step's Newton iterations reached their cap at this relative residual.
    NotConverged { iterations: u32, residual: f64 },
    /// The caller asked the implicit step to stop (`WorldSettings::interrupt`).
    Interrupted,
}

impl Fault {
    /// The error of world step `step` that started at `time` (s); `tolerance` the implicit one.
    pub fn at(self, step: u64, time: f64, tolerance: f64) -> SimError {
        match self {
            Fault::NonFinite => SimError::NonFinite { step },
            Fault::Collapsed(volume) => SimError::Collapsed { step, volume },
            Fault::NotConverged { iterations, residual } => SimError::NotConverged { step, time, iterations, residual, tolerance },
            Fault::Interrupted => SimError::Interrupted { step, time },
        }
    }
}

/// Stages faces, gas, springs and external, and the vertex stage fused into the second pass.
///
/// The force on vertex i is
///   f_i = F_i + s g_i + f_rare,i + f_ext,i      (N)
/// with F the springs' (and bending springs') forces, g_i = Σ n_f over the faces around i (the
/// faces stage), s = (P − P_ref)/6 the gas scale (P from the volume, so known only once every
/// face is summed: hence two passes, `parforces.rs`), f_rare the rare stages' (wind, user face
/// pressures, targets: on the calling thread, into `rare`, only when active) and f_ext the user
/// force plus prestress. Same sum as the C++ reference's `F + Pg · G`.
///
/// `vertex(range, f, a, x, v)` then gets each chunk of vertices with their forces a · f (N; f
/// in a buffer it may overwrite, a = 1 except on one thread with a gas scale s that can be
/// divided by and no rare stage or user force active, where f is (F + s g) / s and a = s,
/// `ParForces::serial_b`) and their positions and velocities (which it may update: no other
/// chunk reads them after the forces are known), and may write those vertices of any array it
/// owns.
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate(
    th: &Threads,
    par: &mut ParForces,
    p: &Material,
    w: &WorldSettings,
    m: &Model,
    x: &mut [f64],
    v: &mut [f64],
    rare: &mut [f64],
    vertex: impl Fn(std::ops::Range<usize>, &[f64], f64, &mut [f64], &mut [f64]) + Sync,
) -> Result<(), Fault> {
    let nrt = p.nrt();
    let gas_active = nrt != 0.0 || m.gas.ambient_pressure != 0.0;
    let q = Coefficients { k: p.stiffness, kb: (p.bending_stiffness > 0.0).then_some(p.bending_stiffness), cs: p.spring_damping, normals: gas_active, scale: 0.0 };

    // Pass A: stage faces (the exact volume, Σ n_f per vertex when a gas uses it) and the
    // crossing springs.
    let six_v = par.pass_a(th, m, &q, x, v);
    if !six_v.is_finite() {
        return Err(Fault::NonFinite);
    }

    // Stage gas: s = (P − P_ref) / 6 with P = nRT / V from the selected volume.
    let mut scale = 0.0;
    if gas_active {
        let volume = gas::measure(m.faces.triangles(), p.volume_mode, six_v, x);
        if !(volume > 0.0) {
            return Err(if volume.is_finite() { Fault::Collapsed(volume) } else { Fault::NonFinite });
        }
        scale = (gas::pressure(nrt, volume) - m.gas.ambient_pressure) / 6.0;
    }

    // Stage external: wind, user face pressures, target springs and hinges, rarely active.
    let mut has_rare = false;
    if w.wind_drag > 0.0 && w.wind != [0.0; 3] {
        external::wind(m.faces.triangles(), x, v, w.wind, w.wind_drag, rare);
        has_rare = true;
    }
    if m.face_pressure_active {
        external::face_pressures(m.faces.triangles(), x, &m.face_pressure, 1.0, rare);
        has_rare = true;
    }
    if m.targets.active() {
        m.targets.accumulate(x, v, 1.0, rare);
        has_rare = true;
    }
    // Stage hinges (`hinges.rs`): bending by the dihedral angles, when the rigidity is set.
    if p.rigidity > 0.0 && !m.hinges.is_empty() {
        m.hinges.add_forces(p.rigidity, p.retardation_time(), x, v, rare);
        has_rare = true;
    }

    // Pass B: stage springs, then the vertex stage on each chunk.
    let q = Coefficients { scale, ..q };
    let (ro, user) = (Out::new(rare), m.external_active.then_some(&m.external[..]));
    par.pass_b(th, m, &q, x, v, |vr, f, g, mut a, x, v| {
        let r3 = 3 * vr.start..3 * vr.end;
        if !g.is_empty() {
            for (fk, gk) in f.iter_mut().zip(g) {
                *fk = a * *fk + scale * gk;
            }
            a = 1.0;
        }
        if a != 1.0 && (has_rare || user.is_some()) {
            f.iter_mut().for_each(|fk| *fk *= a);
            a = 1.0;
        }
        if has_rare {
            // SAFETY: every chunk takes its own vertices of `rare`.
            let r = unsafe { ro.range(r3.clone()) };
            for (fk, rk) in f.iter_mut().zip(r.iter_mut()) {
                *fk += *rk;
                *rk = 0.0;
            }
        }
        if let Some(u) = user {
            for (fk, uk) in f.iter_mut().zip(&u[r3]) {
                *fk += uk;
            }
        }
        vertex(vr, f, a, x, v);
    });
    Ok(())
}

/// Acceleration of vertex i (m/s²) from its force (N), gravity and damping:
///   a = f / m − c v + (0, −g, 0), and 0 for a pinned vertex.
#[inline(always)]
fn accel<const UNIFORM: bool>(im: f64, force: f64, v: f64, c: f64, gravity_k: f64) -> f64 {
    let mut a = im * force;
    if UNIFORM {
        // Pinned vertices (im = 0) feel no gravity or damping either.
        let free = if im != 0.0 { 1.0 } else { 0.0 };
        a += free * (gravity_k - c * v);
    }
    a
}

/// Stage vertices (generic): the accelerations of the vertices `vr` into `a`, from their
/// forces `fa · f` and velocities `v` (all chunk-local).
#[allow(clippy::too_many_arguments)]
pub(crate) fn accelerations(p: &Material, w: &WorldSettings, m: &Model, vr: std::ops::Range<usize>, f: &[f64], fa: f64, v: &[f64], a: &mut [f64]) {
    if w.gravity != 0.0 || p.damping != 0.0 {
        accelerations_impl::<true>(p.damping, w.gravity, &m.inv_mass[vr], f, fa, v, a)
    } else {
        accelerations_impl::<false>(p.damping, w.gravity, &m.inv_mass[vr], f, fa, v, a)
    }
}

#[allow(clippy::too_many_arguments)]
fn accelerations_impl<const UNIFORM: bool>(damping: f64, gravity: f64, inv_mass: &[f64], f: &[f64], fa: f64, v: &[f64], a: &mut [f64]) {
    let n = inv_mass.len();
    let (v, f, a) = (&v[..3 * n], &f[..3 * n], &mut a[..3 * n]);
    let grav = [0.0, -gravity, 0.0];
    for i in 0..n {
        let im = inv_mass[i];
        for d in 0..3 {
            let k = 3 * i + d;
            a[k] = accel::<UNIFORM>(im, fa * f[k], v[k], damping, grav[d]);
        }
    }
}

/// Stage vertices fused with symplectic Euler on the vertices `vr`: v += dt a; x += dt v, with
/// their forces `fa · f` (all chunk-local).
#[allow(clippy::too_many_arguments)]
pub(crate) fn symplectic(p: &Material, w: &WorldSettings, m: &Model, vr: std::ops::Range<usize>, f: &[f64], fa: f64, dt: f64, x: &mut [f64], v: &mut [f64]) {
    if w.gravity != 0.0 || p.damping != 0.0 {
        symplectic_impl::<true>(p.damping, w.gravity, &m.inv_mass[vr], f, fa, dt, x, v)
    } else {
        symplectic_impl::<false>(p.damping, w.gravity, &m.inv_mass[vr], f, fa, dt, x, v)
    }
}

#[allow(clippy::too_many_arguments)]
fn symplectic_impl<const UNIFORM: bool>(damping: f64, gravity: f64, inv_mass: &[f64], f: &[f64], fa: f64, dt: f64, x: &mut [f64], v: &mut [f64]) {
    let n = inv_mass.len();
    let (x, v, f) = (&mut x[..3 * n], &mut v[..3 * n], &f[..3 * n]);
    let grav = [0.0, -gravity, 0.0];
    for i in 0..n {
        let im = inv_mass[i];
        for d in 0..3 {
            let k = 3 * i + d;
            v[k] += dt * accel::<UNIFORM>(im, fa * f[k], v[k], damping, grav[d]);
            x[k] += dt * v[k];
        }
    }
}
