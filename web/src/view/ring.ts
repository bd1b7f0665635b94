// The brush ring: under the cursor on the surface, a circle of the brush radius on the surface's
// tangent plane (the tools act on the vertices within that distance of the point), an inner
// circle whose radius shows the tool's strength as a fraction of its range, and mirrored copies
// where symmetry repeats the stroke. Drawn on top of the surface so it is never hidden by it.

import * as THREE from 'three';

const SEGMENTS = 64;

function circle(color: number, opacity: number): THREE.LineLoop {
  const pts: THREE.Vector3[] = [];
  for (let i = 0; i < SEGMENTS; i++) {
    const a = (2 * Math.PI * i) / SEGMENTS;
    pts.push(new THREE.Vector3(Math.cos(a), Math.sin(a), 0));
  }
  const line = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(pts),
    new THREE.LineBasicMaterial({ color, transparent: true, opacity, depthTest: false }));
  line.renderOrder = 10;
  line.frustumCulled = false;
  return line;
}

export class BrushRing {
  readonly group = new THREE.Group();
  private rings: { outer: THREE.LineLoop; inner: THREE.LineLoop; g: THREE.Group }[] = [];
  /** What was last shown (for tests and the HUD): radius (m), strength fraction in [0, 1]. */
  shown: { radius: number; fraction: number; copies: number; centres: [number, number, number][] } | null = null;

  constructor() { this.group.visible = false; }

  private ring(i: number) {
    while (this.rings.length <= i) {
      const g = new THREE.Group();
      const outer = circle(0xffffff, 0.9), inner = circle(0xffd27f, 0.8);
      g.add(outer, inner);
      this.group.add(g);
      this.rings.push({ outer, inner, g });
    }
    return this.rings[i];
  }

  /**
   * Show the ring at `points` (the point under the cursor, then its mirror images) with the
   * surface `normals` there; `radius` (m), `fraction` of the tool's strength range (null: none).
   */
  show(points: THREE.Vector3[], normals: THREE.Vector3[], radius: number, fraction: number | null): void {
    this.group.visible = true;
    const z = new THREE.Vector3(0, 0, 1);
    points.forEach((p, i) => {
      const r = this.ring(i);
      r.g.visible = true;
      r.g.position.copy(p);
      r.g.quaternion.setFromUnitVectors(z, normals[i].clone().normalize());
      r.outer.scale.setScalar(radius);
      r.inner.visible = fraction !== null;
      r.inner.scale.setScalar(radius * Math.max(0.04, Math.min(1, fraction ?? 0)));
      (r.outer.material as THREE.LineBasicMaterial).opacity = i === 0 ? 0.9 : 0.45;
    });
    for (let i = points.length; i < this.rings.length; i++) this.rings[i].g.visible = false;
    this.shown = { radius, fraction: fraction ?? 0, copies: points.length, centres: points.map((p) => [p.x, p.y, p.z]) };
  }

  hide(): void {
    this.group.visible = false;
    this.shown = null;
  }
}
