// Which body is under the pointer: the first body's surface and the other bodies' meshes (an
// import's pieces, a scene's bodies: view/extras.ts tags each with `userData.body`), the nearest
// hit. The tools start their stroke on that body and send its index (worker/strokes.ts acts on it).

import * as THREE from 'three';
import type { Viewport } from '../view/viewport';

/** The body index of a hit (0: the first body's surface). */
export function bodyOf(hit: THREE.Intersection | null): number {
  const b = hit?.object.userData.body;
  return typeof b === 'number' ? b : 0;
}

/** The nearest surface point under the pointer on any body, or on body `only` alone; null if none. */
export function pickBody(v: Viewport, ev: { clientX: number; clientY: number }, only?: number): THREE.Intersection | null {
  const meshes: THREE.Object3D[] = [];
  if (only === undefined || only === 0) {
    v.surface.geometry.computeBoundingSphere();
    meshes.push(v.surface);
  }
  for (const o of v.extras.group.children) {
    const b = o.userData.body;
    if (typeof b !== 'number' || (only !== undefined && b !== only) || !(o instanceof THREE.Mesh)) continue;
    // Their positions follow the frames: the bounding sphere the ray tests first must too.
    o.geometry.computeBoundingSphere();
    meshes.push(o);
  }
  return v.rayAt(ev).intersectObjects(meshes, false)[0] ?? null;
}
