//! Scenes in the page: open a scene file, step it (contacts and timed events), save bodies back
//! to a scene file.
//!
//! Each body of an open scene is also an ordinary body handle (a one-body world), so every body
//! call (views, tools, parameters, freeze…) works on it. The scene's world keeps a stand-in for
//! each body; a scene step swaps the page's bodies into the world, steps, and swaps them back
//! (moves, no copies). The world parameters the page sets (gravity, wind, ground, integrator)
//! go in from the first body's handle before a step, and come back out to every handle after it
//! (an event may have changed the wind), with the scene's clock. Mesh files a scene names are
//! given beforehand with `ss_scene_add_file`.

use crate::table::{self, with_table, Entry};
use crate::bytes;
use softsculpt::scene::{self, SceneRun, SceneSpec};
use softsculpt::world::{Shape, World, WorldSettings};
use std::cell::RefCell;
use std::collections::HashMap;

struct Slot {
    run: SceneRun,
    handles: Vec<u32>,
    obstacles: Vec<f64>,
}

thread_local! {
    static SCENES: RefCell<Vec<Option<Slot>>> = const { RefCell::new(Vec::new()) };
    static FILES: RefCell<HashMap<String, Vec<u8>>> = RefCell::new(HashMap::new());
}

fn with_scene<R>(s: u32, missing: R, f: impl FnOnce(&mut Slot) -> R) -> R {
    SCENES.with(|v| {
        let mut v = v.borrow_mut();
        match (s as usize).checked_sub(1).and_then(|i| v.get_mut(i)).and_then(|o| o.as_mut()) {
            Some(slot) => f(slot),
            None => {
                table::set_message(&format!("no scene with handle {s}"));
                missing
            }
        }
    })
}

/// Make a file (`name`, bytes) available to the next `ss_scene_open` (mesh files it names).
///
/// # Safety
/// The pointers must point to `name_len` and `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn ss_scene_add_file(name: *const u8, name_len: usize, ptr: *const u8, len: usize) {
    let name = String::from_utf8_lossy(bytes(name, name_len)).into_owned();
    let data = bytes(ptr, len).to_vec();
    FILES.with(|f| f.borrow_mut().insert(name, data));
}

/// Encode obstacles for drawing: per obstacle `[kind, friction, …]` — sphere (0): centre, radius;
/// box (1): centre, half extents, 3 axes; capsule (2): a, b, radius; mesh (3): vertex count,
/// triangle count, positions, indices.
fn encode(obstacles: &[softsculpt::world::Obstacle]) -> Vec<f64> {
    let mut out = Vec::new();
    for o in obstacles {
        match &o.shape {
            Shape::Sphere { center, radius } => out.extend([0.0, o.friction, center[0], center[1], center[2], *radius]),
            Shape::Box { center, half, axes } => {
                out.extend([1.0, o.friction]);
                out.extend(center);
                out.extend(half);
                for a in axes {
                    out.extend(a);
                }
            }
            Shape::Capsule { a, b, radius } => {
                out.extend([2.0, o.friction]);
                out.extend(a);
                out.extend(b);
                out.push(*radius);
            }
            Shape::Mesh(m) => {
                let (x, t) = (m.positions(), m.triangles());
                out.extend([3.0, o.friction, (x.len() / 3) as f64, t.len() as f64]);
                out.extend(x);
                out.extend(t.iter().flatten().map(|&i| i as f64));
            }
        }
    }
    out
}

