//! The snapshot format: a whole world as bytes, to continue exactly where it was
//! (`docs/snapshot.md` is the user's version of this file; keep the two in step).
//!
//! Layout (all integers little-endian):
//!
//! | bytes | what |
//! |---|---|
//! | 5 | magic `SSNAP` |
//! | 4 | format version (u32), [`VERSION`] |
//! | 8 | payload length in bytes (u64) |
//! | 4 | CRC-32 (IEEE) of the payload (u32) |
//! | … | payload: [`WorldV7`] encoded with postcard (serde); version 6: [`WorldV6`]; version 5: [`WorldV5`]; version 4: [`WorldV4`]; version 3: [`WorldV3`]; version 2: [`WorldV2`]; version 1: [`WorldV1`] |
//!
//! The payload holds everything that carries over from one step to the next: every body's mesh
//! (triangles), state, rest and bending rest lengths, masses, pins, prestress, user forces and
//! face pressures, gas reference, frozen state and material; the world's settings (obstacles
//! included: a triangle-mesh obstacle as its triangles, its BVH rebuilt on restore); the clock;
//! the pending events and the loads in force. Nothing else is kept: scratch buffers (force
//! accumulators, Runge–Kutta stages, contact hashes, start-of-step positions) hold nothing
//! between steps and are rebuilt, derived arrays (springs from the triangles, inverse masses,
//! the sum of user force and prestress) are recomputed by the same arithmetic, so stepping a
//! restored world gives the same bits as stepping the original.
//!
//! Version 2 (the implicit integrator) is the version-1 payload followed by [`ExtensionV2`]:
//! the implicit integrator's settings (tolerance, Newton iteration cap) and every body's target
//! springs. When the integrator is `implicit`, the version-1 part holds `Symplectic` in its
//! place and `ExtensionV2::implicit` is true. A version-1 snapshot reads as before, with the
//! defaults for the new settings and no targets.
//!
//! Version 3 (plasticity, the ellipsoid volume) is the version-2 payload followed by
//! `ExtensionV3` (`v3`). Versions 1 and 2 read with its defaults.
//!
//! Version 4 (the implicit integrator's warm start) is the version-3 payload followed by
//! `ExtensionV4` (`v4`). Versions 1 to 3 read without it (the next implicit step
//! starts cold).
//!
//! Version 5 (the hinges' flexural rigidity) is the version-4 payload followed by `ExtensionV5`
//! (`v5`): each body's `Material::rigidity`. Versions 1 to 4 read with rigidity 0.
//!
//! Version 6 (the implicit integrator's kept coarse levels) is the version-5 payload followed by
//! `ExtensionV6` (`v6`): where each body's kept multigrid levels were assembled.
//! Versions 1 to 5 read with none kept.
//!
//! Version 7 (the hinges' plastic rest angles) is the version-6 payload followed by
//! `ExtensionV7` (`v7`): each body's hinge rest angles where the plastic stage
//! moved them. Versions 1 to 6 read with the frozen shape's.
//!
//! Version policy: any change to the payload's types is a new version; this build reads the
//! versions up to [`VERSION`] (a newer one is refused with a message saying so), and keeps the
//! types of every older version it reads here, each with its conversion.

use crate::world::World;
use std::fmt;

mod v1;
mod v3;
mod v4;
mod v5;
mod v6;
mod v7;

pub use v1::*;

pub use v3::{BodyV3, ExtensionV3, WorldV3};
pub(crate) use v3::payload_v3;
pub use v4::{ExtensionV4, WarmV4, WorldV4};
pub(crate) use v4::payload_v4;
pub use v5::{BodyV5, ExtensionV5, WorldV5};
pub(crate) use v5::payload_v5;
pub use v6::{ExtensionV6, KeptV6, WorldV6};
pub(crate) use v6::payload_v6;
pub use v7::{ExtensionV7, WorldV7};
pub(crate) use v7::{payload_v7, world_from_v7};

