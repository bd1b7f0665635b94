//! Mesh formats in the core: writing and reading back each format, and damaged files of each
//! format that must give an error, never a panic.

use softsculpt::mesh::{builtin, load, LoadedMesh, MeshFormat};

fn sphere() -> LoadedMesh {
    LoadedMesh::from_trimesh(builtin::builtin("sphere").unwrap())
}

fn written(format: MeshFormat) -> Vec<u8> {
    let m = sphere();
    m.write(format, &m.mesh.positions, "core test").unwrap()
}

#[test]
fn every_writable_format_reads_back_with_the_same_mesh() {
    let m = sphere();
    for format in [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Glb] {
        let back = load(&written(format), Some(format)).unwrap();
        assert_eq!(back.report.format, Some(format));
        assert_eq!(back.mesh.vertex_count(), m.mesh.vertex_count(), "{format:?}");
        assert_eq!(back.mesh.triangles.len(), m.mesh.triangles.len(), "{format:?}");
        assert_eq!(back.report.pieces, 1);
        assert!(back.mesh.is_closed());
        // f32 formats: the volume moves by about 3 × 2^-24 relative at most.
        let rel = (back.mesh.volume() - m.mesh.volume()).abs() / m.mesh.volume();
        assert!(rel < 1e-6, "{format:?}: {rel}");
        // The format is also told by the first bytes alone (OBJ has no signature).
        if format != MeshFormat::Obj {
            assert_eq!(MeshFormat::sniff(&written(format)), Some(format));
        }
    }
    assert!(m.write(MeshFormat::Gltf, &m.mesh.positions, "").is_err());
}

/// A small deterministic generator for damage.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> usize {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 33) as usize
    }
}

#[test]
fn damaged_files_of_every_format_are_errors_not_panics() {
    let mut rng = Lcg(7);
    for format in [MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Glb, MeshFormat::Obj] {
        let good = written(format);
        for k in 0..60 {
            let cut = good.len() * k / 60;
            let _ = load(&good[..cut], Some(format));
        }
        for _ in 0..300 {
            let mut bad = good.clone();
            for _ in 0..1 + rng.next() % 4 {
                let at = rng.next() % bad.len();
                bad[at] = rng.next() as u8;
            }
            let _ = load(&bad, Some(format));
        }
    }
}

#[test]
fn hostile_gltf_numbers_are_errors_not_panics() {
    let glb = written(MeshFormat::Glb);
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = String::from_utf8(glb[20..20 + json_len].to_vec()).unwrap();
    let edits: &[(&str, &str)] = &[
        ("\"count\":642", "\"count\":0"),
        ("\"count\":642", "\"count\":4294967295"),
        ("\"count\":642", "\"count\":643"),
        ("\"byteOffset\":0", "\"byteOffset\":18446744073709551615"),
        ("\"byteOffset\":0", "\"byteOffset\":9999999"),
        ("\"target\":34962", "\"byteStride\":4"),
        ("\"componentType\":5126", "\"componentType\":5121"),
        ("\"componentType\":5125", "\"componentType\":5126"),
        ("\"mode\":4", "\"mode\":5"),
        ("\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[0]}]"),
        ("\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"scale\":[1e39,1,1]}]"),
    ];
    for (from, to) in edits {
        assert!(json.contains(from), "{from} in {json}");
        let mut text = json.replacen(from, to, 1).into_bytes();
        while text.len() % 4 != 0 {
            text.push(b' ');
        }
        let bin = &glb[20 + json_len..];
        let mut out = Vec::new();
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&((12 + 8 + text.len() + bin.len()) as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(bin);
        assert!(load(&out, Some(MeshFormat::Glb)).is_err(), "{to} should be refused");
    }
}