/// Open a scene from its TOML text: a scene handle (> 0), or 0 with the error (line and key) in
/// the message. Uses, then forgets, the files given by `ss_scene_add_file`.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn ss_scene_open(ptr: *const u8, len: usize) -> u32 {
    let text = match std::str::from_utf8(bytes(ptr, len)) {
        Ok(t) => t.to_string(),
        Err(e) => return table::fail(format!("the scene is not UTF-8 text (byte {})", e.valid_up_to())),
    };
    let files = FILES.with(|f| std::mem::take(&mut *f.borrow_mut()));
    let mut resolve = |path: &str| -> Result<Vec<u8>, String> {
        let base = path.rsplit(['/', '\\']).next().unwrap_or(path);
        files
            .get(path)
            .or_else(|| files.get(base))
            .cloned()
            .ok_or_else(|| format!("not given: open '{base}' together with the scene"))
    };
    let run = match SceneRun::load(&text, &mut resolve) {
        Ok(r) => r,
        Err(e) => return table::fail(e.to_string()),
    };
    let handles = run.world.bodies.iter().map(|b| with_table(|t| t.insert(Entry::new(World::single(b.clone(), run.world.settings.clone()))))).collect();
    let obstacles = encode(&run.world.settings.obstacles);
    table::set_message("");
    SCENES.with(|v| {
        let mut v = v.borrow_mut();
        v.push(Some(Slot { run, handles, obstacles }));
        v.len() as u32
    })
}

/// Forget a scene (its bodies' handles stay valid until freed).
#[no_mangle]
pub extern "C" fn ss_scene_free(s: u32) {
    SCENES.with(|v| {
        if let Some(slot) = (s as usize).checked_sub(1).and_then(|i| v.borrow_mut().get_mut(i).map(|o| o.take())) {
            drop(slot);
        }
    });
}

#[no_mangle]
pub extern "C" fn ss_scene_body_count(s: u32) -> u32 {
    with_scene(s, 0, |sl| sl.handles.len() as u32)
}

/// The body handle of body `i`.
#[no_mangle]
pub extern "C" fn ss_scene_body(s: u32, i: u32) -> u32 {
    with_scene(s, 0, |sl| sl.handles.get(i as usize).copied().unwrap_or(0))
}

/// The bodies' names, one per line, in the message; returns its length.
#[no_mangle]
pub extern "C" fn ss_scene_names(s: u32) -> u32 {
    with_scene(s, 0, |sl| {
        table::set_message(&sl.run.names.join("\n"));
        table::message_len() as u32
    })
}

/// Body `i` is now the body of handle `h` (an undo restored it, say). If its vertex or face
/// count changed, its pending events are dropped (the message says how many).
#[no_mangle]
pub extern "C" fn ss_scene_set_body(s: u32, i: u32, h: u32) -> u32 {
    let counts = table::with(h, None, |e| Some((e.body().vertex_count(), e.body().face_count())));
    let Some((nv, nf)) = counts else { return 1 };
    with_scene(s, 1, |sl| {
        let i = i as usize;
        if i >= sl.handles.len() {
            table::set_message(&format!("the scene has no body {i}"));
            return 1;
        }
        sl.handles[i] = h;
        let dropped = sl.run.body_replaced(i, nv, nf);
        table::set_message(&if dropped > 0 { format!("{dropped} pending events of '{}' no longer fit its mesh and were dropped", sl.run.names[i]) } else { String::new() });
        0
    })
}

/// The world parameters the page sets on a body handle (`ss_set`).
fn share(from: &WorldSettings, to: &mut WorldSettings) {
    to.gravity = from.gravity;
    to.wind = from.wind;
    to.wind_drag = from.wind_drag;
    to.ground = from.ground;
    to.integrator = from.integrator;
}

/// `substeps` steps of `dt` (s), contacts and events included. On failure the whole scene
/// (bodies, clock, fired events and their effects) is rolled back to where it was before the
/// call and the message says why.
#[no_mangle]
pub extern "C" fn ss_scene_step(s: u32, dt: f64, substeps: u32) -> u32 {
    with_scene(s, 1, |sl| {
        sl.run.set_dt(dt);
        let swap = |sl: &mut Slot| {
            with_table(|t| {
                for (k, &h) in sl.handles.iter().enumerate() {
                    if let Some(e) = t.get(h) {
                        std::mem::swap(&mut e.world.bodies[0], &mut sl.run.world.bodies[k]);
                    }
                }
            })
        };
        with_table(|t| {
            if let Some(e) = sl.handles.first().and_then(|&h| t.get(h)) {
                share(&e.world.settings, &mut sl.run.world.settings);
            }
        });
        swap(sl);
        let result = sl.run.world.step_n(substeps as u64);
        swap(sl);
        with_table(|t| {
            for &h in &sl.handles {
                if let Some(e) = t.get(h) {
                    share(&sl.run.world.settings, &mut e.world.settings);
                    e.world.set_clock(sl.run.world.clock());
                }
            }
        });
        match result {
            Ok(()) => 0,
            Err(e) => {
                table::set_message(&e.to_string());
                1
            }
        }
    })
}

