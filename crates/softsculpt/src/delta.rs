//! Undo deltas: what takes a world back over one operation, holding only what the operation
//! changed (SculptGL's rule: undo stores what a stroke touched).
//!
//! A delta is computed between two worlds, `before` and `after`, in the snapshot's payload terms
//! (`crate::snapshot::WorldV7`, so every field a snapshot keeps is covered and nothing else):
//! - if the structure changed (another number of bodies, or a body's triangles differ: a new
//!   model, a subdivision, an opened scene), the delta is the whole earlier world, as a snapshot;
//! - otherwise, per body, the values of each per-vertex, per-spring or per-face array that differ
//!   (compared bit for bit), as index lists with the earlier values; the material, gas references
//!   and pins when they differ (the material's later fields, plasticity and rigidity, with the
//!   version-3 and version-5 additions); the world's settings when they differ.
//!
//! What of the *state* (positions, velocities, the clock, events and loads) it keeps is the
//! [`StateScope`]: `None` (a parameter change: the body goes on from where it is), `Touched` (a
//! brush stroke: the positions and velocities of the vertices whose material changed — the ends
//! of a changed spring, a vertex whose mass, pin or prestress changed — so undo puts the painted
//! region back without rewinding the rest), `All` (a drag, a freeze: every position and velocity
//! that differs, and the clock, events and loads).
//!
//! [`Delta::apply`] returns the inverse delta (what redoes), computed the same way, so undo and
//! redo are the same operation. Bytes: `SSDLT`, a u32 version, a u32 CRC-32 of the payload, the
//! payload in postcard (the same serde path as snapshots).

use crate::mesh::topology;
use crate::snapshot::{self, BodyV1, SnapshotError, WorldV1, WorldV7};
use crate::world::World;
use serde::{Deserialize, Serialize};
use std::fmt;

/// What of the state a delta keeps (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum StateScope {
    None,
    Touched,
    All,
}

impl StateScope {
    pub fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "none" => StateScope::None,
            "touched" => StateScope::Touched,
            "all" => StateScope::All,
            _ => return None,
        })
    }
}

/// Why a delta could not be read or applied. The world is left as it was.
#[derive(Debug, Clone, PartialEq)]
pub enum DeltaError {
    /// Not a delta, truncated, corrupted or of a newer version.
    Malformed(String),
    /// The delta was made for a world of another shape (other bodies or meshes).
    DoesNotFit(String),
    /// The world it would make is not valid (a snapshot it holds, or the patched payload).
    Invalid(String),
}

impl fmt::Display for DeltaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DeltaError::Malformed(m) => write!(f, "not a valid undo step: {m}"),
            DeltaError::DoesNotFit(m) => write!(f, "the undo step does not fit this model: {m}"),
            DeltaError::Invalid(m) => write!(f, "the undo step would make an invalid model: {m}"),
        }
    }
}

impl std::error::Error for DeltaError {}

impl From<SnapshotError> for DeltaError {
    fn from(e: SnapshotError) -> Self {
        DeltaError::Invalid(e.to_string())
    }
}

/// The arrays of a body a delta can hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
enum Field {
    X,
    V,
    Rest,
    BendingRest,
    Mass,
    UserForce,
    Prestress,
    FacePressure,
    FrozenX,
    FrozenRest,
    FrozenBendingRest,
    FrozenPrestress,
}

/// The material-side arrays (everything but positions and velocities).
const MATERIAL_FIELDS: [Field; 10] = [
    Field::Rest,
    Field::BendingRest,
    Field::Mass,
    Field::UserForce,
    Field::Prestress,
    Field::FacePressure,
    Field::FrozenX,
    Field::FrozenRest,
    Field::FrozenBendingRest,
    Field::FrozenPrestress,
];

fn field(b: &BodyV1, f: Field) -> &Vec<f64> {
    match f {
        Field::X => &b.x,
        Field::V => &b.v,
        Field::Rest => &b.rest,
        Field::BendingRest => &b.bending_rest,
        Field::Mass => &b.mass,
        Field::UserForce => &b.user_force,
        Field::Prestress => &b.prestress,
        Field::FacePressure => &b.face_pressure,
        Field::FrozenX => &b.frozen_x,
        Field::FrozenRest => &b.frozen_rest,
        Field::FrozenBendingRest => &b.frozen_bending_rest,
        Field::FrozenPrestress => &b.frozen_prestress,
    }
}

