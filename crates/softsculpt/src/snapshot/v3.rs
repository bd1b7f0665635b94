//! Snapshot format version 3 (`super` holds the header and the policy; `v1.rs` versions 1
//! and 2, and each version below this one its own file): the version-2 payload followed by [`ExtensionV3`], each body's plasticity (yield
//! strain, flow rate, the plastic dissipation so far) and whether its gas uses the bounding
//! ellipsoid (the version-1 part then says `Exact` in its place); and which pending scene freezes
//! keep the tension. Versions 1 and 2 read with the defaults: elastic, no dissipation, the
//! volume mode the version-1 part names, freezes without keeping the tension.

use crate::body::VolumeMode;
use super::v1::{apply_extension, extension, payload, world_from_v1, ExtensionV2, WorldV1};
use crate::world::{Action, World};
use serde::{Deserialize, Serialize};

/// Version 3: the version-2 payload and what version 3 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV3 {
    pub base: WorldV1,
    pub ext: ExtensionV2,
    pub ext3: ExtensionV3,
}

/// What version 3 added: per body, in body order (an empty list: the defaults on every body);
/// and which pending scene events are freezes keeping the tension.
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct ExtensionV3 {
    pub bodies: Vec<BodyV3>,
    /// Indices, among the pending events as the version-1 part lists them, of the freezes that
    /// keep the tension (`keep_tension = true`; the version-1 freeze action has no place for it).
    pub keep_tension_events: Vec<u32>,
}

/// One body's version-3 additions.
#[derive(Clone, Serialize, Deserialize)]
pub struct BodyV3 {
    /// The gas uses the bounding ellipsoid (the version-1 material then says `Exact`).
    pub ellipsoid: bool,
    /// Yield strain (dimensionless) and flow rate (1/s).
    pub yield_strain: f64,
    pub flow_rate: f64,
    /// Energy the plastic stage has taken out (J).
    pub plastic_dissipation: f64,
}

/// The version-3 additions of `w`.
pub(crate) fn extension3(w: &World) -> ExtensionV3 {
    ExtensionV3 {
        bodies: w
            .bodies
            .iter()
            .map(|b| BodyV3 {
                ellipsoid: b.material.volume_mode == VolumeMode::Ellipsoid,
                yield_strain: b.material.yield_strain,
                flow_rate: b.material.flow_rate,
                plastic_dissipation: b.plastic_dissipation(),
            })
            .collect(),
        keep_tension_events: w.events.list[w.events.next..]
            .iter()
            .enumerate()
            .filter(|(_, e)| matches!(e.action, Action::Freeze { keep_tension: true, .. }))
            .map(|(k, _)| k as u32)
            .collect(),
    }
}

/// Apply version-3 additions to a world read from the version-2 part.
pub(crate) fn apply_extension3(w: &mut World, ext: &ExtensionV3) -> Result<(), String> {
    let next = w.events.next;
    for &k in &ext.keep_tension_events {
        match w.events.list.get_mut(next + k as usize).map(|e| &mut e.action) {
            Some(Action::Freeze { keep_tension, .. }) => *keep_tension = true,
            _ => return Err(format!("pending event {k} keeps the tension but is not a freeze")),
        }
    }
    if ext.bodies.is_empty() {
        return Ok(());
    }
    if ext.bodies.len() != w.bodies.len() {
        return Err(format!("plasticity for {} bodies, the world has {}", ext.bodies.len(), w.bodies.len()));
    }
    for (k, (b, e)) in w.bodies.iter_mut().zip(&ext.bodies).enumerate() {
        if e.ellipsoid {
            b.material.volume_mode = VolumeMode::Ellipsoid;
        }
        b.material.yield_strain = e.yield_strain;
        b.material.flow_rate = e.flow_rate;
        b.material.validate().map_err(|err| format!("body {k}: {err}"))?;
        if !e.plastic_dissipation.is_finite() {
            return Err(format!("body {k}: plastic dissipation {} must be finite", e.plastic_dissipation));
        }
        b.set_plastic_dissipation(e.plastic_dissipation);
    }
    Ok(())
}

/// The whole payload of `w`'s snapshot (what `crate::delta` compares).
pub(crate) fn payload_v3(w: &World) -> WorldV3 {
    WorldV3 { base: payload(w), ext: extension(w), ext3: extension3(w) }
}

/// A world from a whole payload (an empty target list means none on any body, an empty
/// version-3 list the defaults on every body).
pub(crate) fn world_from_v3(v3: WorldV3) -> Result<World, String> {
    let mut ext = v3.ext;
    let mut world = world_from_v1(v3.base)?;
    if ext.targets.is_empty() {
        ext.targets = vec![Vec::new(); world.bodies.len()];
    }
    apply_extension(&mut world, &ext)?;
    apply_extension3(&mut world, &v3.ext3)?;
    Ok(world)
}


#[cfg(test)]
mod tests {
    use crate::snapshot::{frame, payload, extension, read, WorldV2, V1, V2};
    use crate::mesh::builtin::icosphere;
    use crate::{Material, SoftBody, World, WorldSettings};

    /// Snapshots written by versions 1 and 2 (their payloads framed as they framed them) still
    /// read, as elastic bodies with no dissipation, and continue exactly as the world they were
    /// taken of (same bits after 100 steps).
    #[test]
    fn versions_one_and_two_still_read() {
        let mut m = Material::default();
        m.set_nrt(5.0);
        let mut w = World::single(SoftBody::new(&icosphere(2, 1.0), 1.0, m).unwrap(), WorldSettings::default());
        w.step_n(50).unwrap();
        let v1 = frame(V1, &postcard::to_stdvec(&payload(&w)).unwrap());
        let v2 = frame(V2, &postcard::to_stdvec(&WorldV2 { base: payload(&w), ext: extension(&w) }).unwrap());
        w.step_n(100).unwrap();
        for bytes in [v1, v2] {
            let mut old = read(&bytes).unwrap();
            assert_eq!(old.bodies[0].material.flow_rate, 0.0);
            assert_eq!(old.bodies[0].plastic_dissipation(), 0.0);
            assert_eq!(old.bodies[0].material.rigidity, 0.0);
            old.step_n(100).unwrap();
            assert_eq!(old.bodies[0].positions(), w.bodies[0].positions());
        }
    }
}
