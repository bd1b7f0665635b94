//! Snapshots: a restored world steps on with the same bits as the original; every kind of bad
//! input is refused with its own message, and never a panic.

use proptest::prelude::*;
use softsculpt::mesh::builtin::icosphere;
use softsculpt::scene::SceneRun;
use softsculpt::snapshot::{self, SnapshotError, HEADER_LEN, VERSION};
use softsculpt::world::World;

/// Two small balloons (42 vertices each) over the ground, beside a sphere and a triangle-mesh
/// obstacle, the upper one self-colliding, with events of every kind spread over 0.01–0.1 s
/// (loads with durations, gas, inflation, pins, masses, freezes, wind, reset).
fn scene(integrator: &str) -> String {
    let obj = String::from_utf8(icosphere(1, 0.5).to_obj("ball")).unwrap();
    format!(
        r#"
[world]
dt = 0.001
integrator = "{integrator}"
ground = {{ height = -0.6 }}
contact_thickness = 0.02

[[body]]
name = "a"
obj = """
{obj}"""
stiffness = 80.0
spring_damping = 0.2
damping = 0.5
bending = 10.0
gas = {{ nrt = 10.0 }}

[[body]]
name = "b"
obj = """
{obj}"""
translate = [0.3, 1.05, 0.0]
self_collision = true
gas = {{ nrt = 5.0, volume = "box" }}

[[obstacle]]
shape = "sphere"
center = [1.2, -0.4, 0.0]
radius = 0.3

[[obstacle]]
shape = "mesh"
model = "sphere"
scale = 0.3
translate = [-1.2, -0.4, 0.0]

[[event]]
time = 0.01
action = "force"
body = "a"
region = {{ all = true }}
force = [0.5, 0.0, 0.0]
duration = 0.03

[[event]]
time = 0.02
action = "set_gas"
body = "a"
nrt = 14.0

[[event]]
time = 0.03
action = "pressure"
body = "b"
region = {{ center = [0.3, 1.55, 0.0], radius = 0.5 }}
pressure = 20.0
duration = 0.02

[[event]]
time = 0.04
action = "inflate"
body = "a"
region = {{ center = [0.0, 0.5, 0.0], radius = 0.4 }}
factor = 1.05

[[event]]
time = 0.05
action = "pin"
body = "b"
region = {{ vertices = [0] }}

[[event]]
time = 0.06
action = "set_mass"
body = "a"
region = {{ vertices = [1, 2] }}
mass = 0.05

[[event]]
time = 0.07
action = "freeze"
body = "a"

[[event]]
time = 0.08
action = "set_wind"
wind = [1.0, 0.0, 0.5]

[[event]]
time = 0.09
action = "reset"
body = "b"

[[event]]
time = 0.1
action = "unpin"
body = "b"
region = {{ vertices = [0] }}
"#
    )
}

fn world(integrator: &str) -> World {
    let mut resolve = |p: &str| Err(format!("no file {p}"));
    SceneRun::load(&scene(integrator), &mut resolve).unwrap_or_else(|e| panic!("{e}")).world
}

/// What the random sequences do, on body `body % 2`.
#[derive(Debug, Clone)]
enum Op {
    Steps(u8),
    ScaleRestByVertex { body: usize, factor: f64 },
    SetMass { body: usize, vertex: usize, mass: f64 },
    Freeze { body: usize },
    FreezeUnderLoad { body: usize },
    Pin { body: usize, vertex: usize, on: bool },
    SetGas { body: usize, nrt: f64 },
    SetRigidity { body: usize, rigidity: f64 },
    UserForce { body: usize, vertex: usize, force: f64 },
    Reset { body: usize },
    Subdivide { body: usize },
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (1u8..30).prop_map(Op::Steps),
        1 => (0usize..2, 0.9f64..1.1).prop_map(|(body, factor)| Op::ScaleRestByVertex { body, factor }),
        1 => (0usize..2, 0usize..42, 0.01f64..0.1).prop_map(|(body, vertex, mass)| Op::SetMass { body, vertex, mass }),
        1 => (0usize..2).prop_map(|body| Op::Freeze { body }),
        1 => (0usize..2).prop_map(|body| Op::FreezeUnderLoad { body }),
        1 => (0usize..2, 0usize..42, any::<bool>()).prop_map(|(body, vertex, on)| Op::Pin { body, vertex, on }),
        1 => (0usize..2, 0.0f64..20.0).prop_map(|(body, nrt)| Op::SetGas { body, nrt }),
        1 => (0usize..2, 0.0f64..0.5).prop_map(|(body, rigidity)| Op::SetRigidity { body, rigidity }),
        1 => (0usize..2, 0usize..42, -2.0f64..2.0).prop_map(|(body, vertex, force)| Op::UserForce { body, vertex, force }),
        1 => (0usize..2).prop_map(|body| Op::Reset { body }),
        1 => (0usize..2).prop_map(|body| Op::Subdivide { body }),
    ]
}

