//! `softsculpt run SCENE --out DIR [--frames N]`: outputs, the glTF animation, and bad scenes.

use serde_json::Value;
use std::process::{Command, Output};

fn softsculpt(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_softsculpt")).args(args).output().expect("runs")
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A small two-body scene with an obstacle, a mesh file beside it and events of several kinds.
const SCENE: &str = r#"
[world]
dt = 0.001
duration = 0.3
ground = { height = 0.0 }

[[body]]
name = "ball"
model = "sphere"
scale = 0.4
translate = [0.0, 1.2, 0.0]
gas = { nrt = 5.0 }

[[body]]
name = "tet"
mesh = "tetra.obj"
translate = [2.0, 0.5, 0.0]
self_collision = true

[[obstacle]]
shape = "capsule"
a = [-1.0, 0.3, 0.0]
b = [1.0, 0.3, 0.0]
radius = 0.1

[[event]]
time = 0.1
action = "force"
body = "ball"
region = { all = true }
force = [1.0, 0.0, 0.0]
duration = 0.1

[[event]]
time = 0.2
action = "freeze"
"#;

const TETRA: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

/// A folder holding SCENE and the mesh it names; returns it, the scene's path and an `out` path in it.
fn scene_folder() -> (tempfile::TempDir, std::path::PathBuf, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), SCENE).unwrap();
    std::fs::write(dir.path().join("tetra.obj"), TETRA).unwrap();
    let (scene, out) = (dir.path().join("scene.toml"), dir.path().join("out"));
    (dir, scene, out)
}

fn read_obj_positions(path: &std::path::Path) -> Vec<f64> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("v "))
        .flat_map(|l| l.split_whitespace().skip(1).map(|x| x.parse::<f64>().unwrap()).collect::<Vec<_>>())
        .collect()
}

#[test]
fn a_scene_writes_final_meshes_frames_summary_and_a_gltf_animation() {
    let (_dir, scene, out) = scene_folder();
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap(), "--frames", "4"]);
    assert!(o.status.success(), "{}", err(&o));
    for f in ["ball.obj", "tet.obj", "summary.json", "animation.glb", "frames/ball_0000.obj", "frames/ball_0003.obj", "frames/tet_0003.obj"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // The last frame is the final mesh; the first is the placed start (bottom of the ball at
    // 1.2 − 0.4 = 0.8 m).
    assert_eq!(read_obj_positions(&out.join("frames/ball_0003.obj")), read_obj_positions(&out.join("ball.obj")));
    let first = read_obj_positions(&out.join("frames/ball_0000.obj"));
    let lowest = first.chunks(3).map(|c| c[1]).fold(f64::INFINITY, f64::min);
    assert!((lowest - 0.8).abs() < 1e-12, "{lowest}");
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["steps"], 300);
    assert!(summary["bodies"]["ball"]["volume"].as_f64().unwrap() > 0.0);

    // The GLB: header, JSON chunk, BIN chunk; per body a mesh with one morph target per frame
    // whose POSITION is the displacement from frame 0 (f32), animated by the weights.
    let glb = std::fs::read(out.join("animation.glb")).unwrap();
    assert_eq!(&glb[0..4], b"glTF");
    assert_eq!(u32::from_le_bytes(glb[4..8].try_into().unwrap()), 2);
    assert_eq!(u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize, glb.len());
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    assert_eq!(&glb[16..20], b"JSON");
    let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let bin = &glb[20 + json_len + 8..];
    assert_eq!(&glb[20 + json_len + 4..20 + json_len + 8], b"BIN\0");
    assert_eq!(doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize, bin.len());
    let accessor = |k: u64| -> Vec<f32> {
        let a = &doc["accessors"][k as usize];
        let v = &doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let off = v["byteOffset"].as_u64().unwrap() as usize;
        let len = v["byteLength"].as_u64().unwrap() as usize;
        bin[off..off + len].chunks(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect()
    };
    let mesh = &doc["meshes"][0];
    assert_eq!(mesh["name"], "ball");
    let prim = &mesh["primitives"][0];
    assert_eq!(prim["targets"].as_array().unwrap().len(), 4);
    let base = accessor(prim["attributes"]["POSITION"].as_u64().unwrap());
    let last = accessor(prim["targets"][3]["POSITION"].as_u64().unwrap());
    // base + target 3 = the final shape (to f32 precision, in the body's vertex order: compare
    // as sorted point sets' bounds).
    let final_y_max = read_obj_positions(&out.join("ball.obj")).chunks(3).map(|c| c[1]).fold(f64::NEG_INFINITY, f64::max);
    let anim_y_max = base.chunks(3).zip(last.chunks(3)).map(|(b, d)| (b[1] + d[1]) as f64).fold(f64::NEG_INFINITY, f64::max);
    assert!((final_y_max - anim_y_max).abs() < 1e-5, "{final_y_max} vs {anim_y_max}");
    let times = accessor(doc["animations"][0]["samplers"][0]["input"].as_u64().unwrap());
    assert_eq!(times.len(), 4);
    assert!((times[3] - 0.3).abs() < 1e-6 && times[0] == 0.0);
    assert_eq!(doc["animations"][0]["channels"][1]["target"]["path"], "weights");
}

#[test]
fn a_bad_scene_is_one_error_line_with_the_line_number_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(&scene, "[world]\ndt = 0.001\n\n[[body]]\nmodel = \"sphere\"\nstiffness = \"stiff\"\n").unwrap();
    let out = dir.path().join("out");
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let e = err(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.starts_with("error:") && e.contains("line 6") && e.contains("body[0].stiffness"), "{e}");
    assert!(!out.exists());

    let o = softsculpt(&["run", dir.path().join("none.toml").to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(err(&o).starts_with("error:") && err(&o).contains("cannot read"), "{}", err(&o));
    std::fs::write(&scene, "[[body]]\nmodel = \"sphere\"\n").unwrap();
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap(), "--frames", "1"]);
    assert!(err(&o).contains("--frames"), "{}", err(&o));
}

