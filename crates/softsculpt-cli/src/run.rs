//! `softsculpt run SCENE --out DIR [--frames N]`: play a scene file headless.
//!
//! Writes, into DIR (created if needed; one that is not empty is refused before the run unless
//! `--overwrite` and all it holds is an earlier run's outputs, removed once the run has
//! succeeded), only once the whole run has
//! succeeded, each file atomically, then one line saying what it wrote:
//! - `NAME.obj` — every body's final shape (in its source file's vertex order and polygons);
//! - `summary.json` — time, steps and every body's final statistics (the `simulate` stats keys);
//! - with `--frames N`: `frames/NAME_0000.obj` … (N frames at equal intervals from the start to
//!   the end, both included) and `animation.glb`, a glTF 2.0 with the motion as morph targets.

use crate::output;
use softsculpt::mesh::animation as gltf;
use clap::Args;
use serde_json::json;
use softsculpt::scene::SceneRun;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct RunArgs {
    /// The scene file (.toml); see docs/scenes.md.
    pub scene: PathBuf,
    /// Directory for the outputs.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Also write N frames (OBJ per body and frame, and animation.glb); N ≥ 2.
    #[arg(long, value_parser = crate::args::count_positive, value_name = "N")]
    pub frames: Option<u64>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Threads for the force stages and the implicit solver (0 or absent: every core).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::args::threads, value_name = "N")]
    pub threads: Option<u64>,
    /// Write into a --out directory that holds an earlier run's outputs: they are removed (once
    /// this run has succeeded), so none of its frames stay beside the new ones. A directory
    /// holding anything else is refused.
    #[arg(long)]
    pub overwrite: bool,
    /// Run an explicit integrator at a dt above the model's stability bound (refused
    /// otherwise, with the dt that would be stable).
    #[arg(long)]
    pub force: bool,    /// Off a terminal, print a progress line every 5 s on stderr (on a terminal a bar shows anyway).
    #[arg(long)]
    pub progress: bool,
}

