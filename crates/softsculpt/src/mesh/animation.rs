//! A binary glTF 2.0 (.glb) of deforming meshes, one node per body, for Blender and other tools.
//!
//! Each body is a mesh whose base positions are its first frame; every frame k is a morph target
//! holding x_k − x_0 (f32). One animation drives the weights: at time t_k the weights are the
//! unit vector e_k, with LINEAR interpolation, so between two frames the shape is the straight
//! blend of the two — exactly how the frames were sampled. (Blender imports morph targets as
//! shape keys and the weights as their animation.)
//!
//! Layout: the GLB container ([`super::gltf::glb_container`]); every accessor has its own buffer
//! view; POSITION accessors carry min/max as the specification requires. Written by `softsculpt
//! run --frames` and by the modeler's recording (the binding's `ss_animation_*`), so both give
//! the same file.

use serde_json::{json, Value};

/// One body's animation: triangles and one flat xyz position array per frame.
pub struct Track<'a> {
    pub name: &'a str,
    pub triangles: &'a [[u32; 3]],
    pub frames: &'a [Vec<f64>],
}

struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn push(&mut self, bytes: &[u8], accessor: Value) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views.push(json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() }));
        self.bin.extend_from_slice(bytes);
        let mut a = accessor;
        a["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn vec3(&mut self, xyz: impl Iterator<Item = f32>) -> usize {
        let v: Vec<f32> = xyz.collect();
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for c in v.chunks_exact(3) {
            for d in 0..3 {
                lo[d] = lo[d].min(c[d]);
                hi[d] = hi[d].max(c[d]);
            }
        }
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.push(&bytes, json!({ "componentType": 5126, "count": v.len() / 3, "type": "VEC3", "min": lo, "max": hi }))
    }

    fn scalars(&mut self, v: &[f32], bounds: bool) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        let mut a = json!({ "componentType": 5126, "count": v.len(), "type": "SCALAR" });
        if bounds {
            a["min"] = json!([v.iter().cloned().fold(f32::INFINITY, f32::min)]);
            a["max"] = json!([v.iter().cloned().fold(f32::NEG_INFINITY, f32::max)]);
        }
        self.push(&bytes, a)
    }
}

/// The .glb bytes of `tracks` sampled at `times` (s, one per frame, increasing); `generator`
/// names the writer in the asset block.
pub fn animation_glb(tracks: &[Track], times: &[f64], generator: &str) -> Vec<u8> {
    let mut b = Builder { bin: Vec::new(), views: Vec::new(), accessors: Vec::new() };
    let mut meshes = Vec::new();
    let mut nodes = Vec::new();
    let mut channels = Vec::new();
    let mut samplers = Vec::new();
    let frames = times.len();
    let time_acc = b.scalars(&times.iter().map(|&t| t as f32).collect::<Vec<_>>(), true);
    // Weights at key k: e_k (row k of the identity), for every target.
    let mut weights = vec![0.0f32; frames * frames];
    for k in 0..frames {
        weights[k * frames + k] = 1.0;
    }
    for (ti, t) in tracks.iter().enumerate() {
        let base = &t.frames[0];
        let pos = b.vec3(base.iter().map(|&x| x as f32));
        let idx_bytes: Vec<u8> = t.triangles.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
        let idx = b.push(&idx_bytes, json!({ "componentType": 5125, "count": 3 * t.triangles.len(), "type": "SCALAR" }));
        let targets: Vec<Value> = t
            .frames
            .iter()
            .map(|f| json!({ "POSITION": b.vec3(f.iter().zip(base).map(|(x, x0)| (x - x0) as f32)) }))
            .collect();
        let target_names: Vec<String> = (0..frames).map(|k| format!("frame{k:04}")).collect();
        meshes.push(json!({
            "name": t.name,
            "primitives": [{ "attributes": { "POSITION": pos }, "indices": idx, "targets": targets, "mode": 4 }],
            "weights": vec![0.0; frames],
            "extras": { "targetNames": target_names },
        }));
        nodes.push(json!({ "name": t.name, "mesh": ti }));
        let out = b.scalars(&weights, false);
        samplers.push(json!({ "input": time_acc, "output": out, "interpolation": "LINEAR" }));
        channels.push(json!({ "sampler": ti, "target": { "node": ti, "path": "weights" } }));
    }
    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    let doc = json!({
        "asset": { "version": "2.0", "generator": generator },
        "scene": 0,
        "scenes": [{ "nodes": (0..tracks.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": meshes,
        "animations": [{ "name": "simulation", "samplers": samplers, "channels": channels }],
        "buffers": [{ "byteLength": b.bin.len() }],
        "bufferViews": b.views,
        "accessors": b.accessors,
    });
    super::gltf::glb_container(&doc, b.bin)
}
