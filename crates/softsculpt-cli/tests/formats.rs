//! Mesh formats through the command line: every format in and out (round trips keep vertex
//! order and values), pieces, the up axis, and malformed files of each format.

mod common;

use common::{softsculpt, stderr, Dir};
use softsculpt::mesh::{builtin, load, LoadedMesh, MeshFormat};
use std::path::Path;
use std::process::Output;

fn ok(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}

fn info(path: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["info", path, "--json"];
    args.extend_from_slice(extra);
    let o = softsculpt(&args);
    ok(&o);
    serde_json::from_slice(&o.stdout).unwrap()
}

fn read(path: &Path) -> LoadedMesh {
    let bytes = std::fs::read(path).unwrap();
    load(&bytes, MeshFormat::from_path(&path.to_string_lossy())).unwrap()
}

/// The built-in model as the CLI writes it with `--steps 0` (its own vertex order).
fn original(name: &str) -> Vec<f64> {
    LoadedMesh::from_trimesh(builtin::builtin(name).unwrap()).source.positions
}

/// f64 → f32 rounds to nearest: the relative error is at most half an f32 ulp, 2^-24 =
/// f32::EPSILON / 2 (no value here is subnormal; zero stays exactly zero).
fn within_f32(a: f64, b: f64) -> bool {
    (a - b).abs() <= b.abs() * (f32::EPSILON as f64 / 2.0)
}

#[test]
fn every_format_round_trips_in_vertex_order() {
    let d = Dir::new();
    for model in ["sphere", "mushroom"] {
        let x0 = original(model);
        for ext in ["obj", "ply", "stl", "glb"] {
            let out = d.s(&format!("{model}.{ext}"));
            ok(&softsculpt(&["simulate", &format!("builtin:{model}"), "--out", &out, "--steps", "0"]));
            let back = read(Path::new(&out));
            assert_eq!(back.mesh.vertex_count(), x0.len() / 3, "{out}: welded vertex count");
            assert_eq!(info(&out, &[])["vertices"], x0.len() / 3, "{out}");
            let p = &back.source.positions;
            match ext {
                // OBJ (shortest round-trip decimals) and PLY (binary double): bit-identical.
                "obj" | "ply" => assert_eq!(
                    p.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    x0.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    "{out}"
                ),
                // GLB stores f32 positions in the same order.
                "glb" => {
                    assert_eq!(p.len(), x0.len());
                    assert!(p.iter().zip(&x0).all(|(a, b)| within_f32(*a, *b)), "{out}");
                }
                // STL is unindexed f32: the corners come back merged, in order of first use by
                // a triangle; each is the f32 rounding of an original vertex, all distinct.
                _ => {
                    let key = |c: &[f64]| [c[0] as f32, c[1] as f32, c[2] as f32].map(f32::to_bits);
                    let originals: std::collections::HashSet<_> = x0.chunks_exact(3).map(key).collect();
                    let read: std::collections::HashSet<_> = p.chunks_exact(3).map(key).collect();
                    assert_eq!(read, originals, "{out}");
                    assert!(p.chunks_exact(3).all(|c| c.iter().all(|x| *x == (*x as f32) as f64)));
                }
            }
            // Read by the CLI and written back as OBJ: the same order and values again.
            let again = d.s(&format!("{model}-{ext}.obj"));
            ok(&softsculpt(&["simulate", &out, "--out", &again, "--steps", "0"]));
            let twice = read(Path::new(&again)).source.positions;
            assert_eq!(twice.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), p.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), "{again}");
        }
    }
}

const TETRA_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";

fn stl_text(tris: &[[[f64; 3]; 3]]) -> String {
    let mut s = String::from("solid t\n");
    for t in tris {
        s.push_str("facet normal 0 0 0\nouter loop\n");
        for v in t {
            s.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        s.push_str("endloop\nendfacet\n");
    }
    s + "endsolid t\n"
}

fn tetra_tris(o: [f64; 3]) -> Vec<[[f64; 3]; 3]> {
    let v = |x: f64, y: f64, z: f64| [o[0] + x, o[1] + y, o[2] + z];
    let p = [v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.), v(0., 0., 1.)];
    [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]].iter().map(|t| [p[t[0]], p[t[1]], p[t[2]]]).collect()
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            s.push(if k <= c.len() { A[(n >> (18 - 6 * k) & 63) as usize] as char } else { '=' });
        }
    }
    s
}

/// A tetrahedron as glTF JSON with its buffer in a data URI, under a node moved by `translation`.
fn tetra_gltf(translation: [f64; 3]) -> String {
    let mut bin = Vec::new();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]] {
        for x in v {
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    for i in [0u16, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "translation": translation}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", base64(&bin))}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}
        ]
    })
    .to_string()
}