fn field_mut(b: &mut BodyV1, f: Field) -> &mut Vec<f64> {
    match f {
        Field::X => &mut b.x,
        Field::V => &mut b.v,
        Field::Rest => &mut b.rest,
        Field::BendingRest => &mut b.bending_rest,
        Field::Mass => &mut b.mass,
        Field::UserForce => &mut b.user_force,
        Field::Prestress => &mut b.prestress,
        Field::FacePressure => &mut b.face_pressure,
        Field::FrozenX => &mut b.frozen_x,
        Field::FrozenRest => &mut b.frozen_rest,
        Field::FrozenBendingRest => &mut b.frozen_bending_rest,
        Field::FrozenPrestress => &mut b.frozen_prestress,
    }
}

/// Earlier values of one array at the listed indices.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Sparse {
    field: Field,
    index: Vec<u32>,
    value: Vec<f64>,
}

/// What changed in one body (the earlier values).
#[derive(Clone, Serialize, Deserialize)]
struct BodyDelta {
    material: Option<snapshot::MaterialV1>,
    gas: Option<[f64; 2]>,
    frozen_gas: Option<[f64; 2]>,
    pinned: Option<Vec<u32>>,
    arrays: Vec<Sparse>,
}

/// The clock, events and loads (kept with [`StateScope::All`]).
#[derive(Clone, Serialize, Deserialize)]
struct Timeline {
    steps: u64,
    t_base: f64,
    since: u64,
    clock_dt: f64,
    events: Vec<snapshot::EventV1>,
    next_event: u64,
    loads: Vec<snapshot::LoadV1>,
}

// One per undo step, never in an array: the size of its largest variant costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Serialize, Deserialize)]
enum Kind {
    /// The structure changed: the whole earlier world, as a snapshot.
    Whole(Vec<u8>),
    Parts {
        settings: Option<snapshot::SettingsV1>,
        /// The version-2 additions (implicit integrator settings, target springs), when they
        /// differ.
        ext: Option<snapshot::ExtensionV2>,
        /// The version-3 additions (plasticity, the ellipsoid volume mode, the plastic
        /// dissipation), when they differ.
        ext3: Option<snapshot::ExtensionV3>,
        /// The version-4 additions (each body's implicit warm start), when they differ; kept
        /// with [`StateScope::All`] only, like the velocities it goes with.
        ext4: Option<snapshot::ExtensionV4>,
        /// The version-5 additions (each body's flexural rigidity), when they differ.
        ext5: Option<snapshot::ExtensionV5>,
        /// The version-6 additions (each body's kept coarse levels), when they differ; kept
        /// with [`StateScope::All`] only, like the warm start.
        ext6: Option<snapshot::ExtensionV6>,
        /// The version-7 additions (each body's hinge rest angles moved by the plastic stage),
        /// when they differ: kept whatever the scope, as the rest lengths are.
        ext7: Option<snapshot::ExtensionV7>,
        timeline: Option<Timeline>,
        bodies: Vec<Option<BodyDelta>>,
        /// Each body's mesh it was made for: vertex count and a hash of the triangles.
        meshes: Vec<(u32, u64)>,
    },
}

/// What takes a world back over one operation. See the module documentation.
#[derive(Clone, Serialize, Deserialize)]
pub struct Delta {
    scope: StateScope,
    kind: Kind,
}

const MAGIC: &[u8; 5] = b"SSDLT";
/// 2: the version-3 snapshot additions (1 had none; deltas live only in a session's memory);
/// 3: the version-4 additions; 4: the version-5 additions; 5: the version-6 additions; 6: the
/// version-7 additions.
const VERSION: u32 = 6;
const HEADER: usize = 5 + 4 + 4;

fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

fn encoded<T: Serialize>(v: &T) -> Vec<u8> {
    postcard::to_stdvec(v).unwrap_or_default()
}

/// Indices where `before` and `after` differ (same lengths).
fn differing(before: &[f64], after: &[f64]) -> Vec<u32> {
    (0..before.len()).filter(|&k| before[k].to_bits() != after[k].to_bits()).map(|k| k as u32).collect()
}

