// Import a model file into one indexed triangle mesh (the engine welds, checks and orients it).
// OBJ goes to the engine's own strict reader (errors name the line); PLY, STL, glTF/GLB go
// through three.js loaders and are merged into one mesh in world coordinates.

import * as THREE from 'three';
import { PLYLoader } from 'three/examples/jsm/loaders/PLYLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

export type Imported = { kind: 'obj'; bytes: Uint8Array } | { kind: 'mesh'; positions: Float64Array; indices: Uint32Array };

export const IMPORT_EXTENSIONS = ['.obj', '.ply', '.stl', '.gltf', '.glb'];

/** Merge the triangle meshes of a three.js object (world transforms applied). */
export function mergeMeshes(root: THREE.Object3D): { positions: Float64Array; indices: Uint32Array } {
  const pos: number[] = [];
  const idx: number[] = [];
  root.updateMatrixWorld(true);
  root.traverse((o) => {
    const mesh = o as THREE.Mesh;
    if (!(mesh as any).isMesh || !mesh.geometry) return;
    const g = mesh.geometry as THREE.BufferGeometry;
    const p = g.getAttribute('position');
    if (!p) return;
    const base = pos.length / 3;
    const v = new THREE.Vector3();
    for (let i = 0; i < p.count; i++) {
      v.fromBufferAttribute(p, i).applyMatrix4(mesh.matrixWorld);
      pos.push(v.x, v.y, v.z);
    }
    const index = g.getIndex();
    if (index) for (let i = 0; i < index.count; i++) idx.push(base + index.getX(i));
    else for (let i = 0; i < p.count; i++) idx.push(base + i);
  });
  if (idx.length < 3) throw new Error('the file contains no triangles');
  if (pos.some((x) => !Number.isFinite(x))) throw new Error('the file has non-finite coordinates (NaN or infinity)');
  return { positions: new Float64Array(pos), indices: new Uint32Array(idx.slice(0, idx.length - (idx.length % 3))) };
}

function extension(name: string): string {
  const dot = name.lastIndexOf('.');
  return dot < 0 ? '' : name.slice(dot).toLowerCase();
}

/** Read a model file's bytes by its name's extension; throws an Error saying what is wrong. */
export async function importModel(name: string, data: ArrayBuffer): Promise<Imported> {
  const ext = extension(name);
  if (data.byteLength === 0) throw new Error(`${name}: the file is empty`);
  try {
    switch (ext) {
      case '.obj':
        return { kind: 'obj', bytes: new Uint8Array(data) };
      case '.stl':
        return { kind: 'mesh', ...mergeMeshes(new THREE.Mesh(new STLLoader().parse(data))) };
      case '.ply':
        return { kind: 'mesh', ...mergeMeshes(new THREE.Mesh(new PLYLoader().parse(data))) };
      case '.gltf':
      case '.glb': {
        const gltf = await new GLTFLoader().parseAsync(data, '');
        return { kind: 'mesh', ...mergeMeshes(gltf.scene) };
      }
      default:
        throw new Error(`unsupported file type '${ext || '(none)'}' (use ${IMPORT_EXTENSIONS.join(', ')})`);
    }
  } catch (e) {
    const msg = e instanceof Error ? e.message : String(e);
    if (msg.startsWith(name)) throw e;
    // Loaders fail with low-level messages (a DataView out of bounds…): say what it means.
    const known = /no triangles|non-finite|unsupported|empty/.test(msg);
    throw new Error(`${name}: ${known ? msg : `the file could not be read as ${ext.slice(1).toUpperCase()} (${msg})`}`);
  }
}
