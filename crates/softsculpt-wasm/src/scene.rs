//! Scene files: open one as the world, save the world as one, describe its obstacles.
//!
//! Mesh files a scene names are given first with `ss_scene_file` (by name; a path in the scene
//! matches by its last component too); `ss_open_scene` uses, then forgets them. The handle keeps
//! the open scene's body names, length and parsed file ([`SceneInfo`], `handle.rs`) so that `ss_save_scene`
//! writes the scene's obstacles and events back (`softsculpt::scene::save`). They stay until
//! `ss_clear`, the next `ss_open_scene`, or `ss_open_project_v1`; `ss_restore` and
//! `ss_apply_delta` keep them (a page that undoes across a scene's opening re-opens the scene
//! and restores the world's snapshot into it to bring them back).
//!
//! `ss_obstacles(w)` writes the world's obstacles as a JSON array in the result, each with its
//! `kind` and `friction`, lengths in m:
//! `{"kind":"sphere","center":[x,y,z],"radius":r}`,
//! `{"kind":"box","center":[…],"half":[…],"axes":[[…],[…],[…]]}` (axes: the box's local axes in
//! world coordinates), `{"kind":"capsule","a":[…],"b":[…],"radius":r}`,
//! `{"kind":"mesh","positions":[x0,y0,z0,…],"indices":[i0,i1,i2,…]}`.

use crate::abi::exports;
use crate::handle::{with_world, SceneInfo};
use crate::{bytes, set_result, status, text, Fail};
use serde_json::json;
use softsculpt::params;
use softsculpt::scene::{self, SceneError, SceneRun};
use softsculpt::world::{Obstacle, Shape};
use softsculpt::SoftBody;
use std::cell::RefCell;
use std::collections::HashMap;

thread_local! {
    static FILES: RefCell<HashMap<String, Vec<u8>>> = RefCell::new(HashMap::new());
}

fn scene_fail(e: SceneError) -> Fail {
    let mut f = Fail::new("scene", e.to_string());
    if let Some(l) = e.line {
        f = f.with("line", l);
    }
    if let Some(k) = e.key {
        f = f.with("key", k);
    }
    f
}

fn obstacle_json(o: &Obstacle) -> serde_json::Value {
    let mut v = match &o.shape {
        Shape::Sphere { center, radius } => {
            json!({ "kind": "sphere", "center": center, "radius": radius })
        }
        Shape::Box { center, half, axes } => {
            json!({ "kind": "box", "center": center, "half": half, "axes": axes })
        }
        Shape::Capsule { a, b, radius } => {
            json!({ "kind": "capsule", "a": a, "b": b, "radius": radius })
        }
        Shape::Mesh(m) => {
            json!({ "kind": "mesh", "positions": m.positions(), "indices": m.triangles().iter().flatten().collect::<Vec<_>>() })
        }
    };
    v["friction"] = json!(o.friction);
    v
}

exports! {
    /// Make a file (`name`, bytes) available to the next `ss_open_scene`.
    ///
    /// # Safety
    /// The pointers must point to `name_len` and `len` readable bytes.
    pub unsafe fn ss_scene_file(
        name: *const u8,
        name_len: usize,
        ptr: *const u8,
        len: usize,
    ) -> i32 {
        status(|| {
            let name = text(name, name_len, "the file name")?.to_string();
            let data = bytes(ptr, len).to_vec();
            FILES.with(|f| f.borrow_mut().insert(name, data));
            Ok(())
        })
    }

    /// The world becomes the scene's (bodies, settings, events, clock at 0); result
    /// `{"names": […], "dt": s, "duration": s}`. On error (kind `scene`, with `line` and `key`
    /// when known) the world is untouched.
    ///
    /// # Safety
    /// `ptr` must point to `len` readable bytes.
    pub unsafe fn ss_open_scene(w: u32, ptr: *const u8, len: usize) -> i32 {
        let files = FILES.with(|f| std::mem::take(&mut *f.borrow_mut()));
        status(|| {
            let text = text(ptr, len, "the scene")?;
            let mut resolve = |path: &str| -> Result<Vec<u8>, String> {
                let base = path.rsplit(['/', '\\']).next().unwrap_or(path);
                files
                    .get(path)
                    .or_else(|| files.get(base))
                    .cloned()
                    .ok_or_else(|| format!("not given: open '{base}' together with the scene"))
            };
            let run = SceneRun::load(text, &mut resolve).map_err(scene_fail)?;
            with_world(w, |h| {
                let SceneRun {
                    spec,
                    world,
                    names,
                    duration,
                    ..
                } = run;
                set_result(
                    json!({ "names": names, "dt": world.settings.dt, "duration": duration })
                        .to_string()
                        .into_bytes(),
                );
                h.world = world;
                h.scene = Some(SceneInfo {
                    spec,
                    names,
                    duration,
                });
                h.rebuild_views();
                Ok(())
            })
        })
    }

    /// The world as a scene file (TOML) in the result: bodies as they are now (named as in the
    /// open scene, `body1`, … otherwise), the world's settings, the open scene's obstacles and
    /// events and its length (the table's default duration otherwise).
    pub fn ss_save_scene(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                if h.world.bodies.is_empty() {
                    return Err(Fail::usage("no bodies to save"));
                }
                let scene = h.scene.as_ref();
                let names: Vec<String> = (0..h.world.bodies.len())
                    .map(|k| {
                        scene
                            .and_then(|s| s.names.get(k).cloned())
                            .unwrap_or_else(|| format!("body{}", k + 1))
                    })
                    .collect();
                let pairs: Vec<(&str, &SoftBody)> = names
                    .iter()
                    .map(String::as_str)
                    .zip(&h.world.bodies)
                    .collect();
                let duration = scene.map_or(params::DURATION.number(), |s| s.duration);
                let spec =
                    scene::save::scene_of(&h.world.settings, &pairs, duration, scene.map(|s| &s.spec));
                let toml = scene::to_toml(&spec)
                    .map_err(|e| Fail::new("scene", format!("cannot write the scene: {e}")))?;
                set_result(toml.into_bytes());
                Ok(())
            })
        })
    }

    /// The world's obstacles as JSON in the result (see the module documentation).
    pub fn ss_obstacles(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                let list: Vec<serde_json::Value> = h
                    .world
                    .settings
                    .obstacles
                    .iter()
                    .map(obstacle_json)
                    .collect();
                set_result(serde_json::Value::Array(list).to_string().into_bytes());
                Ok(())
            })
        })
    }
}