/// Scene clock (s), length of the run (s) and the scene file's time step (s).
#[no_mangle]
pub extern "C" fn ss_scene_time(s: u32) -> f64 {
    with_scene(s, f64::NAN, |sl| sl.run.time())
}
#[no_mangle]
pub extern "C" fn ss_scene_duration(s: u32) -> f64 {
    with_scene(s, f64::NAN, |sl| sl.run.duration)
}
#[no_mangle]
pub extern "C" fn ss_scene_dt(s: u32) -> f64 {
    with_scene(s, f64::NAN, |sl| sl.run.dt())
}

/// The obstacles, encoded (see `encode`); `ss_scene_obstacles_len` f64 values.
#[no_mangle]
pub extern "C" fn ss_scene_obstacles(s: u32) -> *const f64 {
    with_scene(s, std::ptr::null(), |sl| sl.obstacles.as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_scene_obstacles_len(s: u32) -> u32 {
    with_scene(s, 0, |sl| sl.obstacles.len() as u32)
}

/// Write bodies as a scene file (TOML, in the message; status 0): the `n` body handles at `hs`
/// with the names of scene `s` (or `body1`, … if `s` is 0), stepping by `dt` for `duration` s,
/// with scene `s`'s obstacles and events. See `softsculpt::scene::save`.
///
/// # Safety
/// `hs` must point to `n` u32.
#[no_mangle]
pub unsafe extern "C" fn ss_scene_save(s: u32, hs: *const u32, n: u32, dt: f64, duration: f64) -> u32 {
    let handles: Vec<u32> = if n == 0 || hs.is_null() { Vec::new() } else { std::slice::from_raw_parts(hs, n as usize).to_vec() };
    if handles.is_empty() {
        table::set_message("no bodies to save");
        return 1;
    }
    let template: Option<(SceneSpec, Vec<String>, WorldSettings)> =
        if s == 0 { None } else { with_scene(s, None, |sl| Some((sl.run.spec.clone(), sl.run.names.clone(), sl.run.world.settings.clone()))) };
    let bodies: Option<Vec<softsculpt::SoftBody>> = with_table(|t| handles.iter().map(|&h| t.get(h).map(|e| e.body().clone())).collect());
    let settings: Option<WorldSettings> = with_table(|t| t.get(handles[0]).map(|e| e.world.settings.clone()));
    let (Some(bodies), Some(mut settings)) = (bodies, settings) else {
        table::set_message("a body to save does not exist");
        return 1;
    };
    // The page's world parameters (on the first body), the scene's contact settings (or the
    // defaults), the time step asked for.
    settings.contact = template.as_ref().map(|t| t.2.contact).unwrap_or_default();
    settings.dt = dt;
    let names: Vec<String> = (0..bodies.len())
        .map(|k| template.as_ref().and_then(|t| t.1.get(k).cloned()).unwrap_or_else(|| format!("body{}", k + 1)))
        .collect();
    let pairs: Vec<(&str, &softsculpt::SoftBody)> = names.iter().map(String::as_str).zip(bodies.iter()).collect();
    let spec = scene::save::scene_of(&settings, &pairs, duration, template.as_ref().map(|t| &t.0));
    match scene::to_toml(&spec) {
        Ok(text) => {
            table::set_message(&text);
            0
        }
        Err(e) => {
            table::set_message(&format!("cannot write the scene: {e}"));
            1
        }
    }
}
