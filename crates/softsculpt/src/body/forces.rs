//! The force stages: everything that turns a state (x, v) into accelerations.

use super::{external, gas, Material, Model};
use super::parforces::ParForces;
use crate::error::SimError;
use crate::par::{Out, Threads};
use crate::world::WorldSettings;

/// A failure inside a step, before the step number is known.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Fault {
    NonFinite,
    Collapsed(f64),
    /// The implicit step's Newton iterations reached their cap at this relative residual.
    NotConverged { iterations: u32, residual: f64 },
}

impl Fault {
    /// The error of world step `step` that started at `time` (s); `tolerance` the implicit one.
    pub fn at(self, step: u64, time: f64, tolerance: f64) -> SimError {
        match self {
            Fault::NonFinite => SimError::NonFinite { step },
            Fault::Collapsed(volume) => SimError::Collapsed { step, volume },
            Fault::NotConverged { iterations, residual } => SimError::NotConverged { step, time, iterations, residual, tolerance },
        }
    }
}

/// Result of the force stages: the accumulator `f` holds forces divided by `scale`.
///
/// Why a scale: the gas force on vertex i is s g_i with s = (P − P_ref)/6 and g_i = Σ n_f over
/// the faces around i, and P is known only once the faces stage has summed the whole volume.
/// Rather than keep g in a second array until then (one more array read and written per vertex
/// and step), the faces stage accumulates g into `f`, and the springs and external stages that
/// follow add their forces divided by s. The vertex stage multiplies back by s. Division and
/// multiplication by the same s round to within 2 ulp of the direct sum.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Gathered {
    /// Multiplies the accumulator to give forces in N.
    pub scale: f64,
}

/// |s| outside this range is not used as a scale (the gas force is then dropped if tiny).
const SCALE_MIN: f64 = 1e-200;

/// Stages faces, gas, springs and external: fill `f` (zero on entry) with force / scale.
///
/// With `par` (several threads) the faces and springs stages run on the pool in chunks of
/// vertices (`parforces.rs`); the rare stages (wind, face pressures, targets) stay on this thread.
#[allow(clippy::too_many_arguments)]
pub(crate) fn gather(th: &Threads, mut par: Option<&mut ParForces>, p: &Material, w: &WorldSettings, m: &Model, x: &[f64], v: &[f64], f: &mut [f64]) -> Result<Gathered, Fault> {
    let nrt = p.nrt();
    let gas_active = nrt != 0.0 || m.gas.ambient_pressure != 0.0;

    // Stage faces: the exact volume, plus Σ n_f per vertex into f when a gas will use it.
    let six_v = match par.as_deref_mut() {
        Some(par) => par.faces(th, m, x, f, gas_active),
        None if gas_active => m.faces.volume6_and_normals(x, f),
        None => m.faces.volume6(x),
    };
    if !six_v.is_finite() {
        return Err(Fault::NonFinite);
    }

    // Stage gas: s = (P − P_ref) / 6 with P = nRT / V from the selected volume.
    let mut scale = 1.0;
    if gas_active {
        let volume = gas::measure(m.faces.triangles(), p.volume_mode, six_v, x);
        if !(volume > 0.0) {
            return Err(if volume.is_finite() { Fault::Collapsed(volume) } else { Fault::NonFinite });
        }
        let s = (gas::pressure(nrt, volume) - m.gas.ambient_pressure) / 6.0;
        if s.abs() >= SCALE_MIN && s.is_finite() {
            scale = s;
        } else {
            // No net gas force (typically right after a freeze, where P = P_ref exactly).
            f.fill(0.0);
        }
    }
    let inv = 1.0 / scale;

    // Stage springs.
    if let Some(par) = par {
        let kb = (p.bending_stiffness > 0.0).then_some(p.bending_stiffness * inv);
        par.springs(th, m, p.stiffness * inv, kb, p.spring_damping * inv, x, v, f);
    } else {
        m.springs.accumulate(p.stiffness * inv, p.spring_damping * inv, x, v, f);
        if p.bending_stiffness > 0.0 {
            m.bending.accumulate(p.bending_stiffness * inv, p.spring_damping * inv, x, v, f);
        }
    }

    // Stage external: wind and user face pressures.
    if w.wind_drag > 0.0 && w.wind != [0.0; 3] {
        external::wind(m.faces.triangles(), x, v, w.wind, w.wind_drag * inv, f);
    }
    if m.face_pressure_active {
        external::face_pressures(m.faces.triangles(), x, &m.face_pressure, inv, f);
    }

    // Stage targets: the target springs (`targets.rs`).
    if m.targets.active() {
        m.targets.accumulate(x, v, inv, f);
    }
    Ok(Gathered { scale })
}

/// Acceleration of vertex i (m/s²) from the accumulators, user force, gravity and damping:
///   a = (scale · f + f_user + f_prestress) / m − c v + (0, −g, 0), and 0 for a pinned vertex.
#[inline(always)]
fn accel<const USER: bool, const UNIFORM: bool>(
    k: usize,
    im: f64,
    f: &[f64],
    user: &[f64],
    scale: f64,
    v: f64,
    c: f64,
    gravity_k: f64,
) -> f64 {
    let mut force = scale * f[k];
    if USER {
        force += user[k];
    }
    let mut a = im * force;
    if UNIFORM {
        // Pinned vertices (im = 0) feel no gravity or damping either.
        let free = if im != 0.0 { 1.0 } else { 0.0 };
        a += free * (gravity_k - c * v);
    }
    a
}

