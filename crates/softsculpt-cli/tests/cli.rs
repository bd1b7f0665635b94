//! The `softsculpt` command as other tools call it: flags, outputs, and every bad input.

mod common;

use common::{softsculpt, stderr, Dir};
use std::path::Path;
use std::process::Output;

/// Failed with exactly one line on stderr that starts with `error:` and contains `needle`.
fn assert_clean_error(o: &Output, needle: &str) {
    let e = stderr(o);
    assert!(!o.status.success(), "should fail: {e}");
    assert!(!e.contains("panicked"), "panic: {e}");
    let lines: Vec<&str> = e.lines().filter(|l| !l.starts_with("warning:")).collect();
    assert_eq!(lines.len(), 1, "one error line expected, got: {e}");
    assert!(lines[0].starts_with("error:"), "{e}");
    assert!(lines[0].contains(needle), "'{}' lacks '{needle}'", lines[0]);
}

const TETRA: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

#[test]
fn every_malformed_input_file_is_one_clear_error() {
    let d = Dir::new();
    let cases: Vec<(String, &str)> = vec![
        (d.file("empty.obj", b""), "no faces"),
        (d.file("garbage.obj", b"this is not a mesh\n"), "line 1"),
        (d.file("badindex.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), "refers to vertex 7"),
        (d.file("zeroindex.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "index 0"),
        (d.file("nan.obj", b"v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), "not finite"),
        (d.file("inf.obj", b"v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n"), "not finite"),
        (d.file("missing.obj", b"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"), "3 coordinates"),
        (d.file("binary.obj", &[0x7f, 0x45, 0x4c, 0x46, 0, 1, 2, 3, 0xff]), "not a text"),
        (d.file("mesh.stl", TETRA.as_bytes()), "not a valid STL file"),
        (d.file("mesh.fbx", TETRA.as_bytes()), "unsupported file type"),
        (d.file("noext", TETRA.as_bytes()), "no file extension"),
        (d.path("does-not-exist.obj").to_string_lossy().into_owned(), "no such file"),
        (d.0.path().to_string_lossy().into_owned(), "is a directory"),
        ("builtin:teapot".to_string(), "unknown built-in"),
    ];
    let out = d.path("out.obj");
    for (input, needle) in &cases {
        let o = softsculpt(&["simulate", input, "--out", out.to_str().unwrap(), "--steps", "1"]);
        assert_clean_error(&o, needle);
        assert!(stderr(&o).contains(input.as_str()), "the error names the input: {}", stderr(&o));
        assert_eq!(o.status.code(), Some(1));
        let o = softsculpt(&["info", input]);
        assert_clean_error(&o, needle);
    }
    assert!(!out.exists());
}

#[test]
fn every_bad_flag_is_one_clear_error_naming_the_flag() {
    let d = Dir::new();
    let out = d.path("o.obj");
    let out = out.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--dt", "0"], "--dt"),
        (&["--dt", "-1e-3"], "--dt"),
        (&["--dt", "nan"], "--dt"),
        (&["--steps", "-5"], "--steps"),
        (&["--steps", "many"], "--steps"),
        (&["--integrator", "verlet"], "--integrator"),
        (&["--volume", "cube"], "--volume"),
        (&["--stiffness", "inf"], "--stiffness"),
        (&["--stiffness", "-1"], "--stiffness"),
        (&["--mass", "0"], "--mass"),
        (&["--mass", "-2"], "--mass"),
        (&["--gas", "-1"], "--gas"),
        (&["--wind", "1,2"], "--wind"),
        (&["--velocity", "a,b,c"], "--velocity"),
        (&["--gravity", "nan"], "--gravity"),
        (&["--stats-every", "0"], "--stats-every"),
        (&["--until-rest", "0"], "--until-rest"),
        (&["--frobnicate"], "--frobnicate"),
    ];
    for (flags, needle) in cases {
        let mut args = vec!["simulate", "builtin:sphere", "--out", out];
        args.extend_from_slice(flags);
        let o = softsculpt(&args);
        assert_clean_error(&o, needle);
        assert_eq!(o.status.code(), Some(2), "{flags:?}");
    }
    assert!(!Path::new(out).exists());
    // A missing required argument is named, not only announced.
    let o = softsculpt(&["simulate", "builtin:sphere", "--steps", "1"]);
    assert_clean_error(&o, "--out");
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn a_failed_run_leaves_an_existing_output_untouched() {
    let d = Dir::new();
    let out = d.file("keep.obj", b"precious work\n");
    // An explosion (dt far too large for the stiffness: forced past the stability check) fails mid-run.
    let o = softsculpt(&["simulate", "builtin:sphere", "--out", &out, "--stiffness", "1e7", "--dt", "0.01", "--steps", "500", "--force"]);
    assert_clean_error(&o, "smaller");
    assert!(stderr(&o).contains("step"));
    assert_eq!(std::fs::read(&out).unwrap(), b"precious work\n");
    // Gas in an open mesh is refused before anything is written.
    let open = d.file("open.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n");
    let o = softsculpt(&["simulate", &open, "--out", &out, "--gas", "1"]);
    assert_clean_error(&o, "boundary");
    assert_eq!(std::fs::read(&out).unwrap(), b"precious work\n");
    // No temporary files are left behind.
    let names: Vec<_> = std::fs::read_dir(d.0.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn zero_steps_writes_the_input_back_exactly() {
    let d = Dir::new();
    // Quads, an unused vertex, awkward decimals: all must come back unchanged.
    let text = "v 0.1 0.2 0.30000000000000004\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nv 9 9 9\n\
                f 1 4 3 2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
    let input = d.file("pyramid.obj", text.as_bytes());
    let out = d.path("out.obj");
    let o = softsculpt(&["simulate", &input, "--out", out.to_str().unwrap(), "--steps", "0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = std::fs::read_to_string(&out).unwrap();
    let strip = |s: &str| s.lines().filter(|l| !l.starts_with('#')).map(|l| l.split_whitespace().collect::<Vec<_>>().join(" ")).collect::<Vec<_>>();
    let (a, b) = (strip(text), strip(&written));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        let xs: Vec<&str> = x.split(' ').collect();
        let ys: Vec<&str> = y.split(' ').collect();
        assert_eq!(xs[0], ys[0]);
        for (p, q) in xs[1..].iter().zip(&ys[1..]) {
            if xs[0] == "v" {
                assert_eq!(p.parse::<f64>().unwrap().to_bits(), q.parse::<f64>().unwrap().to_bits(), "{x} vs {y}");
            } else {
                assert_eq!(p, q);
            }
        }
    }
}

#[test]
fn stats_lines_carry_the_contract_keys() {
    let d = Dir::new();
    let out = d.path("s.obj");
    let stats = d.path("s.jsonl");
    let o = softsculpt(&[
        "simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--steps", "250", "--stats", stats.to_str().unwrap(),
        "--stats-every", "100", "--gas", "2", "--ground", "-1.2", "--wind", "1,0,0", "--velocity", "0,-1,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&stats).unwrap();
    let lines: Vec<serde_json::Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let steps: Vec<u64> = lines.iter().map(|l| l["step"].as_u64().unwrap()).collect();
    assert_eq!(steps, vec![0, 100, 200, 250]);
    let keys = [
        "step", "time", "volume", "pressure", "kinetic_energy", "elastic_energy", "gas_energy", "gravity_energy",
        "total_energy", "momentum", "center_of_mass", "max_speed", "solver_iterations", "plastic_dissipation",
    ];
    for (i, l) in lines.iter().enumerate() {
        let obj = l.as_object().unwrap();
        // The contract's keys, in order; the first row adds the run's record after them (record.rs).
        let got: Vec<&str> = obj.keys().map(|k| k.as_str()).filter(|&k| !(i == 0 && k == "run")).collect();
        assert_eq!(got, keys);
        assert_eq!(l["momentum"].as_array().unwrap().len(), 3);
        // Explicit integrators report no solver iterations.
        assert_eq!(l["solver_iterations"], serde_json::json!({"newton": 0, "linear": 0}));
    }
    // Step 0: initial velocity (0,-1,0) for a 1 kg body.
    assert!((lines[0]["momentum"][1].as_f64().unwrap() + 1.0).abs() < 1e-12);
    // P V = nRT at every line.
    for l in &lines {
        let pv = l["pressure"].as_f64().unwrap() * l["volume"].as_f64().unwrap();
        assert!((pv - 2.0).abs() < 1e-9);
    }
    let mesh = softsculpt::mesh::obj::parse(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(mesh.vertex_count(), 642);
}

#[test]
fn until_rest_stops_a_settled_body_early() {
    let d = Dir::new();
    let out = d.path("r.obj");
    let o = softsculpt(&[
        "simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--steps", "100000", "--gas", "5", "--gravity", "0",
        "--damping", "20", "--until-rest", "1e-4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("(at rest)"), "{e}");
    let steps: u64 = e.split("after ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!(steps < 100000, "{steps}");
}

#[test]
fn info_reports_welds_and_defects() {
    let d = Dir::new();
    // The tetrahedron with vertex 1 duplicated (as a seam would) in the last face.
    let text = format!("{TETRA}v 0 0 0\nf 3 5 4\n").replace("f 3 1 4\nv 0 0 0\nf 3 5 4\n", "v 0 0 0\nf 3 5 4\n");
    let input = d.file("seam.obj", text.as_bytes());
    let o = softsculpt(&["info", &input, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["welded_vertices"], 1);
    assert_eq!(v["closed"], true);
    assert_eq!(v["vertices"], 4);
    assert!((v["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() < 1e-15);
    let o = softsculpt(&["info", "builtin:octopus"]);
    let t = String::from_utf8_lossy(&o.stdout);
    assert!(t.contains("closed:              yes") && t.contains("boundary edges:      0"), "{t}");
}

#[test]
fn bench_json_has_the_contract_keys() {
    let o = softsculpt(&["bench", "--levels", "1,2", "--steps", "20", "--reps", "1", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stdout).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[1]["vertices"], 162);
    assert_eq!(lines[1]["springs"], 480);
    for k in ["ms_per_step", "ns_per_spring_step", "volume"] {
        assert!(lines[1][k].as_f64().unwrap() > 0.0, "{k}");
    }
}

#[test]
fn bending_springs_change_the_result() {
    let d = Dir::new();
    let run = |kb: &str, name: &str| {
        let out = d.path(name);
        let o = softsculpt(&["simulate", "builtin:mushroom", "--out", out.to_str().unwrap(), "--steps", "800", "--gas", "30", "--ground", "0", "--bending", kb]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(out).unwrap()
    };
    assert_ne!(run("0", "a.obj"), run("100", "b.obj"));
    let o = softsculpt(&["simulate", "builtin:mushroom", "--out", d.path("c.obj").to_str().unwrap(), "--bending", "-1"]);
    assert_clean_error(&o, "--bending");
}

/// `--rigidity D` is taken like `--bending` (given alone and over a preset); a bad value
/// (negative, NaN, infinite, not a number) is one clean error naming the flag, as for `--bending`.
#[test]
fn rigidity_is_taken_like_bending_and_bad_values_are_refused() {
    let d = Dir::new();
    for extra in [&[][..], &["--preset", "clay"][..]] {
        let out = d.path("r.obj");
        // (--force: clay is above the symplectic stable step at the default dt; 20 steps hold.)
        let mut args = vec!["simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--steps", "20", "--gas", "5", "--rigidity", "0.05", "--force"];
        args.extend_from_slice(extra);
        let o = softsculpt(&args);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        assert!(out.exists());
    }
    for (bad, flag) in [("-1", "--rigidity"), ("NaN", "--rigidity"), ("inf", "--rigidity"), ("stiff", "--rigidity"), ("-1", "--bending"), ("NaN", "--bending")] {
        let o = softsculpt(&["simulate", "builtin:sphere", "--out", d.path("bad.obj").to_str().unwrap(), flag, bad]);
        assert_eq!(o.status.code(), Some(2), "{flag} {bad}");
        assert_clean_error(&o, flag);
    }
}

/// The flags' defaults and help lines are the core's parameter table's (the README's table
/// documents the same values).
#[test]
fn the_help_shows_the_defaults_of_the_parameter_table() {
    let o = softsculpt(&["simulate", "--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout).split_whitespace().collect::<Vec<_>>().join(" ");
    for (flag, default) in [("--stiffness", "100"), ("--spring-damping", "0.1"), ("--bending", "0"), ("--rigidity", "0"), ("--damping", "0"), ("--mass", "1"), ("--gravity", "9.81"), ("--friction", "0.5"), ("--wind-drag", "1"), ("--integrator", "symplectic"), ("--volume", "exact")] {
        let at = help.find(&format!("{flag} <")).unwrap_or_else(|| panic!("{flag} in the help"));
        let rest = &help[at..];
        let line = &rest[..rest[2..].find(" --").map_or(rest.len(), |e| e + 2)];
        assert!(line.contains(&format!("[default: {default}]")), "{flag}: {line}");
    }
    assert!(help.contains("Spring stiffness k of every edge [N/m]"), "{help}");
}

#[test]
fn implicit_runs_report_solver_iterations_and_bad_tolerances_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.obj");
    let stats = dir.path().join("s.jsonl");
    let o = softsculpt(&[
        "simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--steps", "20", "--dt", "0.0166", "--integrator", "implicit",
        "--tolerance", "1e-5", "--gas", "5", "--threads", &two_or_fewer_threads(), "--stats", stats.to_str().unwrap(), "--stats-every", "10",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let last: serde_json::Value = serde_json::from_str(std::fs::read_to_string(&stats).unwrap().lines().last().unwrap()).unwrap();
    assert!(last["solver_iterations"]["newton"].as_u64().unwrap() >= 1, "{last}");
    assert!(last["solver_iterations"]["linear"].as_u64().unwrap() >= 1, "{last}");
    for bad in ["0", "-1", "NaN"] {
        let o = softsculpt(&["simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--integrator", "implicit", "--tolerance", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        let e = stderr(&o);
        assert!(e.starts_with("error:") && e.contains("--tolerance") && e.lines().count() == 1, "{e}");
    }
}

/// `softsculpt info … | head -1`: the reader closes the pipe before the command has printed
/// everything; the command ends quietly (killed by SIGPIPE, as `cat` is), no panic message.
/// The pipe's read end is closed before the command starts, so its first write always meets
/// the closed pipe. (Closing it after the spawn raced the command: a 42-vertex `bench` once
/// wrote its whole report into the pipe's buffer first and exited 0 on a loaded machine.)
#[cfg(unix)]
#[test]
fn a_reader_that_closes_the_pipe_early_gets_no_panic() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    for args in [&["info", "builtin:octopus"][..], &["bench", "--levels", "1", "--steps", "2", "--reps", "1"][..]] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader); // closed before the command's first line
        let mut child = Command::new(env!("CARGO_BIN_EXE_softsculpt")).args(args).stdout(writer).stderr(Stdio::piped()).spawn().unwrap();
        let mut e = String::new();
        child.stderr.take().unwrap().read_to_string(&mut e).unwrap();
        let status = child.wait().unwrap();
        assert!(!e.contains("panicked") && !e.contains("Broken pipe"), "{args:?}: {e}");
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(status.signal(), Some(13), "{args:?}: {status:?}"); // SIGPIPE
    }
}

/// Two threads, or as many as the machine runs if fewer (`--threads` refuses more).
fn two_or_fewer_threads() -> String {
    std::thread::available_parallelism().map_or(1, |n| n.get()).min(2).to_string()
}

/// `--threads` above what the machine runs at once is refused before anything runs, saying how
/// many it runs (`--threads 99999` once started 2,498 threads and stopped the machine).
#[test]
fn more_threads_than_the_machine_runs_are_refused_up_front() {
    let d = Dir::new();
    let most = std::thread::available_parallelism().map_or(1, |n| n.get());
    for command in [&["simulate", "builtin:sphere", "--out", &d.s("t.obj")][..], &["bench", "--levels", "1"][..]] {
        for n in [most + 1, 99999] {
            let mut args = command.to_vec();
            let n = n.to_string();
            args.extend_from_slice(&["--threads", &n]);
            let o = softsculpt(&args);
            assert_eq!(o.status.code(), Some(2), "{args:?}");
            assert_clean_error(&o, "--threads");
            assert!(stderr(&o).contains(&format!("this machine runs {most} threads at once")), "{}", stderr(&o));
        }
    }
    assert!(!d.path("t.obj").exists());
}

/// An input that is not a regular file (a device: `/dev/zero` grew the process to 4.7 GB) or is
/// larger than the limit is one clear error before anything is read; nothing is written.
#[cfg(unix)]
#[test]
fn a_device_or_an_oversized_input_is_refused_before_it_is_read() {
    let d = Dir::new();
    let out = d.path("never.obj");
    let o = softsculpt(&["simulate", "/dev/zero", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("error: /dev/zero: not a regular file") && stderr(&o).lines().count() == 1, "{}", stderr(&o));
    // A sparse file one byte over 1 GiB: refused by its size, never read (no disk, no memory).
    let big = d.path("big.stl");
    std::fs::File::create(&big).unwrap().set_len((1u64 << 30) + 1).unwrap();
    let o = softsculpt(&["info", big.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("1073741825 bytes is more than the 1024 MiB an input file may have") && stderr(&o).lines().count() == 1, "{}", stderr(&o));
    assert!(!out.exists());
}

/// An explicit run far above the model's stability bound is refused before it starts, with the
/// step that would be stable and the implicit integrator as the fixes (before: `--preset
/// stiff_rubber` on the sphere collapsed at step 12 and the advice said "stiffer springs");
/// `--force` runs it, and it does collapse; at the advised step, or implicit, it runs.
#[test]
fn an_explicit_step_far_above_the_stable_step_is_refused_with_the_fix() {
    let d = Dir::new();
    let out = d.path("r.obj");
    let base = ["simulate", "builtin:sphere", "--out", out.to_str().unwrap(), "--preset", "stiff_rubber", "--integrator", "symplectic"];
    let o = softsculpt(&base);
    assert_clean_error(&o, "--dt 0.001 s is above the largest step symplectic is stable at for this model");
    let e = stderr(&o);
    assert!(e.contains("the implicit integrator") && e.contains("--force"), "{e}");
    assert!(!out.exists(), "nothing written");
    // The advised step, read from the message: it runs.
    let advised = e.split("give --dt ").nth(1).and_then(|r| r.split(' ').next()).unwrap().to_string();
    let mut args = base.to_vec();
    args.extend_from_slice(&["--dt", &advised, "--steps", "200"]);
    assert!(softsculpt(&args).status.success(), "at --dt {advised}");
    let mut args = base[..6].to_vec();
    args.extend_from_slice(&["--integrator", "implicit", "--dt", "0.0166", "--steps", "20"]);
    assert!(softsculpt(&args).status.success(), "implicit");
    // Forced: it runs and collapses, as measured before the check (step 12).
    let mut args = base.to_vec();
    args.push("--force");
    let o = softsculpt(&args);
    assert_clean_error(&o, "collapsed");
    assert!(!stderr(&o).contains("stiffer springs"), "{}", stderr(&o));
}

/// An open surface has no inside: `info --json` gives its volume as null, as the text calls it
/// not meaningful (before, the JSON gave a number for it).
#[test]
fn an_open_surface_has_no_volume_in_the_json() {
    let d = Dir::new();
    let open = d.file("open.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n");
    let o = softsculpt(&["info", &open, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["closed"], false);
    assert!(v["volume"].is_null(), "{v}");
    let t = String::from_utf8_lossy(&softsculpt(&["info", &open]).stdout).to_string();
    assert!(t.contains("(not meaningful: open surface)"), "{t}");
}

/// `simulate --help` names every built-in model (it once left out the kangaroo), and so does
/// docs/scenes.md's `model` key.
#[test]
fn the_help_and_the_scene_docs_name_every_built_in_model() {
    let help = String::from_utf8_lossy(&softsculpt(&["simulate", "--help"]).stdout).split_whitespace().collect::<Vec<_>>().join(" ");
    let docs = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scenes.md")).unwrap();
    let row = docs.lines().find(|l| l.starts_with("| `model` |")).unwrap();
    for name in softsculpt::mesh::builtin::NAMES {
        assert!(help.contains(name), "simulate --help lacks {name}");
        assert!(row.contains(&format!("`{name}`")), "docs/scenes.md lacks {name}: {row}");
    }
}

/// Off a terminal (a pipe, as here) a long run prints nothing but its final line: no bar, no
/// escape codes; `--progress` is accepted by every long command (its lines come every 5 s, so a
/// run this short prints none).
#[test]
fn off_a_terminal_only_the_final_line_is_printed() {
    let d = Dir::new();
    let (p, r) = (d.s("p.obj"), d.s("r.obj"));
    for extra in [&[][..], &["--progress"][..]] {
        let mut args = vec!["simulate", "builtin:sphere", "--out", &p, "--steps", "2000"];
        args.extend_from_slice(extra);
        let o = softsculpt(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        // (A loaded machine may take over 5 s: then --progress's lines come before it.)
        let e = stderr(&o);
        let rest: Vec<&str> = e.lines().filter(|l| !(extra.len() == 1 && l.starts_with("progress: simulate: "))).collect();
        assert_eq!(rest.len(), 1, "{extra:?}: {e}");
        assert!(rest[0].starts_with("wrote ") && !e.contains('\u{1b}'), "{e}");
    }
    for args in [
        vec!["remesh", "builtin:sphere", "--edge", "0.1", "--out", &r, "--progress"],
        vec!["bench", "--levels", "1", "--steps", "10", "--reps", "1", "--progress"],
    ] {
        let o = softsculpt(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains('\u{1b}'), "{}", stderr(&o));
    }
}

/// The first statistics row records the run (the stats keys as every row has them, and "run"):
/// the command line, the version, every world and body parameter by its table id with the
/// values the run used, and the input file with the SHA-256 of its bytes; the other rows are
/// plain statistics rows.
#[test]
fn the_first_stats_row_records_the_run() {
    use sha2::Digest;
    let d = Dir::new();
    let mesh = d.file("tetra.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
    let stats = d.s("s.jsonl");
    let o = softsculpt(&["simulate", &mesh, "--out", &d.s("o.obj"), "--steps", "20", "--stiffness", "250", "--gas", "3", "--stats", &stats]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: Vec<serde_json::Value> = std::fs::read_to_string(&stats).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let run = &rows[0]["run"];
    assert_eq!(rows[0]["step"], 0);
    assert!(rows[0]["volume"].is_number(), "the contract's keys are in the first row too");
    assert!(rows[1..].iter().all(|r| r.get("run").is_none()), "only the first row records the run");
    assert_eq!(run["version"], env!("CARGO_PKG_VERSION"));
    assert!(run["command"].as_array().unwrap().iter().any(|a| a == "--stiffness"), "{run}");
    assert_eq!(run["bodies"]["body"]["stiffness"], 250.0);
    // (nRT is kept as an amount n: 3 J back to within rounding.)
    assert!((run["bodies"]["body"]["gas.nrt"].as_f64().unwrap() - 3.0).abs() < 1e-12, "{run}");
    assert_eq!(run["world"]["integrator"], "symplectic");
    assert_eq!(run["world"]["dt"], 0.001);
    let hex: String = sha2::Sha256::digest(std::fs::read(&mesh).unwrap()).iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(run["inputs"][0]["sha256"], hex);
    assert_eq!(run["inputs"][0]["name"], mesh);
}

#[test]
fn sweep_without_the_python_package_says_how_to_get_it() {
    // The sweep runs in Python (softsculpt.sweep): a Python that cannot import the package is
    // one error line naming what to install, before anything runs.
    let d = Dir::new();
    let grid = d.file("grid.toml", b"stiffness = [100.0]\n");
    for python in ["/no/such/python", "false"] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_softsculpt"))
            .args(["sweep", "scene.toml", "--grid", &grid, "--out", "o"])
            .env("SOFTSCULPT_PYTHON", python)
            .output()
            .unwrap();
        assert_clean_error(&o, "SOFTSCULPT_PYTHON");
    }
}

/// A preset carries what it needs to run: `--preset stiff_rubber` or `clay` alone (no
/// `--integrator`, no `--dt`) is stepped by the implicit integrator, with a note, and keeps its
/// volume (before: collapsed at step 12 and at step 300); a preset the default step can take
/// (balloon) stays symplectic, without a note.
#[test]
fn a_stiff_preset_alone_runs_on_the_implicit_integrator() {
    let d = Dir::new();
    for preset in ["stiff_rubber", "clay"] {
        let out = d.path(&format!("{preset}.obj"));
        let stats = d.path(&format!("{preset}.jsonl"));
        let o = softsculpt(&["simulate", "builtin:sphere", "--preset", preset, "--steps", "320", "--out", out.to_str().unwrap(), "--stats", stats.to_str().unwrap()]);
        let e = stderr(&o);
        assert!(o.status.success(), "{preset}: {e}");
        assert!(e.contains(&format!("note: --preset {preset}")) && e.contains("implicit"), "{e}");
        // Free fall under gravity for 0.32 s with gas inside: the volume stays within 5 % of
        // the sphere's 4.15 m^3 (a collapse takes it to zero).
        let last: serde_json::Value = serde_json::from_str(std::fs::read_to_string(&stats).unwrap().lines().last().unwrap()).unwrap();
        let v = last["volume"].as_f64().unwrap();
        assert!((v - 4.1527).abs() < 0.05 * 4.1527, "{preset}: volume {v}");
        assert!(last["solver_iterations"]["newton"].as_u64().unwrap() > 0, "implicit steps report Newton iterations");
    }
    let out = d.path("balloon.obj");
    let o = softsculpt(&["simulate", "builtin:sphere", "--preset", "balloon", "--steps", "20", "--out", out.to_str().unwrap()]);
    assert!(o.status.success() && !stderr(&o).contains("note:"), "{}", stderr(&o));
}
