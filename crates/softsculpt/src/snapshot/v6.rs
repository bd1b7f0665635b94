//! Snapshot format version 6 (`super` holds the header and the policy; `v1.rs` versions 1
//! and 2, and each version below this one its own file): the version-5 payload
//! followed by [`ExtensionV6`], each body's kept coarse levels — where the implicit integrator's
//! multigrid levels it reuses while the body rests were assembled (`body/implicit/keep.rs`), so a
//! restored world assembles the same levels and takes the same steps bit for bit. Versions 1
//! to 5 read with none kept (the next resting step assembles afresh: the same backward-Euler
//! step within the tolerance, not the same bits).
//!
//! Undo deltas (`crate::delta`, format 5) keep it with the velocities, as the warm start.

use crate::body::implicit::Kept;
use super::v5::{payload_v5, world_from_v5, WorldV5};
use crate::world::World;
use serde::{Deserialize, Serialize};

/// Version 6: the version-5 payload and what version 6 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV6 {
    pub v5: WorldV5,
    pub ext6: ExtensionV6,
}

/// What version 6 added: per body, in body order (an empty list: none kept on any body).
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct ExtensionV6 {
    pub bodies: Vec<KeptV6>,
}

/// One body's kept coarse levels (`Kept`): empty `xt` for none.
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct KeptV6 {
    /// x_t = x + dt v⁺ at their assembly (m, flat xyz).
    pub xt: Vec<f64>,
    /// The vertices the ground held then, ascending.
    pub held: Vec<u32>,
    /// Compressed springs by the absolute value of their transverse factor.
    pub absolute: bool,
    /// The fingerprint of the model's other inputs to the assembly then.
    pub inputs: u64,
}

/// The version-6 additions of `w`.
pub(crate) fn extension6(w: &World) -> ExtensionV6 {
    ExtensionV6 {
        bodies: w
            .bodies
            .iter()
            .map(|b| {
                let k = &b.state.kept;
                KeptV6 { xt: k.xt.clone(), held: k.held.clone(), absolute: k.absolute, inputs: k.inputs }
            })
            .collect(),
    }
}

/// The whole version-6 payload of `w`.
pub(crate) fn payload_v6(w: &World) -> WorldV6 {
    WorldV6 { v5: payload_v5(w), ext6: extension6(w) }
}

/// A world from a whole version-6 payload.
pub(crate) fn world_from_v6(v6: WorldV6) -> Result<World, String> {
    let mut world = world_from_v5(v6.v5)?;
    apply_extension6(&mut world, &v6.ext6)?;
    Ok(world)
}

/// Apply the version-6 additions to a world read from the version-5 part (an empty list: none
/// kept on any body, as versions 1 to 5 read).
pub(crate) fn apply_extension6(w: &mut World, ext: &ExtensionV6) -> Result<(), String> {
    if ext.bodies.is_empty() {
        return Ok(());
    }
    if ext.bodies.len() != w.bodies.len() {
        return Err(format!("kept coarse levels for {} bodies, the world has {}", ext.bodies.len(), w.bodies.len()));
    }
    for (k, (b, e)) in w.bodies.iter_mut().zip(&ext.bodies).enumerate() {
        let n = b.state.x.len() / 3;
        if e.xt.is_empty() {
            if !e.held.is_empty() {
                return Err(format!("body {k}: kept coarse levels hold vertices but have no positions"));
            }
        } else {
            if e.xt.len() != 3 * n {
                return Err(format!("body {k}: kept coarse levels of {} values, expected {}", e.xt.len(), 3 * n));
            }
            if !e.xt.iter().all(|x| x.is_finite()) {
                return Err(format!("body {k}: the kept coarse levels' positions must be finite"));
            }
            if e.held.iter().any(|&i| i as usize >= n) || e.held.windows(2).any(|p| p[0] >= p[1]) {
                return Err(format!("body {k}: the kept coarse levels' held vertices must be ascending indices below {n}"));
            }
        }
        b.state.kept = Kept { xt: e.xt.clone(), held: e.held.clone(), absolute: e.absolute, inputs: e.inputs };
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::payload_v6;
    use crate::body::implicit::Kept;
    use crate::mesh::builtin::icosphere;
    use crate::snapshot::{frame, payload_v5, read, V5, V6};
    use crate::{Material, SoftBody, World, WorldSettings};

    fn world() -> World {
        let mut m = Material::default();
        m.set_nrt(5.0);
        let mut w = World::single(SoftBody::new(&icosphere(2, 1.0), 1.0, m).unwrap(), WorldSettings::default());
        w.bodies[0].state.kept = Kept { xt: w.bodies[0].positions().to_vec(), held: vec![3, 9], absolute: true, inputs: 0x1234_5678_9abc_def0 };
        w
    }

    /// A version-6 snapshot keeps each body's kept coarse levels, at the end of the payload.
    #[test]
    fn the_kept_levels_round_trip_at_the_end_of_the_payload() {
        let w = world();
        let bytes = w.snapshot();
        let back = read(&bytes).unwrap();
        assert_eq!(back.bodies[0].state.kept, w.bodies[0].state.kept);
        assert_eq!(back.snapshot(), bytes);
        let v5 = postcard::to_stdvec(&payload_v5(&w)).unwrap();
        let v6 = postcard::to_stdvec(&payload_v6(&w)).unwrap();
        assert_eq!(v6[..v5.len()], v5[..], "version 6 = the version-5 payload, then the extension");
        // A version-5 snapshot reads with none kept.
        let old = read(&frame(V5, &v5)).unwrap();
        assert!(old.bodies[0].state.kept.is_empty());
    }

    /// Kept levels of the wrong size, with non-finite positions, or held vertices out of range
    /// or out of order are refused as corrupted, naming the body.
    #[test]
    fn bad_kept_levels_are_refused() {
        let w = world();
        let n = w.bodies[0].positions().len() / 3;
        type Spoil = fn(&mut super::KeptV6, usize);
        let cases: [(Spoil, &str); 5] = [
            (|k, _| k.xt.pop().map(|_| ()).unwrap(), "kept coarse levels of"),
            (|k, _| k.xt[4] = f64::NAN, "positions must be finite"),
            (|k, n| k.held.push(n as u32), "ascending indices below"),
            (|k, _| k.held = vec![9, 3], "ascending indices below"),
            (|k, _| k.xt.clear(), "hold vertices but have no positions"),
        ];
        for (spoil, says) in cases {
            let mut p = payload_v6(&w);
            spoil(&mut p.ext6.bodies[0], n);
            let e = read(&frame(V6, &postcard::to_stdvec(&p).unwrap())).map(|_| ()).expect_err("refused").to_string();
            assert!(e.starts_with("the snapshot is corrupted: body 0: ") && e.contains(says), "{e}");
        }
    }
}