#[test]
fn every_shipped_scene_runs_from_the_command_line() {
    let scenes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let dir = tempfile::tempdir().unwrap();
    let mut n = 0;
    for e in std::fs::read_dir(&scenes).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let o = softsculpt(&["run", p.to_str().unwrap(), "--out", dir.path().join(format!("{n}")).to_str().unwrap(), "--frames", "3"]);
            assert!(o.status.success(), "{}: {}", p.display(), err(&o));
            n += 1;
        }
    }
    assert!(n >= 6, "{n} scenes");
}

/// `run` into a directory that is not empty is refused before the run (an earlier run's frames
/// and `animation.glb` stayed beside the new ones); `--overwrite` empties it once the run has
/// succeeded; the run ends with one line saying what it wrote.
#[test]
fn a_full_output_directory_is_refused_unless_overwrite_empties_it() {
    let (dir, scene, out) = scene_folder();
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap(), "--frames", "4"]);
    assert!(o.status.success(), "{}", err(&o));
    let said = err(&o);
    assert!(said.starts_with(&format!("wrote {}: 2 bodies (ball.obj, tet.obj), summary.json, 4 frames and animation.glb; after 300 steps", out.display())), "{said}");
    let before = std::fs::read(out.join("summary.json")).unwrap();
    // Again without --overwrite: refused, nothing touched.
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("the directory is not empty") && err(&o).contains("--overwrite") && err(&o).lines().count() == 1, "{}", err(&o));
    assert!(out.join("animation.glb").is_file() && out.join("frames/ball_0003.obj").is_file());
    assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), before);
    // With --overwrite and no frames: the old frames and animation are gone, the new run is there.
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap(), "--overwrite"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(!out.join("animation.glb").exists() && !out.join("frames").exists());
    assert!(out.join("ball.obj").is_file() && out.join("summary.json").is_file());
    // A directory holding anything a run did not write (here the scene's own folder) is never
    // emptied: --overwrite is refused, every file kept.
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", dir.path().to_str().unwrap(), "--overwrite"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("replaces only an earlier run's outputs") && err(&o).lines().count() == 1, "{}", err(&o));
    assert!(scene.is_file() && dir.path().join("tetra.obj").is_file() && out.join("ball.obj").is_file());
}

/// A scene whose explicit step is far above a body's stability bound is refused before it runs,
/// naming the scene's dt and the fix; `--force` runs it (and it blows up, as the bound said).
#[test]
fn a_scene_stepped_far_above_its_stable_step_is_refused_with_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("stiff.toml");
    std::fs::write(&scene, "[world]\ndt = 0.001\nintegrator = \"symplectic\"\n\n[[body]]\nmodel = \"sphere\"\nstiffness = 20000.0\n").unwrap();
    let out = dir.path().join("out");
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let e = err(&o);
    assert!(e.starts_with("error:") && e.lines().count() == 1, "{e}");
    assert!(e.contains("the scene's dt 0.001 s is above the largest step symplectic is stable at") && e.contains("the implicit integrator") && e.contains("--force"), "{e}");
    assert!(!out.exists());
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap(), "--force"]);
    assert!(!o.status.success() && (err(&o).contains("blew up") || err(&o).contains("collapsed")), "{}", err(&o));
}

/// A value the scene checks after parsing (a range, a missing companion key) is reported at the
/// line that sets it, not at its table's header (before: `[body.gas]`'s `nrt = -5` on line 8
/// was cited as line 4, `[[body]]`).
#[test]
fn a_bad_value_is_cited_at_its_own_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for (text, line, key) in [
        ("[world]\ndt = 0.001\n\n[[body]]\nmodel = \"sphere\"\n\n[body.gas]\nnrt = -5.0\n", 8, "body[0].gas.nrt"),
        ("[[body]]\nmodel = \"sphere\"\nmass = 2.0\ngas = { nrt = -5.0 }\n", 4, "body[0].gas.nrt"),
        ("# a comment\n[world]\nduration = 1.0\ndt = -0.001\n\n[[body]]\nmodel = \"sphere\"\n", 4, "world.dt"),
        ("[[body]]\nmodel = \"sphere\"\n\n[[body]]\nmodel = \"sphere\"\nmass = 1.0\nstiffness = -5\n", 7, "body[1].stiffness"),
    ] {
        let scene = dir.path().join("bad.toml");
        std::fs::write(&scene, text).unwrap();
        let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let e = err(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.contains(&format!("line {line}: {key}:")) && e.lines().count() == 1, "{text}\n{e}");
    }
}

/// `summary.json` records the run: the scene file and the mesh files it read, each with the
/// SHA-256 of its bytes, and every body's parameters by table id.
#[test]
fn the_summary_records_the_run_and_its_files() {
    let (_dir, scene, out) = scene_folder();
    let o = softsculpt(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", err(&o));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let run = &summary["run"];
    let files: Vec<&str> = run["inputs"].as_array().unwrap().iter().map(|i| i["name"].as_str().unwrap()).collect();
    assert!(files[0].ends_with("scene.toml") && files.contains(&"tetra.obj"), "{files:?}");
    assert!(run["inputs"].as_array().unwrap().iter().all(|i| i["sha256"].as_str().is_some_and(|h| h.len() == 64)), "{run}");
    assert!((run["bodies"]["ball"]["gas.nrt"].as_f64().unwrap() - 5.0).abs() < 1e-12, "{run}");
    assert_eq!(run["world"]["dt"], 0.001);
    assert_eq!(summary["steps"], 300, "the summary's own keys are kept");
}
