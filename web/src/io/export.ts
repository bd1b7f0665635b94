// Export the current shapes as OBJ, STL or GLB (three.js exporters), in the imported file's own
// units, up axis and placement (GLB always Y-up, as glTF is), and download files.

import * as THREE from 'three';
import { OBJExporter } from 'three/examples/jsm/exporters/OBJExporter.js';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';
import { IDENTITY_FRAME, toFile, type ImportFrame } from './import';

export type ExportFormat = 'obj' | 'stl' | 'glb';

/** One body's shape: positions (xyz, m, the engine's frame) and triangles. */
export interface Shape { positions: ArrayLike<number>; triangles: ArrayLike<number> }

/** A three.js mesh of the shape (positions f64 xyz, triangles). */
export function shapeMesh(positions: ArrayLike<number>, triangles: ArrayLike<number>, name = 'softsculpt'): THREE.Mesh {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(positions), 3));
  g.setIndex(new THREE.BufferAttribute(Uint32Array.from(triangles), 1));
  g.computeVertexNormals();
  const m = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: 0xd9a066 }));
  m.name = name;
  return m;
}

/**
 * The shapes as a file: each body one mesh (`softsculpt`, `softsculpt.001`, …), positions taken
 * back to the file's frame (`frame`: the import's; none for built-in models).
 */
export async function exportShape(format: ExportFormat, positions: ArrayLike<number> | Shape[], triangles?: ArrayLike<number>, frame: ImportFrame | null = null): Promise<Blob> {
  const shapes: Shape[] = Array.isArray(positions) ? positions : [{ positions: positions as ArrayLike<number>, triangles: triangles! }];
  const f = frame ?? IDENTITY_FRAME;
  const root = new THREE.Group();
  shapes.forEach((s, i) => root.add(shapeMesh(toFile(s.positions, f, format === 'glb'), s.triangles, i === 0 ? 'softsculpt' : `softsculpt.${String(i).padStart(3, '0')}`)));
  const object = shapes.length === 1 ? root.children[0] : root;
  switch (format) {
    case 'obj':
      return new Blob([new OBJExporter().parse(object)], { type: 'text/plain' });
    case 'stl': {
      const data = new STLExporter().parse(object, { binary: true }) as unknown as DataView;
      return new Blob([data.buffer as ArrayBuffer], { type: 'model/stl' });
    }
    case 'glb': {
      const buf = (await new GLTFExporter().parseAsync(object, { binary: true })) as ArrayBuffer;
      return new Blob([buf], { type: 'model/gltf-binary' });
    }
  }
}

/** Save `blob` as `filename` (a link clicked). */
export function download(blob: Blob, filename: string): void {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
}
