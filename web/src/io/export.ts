// Export the current shapes as OBJ, STL or GLB (three.js exporters), in the imported file's own
// units, up axis and placement (GLB always Y-up, as glTF is), and download files. STL and OBJ
// declare no up axis, so ours say it on their first line (the binary STL's 80-byte header, an
// OBJ comment), where the import reads it back (io/import.ts `guessUp`).

import * as THREE from 'three';
import { OBJExporter } from 'three/examples/jsm/exporters/OBJExporter.js';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';
import { IDENTITY_FRAME, toFile, type ImportFrame } from './import';

export type ExportFormat = 'obj' | 'stl' | 'glb';

/** One body's shape: positions (xyz, m, the engine's frame) and triangles. */
export interface Shape { positions: ArrayLike<number>; triangles: ArrayLike<number> }

/**
 * The first line of an exported STL or OBJ: who wrote it, the up axis its coordinates are in (the
 * imported file's, else Y: built-in models and glTF are Y-up) and their units (nothing is
 * rescaled: a built-in model's and a glTF file's are metres, an imported OBJ, PLY or STL keeps
 * the file's own numbers). The import reads the up axis back (`OWN_EXPORT` in io/import.ts);
 * at most 80 ASCII characters, not starting with "solid" (binary STL).
 */
export function exportHeader(frame: ImportFrame | null): string {
  const up = frame?.up === 'z' ? 'Z' : 'Y';
  const metres = !frame || frame.format === 'glTF' || frame.format === 'GLB';
  return `SoftSculpt export, ${up}-up, ${metres ? 'metres' : `units as in the imported ${frame.format ? `${frame.format} ` : ''}file`}`;
}

/** A binary STL's 80-byte header: `text`'s ASCII, padded with spaces. */
function writeStlHeader(data: DataView, text: string): void {
  for (let i = 0; i < 80; i++) {
    const c = i < text.length ? text.charCodeAt(i) : 32;
    data.setUint8(i, c >= 32 && c < 127 ? c : 32);
  }
}

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
 * back to the file's frame (`frame`: the import's; none for built-in models). STL and OBJ start
 * with `exportHeader(frame)`.
 */
export async function exportShape(format: ExportFormat, positions: ArrayLike<number> | Shape[], triangles?: ArrayLike<number>, frame: ImportFrame | null = null): Promise<Blob> {
  const shapes: Shape[] = Array.isArray(positions) ? positions : [{ positions: positions as ArrayLike<number>, triangles: triangles! }];
  const f = frame ?? IDENTITY_FRAME;
  const root = new THREE.Group();
  shapes.forEach((s, i) => root.add(shapeMesh(toFile(s.positions, f, format === 'glb'), s.triangles, i === 0 ? 'softsculpt' : `softsculpt.${String(i).padStart(3, '0')}`)));
  const object = shapes.length === 1 ? root.children[0] : root;
  switch (format) {
    case 'obj':
      return new Blob([`# ${exportHeader(frame)}\n`, new OBJExporter().parse(object)], { type: 'text/plain' });
    case 'stl': {
      const data = new STLExporter().parse(object, { binary: true }) as unknown as DataView;
      writeStlHeader(data, exportHeader(frame));
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
