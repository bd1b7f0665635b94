//! Snapshot format version 7 (`super` holds the header and the policy; `v1.rs` versions 1
//! and 2, and each version below this one its own file): the version-6 payload
//! followed by [`ExtensionV7`]: each body's hinge rest angles where the plastic stage moved them
//! off the frozen shape's (`body/plastic.rs`, "Bending"), and the pairs of bodies whose contacts
//! are off until they part (`world/overlaps.rs`). Versions 1 to 6 read with the rest angles of
//! the frozen shape, as they were written (before version 7 nothing moved them), and no such
//! pairs.
//!
//! Undo deltas (`crate::delta`, format 6) keep it with the rest lengths: what a plastic step
//! changed, undo puts back.

use super::v6::{payload_v6, world_from_v6, WorldV6};
use crate::world::World;
use serde::{Deserialize, Serialize};

/// Version 7: the version-6 payload and what version 7 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV7 {
    pub v6: WorldV6,
    pub ext7: ExtensionV7,
}

/// What version 7 added.
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct ExtensionV7 {
    /// Per body, in body order, its hinge rest angles (rad, one per hinge in `topology::hinges`
    /// order), or an empty list where they are the frozen shape's (every body: an empty list).
    pub bodies: Vec<Vec<f64>>,
    /// Pairs of bodies `[a, b]`, a < b, ascending, whose contacts are off until they part.
    pub overlaps: Vec<[u32; 2]>,
}

/// The version-7 additions of `w`: the rest angles of each body whose angles differ (bit for
/// bit) from those its frozen shape gives.
pub(crate) fn extension7(w: &World) -> ExtensionV7 {
    let bodies: Vec<Vec<f64>> = w
        .bodies
        .iter()
        .map(|b| if b.model.hinges.rest_is_of(&b.frozen.x) { Vec::new() } else { b.model.hinges.rest.clone() })
        .collect();
    ExtensionV7 { bodies: if bodies.iter().all(Vec::is_empty) { Vec::new() } else { bodies }, overlaps: w.overlaps.clone() }
}

/// The whole version-7 payload of `w`.
pub(crate) fn payload_v7(w: &World) -> WorldV7 {
    WorldV7 { v6: payload_v6(w), ext7: extension7(w) }
}

/// A world from a whole version-7 payload.
pub(crate) fn world_from_v7(v7: WorldV7) -> Result<World, String> {
    let mut world = world_from_v6(v7.v6)?;
    apply_extension7(&mut world, &v7.ext7)?;
    Ok(world)
}

/// Apply the version-7 additions to a world read from the version-6 part (an empty list: every
/// body's rest angles are its frozen shape's, as versions 1 to 6 read).
pub(crate) fn apply_extension7(w: &mut World, ext: &ExtensionV7) -> Result<(), String> {
    let n = w.bodies.len() as u32;
    if ext.overlaps.iter().any(|&[a, b]| a >= b || b >= n) || ext.overlaps.windows(2).any(|p| p[0] >= p[1]) {
        return Err(format!("overlapping bodies must be ascending pairs [a, b] with a < b < {n}"));
    }
    w.overlaps.clone_from(&ext.overlaps);
    if ext.bodies.is_empty() {
        return Ok(());
    }
    if ext.bodies.len() != w.bodies.len() {
        return Err(format!("hinge rest angles for {} bodies, the world has {}", ext.bodies.len(), w.bodies.len()));
    }
    for (k, (b, rest)) in w.bodies.iter_mut().zip(&ext.bodies).enumerate() {
        if rest.is_empty() {
            continue;
        }
        let hinges = &mut b.model.hinges;
        if rest.len() != hinges.len() {
            return Err(format!("body {k}: {} hinge rest angles, expected {}", rest.len(), hinges.len()));
        }
        if !rest.iter().all(|t| t.is_finite() && t.abs() <= std::f64::consts::PI) {
            return Err(format!("body {k}: hinge rest angles must be finite, within ±π rad"));
        }
        hinges.rest.clone_from(rest);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::payload_v7;
    use crate::mesh::builtin::icosphere;
    use crate::snapshot::{frame, payload_v6, read, V6, VERSION};
    use crate::{Material, SoftBody, World, WorldSettings};

    /// A gas ball with hinges whose rest angles were moved off the frozen shape's (as the
    /// plastic stage does).
    fn world() -> World {
        let mut m = Material::default();
        m.set_nrt(5.0);
        m.rigidity = 0.05;
        let body = SoftBody::new(&icosphere(2, 1.0), 1.0, m).unwrap();
        let mut w = World::new(vec![body.clone(), body.clone(), body], WorldSettings::default());
        for (h, t) in w.bodies[0].model.hinges.rest.iter_mut().enumerate() {
            *t += 1e-3 * (h as f64).sin();
        }
        w.overlaps = vec![[0, 2], [1, 2]];
        w
    }

    /// A version-7 snapshot keeps the moved rest angles, at the end of the payload; one whose
    /// angles are the frozen shape's writes none; a version-6 snapshot reads with the frozen
    /// shape's.
    #[test]
    fn moved_hinge_rest_angles_round_trip_at_the_end_of_the_payload() {
        let w = world();
        let bytes = w.snapshot();
        assert_eq!(bytes[5..9], VERSION.to_le_bytes());
        let back = read(&bytes).unwrap();
        assert_eq!(back.bodies[0].model.hinges.rest, w.bodies[0].model.hinges.rest);
        assert_eq!(back.overlaps, w.overlaps);
        assert_eq!(back.snapshot(), bytes);
        let v6 = postcard::to_stdvec(&payload_v6(&w)).unwrap();
        let v7 = postcard::to_stdvec(&payload_v7(&w)).unwrap();
        assert_eq!(v7[..v6.len()], v6[..], "version 7 = the version-6 payload, then the extension");
        let old = read(&frame(V6, &v6)).unwrap();
        let mut frozen = w.bodies[0].model.hinges.clone();
        frozen.rest_to(&w.bodies[0].frozen.x);
        assert_eq!(old.bodies[0].model.hinges.rest, frozen.rest);
        assert!(payload_v7(&old).ext7.bodies.is_empty(), "the frozen shape's angles are not written");
        assert!(old.overlaps.is_empty());
    }

    /// Rest angles of the wrong count, not finite or beyond ±π are refused as corrupted, naming
    /// the body; so are pairs of overlapping bodies out of order or out of range.
    #[test]
    fn bad_hinge_rest_angles_are_refused() {
        let w = world();
        type Spoil = fn(&mut Vec<f64>);
        let cases: [(Spoil, &str); 3] = [(|r| r.truncate(r.len() - 1), "hinge rest angles, expected"), (|r| r[2] = f64::NAN, "must be finite"), (|r| r[0] = 4.0, "within ±π")];
        for (spoil, says) in cases {
            let mut p = payload_v7(&w);
            spoil(&mut p.ext7.bodies[0]);
            let e = read(&frame(VERSION, &postcard::to_stdvec(&p).unwrap())).map(|_| ()).expect_err("refused").to_string();
            assert!(e.starts_with("the snapshot is corrupted: body 0: ") && e.contains(says), "{e}");
        }
        for pairs in [vec![[2, 1]], vec![[0, 3]], vec![[1, 2], [0, 2]], vec![[0, 0]]] {
            let mut p = payload_v7(&w);
            p.ext7.overlaps = pairs;
            let e = read(&frame(VERSION, &postcard::to_stdvec(&p).unwrap())).map(|_| ()).expect_err("refused").to_string();
            assert!(e.contains("ascending pairs"), "{e}");
        }
    }
}