fn sparse(field: Field, before: &[f64], index: Vec<u32>) -> Sparse {
    let value = index.iter().map(|&k| before[k as usize]).collect();
    Sparse { field, index, value }
}

/// Vertices whose material changed between `b` and `a` (same mesh): the ends of changed edge
/// and bending springs, vertices whose mass, pin, loads or frozen position changed, the corners
/// of faces whose pressure changed.
fn touched(b: &BodyV1, a: &BodyV1, arrays: &[Sparse]) -> Vec<u32> {
    let n = b.mass.len();
    let mut mark = vec![false; n];
    let (mut edges, mut bends) = (None, None);
    for s in arrays {
        for &k in &s.index {
            let k = k as usize;
            match s.field {
                Field::Rest | Field::FrozenRest => {
                    let e = edges.get_or_insert_with(|| topology::edges(&b.triangles));
                    e[k].iter().for_each(|&v| mark[v as usize] = true);
                }
                Field::BendingRest | Field::FrozenBendingRest => {
                    let e = bends.get_or_insert_with(|| topology::bending_pairs(&b.triangles));
                    e[k].iter().for_each(|&v| mark[v as usize] = true);
                }
                Field::Mass => mark[k] = true,
                Field::UserForce | Field::Prestress | Field::FrozenX | Field::FrozenPrestress => mark[k / 3] = true,
                Field::FacePressure => b.triangles[k].iter().for_each(|&v| mark[v as usize] = true),
                Field::X | Field::V => {}
            }
        }
    }
    if b.pinned != a.pinned {
        for &p in b.pinned.iter().chain(&a.pinned) {
            mark[p as usize] = true;
        }
    }
    (0..n).filter(|&v| mark[v]).map(|v| v as u32).collect()
}

fn body_delta(b: &BodyV1, a: &BodyV1, scope: StateScope) -> Option<BodyDelta> {
    let mut arrays: Vec<Sparse> = MATERIAL_FIELDS
        .iter()
        .filter_map(|&f| {
            let index = differing(field(b, f), field(a, f));
            (!index.is_empty()).then(|| sparse(f, field(b, f), index))
        })
        .collect();
    // Positions and velocities: every differing value (All), those of the touched vertices
    // (Touched), or none.
    let state: Vec<(Field, Vec<u32>)> = match scope {
        StateScope::None => Vec::new(),
        StateScope::All => [Field::X, Field::V].into_iter().map(|f| (f, differing(field(b, f), field(a, f)))).collect(),
        StateScope::Touched => {
            let xyz: Vec<u32> = touched(b, a, &arrays).iter().flat_map(|&v| [3 * v, 3 * v + 1, 3 * v + 2]).collect();
            vec![(Field::X, xyz.clone()), (Field::V, xyz)]
        }
    };
    for (f, index) in state {
        if !index.is_empty() {
            arrays.push(sparse(f, field(b, f), index));
        }
    }
    let material = (encoded(&b.material) != encoded(&a.material)).then(|| b.material.clone());
    let gas = (!same_bits(&b.gas, &a.gas)).then_some(b.gas);
    let frozen_gas = (!same_bits(&b.frozen_gas, &a.frozen_gas)).then_some(b.frozen_gas);
    let pinned = (b.pinned != a.pinned).then(|| b.pinned.clone());
    if arrays.is_empty() && material.is_none() && gas.is_none() && frozen_gas.is_none() && pinned.is_none() {
        return None;
    }
    Some(BodyDelta { material, gas, frozen_gas, pinned, arrays })
}

fn timeline(w: &WorldV1) -> Timeline {
    Timeline { steps: w.steps, t_base: w.t_base, since: w.since, clock_dt: w.clock_dt, events: w.events.clone(), next_event: w.next_event, loads: w.loads.clone() }
}