/// Which per-vertex terms are present: chosen once per stage, not per vertex.
macro_rules! dispatch {
    ($m:expr, $p:expr, $w:expr, $fun:ident ( $($arg:expr),* )) => {{
        let user = $m.external_active;
        let uniform = $w.gravity != 0.0 || $p.damping != 0.0;
        match (user, uniform) {
            (false, false) => $fun::<false, false>($($arg),*),
            (false, true) => $fun::<false, true>($($arg),*),
            (true, false) => $fun::<true, false>($($arg),*),
            (true, true) => $fun::<true, true>($($arg),*),
        }
    }};
}

/// Stage vertices (generic): write accelerations into `a` and clear the accumulators; the
/// vertices in chunks on the pool when `par` is given.
#[allow(clippy::too_many_arguments)]
pub(crate) fn accelerations(th: &Threads, par: Option<&mut ParForces>, p: &Material, w: &WorldSettings, m: &Model, gathered: Gathered, v: &[f64], f: &mut [f64], a: &mut [f64]) {
    let Some(par) = par else {
        return dispatch!(m, p, w, accelerations_impl(p, w.gravity, &m.inv_mass, &m.external, gathered.scale, v, f, a));
    };
    let (fo, ao) = (Out::new(f), Out::new(a));
    par.vertices(th, |vr| {
        let r3 = 3 * vr.start..3 * vr.end;
        // SAFETY: every chunk writes its own vertices only.
        let (f, a) = unsafe { (fo.range(r3.clone()), ao.range(r3.clone())) };
        dispatch!(m, p, w, accelerations_impl(p, w.gravity, &m.inv_mass[vr.clone()], &m.external[r3.clone()], gathered.scale, &v[r3.clone()], f, a))
    });
}

/// On the vertices of `inv_mass` (a range of the body's, with the matching slices).
#[allow(clippy::too_many_arguments)]
fn accelerations_impl<const USER: bool, const UNIFORM: bool>(
    p: &Material,
    gravity: f64,
    inv_mass: &[f64],
    user: &[f64],
    scale: f64,
    v: &[f64],
    f: &mut [f64],
    a: &mut [f64],
) {
    let n = inv_mass.len();
    let (v, f, a, user) = (&v[..3 * n], &mut f[..3 * n], &mut a[..3 * n], &user[..3 * n]);
    let grav = [0.0, -gravity, 0.0];
    for i in 0..n {
        let im = inv_mass[i];
        for d in 0..3 {
            let k = 3 * i + d;
            a[k] = accel::<USER, UNIFORM>(k, im, f, user, scale, v[k], p.damping, grav[d]);
            f[k] = 0.0;
        }
    }
}

/// Stage vertices fused with symplectic Euler: v += dt a; x += dt v; clear the accumulators;
/// the vertices in chunks on the pool when `par` is given.
#[allow(clippy::too_many_arguments)]
pub(crate) fn symplectic_update(th: &Threads, par: Option<&mut ParForces>, p: &Material, w: &WorldSettings, m: &Model, gathered: Gathered, dt: f64, x: &mut [f64], v: &mut [f64], f: &mut [f64]) {
    let Some(par) = par else {
        return dispatch!(m, p, w, symplectic_impl(p, w.gravity, &m.inv_mass, &m.external, gathered.scale, dt, x, v, f));
    };
    let (xo, vo, fo) = (Out::new(x), Out::new(v), Out::new(f));
    par.vertices(th, |vr| {
        let r3 = 3 * vr.start..3 * vr.end;
        // SAFETY: every chunk writes its own vertices only.
        let (x, v, f) = unsafe { (xo.range(r3.clone()), vo.range(r3.clone()), fo.range(r3.clone())) };
        dispatch!(m, p, w, symplectic_impl(p, w.gravity, &m.inv_mass[vr.clone()], &m.external[r3.clone()], gathered.scale, dt, x, v, f))
    });
}

/// On the vertices of `inv_mass` (a range of the body's, with the matching slices).
#[allow(clippy::too_many_arguments)]
fn symplectic_impl<const USER: bool, const UNIFORM: bool>(
    p: &Material,
    gravity: f64,
    inv_mass: &[f64],
    user: &[f64],
    scale: f64,
    dt: f64,
    x: &mut [f64],
    v: &mut [f64],
    f: &mut [f64],
) {
    let n = inv_mass.len();
    let (x, v, f, user) = (&mut x[..3 * n], &mut v[..3 * n], &mut f[..3 * n], &user[..3 * n]);
    let grav = [0.0, -gravity, 0.0];
    for i in 0..n {
        let im = inv_mass[i];
        for d in 0..3 {
            let k = 3 * i + d;
            let acc = accel::<USER, UNIFORM>(k, im, f, user, scale, v[k], p.damping, grav[d]);
            v[k] += dt * acc;
            x[k] += dt * v[k];
            f[k] = 0.0;
        }
    }
}
