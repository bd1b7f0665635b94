//! Snapshot format version 5 (`super` holds the header and the policy; `v1.rs` versions 1
//! and 2, and each version below this one its own file): the version-4
//! payload followed by [`ExtensionV5`], each body's flexural rigidity D (J, `Material::rigidity`,
//! the hinges' bending energy). Versions 1 to 4 read with D = 0 (no hinge energy: what those
//! versions' bodies had).
//!
//! Undo deltas (`crate::delta`, format 4) compare it with the material.

use super::v4::{payload_v4, world_from_v4, WorldV4};
use crate::world::World;
use serde::{Deserialize, Serialize};

/// Version 5: the version-4 payload and what version 5 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV5 {
    pub v4: WorldV4,
    pub ext5: ExtensionV5,
}

/// What version 5 added: per body, in body order (an empty list: rigidity 0 on every body).
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct ExtensionV5 {
    pub bodies: Vec<BodyV5>,
}

/// One body's version-5 additions.
#[derive(Clone, Serialize, Deserialize)]
pub struct BodyV5 {
    /// Flexural rigidity D (J = N·m), `Material::rigidity`.
    pub rigidity: f64,
}

/// The version-5 additions of `w`.
pub(crate) fn extension5(w: &World) -> ExtensionV5 {
    ExtensionV5 { bodies: w.bodies.iter().map(|b| BodyV5 { rigidity: b.material.rigidity }).collect() }
}

/// The whole version-5 payload of `w`.
pub(crate) fn payload_v5(w: &World) -> WorldV5 {
    WorldV5 { v4: payload_v4(w), ext5: extension5(w) }
}

/// A world from a whole version-5 payload.
pub(crate) fn world_from_v5(v5: WorldV5) -> Result<World, String> {
    let mut world = world_from_v4(v5.v4)?;
    apply_extension5(&mut world, &v5.ext5)?;
    Ok(world)
}

/// Apply the version-5 additions to a world read from the version-4 part (an empty list: every
/// body's rigidity is 0, as versions 1 to 4 had it).
pub(crate) fn apply_extension5(w: &mut World, ext: &ExtensionV5) -> Result<(), String> {
    if ext.bodies.is_empty() {
        for b in &mut w.bodies {
            b.material.rigidity = 0.0;
        }
        return Ok(());
    }
    if ext.bodies.len() != w.bodies.len() {
        return Err(format!("rigidity for {} bodies, the world has {}", ext.bodies.len(), w.bodies.len()));
    }
    for (k, (b, e)) in w.bodies.iter_mut().zip(&ext.bodies).enumerate() {
        b.material.rigidity = e.rigidity;
        b.material.validate().map_err(|err| format!("body {k}: {err}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::payload_v5;
    use crate::mesh::builtin::icosphere;
    use crate::snapshot::{frame, payload_v4, read, V4, V5, VERSION};
    use crate::{Material, SoftBody, World, WorldSettings};

    fn world(rigidity: f64) -> World {
        let mut m = Material { rigidity, ..Material::default() };
        m.set_nrt(5.0);
        World::single(SoftBody::new(&icosphere(2, 1.0), 1.0, m).unwrap(), WorldSettings::default())
    }

    /// A version-5 snapshot keeps each body's rigidity; it is the last thing in the payload.
    #[test]
    fn the_rigidity_round_trips_at_the_end_of_the_payload() {
        let mut w = world(0.25);
        w.step_n(5).unwrap();
        let bytes = w.snapshot();
        assert_eq!(bytes[5..9], VERSION.to_le_bytes());
        let back = read(&bytes).unwrap();
        assert_eq!(back.bodies[0].material.rigidity, 0.25);
        assert_eq!(back.snapshot(), bytes);
        let v4 = postcard::to_stdvec(&payload_v4(&w)).unwrap();
        let v5 = postcard::to_stdvec(&payload_v5(&w)).unwrap();
        assert_eq!(v5[..v4.len()], v4[..], "version 5 = the version-4 payload, then the extension");
    }

    /// A version-4 snapshot reads with rigidity 0 and continues bit for bit otherwise.
    #[test]
    fn a_version_4_snapshot_reads_with_no_rigidity() {
        let mut w = world(0.0);
        w.step_n(20).unwrap();
        let v4 = frame(V4, &postcard::to_stdvec(&payload_v4(&w)).unwrap());
        let mut old = read(&v4).unwrap();
        assert_eq!(old.bodies[0].material.rigidity, 0.0);
        w.step_n(20).unwrap();
        old.step_n(20).unwrap();
        assert_eq!(old.bodies[0].positions(), w.bodies[0].positions());
        assert_eq!(old.snapshot(), w.snapshot());
    }

    /// A negative or NaN rigidity in a payload is refused as corrupted, naming the body.
    #[test]
    fn a_bad_rigidity_is_refused() {
        let w = world(0.1);
        for bad in [-1.0, f64::NAN] {
            let mut p = payload_v5(&w);
            p.ext5.bodies[0].rigidity = bad;
            let e = read(&frame(V5, &postcard::to_stdvec(&p).unwrap())).map(|_| ()).expect_err("refused").to_string();
            assert!(e.starts_with("the snapshot is corrupted: body 0: rigidity"), "{e}");
        }
    }
}
