// Press (P): push on the faces under the brush with an external pressure along their inward
// normal, while the button is held. Strength: the pressure (Pa) at the brush centre.

import type * as THREE from 'three';
import { BaseTool, point } from './tool';
import { facesAround } from './brush';

export class PressTool extends BaseTool {
  readonly name = 'press';
  readonly label = 'Press';
  readonly key = 'p';
  readonly tooltip = 'Press (P): push the faces under the brush inward (strength = pressure, Pa)';
  strength = 60;
  readonly strengthInfo = { label: 'pressure (Pa)', min: 1, max: 2000 };

  start(hit: THREE.Intersection, ev: PointerEvent): boolean {
    super.start(hit, ev);
    this.ctx!.beginEdit('press');
    this.apply(hit);
    return true;
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    const hit = this.ctx.viewport.pick(ev);
    if (hit) this.apply(hit);
  }

  private apply(hit: THREE.Intersection): void {
    const ctx = this.ctx!;
    const body = ctx.body();
    const p = body.facePressures();
    p.fill(0);
    const faces = facesAround(body.positions(), body.triangles(), point(hit.point), ctx.brush.radius);
    faces.indices.forEach((f, k) => (p[f] = this.strength * faces.weights[k]));
    body.applyFacePressures();
  }

  end(): void {
    if (!this.dragging || !this.ctx) return;
    super.end();
    const body = this.ctx.body();
    body.facePressures().fill(0);
    body.applyFacePressures();
    this.ctx.endEdit();
  }
}
