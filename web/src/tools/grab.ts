// Grab (G): press on the surface and drag. Each vertex under the brush is tied by a target spring
// (inside the implicit step, so any strength is stable) to the cursor's point on the view plane
// through the grab point plus its offset, so the surface follows the mouse. Strength: the pull's
// angular frequency ω (1/s): stiffness m w ω² per vertex, critically damped.

import * as THREE from 'three';
import { BaseTool, penPressure, point } from './tool';

/** Default pull: stiff enough that the grabbed point stays within a few pixels of the cursor. */
export const GRAB_OMEGA = 600;
/** The strongest setting (stable too: the springs are in the implicit system). */
export const GRAB_OMEGA_MAX = 3000;

export class GrabTool extends BaseTool {
  readonly name = 'grab';
  readonly label = 'Grab';
  readonly key = 'g';
  readonly tooltip = 'Grab (G): drag the surface; the brush area follows the mouse on a spring (strength = ω, 1/s)';
  strength = GRAB_OMEGA;
  readonly strengthInfo = { label: 'pull ω (1/s)', min: 1, max: GRAB_OMEGA_MAX };
  private plane = new THREE.Plane();
  private cursor = new THREE.Vector3();

  start(hit: THREE.Intersection, ev: PointerEvent): boolean {
    const ctx = this.ctx!;
    const normal = ctx.viewport.camera.getWorldDirection(new THREE.Vector3());
    this.plane.setFromNormalAndCoplanarPoint(normal, hit.point);
    return super.start(hit, ev);
  }

  move(ev: PointerEvent): void {
    if (!this.dragging || !this.ctx) return;
    if (this.ctx.viewport.rayAt(ev).ray.intersectPlane(this.plane, this.cursor)) {
      this.ctx.send({ type: 'strokeMove', point: point(this.cursor), inverted: false, pressure: penPressure(ev) });
    }
  }
}