fn diff(before7: &WorldV7, after7: &WorldV7, scope: StateScope) -> Delta {
    let (before6, after6) = (&before7.v6, &after7.v6);
    let (before5, after5) = (&before6.v5, &after6.v5);
    let (before4, after4) = (&before5.v4, &after5.v4);
    let (before2, after2) = (&before4.v3, &after4.v3);
    let (before, after) = (&before2.base, &after2.base);
    let same_structure = before.bodies.len() == after.bodies.len() && before.bodies.iter().zip(&after.bodies).all(|(b, a)| b.triangles == a.triangles);
    if !same_structure {
        let whole = snapshot::frame(snapshot::VERSION, &encoded(before7));
        return Delta { scope, kind: Kind::Whole(whole) };
    }
    let settings = (encoded(&before.settings) != encoded(&after.settings)).then(|| before.settings.clone());
    let ext = (encoded(&before2.ext) != encoded(&after2.ext)).then(|| before2.ext.clone());
    let ext3 = (encoded(&before2.ext3) != encoded(&after2.ext3)).then(|| before2.ext3.clone());
    let ext4 = (scope == StateScope::All && encoded(&before4.ext4) != encoded(&after4.ext4)).then(|| before4.ext4.clone());
    let ext5 = (encoded(&before5.ext5) != encoded(&after5.ext5)).then(|| before5.ext5.clone());
    let ext6 = (scope == StateScope::All && encoded(&before6.ext6) != encoded(&after6.ext6)).then(|| before6.ext6.clone());
    let ext7 = (encoded(&before7.ext7) != encoded(&after7.ext7)).then(|| before7.ext7.clone());
    let timeline = (scope == StateScope::All && encoded(&timeline(before)) != encoded(&timeline(after))).then(|| timeline(before));
    let bodies = before.bodies.iter().zip(&after.bodies).map(|(b, a)| body_delta(b, a, scope)).collect();
    Delta { scope, kind: Kind::Parts { settings, ext, ext3, ext4, ext5, ext6, ext7, timeline, bodies, meshes: meshes(before) } }
}

/// Each body's vertex count and an FNV-1a hash of its triangles: which meshes a delta fits.
fn meshes(w: &WorldV1) -> Vec<(u32, u64)> {
    w.bodies
        .iter()
        .map(|b| {
            let h = b.triangles.iter().flatten().fold(0xcbf2_9ce4_8422_2325u64, |h, &i| (h ^ i as u64).wrapping_mul(0x100_0000_01b3));
            (b.mass.len() as u32, h)
        })
        .collect()
}

fn patch(w: &mut WorldV1, settings: &Option<snapshot::SettingsV1>, timeline: &Option<Timeline>, bodies: &[Option<BodyDelta>]) -> Result<(), DeltaError> {
    if bodies.len() != w.bodies.len() {
        return Err(DeltaError::DoesNotFit(format!("it was made for {} bodies, the world has {}", bodies.len(), w.bodies.len())));
    }
    if let Some(s) = settings {
        w.settings = s.clone();
    }
    if let Some(t) = timeline {
        (w.steps, w.t_base, w.since, w.clock_dt) = (t.steps, t.t_base, t.since, t.clock_dt);
        (w.events, w.next_event, w.loads) = (t.events.clone(), t.next_event, t.loads.clone());
    }
    for (k, (body, d)) in w.bodies.iter_mut().zip(bodies).enumerate() {
        let Some(d) = d else { continue };
        for s in &d.arrays {
            let target = field_mut(body, s.field);
            if s.index.len() != s.value.len() {
                return Err(DeltaError::Malformed(format!("body {k}: {} indices for {} values", s.index.len(), s.value.len())));
            }
            if let Some(&i) = s.index.iter().find(|&&i| i as usize >= target.len()) {
                return Err(DeltaError::DoesNotFit(format!("body {k}: index {i} of {} values ({:?})", target.len(), s.field)));
            }
            for (&i, &v) in s.index.iter().zip(&s.value) {
                target[i as usize] = v;
            }
        }
        if let Some(m) = &d.material {
            body.material = m.clone();
        }
        if let Some(g) = d.gas {
            body.gas = g;
        }
        if let Some(g) = d.frozen_gas {
            body.frozen_gas = g;
        }
        if let Some(p) = &d.pinned {
            body.pinned = p.clone();
        }
    }
    Ok(())
}

/// The thread pool is how this machine runs the world, not part of it: it stays across an undo
/// or redo.
fn carry_over(now: &World, to: &mut World) {
    to.threads = now.threads.clone();
}

impl Delta {
    /// What takes `after` back to `before` (see the module documentation for `scope`).
    pub fn between(before: &World, after: &World, scope: StateScope) -> Delta {
        diff(&snapshot::payload_v7(before), &snapshot::payload_v7(after), scope)
    }