/// The first bytes of every snapshot.
pub const MAGIC: &[u8; 5] = b"SSNAP";
/// The format version this build writes (and the newest it reads).
pub const VERSION: u32 = 7;
/// The first version, still read.
pub const V1: u32 = 1;
/// The second version (the implicit integrator), still read.
pub const V2: u32 = 2;
/// The third version (plasticity), still read.
pub const V3: u32 = 3;
/// The fourth version (the implicit warm start), still read.
pub const V4: u32 = 4;
/// The fifth version (the hinges' rigidity), still read.
pub const V5: u32 = 5;
/// The sixth version (the implicit integrator's kept coarse levels), still read.
pub const V6: u32 = 6;
/// Magic, version, payload length, checksum.
pub const HEADER_LEN: usize = 5 + 4 + 8 + 4;

/// Why bytes could not be restored as a world. Never a panic.
#[derive(Debug, Clone, PartialEq)]
pub enum SnapshotError {
    /// The bytes do not start with `SSNAP`.
    NotASnapshot,
    /// Fewer bytes than the header says there are.
    Truncated { expected: usize, got: usize },
    /// Made by a newer SoftSculpt.
    NewerVersion { found: u32, supported: u32 },
    /// A version no SoftSculpt wrote (0).
    UnknownVersion(u32),
    /// Checksum mismatch, trailing bytes, or a payload that does not decode into a valid world.
    Corrupted(String),
}

impl fmt::Display for SnapshotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SnapshotError::NotASnapshot => write!(f, "not a SoftSculpt snapshot (it does not start with SSNAP)"),
            SnapshotError::Truncated { expected, got } => write!(f, "the snapshot is truncated: {got} of {expected} bytes"),
            SnapshotError::NewerVersion { found, supported } => {
                write!(f, "snapshot format version {found} is newer than this SoftSculpt reads (≤ {supported})")
            }
            SnapshotError::UnknownVersion(v) => write!(f, "snapshot format version {v} does not exist"),
            SnapshotError::Corrupted(why) => write!(f, "the snapshot is corrupted: {why}"),
        }
    }
}

impl std::error::Error for SnapshotError {}


/// The snapshot of `w`: header and payload (see the module documentation).
pub fn write(w: &World) -> Vec<u8> {
    // Plain numbers, vectors and enums: postcard cannot fail on them.
    frame(VERSION, &postcard::to_stdvec(&payload_v7(w)).unwrap_or_default())
}

/// The bytes version `version` (1 to [`VERSION`]) of the format holds of `w`, or `None` for
/// another number: what an older SoftSculpt would have written of the state it knew (a newer
/// version's additions left out, an implicit world's version-1 part written as `Symplectic`).
/// For the stored snapshots of every older version that `tests/snapshot.rs` keeps opening
/// (`tests/fixtures/snapshots/`).
pub fn write_version(w: &World, version: u32) -> Option<Vec<u8>> {
    let bytes = match version {
        V1 => postcard::to_stdvec(&payload(w)),
        V2 => {
            let v3 = payload_v3(w);
            postcard::to_stdvec(&WorldV2 { base: v3.base, ext: v3.ext })
        }
        V3 => postcard::to_stdvec(&payload_v3(w)),
        V4 => postcard::to_stdvec(&payload_v4(w)),
        V5 => postcard::to_stdvec(&payload_v5(w)),
        V6 => postcard::to_stdvec(&payload_v6(w)),
        VERSION => postcard::to_stdvec(&payload_v7(w)),
        _ => return None,
    };
    Some(frame(version, &bytes.unwrap_or_default()))
}

/// Header (magic, `version`, length, checksum) and `payload`.
pub fn frame(version: u32, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(payload).to_le_bytes());
    out.extend_from_slice(payload);
    out
}

// ----- reading -----------------------------------------------------------------------------------

fn corrupted(why: impl Into<String>) -> SnapshotError {
    SnapshotError::Corrupted(why.into())
}