#[test]
fn text_stl_ascii_ply_and_embedded_gltf_are_read() {
    let d = Dir::new();
    let files = [
        d.file("t.ply", TETRA_PLY.as_bytes()),
        d.file("t.stl", stl_text(&tetra_tris([0.0; 3])).as_bytes()),
        d.file("t.gltf", tetra_gltf([0.0, 2.0, 0.0]).as_bytes()),
    ];
    for f in &files {
        let v = info(f, &[]);
        assert_eq!(v["vertices"], 4, "{f}");
        assert_eq!(v["closed"], true, "{f}");
        assert_eq!(v["pieces"], 1, "{f}");
        assert!((v["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() < 1e-12, "{f}: {v}");
    }
    let g = info(&files[2], &[]);
    assert_eq!(g["format"], "glTF");
    assert_eq!(g["up_axis"], "y", "glTF is Y-up by specification");
    assert_eq!(g["bounds_min"][1], 2.0, "the node's translation applies");
    assert_eq!(info(&files[0], &[])["up_axis"], "unknown");
    // No extension: the first bytes tell PLY.
    let noext = d.file("tetra", TETRA_PLY.as_bytes());
    assert_eq!(info(&noext, &[])["format"], "PLY");
}

#[test]
fn scenes_read_every_format_for_bodies_and_mesh_obstacles() {
    let d = Dir::new();
    for ext in ["ply", "stl", "glb"] {
        ok(&softsculpt(&["simulate", "builtin:sphere", "--out", &d.s(&format!("ball.{ext}")), "--steps", "0"]));
    }
    d.file("floor.gltf", tetra_gltf([0.0, -3.0, 0.0]).as_bytes());
    let scene = r#"
[world]
dt = 0.001
duration = 0.01

[[body]]
name = "a"
mesh = "ball.ply"

[[body]]
name = "b"
mesh = "ball.stl"
translate = [3.0, 0.0, 0.0]

[[body]]
name = "c"
mesh = "ball.glb"
translate = [6.0, 0.0, 0.0]

[[obstacle]]
shape = "mesh"
mesh = "floor.gltf"
"#;
    let path = d.file("scene.toml", scene.as_bytes());
    let out = d.s("out");
    ok(&softsculpt(&["run", &path, "--out", &out]));
    for name in ["a", "b", "c"] {
        assert!(d.path(&format!("out/{name}.obj")).exists(), "{name}");
    }
    let bad = d.file("bad.toml", scene.replace("ball.stl", "bad.stl").as_bytes());
    d.file("bad.stl", b"solid nothing\nfacet\n");
    let o = softsculpt(&["run", &bad, "--out", &d.s("out2")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("bad.stl") && stderr(&o).contains("not a valid STL file"), "{}", stderr(&o));
}

#[test]
fn a_two_piece_file_reports_two_pieces() {
    let d = Dir::new();
    let mut tris = tetra_tris([0.0; 3]);
    tris.extend(tetra_tris([3.0, 0.0, 0.0]));
    let f = d.file("two.stl", stl_text(&tris).as_bytes());
    let v = info(&f, &[]);
    assert_eq!(v["pieces"], 2);
    assert_eq!(v["vertices"], 8);
    assert!(v["warnings"].as_array().unwrap().iter().any(|w| w.as_str().unwrap().contains("2 separate pieces")), "{v}");
    let o = softsculpt(&["info", &f]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("pieces:              2"));
}

/// `--up z` turns a Z-up file Y-up for the run and its output back to Z-up (the input's frame:
/// before, the output stayed Y-up and Blender laid it on its side); `--out-up` chooses.
#[test]
fn a_z_up_file_runs_y_up_and_is_written_back_in_its_own_frame() {
    let d = Dir::new();
    // A tetrahedron 3 m tall along +Z.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 3\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    let f = d.file("zup.obj", text.as_bytes());
    let before = info(&f, &[]);
    assert_eq!(before["bounds_max"], serde_json::json!([1.0, 1.0, 3.0]));
    let v = info(&f, &["--up", "z"]);
    assert_eq!(v["up_axis"], "z");
    assert_eq!(v["rotated_to_y_up"], true);
    // (x, y, z) → (x, z, −y): the height is now along +Y; units unchanged.
    assert_eq!(v["bounds_min"], serde_json::json!([0.0, 0.0, -1.0]));
    assert_eq!(v["bounds_max"], serde_json::json!([1.0, 3.0, 0.0]));
    assert_eq!(v["volume"], before["volume"]);
    for ext in ["obj", "ply", "glb"] {
        // Written in the input's frame: the height along Z again (a proper rotation and back:
        // exact for these coordinates) — except glTF, Y-up by specification.
        let out = d.s(&format!("zup.{ext}"));
        ok(&softsculpt(&["simulate", &f, "--up", "z", "--out", &out, "--steps", "0"]));
        let (lo, hi) = read(Path::new(&out)).mesh.bounds();
        if ext == "glb" {
            assert_eq!((lo[1], hi[1]), (0.0, 3.0), "{out}: glTF is Y-up");
            let o = softsculpt(&["simulate", &f, "--up", "z", "--out-up", "z", "--out", &out, "--steps", "0"]);
            assert!(o.status.code() == Some(1) && stderr(&o).contains("glTF is Y-up by specification"), "{}", stderr(&o));
            continue;
        }
        assert_eq!((lo, hi), ([0.0, 0.0, 0.0], [1.0, 1.0, 3.0]), "{out}: the height axis is Z, as in the file");
        // --out-up y: written as run, the height along Y.
        let out = d.s(&format!("yup.{ext}"));
        ok(&softsculpt(&["simulate", &f, "--up", "z", "--out-up", "y", "--out", &out, "--steps", "0"]));
        let (lo, hi) = read(Path::new(&out)).mesh.bounds();
        assert_eq!((lo[1], hi[1]), (0.0, 3.0), "{out}: the height axis is Y");
    }
    // A Y-up model written Z-up for Blender's STL importer: read back with --up z, it is the model.
    let out = d.s("mushroom.stl");
    ok(&softsculpt(&["simulate", "builtin:mushroom", "--out-up", "z", "--out", &out, "--steps", "0"]));
    let (lo, hi) = read(Path::new(&out)).mesh.bounds();
    let (lo_y, hi_y) = softsculpt::mesh::builtin::builtin("mushroom").unwrap().bounds();
    // f32 STL: within an f32 rounding of the Y-up model's height, now along +Z.
    assert!((hi[2] - hi_y[1]).abs() < 1e-6 && (lo[2] - lo_y[1]).abs() < 1e-6, "{lo:?} {hi:?} vs {lo_y:?} {hi_y:?}");
    let text = String::from_utf8_lossy(&softsculpt(&["info", &f, "--up", "z"]).stdout).into_owned();
    assert!(text.contains("format:              OBJ") && text.contains("up axis:             z (given by --up; rotated to Y-up)"), "{text}");
    // glTF says Y-up: --up z still rotates, with a warning.
    let g = d.file("t.gltf", tetra_gltf([0.0; 3]).as_bytes());
    let o = softsculpt(&["info", &g, "--up", "z", "--json"]);
    ok(&o);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["warnings"][0].as_str().unwrap().contains("Y-up by specification"), "{v}");
    let o = softsculpt(&["info", &f, "--up", "x"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--up"), "{}", stderr(&o));
}

/// Each file fails `simulate` and `info` with one `error:` line naming the file and `needle`,
/// exit status 1, and no output file.
fn assert_refused(d: &Dir, input: &str, needle: &str) {
    for ext in ["obj", "glb"] {
        let out = d.path(&format!("never.{ext}"));
        let o = softsculpt(&["simulate", input, "--out", out.to_str().unwrap(), "--steps", "1"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{input}: {e}");
        assert!(!e.contains("panicked"), "{e}");
        let lines: Vec<&str> = e.lines().filter(|l| !l.starts_with("warning:")).collect();
        assert_eq!(lines.len(), 1, "{input}: one line expected: {e}");
        assert!(lines[0].starts_with("error:") && lines[0].contains(input) && lines[0].contains(needle), "{input}: '{}' lacks '{needle}'", lines[0]);
        assert!(!out.exists(), "{input}: nothing written");
    }
    let o = softsculpt(&["info", input]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
}

#[test]
fn malformed_files_of_each_format_are_one_clear_error() {
    let d = Dir::new();
    ok(&softsculpt(&["simulate", "builtin:sphere", "--out", &d.s("good.ply"), "--steps", "0"]));
    ok(&softsculpt(&["simulate", "builtin:sphere", "--out", &d.s("good.stl"), "--steps", "0"]));
    ok(&softsculpt(&["simulate", "builtin:sphere", "--out", &d.s("good.glb"), "--steps", "0"]));
    let (ply, stl, glb) = (std::fs::read(d.path("good.ply")).unwrap(), std::fs::read(d.path("good.stl")).unwrap(), std::fs::read(d.path("good.glb")).unwrap());
    let mut stl_count = stl.clone();
    stl_count[80..84].copy_from_slice(&5000u32.to_le_bytes());
    let mut glb_length = glb.clone();
    glb_length[8..12].copy_from_slice(&(glb.len() as u32 * 2).to_le_bytes());
    let ascii_short = TETRA_PLY.replace("3 2 0 3\n", "");
    let ascii_index = TETRA_PLY.replace("3 2 0 3", "3 2 0 9");
    let stl_garbage = stl_text(&tetra_tris([0.0; 3])).replace("outer loop", "outer banana");
    let gltf = tetra_gltf([0.0; 3]);
    let gltf_external = gltf.replace(&gltf[gltf.find("data:").unwrap()..gltf.find("\"}],\"bufferViews").unwrap_or(gltf.len())], "tetra.bin");
    let cases: Vec<(String, &str)> = vec![
        (d.file("truncated.ply", &ply[..ply.len() / 2]), "not a valid PLY file"),
        (d.file("header.ply", b"ply\nformat binary_middle_endian 1.0\nelement vertex 1\nend_header\n"), "not a valid PLY file"),
        (d.file("short.ply", ascii_short.as_bytes()), "not a valid PLY file"),
        (d.file("index.ply", ascii_index.as_bytes()), "vertex 9"),
        (d.file("garbage.ply", b"\x00\x01garbage"), "not a valid PLY file"),
        (d.file("truncated.stl", &stl[..stl.len() - 7]), "truncated"),
        (d.file("count.stl", &stl_count), "5000 triangles"),
        (d.file("garbage.stl", stl_garbage.as_bytes()), "not a valid STL file"),
        (d.file("empty.stl", b""), "not a valid STL file"),
        (d.file("truncated.glb", &glb[..glb.len() - 100]), "not a valid GLB file"),
        (d.file("length.glb", &glb_length), "not a valid GLB file"),
        (d.file("magic.glb", b"v 0 0 0\n"), "magic"),
        (d.file("garbage.gltf", b"{ this is not json"), "not a valid glTF file"),
        (d.file("external.gltf", gltf_external.as_bytes()), "external file"),
        (d.file("base64.gltf", gltf.replace("base64,", "base64,!!").as_bytes()), "base64"),
        (d.file("accessor.gltf", gltf.replace("\"indices\":1", "\"indices\":7").as_bytes()), "not a valid glTF file"),
        (d.file("nofaces.gltf", br#"{"asset":{"version":"2.0"}}"#), "no faces"),
        // gltf-json's validation panicked on a POSITION accessor past the accessors (exit 101).
        (d.file("position.gltf", br#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]}"#), "attribute POSITION names accessor 7, but the file has 0 accessors"),
    ];
    for (input, needle) in &cases {
        if std::env::var_os("SHOW_ERRORS").is_some() {
            eprintln!("{}", stderr(&softsculpt(&["info", input])).trim_end());
        }
        assert_refused(&d, input, needle);
    }
}

#[test]
fn an_unknown_output_type_is_refused_before_the_run() {
    let d = Dir::new();
    for (out, needle) in [("x.fbx", "unknown output type '.fbx'"), ("x", "(no extension)"), ("x.gltf", "use .glb")] {
        let path = d.path(out);
        let o = softsculpt(&["simulate", "builtin:sphere", "--out", path.to_str().unwrap(), "--steps", "100000000"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.starts_with("error: --out") && e.contains(needle) && e.lines().count() == 1, "{e}");
        assert!(!path.exists());
    }
}

/// `--triangulate` writes OBJ and PLY as triangles (fans of the input's polygons), the same
/// positions; without it the input's quads are kept (a PLY mixing quads and triangles is valid,
/// but trimesh refuses it).
#[test]
fn triangulate_writes_triangles_with_the_same_vertices() {
    let d = Dir::new();
    // A cube of five quads and a top split into two triangles.
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
                f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5 8\n";
    let f = d.file("mixed.obj", text.as_bytes());
    for ext in ["obj", "ply"] {
        let kept = d.s(&format!("kept.{ext}"));
        let tri = d.s(&format!("tri.{ext}"));
        ok(&softsculpt(&["simulate", &f, "--out", &kept, "--steps", "0"]));
        ok(&softsculpt(&["simulate", &f, "--out", &tri, "--steps", "0", "--triangulate"]));
        let (k, t) = (read(Path::new(&kept)), read(Path::new(&tri)));
        assert_eq!(k.source.arities.iter().filter(|&&n| n == 4).count(), 5, "{ext}: the quads kept");
        assert!(t.source.arities.iter().all(|&n| n == 3), "{ext}: triangles only");
        // 5 quads → 10 triangles, plus the 2 triangles: 12, over the same 8 vertices.
        assert_eq!(t.source.arities.len(), 12, "{ext}");
        assert_eq!(t.source.positions, k.source.positions, "{ext}: the same vertices in the same order");
    }
}