/// Apply `op`; a step that fails is part of the run (the same failure must happen after a
/// restore), so its result is returned as text.
fn apply(w: &mut World, op: &Op) -> String {
    let b = |k: usize| k % 2;
    match *op {
        Op::Steps(n) => return format!("{:?}", w.step_n(n as u64)),
        Op::ScaleRestByVertex { body, factor } => {
            let n = w.bodies[b(body)].vertex_count();
            let factors: Vec<f64> = (0..n).map(|i| if i % 3 == 0 { factor } else { 1.0 }).collect();
            w.bodies[b(body)].scale_rest_lengths_by_vertex(&factors).unwrap();
        }
        Op::SetMass { body, vertex, mass } => w.bodies[b(body)].set_vertex_mass(vertex, mass).unwrap(),
        Op::Freeze { body } => w.bodies[b(body)].freeze(),
        Op::FreezeUnderLoad { body } => {
            w.freeze(b(body), softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
        }
        Op::Pin { body, vertex, on } => w.bodies[b(body)].set_pinned(vertex, on).unwrap(),
        Op::SetGas { body, nrt } => {
            let t = w.bodies[b(body)].material.temperature;
            w.bodies[b(body)].set_gas(nrt / (softsculpt::GAS_CONSTANT * t), t).unwrap();
        }
        Op::SetRigidity { body, rigidity } => w.bodies[b(body)].material.rigidity = rigidity,
        Op::UserForce { body, vertex, force } => {
            let mut f = vec![0.0; 3 * w.bodies[b(body)].vertex_count()];
            f[3 * vertex + 1] = force;
            w.bodies[b(body)].set_user_forces(&f).unwrap();
        }
        Op::Reset { body } => w.bodies[b(body)].reset(),
        Op::Subdivide { body } => {
            // Once per body (a second one would be 16 times the vertices): only while coarse.
            if w.bodies[b(body)].vertex_count() == 42 {
                let sub = w.bodies[b(body)].subdivided().unwrap();
                w.replace_body(b(body), sub);
            }
        }
    }
    String::new()
}

/// Positions, velocities and the clock, as bits.
fn bits(w: &World) -> Vec<u64> {
    let mut out: Vec<u64> = w.bodies.iter().flat_map(|b| b.positions().iter().chain(b.velocities()).map(|x| x.to_bits())).collect();
    out.extend([w.steps(), w.time().to_bits()]);
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// Random operations, a snapshot and a restore, then more steps and operations: the
    /// restored world and the original give the same bits at every point (positions,
    /// velocities, clock, and everything else through their snapshots).
    #[test]
    fn stepping_after_a_restore_gives_the_same_bits(
        integrator in prop::sample::select(vec!["symplectic", "euler", "midpoint", "rk4"]),
        before in prop::collection::vec(op(), 1..12),
        after in prop::collection::vec(op(), 1..6),
    ) {
        let mut original = world(integrator);
        for o in &before {
            apply(&mut original, o);
        }
        let bytes = original.snapshot();
        let mut restored = World::restore(&bytes).unwrap();
        prop_assert_eq!(restored.snapshot(), bytes, "restore → snapshot is the identity");
        for o in after.iter().chain([Op::Steps(25)].iter()) {
            let (a, b) = (apply(&mut original, o), apply(&mut restored, o));
            prop_assert_eq!(a, b, "the same outcome of {:?}", o);
            prop_assert_eq!(bits(&original), bits(&restored), "after {:?}", o);
        }
        prop_assert_eq!(original.snapshot(), restored.snapshot());
    }
}

fn sample() -> Vec<u8> {
    let mut w = world("symplectic");
    w.step_n(35).unwrap(); // a load in force, events fired and pending
    w.snapshot()
}

fn refused(bytes: &[u8]) -> String {
    let e = World::restore(bytes).expect_err("refused");
    e.to_string()
}

#[test]
fn a_truncated_snapshot_is_refused_at_any_length() {
    let good = sample();
    for len in [0, 3, 5, 12, HEADER_LEN - 1, HEADER_LEN, HEADER_LEN + 1, good.len() / 2, good.len() - 1] {
        let e = World::restore(&good[..len]).expect_err("truncated");
        let expected = if len < HEADER_LEN { HEADER_LEN } else { good.len() };
        assert_eq!(e, SnapshotError::Truncated { expected, got: len }, "at {len} bytes");
        assert_eq!(e.to_string(), format!("the snapshot is truncated: {len} of {expected} bytes"));
    }
}

#[test]
fn a_flipped_byte_is_caught_by_the_checksum() {
    let good = sample();
    for at in [HEADER_LEN, HEADER_LEN + 100, good.len() / 2, good.len() - 1] {
        let mut bad = good.clone();
        bad[at] ^= 0x10;
        assert_eq!(refused(&bad), "the snapshot is corrupted: checksum mismatch", "byte {at}");
    }
    // A flipped bit in the checksum itself, too.
    let mut bad = good.clone();
    bad[HEADER_LEN - 1] ^= 1;
    assert_eq!(refused(&bad), "the snapshot is corrupted: checksum mismatch");
}

#[test]
fn bytes_that_are_not_a_snapshot_are_refused() {
    assert_eq!(refused(b"v 0 0 0\nf 1 2 3\n"), "not a SoftSculpt snapshot (it does not start with SSNAP)");
    let mut bad = sample();
    bad[0] = b'X';
    assert_eq!(refused(&bad), "not a SoftSculpt snapshot (it does not start with SSNAP)");
}

#[test]
fn a_newer_version_is_refused_saying_so() {
    let mut newer = sample();
    newer[5..9].copy_from_slice(&(VERSION + 1).to_le_bytes());
    assert_eq!(refused(&newer), format!("snapshot format version {} is newer than this SoftSculpt reads (≤ {VERSION})", VERSION + 1));
}

#[test]
fn a_payload_that_does_not_decode_or_does_not_fit_is_corrupted() {
    let e = refused(&snapshot::frame(VERSION, b"garbage"));
    assert!(e.starts_with("the snapshot is corrupted: the payload does not decode"), "{e}");
    let mut long = sample();
    long.push(0);
    assert_eq!(refused(&long), "the snapshot is corrupted: 1 bytes after the end of the payload");
}

#[test]
fn a_failed_restore_leaves_the_world_as_it_was() {
    let mut w = world("rk4");
    w.step_n(12).unwrap();
    let before = w.snapshot();
    let mut bad = before.clone();
    bad[HEADER_LEN + 7] ^= 0xff;
    assert!(w.restore_from(&bad).is_err());
    assert_eq!(w.snapshot(), before);
}

/// A snapshot carries the scene's pending events and loads: restored mid-scene, the rest of the
/// scene plays exactly as in the original (checked at the end, 0.15 s, after every event).
#[test]
fn a_restored_scene_plays_its_remaining_events_exactly() {
    let mut w = world("midpoint");
    w.step_n(35).unwrap();
    assert!(w.pending_events() > 0);
    let mut r = World::restore(&w.snapshot()).unwrap();
    w.step_n(115).unwrap();
    r.step_n(115).unwrap();
    assert_eq!(w.pending_events(), 0);
    assert_eq!(bits(&w), bits(&r));
    assert_eq!(w.snapshot(), r.snapshot());
}

/// Restarting a scene is restoring the snapshot taken when it opened: the second play replays
/// the first exactly (every event fires again at its time; the same bits at the end, 0.15 s).
#[test]
fn a_restarted_scene_replays_exactly() {
    let mut w = world("symplectic");
    let start = w.snapshot();
    w.step_n(150).unwrap();
    let first = (bits(&w), w.snapshot());
    assert_eq!(w.pending_events(), 0);
    w.restore_from(&start).unwrap();
    assert_eq!(w.time(), 0.0);
    assert!(w.pending_events() > 0);
    w.step_n(150).unwrap();
    assert_eq!(bits(&w), first.0);
    assert_eq!(w.snapshot(), first.1);
}

/// The bytes of a version-5 snapshot of an explicit world from its version-7 snapshot: without
/// the version-7 extension, which for bodies whose hinge rest angles are their frozen shape's
/// and no pairs of overlapping bodies is, in postcard, two empty lists (a byte 0 each), and
/// without the version-6 extension, which for
/// bodies that have kept no coarse levels (explicit steps never do) is the list's length (one
/// byte) and per body an empty list of positions, an empty list of held vertices, `false` and a
/// fingerprint of 0 (one byte each).
fn as_version_5(v7: &[u8], bodies: usize) -> Vec<u8> {
    assert_eq!(v7[v7.len() - 2..], [0, 0], "version 7 ends with its (empty) extension");
    let v6 = &v7[..v7.len() - 2];
    let ext6 = 1 + 4 * bodies;
    let mut tail = vec![0u8; ext6];
    tail[0] = bodies as u8;
    assert_eq!(v6[v6.len() - ext6..], tail[..], "version 6 ends with its extension");
    snapshot::frame(5, &v6[HEADER_LEN..v6.len() - ext6])
}

/// Version 5 adds each body's flexural rigidity (J) after the version-4 payload. Bodies with a
/// rigidity keep it through a snapshot; a version-4 snapshot (the version-5 payload without its
/// extension, framed as version 4: the bytes version 4 wrote) still reads, with rigidity 0, and
/// continues with the same bits as the world it was taken of (0.15 s, every event fired).
#[test]
fn the_rigidity_round_trips_and_a_version_4_snapshot_still_reads() {
    assert_eq!(VERSION, 7);
    let mut w = world("symplectic");
    w.step_n(35).unwrap();
    w.bodies[0].material.rigidity = 0.125;
    w.bodies[1].material.rigidity = 0.5;
    let bytes = w.snapshot();
    assert_eq!(bytes[5..9], 7u32.to_le_bytes());
    let r = World::restore(&bytes).unwrap();
    assert_eq!([r.bodies[0].material.rigidity, r.bodies[1].material.rigidity], [0.125, 0.5]);
    assert_eq!(r.snapshot(), bytes);
    let v5 = as_version_5(&bytes, 2);
    let r = World::restore(&v5).unwrap();
    assert_eq!([r.bodies[0].material.rigidity, r.bodies[1].material.rigidity], [0.125, 0.5]);
    assert_eq!(r.snapshot(), bytes, "read as version 5, written as version 7");

    for b in &mut w.bodies {
        b.material.rigidity = 0.0;
    }
    let v5 = as_version_5(&w.snapshot(), 2);
    // The extension in postcard: the list's length (2, one byte), then each body's f64 (8 bytes).
    let ext5 = 1 + 2 * 8;
    let mut tail = vec![0u8; ext5];
    tail[0] = 2;
    assert_eq!(v5[v5.len() - ext5..], tail[..], "version 5 ends with its extension");
    let v4 = snapshot::frame(4, &v5[HEADER_LEN..v5.len() - ext5]);
    let mut old = World::restore(&v4).unwrap();
    assert!(old.bodies.iter().all(|b| b.material.rigidity == 0.0));
    assert_eq!(as_version_5(&old.snapshot(), 2), v5, "read as version 4, written as version 7");
    // Version 4 with a rigidity in the world it came from: still 0 (version 4 had no place for it).
    w.bodies[1].material.rigidity = 0.5;
    let set = as_version_5(&w.snapshot(), 2);
    let v4_of_set = snapshot::frame(4, &set[HEADER_LEN..set.len() - ext5]);
    assert_eq!(World::restore(&v4_of_set).unwrap().bodies[1].material.rigidity, 0.0);
    w.bodies[1].material.rigidity = 0.0;
    w.step_n(115).unwrap();
    old.step_n(115).unwrap();
    assert_eq!(old.pending_events(), 0);
    assert_eq!(bits(&old), bits(&w));
    assert_eq!(old.snapshot(), w.snapshot());
}

/// The world the stored snapshots hold (`tests/fixtures/snapshots/`): the implicit scene 35
/// steps in (events pending, loads in force), its first body made clay (plastic, hinges) with
/// every strain and bend flowing (yield 0) and stepped 40 more under the scene's loads, so that
/// its rest lengths, gas reference and hinge rest angles have flowed.
fn stored_world() -> World {
    let mut w = world("implicit");
    w.step_n(35).unwrap();
    w.apply_preset(0, "clay").unwrap();
    w.set_param(0, "yield", softsculpt::params::Value::Number(0.0)).unwrap();
    w.step_n(40).unwrap();
    w
}

/// FNV-1a over `bits` (a stored result: 16 hex digits instead of every value).
fn fingerprint(bits: &[u64]) -> u64 {
    bits.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (0..8).fold(h, |h, k| (h ^ ((b >> (8 * k)) & 0xff)).wrapping_mul(0x100_0000_01b3)))
}