/// Check the header and checksum; the payload's bytes and the version.
fn open(bytes: &[u8]) -> Result<(u32, &[u8]), SnapshotError> {
    let magic_len = MAGIC.len().min(bytes.len());
    if bytes[..magic_len] != MAGIC[..magic_len] {
        return Err(SnapshotError::NotASnapshot);
    }
    if bytes.len() < HEADER_LEN {
        return Err(SnapshotError::Truncated { expected: HEADER_LEN, got: bytes.len() });
    }
    let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let version = word(5);
    if version > VERSION {
        return Err(SnapshotError::NewerVersion { found: version, supported: VERSION });
    }
    if version == 0 {
        return Err(SnapshotError::UnknownVersion(version));
    }
    let mut len = [0u8; 8];
    len.copy_from_slice(&bytes[9..17]);
    let len = u64::from_le_bytes(len);
    let expected = (HEADER_LEN as u64).saturating_add(len);
    if (bytes.len() as u64) < expected {
        return Err(SnapshotError::Truncated { expected: usize::try_from(expected).unwrap_or(usize::MAX), got: bytes.len() });
    }
    if (bytes.len() as u64) > expected {
        return Err(corrupted(format!("{} bytes after the end of the payload", bytes.len() as u64 - expected)));
    }
    let payload = &bytes[HEADER_LEN..];
    if crc32fast::hash(payload) != word(17) {
        return Err(corrupted("checksum mismatch"));
    }
    Ok((version, payload))
}

/// Restore a world from a snapshot (see [`SnapshotError`] for what can be wrong).
pub fn read(bytes: &[u8]) -> Result<World, SnapshotError> {
    let (version, payload) = open(bytes)?;
    let undecodable = |e: postcard::Error| corrupted(format!("the payload does not decode ({e})"));
    // Versions 1 to 6 take the later extensions' defaults (`ExtensionV5::default()`: rigidity 0;
    // `ExtensionV6::default()`: no kept coarse levels; `ExtensionV7::default()`: the frozen
    // shape's hinge rest angles).
    let v7 = |v6: WorldV6| WorldV7 { v6, ext7: ExtensionV7::default() };
    let v6 = |v5: WorldV5| v7(WorldV6 { v5, ext6: ExtensionV6::default() });
    let v5 = |v4: WorldV4| v6(WorldV5 { v4, ext5: ExtensionV5::default() });
    let (v7, rest): (WorldV7, &[u8]) = match version {
        V1 => {
            let (base, rest) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            let ext = ExtensionV2 { implicit: false, tolerance: crate::params::TOLERANCE.number(), newton_iterations: crate::params::NEWTON_ITERATIONS.number() as u32, targets: Vec::new() };
            (v5(WorldV4 { v3: WorldV3 { base, ext, ext3: ExtensionV3::default() }, ext4: ExtensionV4::default() }), rest)
        }
        V2 => {
            let (v2, rest): (WorldV2, &[u8]) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            (v5(WorldV4 { v3: WorldV3 { base: v2.base, ext: v2.ext, ext3: ExtensionV3::default() }, ext4: ExtensionV4::default() }), rest)
        }
        V3 => {
            let (v3, rest) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            (v5(WorldV4 { v3, ext4: ExtensionV4::default() }), rest)
        }
        V4 => {
            let (v4, rest) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            (v5(v4), rest)
        }
        V5 => {
            let (v5, rest) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            (v6(v5), rest)
        }
        V6 => {
            let (v6, rest) = postcard::take_from_bytes(payload).map_err(undecodable)?;
            (v7(v6), rest)
        }
        _ => postcard::take_from_bytes(payload).map_err(undecodable)?,
    };
    if !rest.is_empty() {
        return Err(corrupted(format!("{} unread bytes at the end of the payload", rest.len())));
    }
    world_from_v7(v7).map_err(corrupted)
}


impl World {
    /// The whole world as bytes (the format: `crate::snapshot`, `docs/snapshot.md`).
    pub fn snapshot(&self) -> Vec<u8> {
        write(self)
    }

    /// A world from [`World::snapshot`]'s bytes; stepping it gives the same bits as stepping
    /// the world the snapshot was taken of.
    pub fn restore(bytes: &[u8]) -> Result<World, SnapshotError> {
        read(bytes)
    }

    /// Replace this world by the snapshot's; on error this world is left as it was.
    pub fn restore_from(&mut self, bytes: &[u8]) -> Result<(), SnapshotError> {
        *self = read(bytes)?;
        Ok(())
    }
}