    /// What takes any later world back to `before` whole: every setting, mesh and the whole
    /// state (positions, velocities, clock, events, loads), as of `before`. For an operation
    /// whose effect unfolds over the steps after it (a material that makes the body fold), so
    /// that undoing it also undoes what the steps since made of it.
    pub fn whole(before: &World) -> Delta {
        Delta { scope: StateScope::All, kind: Kind::Whole(before.snapshot()) }
    }

    /// Take `world` back; returns the inverse (what takes it forward again). On error the world
    /// is left as it was.
    pub fn apply(&self, world: &mut World) -> Result<Delta, DeltaError> {
        match &self.kind {
            Kind::Whole(bytes) => {
                let mut earlier = World::restore(bytes)?;
                let inverse = Delta { scope: self.scope, kind: Kind::Whole(world.snapshot()) };
                carry_over(world, &mut earlier);
                *world = earlier;
                Ok(inverse)
            }
            Kind::Parts { settings, ext, ext3, ext4, ext5, ext6, ext7, timeline, bodies, meshes: made_for } => {
                let now = snapshot::payload_v7(world);
                let here = meshes(&now.v6.v5.v4.v3.base);
                if made_for.len() == here.len() && made_for != &here {
                    let k = (0..here.len()).find(|&k| made_for[k] != here[k]).unwrap_or(0);
                    return Err(DeltaError::DoesNotFit(format!("body {k} has another mesh ({} vertices) than it was made for ({})", here[k].0, made_for[k].0)));
                }
                let mut earlier = now.clone();
                patch(&mut earlier.v6.v5.v4.v3.base, settings, timeline, bodies)?;
                if let Some(e) = ext {
                    earlier.v6.v5.v4.v3.ext = e.clone();
                }
                if let Some(e) = ext3 {
                    earlier.v6.v5.v4.v3.ext3 = e.clone();
                }
                if let Some(e) = ext4 {
                    earlier.v6.v5.v4.ext4 = e.clone();
                }
                if let Some(e) = ext5 {
                    earlier.v6.v5.ext5 = e.clone();
                }
                if let Some(e) = ext6 {
                    earlier.v6.ext6 = e.clone();
                }
                if let Some(e) = ext7 {
                    earlier.ext7 = e.clone();
                }
                let inverse = diff(&now, &earlier, self.scope);
                let mut earlier = snapshot::world_from_v7(earlier).map_err(DeltaError::Invalid)?;
                carry_over(world, &mut earlier);
                *world = earlier;
                Ok(inverse)
            }
        }
    }

    /// What the delta keeps of the state.
    pub fn scope(&self) -> StateScope {
        self.scope
    }

    /// Whether it holds the whole earlier world (the structure changed).
    pub fn is_whole(&self) -> bool {
        matches!(self.kind, Kind::Whole(_))
    }

    /// Whether applying it would change nothing.
    pub fn is_empty(&self) -> bool {
        match &self.kind {
            Kind::Whole(_) => false,
            Kind::Parts { settings, ext, ext3, ext5, ext7, timeline, bodies, .. } => {
                settings.is_none() && ext.is_none() && ext3.is_none() && ext5.is_none() && ext7.is_none() && timeline.is_none() && bodies.iter().all(Option::is_none)
            }
        }
    }

    /// `SSDLT`, version, CRC-32, postcard payload.
    pub fn to_bytes(&self) -> Vec<u8> {
        let payload = encoded(self);
        let mut out = Vec::with_capacity(HEADER + payload.len());
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
        out.extend_from_slice(&payload);
        out
    }

    pub fn from_bytes(bytes: &[u8]) -> Result<Delta, DeltaError> {
        if bytes.len() < HEADER || &bytes[..5] != MAGIC {
            return Err(DeltaError::Malformed("it does not start with SSDLT".into()));
        }
        let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        let version = word(5);
        if version != VERSION {
            return Err(DeltaError::Malformed(format!("version {version}, this build reads {VERSION}")));
        }
        let payload = &bytes[HEADER..];
        if crc32fast::hash(payload) != word(9) {
            return Err(DeltaError::Malformed("checksum mismatch".into()));
        }
        postcard::from_bytes(payload).map_err(|e| DeltaError::Malformed(format!("the payload does not decode ({e})")))
    }
}
