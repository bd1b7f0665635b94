// Grab (G): press on the surface and drag. The vertices under the brush are pulled by a spring
// toward the cursor's point on the view plane through the grab point (each keeps its offset), so
// the pull follows the mouse. Strength: the pull's angular frequency ω (1/s).

import * as THREE from 'three';
import { BaseTool, point } from './tool';
import { verticesAround } from './brush';

export class GrabTool extends BaseTool {
  readonly name = 'grab';
  readonly label = 'Grab';
  readonly key = 'g';
  readonly tooltip = 'Grab (G): drag the surface; the brush area follows the mouse on a spring (strength = ω, 1/s)';
  strength = 30;
  readonly strengthInfo = { label: 'pull ω (1/s)', min: 1, max: 200 };
  private plane = new THREE.Plane();
  private cursor = new THREE.Vector3();

  start(hit: THREE.Intersection, ev: PointerEvent): boolean {
    const ctx = this.ctx!;
    // Nothing under the brush (a tiny brush on a coarse mesh): the trackball takes the drag.
    if (verticesAround(ctx.body().positions, point(hit.point), ctx.brush.radius).indices.length === 0) return false;
    const normal = ctx.viewport.camera.getWorldDirection(new THREE.Vector3());
    this.plane.setFromNormalAndCoplanarPoint(normal, hit.point);
    return super.start(hit, ev);
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    if (this.ctx.viewport.rayAt(ev).ray.intersectPlane(this.plane, this.cursor)) {
      this.ctx.send({ type: 'strokeMove', point: point(this.cursor), inverted: false });
    }
  }
}
