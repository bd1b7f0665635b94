// Export the current shape as OBJ, STL or GLB (three.js exporters), and download files.

import * as THREE from 'three';
import { OBJExporter } from 'three/examples/jsm/exporters/OBJExporter.js';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';

export type ExportFormat = 'obj' | 'stl' | 'glb';

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

export async function exportShape(format: ExportFormat, positions: ArrayLike<number>, triangles: ArrayLike<number>): Promise<Blob> {
  const mesh = shapeMesh(positions, triangles);
  switch (format) {
    case 'obj':
      return new Blob([new OBJExporter().parse(mesh)], { type: 'text/plain' });
    case 'stl': {
      const data = new STLExporter().parse(mesh, { binary: true }) as unknown as DataView;
      return new Blob([data.buffer as ArrayBuffer], { type: 'model/stl' });
    }
    case 'glb': {
      const buf = (await new GLTFExporter().parseAsync(mesh, { binary: true })) as ArrayBuffer;
      return new Blob([buf], { type: 'model/gltf-binary' });
    }
  }
}

export function download(blob: Blob, filename: string): void {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
}