pub fn run(a: RunArgs) -> Result<(), String> {
    let shown = a.scene.display().to_string();
    if a.out.is_file() {
        return Err(format!("{}: is a file, --out needs a directory", a.out.display()));
    }
    let occupied = std::fs::read_dir(&a.out).map(|mut d| d.next().is_some()).unwrap_or(false);
    if occupied && !a.overwrite {
        return Err(format!("{}: the directory is not empty (an earlier run's files would stay beside the new ones): give an empty or new --out, or --overwrite to replace an earlier run's outputs", a.out.display()));
    }
    // --overwrite removes only what a run writes, so a wrong --out (the scene's own folder, `.`,
    // home) loses nothing: anything else there refuses it.
    let earlier = if occupied { earlier_outputs(&a.out)? } else { Vec::new() };
    let text = crate::input::read_file(&a.scene, &shown)?;
    let text = String::from_utf8(text).map_err(|_| format!("{shown}: not UTF-8 text"))?;
    let dir = a.scene.parent().map(Path::to_path_buf).unwrap_or_default();
    // The files the scene reads, with their hashes, for the run record (record.rs).
    let mut inputs = vec![serde_json::json!({ "name": shown, "sha256": crate::record::sha256(text.as_bytes()), "bytes": text.len() })];
    let mut resolve = |path: &str| -> Result<Vec<u8>, String> {
        // (The scene's error names the file: the reason alone here.)
        let p = dir.join(path);
        let shown = p.display().to_string();
        let bytes = crate::input::read_file(&p, &shown).map_err(|e| e.trim_start_matches(&format!("{shown}: ")).trim_start_matches("cannot read: ").to_string())?;
        inputs.push(serde_json::json!({ "name": path, "sha256": crate::record::sha256(&bytes), "bytes": bytes.len() }));
        Ok(bytes)
    };
    let mut scene = SceneRun::load(&text, &mut resolve).map_err(|e| format!("{shown}: {e}"))?;
    // Recorded as the run starts (the parameters the scene set; events change some later).
    let record = crate::record::run(&scene.world, &scene.names, inputs);
    scene.world.set_threads(a.threads.unwrap_or(0) as usize).map_err(|e| format!("--threads: {e}"))?;
    crate::simulate::check_stable(&scene.world, a.force, "the scene's dt").map_err(|e| format!("{shown}: {e}"))?;
    if a.frames == Some(1) {
        return Err("--frames: at least 2 (the first frame is the start, the last the end)".into());
    }

    let total = scene.total_steps();
    // Steps at which frames are taken: k · total / (N − 1), rounded.
    let frame_steps: Vec<u64> = match a.frames {
        Some(n) => (0..n).map(|k| ((k as f64) * total as f64 / (n - 1) as f64).round() as u64).collect(),
        None => Vec::new(),
    };
    let mut frames: Vec<Vec<Vec<f64>>> = vec![Vec::new(); scene.world.bodies.len()];
    let mut times = Vec::new();
    let take = |s: &SceneRun, frames: &mut Vec<Vec<Vec<f64>>>, times: &mut Vec<f64>| {
        while times.len() < frame_steps.len() && frame_steps[times.len()] <= s.steps() {
            times.push(s.time());
            for (k, b) in s.world.bodies.iter().enumerate() {
                frames[k].push(b.positions().to_vec());
            }
        }
    };
    take(&scene, &mut frames, &mut times);
    let mut bar = crate::progress::Progress::counted("run", total, "steps", !a.quiet, a.progress);
    scene
        .run(|s| {
            take(s, &mut frames, &mut times);
            if s.steps() % 100 == 0 {
                bar.set(s.steps());
            }
        })
        .map_err(|e| format!("{shown}: {e}"))?;
    bar.finish();

    remove_all(&a.out, &earlier)?;
    let header = |t: f64| format!("softsculpt run {shown}: t = {t} s");
    let mut summary = serde_json::Map::new();
    summary.insert("run".into(), record);
    summary.insert("time".into(), json!(scene.time()));
    summary.insert("steps".into(), json!(scene.steps()));
    let mut bodies = serde_json::Map::new();
    for (k, b) in scene.world.bodies.iter().enumerate() {
        let name = &scene.names[k];
        output::write_atomic(&a.out.join(format!("{name}.obj")), &scene.meshes[k].write_obj(b.positions(), &header(scene.time())))?;
        bodies.insert(name.clone(), scene.world.stats(k).to_json());
    }
    summary.insert("bodies".into(), json!(bodies));
    if !times.is_empty() {
        for (k, name) in scene.names.iter().enumerate() {
            for (f, x) in frames[k].iter().enumerate() {
                let path = a.out.join("frames").join(format!("{name}_{f:04}.obj"));
                output::write_atomic(&path, &scene.meshes[k].write_obj(x, &header(times[f])))?;
            }
        }
        let tracks: Vec<gltf::Track> = scene
            .names
            .iter()
            .enumerate()
            .map(|(k, name)| gltf::Track { name, triangles: scene.world.bodies[k].triangles(), frames: &frames[k] })
            .collect();
        output::write_atomic(&a.out.join("animation.glb"), &gltf::animation_glb(&tracks, &times, "softsculpt run"))?;
    }
    let text = serde_json::to_string_pretty(&json!(summary)).expect("JSON of plain values");
    output::write_atomic(&a.out.join("summary.json"), format!("{text}\n").as_bytes())?;
    let n = scene.names.len();
    let framed = if times.is_empty() { String::new() } else { format!(", {} frames and animation.glb", times.len()) };
    eprintln!("wrote {}: {n} {} ({}), summary.json{framed}; after {} steps, t = {:.4} s", a.out.display(), if n == 1 { "body" } else { "bodies" }, scene.names.iter().map(|s| format!("{s}.obj")).collect::<Vec<_>>().join(", "), scene.steps(), scene.time());
    Ok(())
}

/// The entries of `dir` an earlier `run` wrote (`summary.json`, `animation.glb`, `frames/`, and
/// OBJ files whose first line is run's header), for `--overwrite` to remove; an error naming the
/// first entry that is anything else.
fn earlier_outputs(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let fail = |e: std::io::Error| format!("{}: cannot list it: {e}", dir.display());
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(fail)? {
        let p = entry.map_err(fail)?.path();
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let ours = match name.as_str() {
            "summary.json" | "animation.glb" => p.is_file(),
            "frames" => p.is_dir() && !p.is_symlink() && std::fs::read_dir(&p).map_err(fail)?.all(|e| e.is_ok_and(|e| written_by_run(&e.path()))),
            _ => written_by_run(&p),
        };
        if !ours {
            return Err(format!(
                "{}: --overwrite replaces only an earlier run's outputs, and '{name}' is not one (give another --out)",
                dir.display()
            ));
        }
        out.push(p);
    }
    Ok(out)
}

/// An OBJ file `run` wrote: its first line is run's header (`# softsculpt run …`).
fn written_by_run(p: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 16];
    p.extension().is_some_and(|e| e == "obj")
        && p.is_file()
        && std::fs::File::open(p).and_then(|mut f| f.read_exact(&mut head)).is_ok()
        && &head == b"# softsculpt run"
}

/// Remove `paths` (an earlier run's outputs: files, and the frames folder).
fn remove_all(dir: &Path, paths: &[PathBuf]) -> Result<(), String> {
    for p in paths {
        if p.is_dir() { std::fs::remove_dir_all(p) } else { std::fs::remove_file(p) }
            .map_err(|e| format!("{}: cannot remove {} for --overwrite: {e}", dir.display(), p.display()))?;
    }
    Ok(())
}
