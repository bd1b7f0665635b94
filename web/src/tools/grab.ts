// Grab (G): press on the surface and drag. The vertices under the brush are pulled by a spring
// toward the cursor's point on the view plane through the grab point (each keeps its offset), so
// the pull follows the mouse. Strength: the pull's angular frequency ω (1/s).

import * as THREE from 'three';
import { BaseTool, point } from './tool';
import { grabForce, verticesAround, type Weighted } from './brush';

export class GrabTool extends BaseTool {
  readonly name = 'grab';
  readonly label = 'Grab';
  readonly key = 'g';
  readonly tooltip = 'Grab (G): drag the surface; the brush area follows the mouse on a spring (strength = ω, 1/s)';
  strength = 30;
  readonly strengthInfo = { label: 'pull ω (1/s)', min: 1, max: 200 };
  private picked: Weighted = { indices: [], weights: [] };
  private offsets: number[] = [];
  private plane = new THREE.Plane();
  private cursor = new THREE.Vector3();

  start(hit: THREE.Intersection, ev: PointerEvent): boolean {
    const ctx = this.ctx!;
    super.start(hit, ev);
    const x = ctx.body().positions();
    this.picked = verticesAround(x, point(hit.point), ctx.brush.radius);
    if (this.picked.indices.length === 0) {
      this.dragging = false;
      return false;
    }
    this.offsets = this.picked.indices.flatMap((i) => [x[3 * i] - hit.point.x, x[3 * i + 1] - hit.point.y, x[3 * i + 2] - hit.point.z]);
    const normal = ctx.viewport.camera.getWorldDirection(new THREE.Vector3());
    this.plane.setFromNormalAndCoplanarPoint(normal, hit.point);
    this.cursor.copy(hit.point);
    ctx.beginEdit('grab');
    return true;
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    this.ctx.viewport.rayAt(ev).ray.intersectPlane(this.plane, this.cursor);
  }

  /** Refresh the spring forces from the current positions (every frame while dragging). */
  update(): void {
    if (!this.dragging || !this.ctx) return;
    const body = this.ctx.body();
    const x = body.positions(), v = body.velocities(), m = body.masses();
    const f = body.userForces();
    f.fill(0);
    const omega = this.strength;
    const c = [this.cursor.x, this.cursor.y, this.cursor.z];
    this.picked.indices.forEach((i, k) => {
      for (let d = 0; d < 3; d++) {
        f[3 * i + d] = grabForce(m[i], this.picked.weights[k], omega, c[d] + this.offsets[3 * k + d], x[3 * i + d], v[3 * i + d]);
      }
    });
    body.applyUserForces();
  }

  end(): void {
    if (!this.dragging || !this.ctx) return;
    super.end();
    const body = this.ctx.body();
    body.userForces().fill(0);
    body.applyUserForces();
    this.picked = { indices: [], weights: [] };
    this.ctx.endEdit();
  }
}
