//! Snapshot format version 4 (`super` holds the header and the policy; `v1.rs` versions 1
//! and 2, and each version below this one its own file): the version-3 payload followed by [`ExtensionV4`],
//! each body's implicit warm start — the velocity change v⁺ − v of its last accepted implicit
//! step and that step's dt, from which the next implicit step starts its Newton iterations
//! (`body/implicit/mod.rs`). A restored world therefore takes the same steps, bit for bit, as
//! the world it was taken of. Versions 1 to 3 read without it: the first implicit step after
//! the restore starts cold (from v⁺ = v), which gives a step within the same tolerance of the
//! same backward-Euler solution, not the same bits.
//!
//! Undo deltas (`crate::delta`, format 3) keep it with the velocities (scope `All`).

use super::v3::{payload_v3, world_from_v3, WorldV3};
use crate::world::World;
use serde::{Deserialize, Serialize};

/// Version 4: the version-3 payload and what version 4 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV4 {
    pub v3: WorldV3,
    pub ext4: ExtensionV4,
}

/// What version 4 added: per body, in body order (an empty list: no warm start on any body).
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct ExtensionV4 {
    pub bodies: Vec<WarmV4>,
}

/// One body's implicit warm start.
#[derive(Clone, Serialize, Deserialize)]
pub struct WarmV4 {
    /// v⁺ − v of the last accepted implicit step (m/s, flat xyz); empty: none.
    pub dv: Vec<f64>,
    /// That step's dt (s); 0 when `dv` is empty.
    pub dt: f64,
}

/// The whole version-4 payload of `w`.
pub(crate) fn payload_v4(w: &World) -> WorldV4 {
    WorldV4 { v3: payload_v3(w), ext4: ExtensionV4 { bodies: w.bodies.iter().map(|b| WarmV4 { dv: b.state.warm.clone(), dt: b.state.warm_dt }).collect() } }
}

/// A world from a whole version-4 payload.
pub(crate) fn world_from_v4(v4: WorldV4) -> Result<World, String> {
    let mut world = world_from_v3(v4.v3)?;
    apply_extension4(&mut world, &v4.ext4)?;
    Ok(world)
}

/// Apply the version-4 additions to a world read from the version-3 part.
pub(crate) fn apply_extension4(w: &mut World, ext: &ExtensionV4) -> Result<(), String> {
    if ext.bodies.is_empty() {
        return Ok(());
    }
    if ext.bodies.len() != w.bodies.len() {
        return Err(format!("warm starts for {} bodies, the world has {}", ext.bodies.len(), w.bodies.len()));
    }
    for (k, (b, e)) in w.bodies.iter_mut().zip(&ext.bodies).enumerate() {
        let n3 = b.state.v.len();
        if !e.dv.is_empty() && e.dv.len() != n3 {
            return Err(format!("body {k}: warm start of {} values, expected {n3}", e.dv.len()));
        }
        if !(e.dt.is_finite() && e.dt >= 0.0) || e.dv.iter().any(|d| !d.is_finite()) {
            return Err(format!("body {k}: the warm start must be finite (dt {} s)", e.dt));
        }
        b.state.warm = e.dv.clone();
        b.state.warm_dt = if e.dv.is_empty() { 0.0 } else { e.dt };
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::snapshot::{frame, payload_v3, read, V3};
    use crate::mesh::builtin::icosphere;
    use crate::world::Integrator;
    use crate::{Material, SoftBody, World, WorldSettings};

    fn implicit_world() -> World {
        let mut m = Material::default();
        m.set_nrt(5.0);
        let s = WorldSettings { integrator: Integrator::Implicit, dt: 1.0 / 60.0, tolerance: 1e-4, ..WorldSettings::default() };
        World::single(SoftBody::new(&icosphere(2, 1.0), 1.0, m).unwrap(), s)
    }

    /// A version-4 snapshot keeps the warm start: the restored world continues bit for bit.
    #[test]
    fn a_restored_world_continues_its_warm_started_steps_bit_for_bit() {
        let mut w = implicit_world();
        w.step_n(5).unwrap();
        assert!(!w.bodies[0].state.warm.is_empty());
        let mut copy = read(&w.snapshot()).unwrap();
        assert_eq!(copy.bodies[0].state.warm, w.bodies[0].state.warm);
        w.step_n(5).unwrap();
        copy.step_n(5).unwrap();
        assert_eq!(copy.bodies[0].positions(), w.bodies[0].positions());
    }

    /// A version-3 snapshot (no warm start) still reads and steps cold: within the tolerance of
    /// the same solution. Bound: each step's residual is ≤ 1e-4 of its explicit prediction's
    /// (a velocity error of ≲ 1e-4 · dt · |a| ≈ 1e-4 · 0.16 m/s per step under gravity), so over
    /// 5 steps of 1/60 s the positions differ by ≲ 5 · 1e-4 · 0.16 · 5/60 m ≈ 7e-6 m: 1e-4 m.
    #[test]
    fn a_version_3_snapshot_still_reads_and_starts_cold() {
        let mut w = implicit_world();
        w.step_n(5).unwrap();
        let v3 = frame(V3, &postcard::to_stdvec(&payload_v3(&w)).unwrap());
        let mut old = read(&v3).unwrap();
        assert!(old.bodies[0].state.warm.is_empty());
        assert_eq!(old.bodies[0].material.rigidity, 0.0);
        w.step_n(5).unwrap();
        old.step_n(5).unwrap();
        let gap = old.bodies[0].positions().iter().zip(w.bodies[0].positions()).fold(0.0f64, |g, (a, b)| g.max((a - b).abs()));
        assert!(gap < 1e-4, "cold vs warm after 5 steps: {gap} m");
    }
}
