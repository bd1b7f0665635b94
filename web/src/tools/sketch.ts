// Sketch (K): draw a closed outline on the view plane with the mouse or pen; on release it
// becomes a balloon that replaces the model (undoable). The outline is the stroke's points on
// the plane through the view's centre facing the camera, in that plane's own coordinates; the
// worker builds the pillow and inflates it with the engine (crates/softsculpt/src/sketch/) and
// places it back in that plane, standing on the ground.

import * as THREE from 'three';
import type { Tool, ToolContext } from './tool';

/** Screen distance (px) between kept samples of the stroke. */
const SPACING_PX = 4;

/** An outline is drawn on an upright plane when the view direction's horizontal part is at least
 * this (of 1); below it the view looks almost straight down and the view plane is kept. */
const UPRIGHT_FROM = 0.1;

export class SketchTool implements Tool {
  readonly name = 'sketch' as const;
  readonly label = 'Sketch';
  readonly key = 'k';
  readonly tooltip = 'Draw a closed outline on the view: it becomes a balloon inflated by gas (replaces the model; undoable)';
  strength = 0;
  readonly strengthInfo = null;
  /** Starts anywhere on the view, not only on the body. */
  readonly anywhere = true;
  private ctx: ToolContext | null = null;
  private stroke: [number, number][] = [];
  private svg: SVGSVGElement | null = null;
  private line: SVGPolylineElement | null = null;

  connect(ctx: ToolContext): void { this.ctx = ctx; }
  disconnect(): void { this.clear(); this.ctx = null; }
  dispose(): void { this.disconnect(); }

  start(_hit: THREE.Intersection | null, ev: PointerEvent): boolean {
    if (!this.ctx) return false;
    this.stroke = [[ev.clientX, ev.clientY]];
    const rect = this.ctx.viewport.canvas.getBoundingClientRect();
    const ns = 'http://www.w3.org/2000/svg';
    this.svg = document.createElementNS(ns, 'svg');
    Object.assign(this.svg.style, { position: 'fixed', left: `${rect.left}px`, top: `${rect.top}px`, width: `${rect.width}px`, height: `${rect.height}px`, pointerEvents: 'none', zIndex: '5' });
    this.line = document.createElementNS(ns, 'polyline');
    this.line.setAttribute('fill', 'rgba(255, 200, 80, 0.15)');
    this.line.setAttribute('stroke', '#ffc850');
    this.line.setAttribute('stroke-width', '2');
    this.svg.appendChild(this.line);
    document.body.appendChild(this.svg);
    this.draw();
    return true;
  }

  move(ev: PointerEvent): void {
    const last = this.stroke[this.stroke.length - 1];
    if (!last || Math.hypot(ev.clientX - last[0], ev.clientY - last[1]) < SPACING_PX) return;
    this.stroke.push([ev.clientX, ev.clientY]);
    this.draw();
  }

  end(): void {
    const ctx = this.ctx, stroke = this.stroke;
    this.clear();
    if (!ctx || stroke.length < 3) return;
    // The plane the outline is drawn on: through the trackball's centre, upright (containing the
    // world's up) and facing the camera's horizontal direction, so a balloon drawn on a tilted
    // view stands as drawn (the view plane itself laid a 60°-tilted drawing nearly flat on the
    // ground). The view rays through the outline meet it where the camera sees the outline,
    // so it looks as drawn. Looking nearly straight down (the horizontal direction under a tenth
    // of the view's), the view plane: an outline drawn from above lies as drawn.
    const { camera, controls, canvas } = ctx.viewport;
    const origin = controls.target.clone();
    let right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0).normalize();
    let up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1).normalize();
    let normal = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 2).normalize();
    const level = new THREE.Vector3(normal.x, 0, normal.z);
    if (level.length() > UPRIGHT_FROM) {
      normal = level.normalize();
      up = new THREE.Vector3(0, 1, 0);
      right = new THREE.Vector3().crossVectors(up, normal);
    }
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, origin);
    const rect = canvas.getBoundingClientRect();
    const ray = new THREE.Raycaster(), hit = new THREE.Vector3();
    const points: number[] = [];
    for (const [x, y] of stroke) {
      ray.setFromCamera(new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1), camera);
      if (!ray.ray.intersectPlane(plane, hit)) continue;
      const d = hit.sub(origin);
      points.push(d.dot(right), d.dot(up));
    }
    ctx.send({ type: 'sketch', points, origin: origin.toArray(), right: right.toArray(), up: up.toArray(), normal: normal.toArray() });
  }

  private draw(): void {
    if (!this.line || !this.ctx) return;
    const rect = this.ctx.viewport.canvas.getBoundingClientRect();
    this.line.setAttribute('points', this.stroke.map(([x, y]) => `${x - rect.left},${y - rect.top}`).join(' '));
  }

  private clear(): void {
    this.svg?.remove();
    this.svg = null;
    this.line = null;
    this.stroke = [];
  }
}