/// Snapshots of every format version, stored as bytes when that version was current or, for
/// the versions before the files were kept, as `snapshot::write_version` writes them
/// (`tests/fixtures/snapshots/vN.bin`; issue #39: the format may be rebuilt, but what users
/// saved must keep opening): each opens, and 40 steps later holds the same bits as the code
/// that stored it computed on one thread (`expected.txt`: the fingerprint of every body's
/// positions and velocities, the step count and the time). A change of the physics that changes these bits
/// on purpose rewrites `expected.txt` with `UPDATE_FIXTURES=1`, which also stores the bytes of
/// a version that has none yet — it never rewrites stored bytes.
#[test]
fn stored_snapshots_of_every_version_open_and_step_as_they_did() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/snapshots");
    let update = std::env::var_os("UPDATE_FIXTURES").is_some();
    if update {
        std::fs::create_dir_all(&dir).unwrap();
        let w = stored_world();
        for v in 1..=VERSION {
            let path = dir.join(format!("v{v}.bin"));
            if !path.exists() {
                std::fs::write(&path, snapshot::write_version(&w, v).unwrap()).unwrap();
            }
        }
    }
    let mut results = String::new();
    for v in 1..=VERSION {
        let bytes = std::fs::read(dir.join(format!("v{v}.bin"))).unwrap_or_else(|e| panic!("v{v}.bin: {e} (UPDATE_FIXTURES=1 stores it)"));
        assert_eq!(bytes[5..9], v.to_le_bytes(), "v{v}.bin holds version {v}");
        let mut w = World::restore(&bytes).unwrap_or_else(|e| panic!("version {v}: {e}"));
        // One thread: the same sums in the same order on any machine.
        w.set_threads(1).unwrap();
        w.step_n(40).unwrap_or_else(|e| panic!("version {v}: {e}"));
        results += &format!("v{v} {:016x}\n", fingerprint(&bits(&w)));
    }
    let expected = dir.join("expected.txt");
    if update {
        std::fs::write(&expected, &results).unwrap();
    }
    let want = std::fs::read_to_string(&expected).expect("expected.txt (UPDATE_FIXTURES=1 writes it)");
    assert_eq!(results, want, "a stored snapshot steps to other bits than when it was stored");
}
