// The camera's controls. Turntable by default (three.js OrbitControls, the convention of Blender,
// SculptGL and most modelers): left drag turns the view about the vertical axis and tilts it,
// the horizon stays level, right drag pans, the wheel zooms; no inertia, so the view stops when
// the mouse stops. The paper's free trackball (TrackballControls) stays selectable, also without
// inertia (`staticMoving`). Zoom is limited relative to the model's size so the camera never goes
// inside it nor loses it in the distance; "frame" (V) fits the model in the view.
//
// Rates: OrbitControls turns 2π·rotateSpeed per canvas height of drag; at 0.8 a 60 px drag on an
// 800 px view turns 0.8·360°·60/800 ≈ 22° (the issue measured 60° for the trackball before).

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { TrackballControls } from 'three/examples/jsm/controls/TrackballControls.js';

export type CameraMode = 'turntable' | 'trackball';

/** Where the camera looks from, relative to the model's centre, before any model is known. */
const HOME_DIRECTION = new THREE.Vector3(3.2, 1.6, 4.2).normalize();
/** The camera stays at least this many model radii from the target (outside the model)… */
export const MIN_DISTANCE_RADII = 1.3;
/** …and at most this many (the model stays more than a few pixels wide). */
export const MAX_DISTANCE_RADII = 25;

/** The turntable's lowest view: just above horizontal (rad from straight down… from the zenith). */
export const MAX_POLAR = 0.49 * Math.PI;

/** The model's centre may wander this many model radii from where the view keeps it before the camera follows… */
export const FOLLOW_ZONE = 0.25;
/** …then the camera closes the excess with this time constant (s): 1 − e^(−Δt/τ) of it per frame. */
export const FOLLOW_TAU = 0.1;

/**
 * Where the camera's target should be (m): `base`, the target the view was set with when the
 * model's centre was at `anchor`, moved by the part of the centre's displacement beyond `zone`
 * (m) — d (1 − zone/|d|) for d = centre − anchor, nothing inside the zone.
 */
export function followTarget(base: THREE.Vector3, anchor: THREE.Vector3, centre: THREE.Vector3, zone: number, out = new THREE.Vector3()): THREE.Vector3 {
  const d = out.subVectors(centre, anchor);
  const len = d.length();
  return d.multiplyScalar(len > zone ? 1 - zone / len : 0).add(base);
}

export interface CameraState { position: number[]; target: number[]; mode: CameraMode }

export class CameraRig {
  mode: CameraMode = 'turntable';
  private orbit: OrbitControls;
  private trackball: TrackballControls | null = null;
  /** The model's bounding sphere (centre, radius in m), for framing and zoom limits. */
  private centre = new THREE.Vector3(0, 0.8, 0);
  private radius = 1.25;

  constructor(readonly camera: THREE.PerspectiveCamera, private readonly dom: HTMLElement, private readonly changed: () => void) {
    this.orbit = this.makeOrbit();
    this.camera.position.copy(this.centre).addScaledVector(HOME_DIRECTION, this.frameDistance());
    this.orbit.target.copy(this.centre);
    this.orbit.update();
  }

  /** The active controls (the tools switch `enabled` off while they drag). */
  get controls(): OrbitControls | TrackballControls { return this.mode === 'turntable' ? this.orbit : this.trackball!; }
  get target(): THREE.Vector3 { return this.controls.target; }

  private makeOrbit(): OrbitControls {
    const c = new OrbitControls(this.camera, this.dom);
    c.enableDamping = false;
    c.rotateSpeed = 0.8;
    c.zoomSpeed = 1;
    c.panSpeed = 0.8;
    c.screenSpacePanning = true;
    // Never below the horizon: the model stands on the ground, which would hide it (and the
    // grid would cut through it) seen from under the floor.
    c.maxPolarAngle = MAX_POLAR;
    // Touch: one finger on empty space turns the view; two fingers turn and pinch-zoom.
    c.touches = { ONE: THREE.TOUCH.ROTATE, TWO: THREE.TOUCH.DOLLY_ROTATE };
    c.addEventListener('change', this.changed);
    c.addEventListener('start', this.started);
    c.addEventListener('end', this.ended);
    return c;
  }

  /** Called when the user has finished moving the camera (a drag or a wheel turn), and after framing. */
  onSettled(f: () => void): void { this.settled.push(f); }
  private settled: (() => void)[] = [];
  private readonly ended = () => {
    // What the user moved the target by (a pan) is kept; a turn or a zoom keeps the target, and
    // the model's own motion meanwhile is not the user's.
    if (this.moving) this.base.add(this.target).sub(this.startTarget);
    else this.reanchor = true;
    this.moving = false;
    for (const f of this.settled) f();
  };
  private readonly started = () => { this.moving = true; this.startTarget.copy(this.target); };
  private startTarget = new THREE.Vector3();

  // ----- following the model (a body the wind blows away, one that falls, stays in view) -----
  /** The user is moving the camera. */
  private moving = false;
  /** The model's centre when the view was last set (framed, restored, turned, a new model)… */
  private anchor = new THREE.Vector3();
  /** …and the target the view had then, plus the user's pans since (a pan is kept while the model moves). */
  private base = new THREE.Vector3();
  /** The view was just set (framed, restored, a new model): the next centre seen is where it keeps the model. */
  private reanchor = true;
  private followedAt = performance.now();
  /** Scratch for `follow` (called every frame: no allocation). */
  private readonly away = new THREE.Vector3();
  /** The last centre `follow` was given (what `ease` goes on following). */
  private readonly last = new THREE.Vector3();

  /**
   * Every drawn frame: go on easing towards the last centre seen. A frame of the model comes
   * only when it changes, so without this the view stopped wherever it was when the frames
   * stopped: after a blow-up the model put back and paused came in one frame, and the view
   * stayed part way along its ease, the model off screen. Not before a new view's first centre
   * (`reanchor`).
   */
  ease(now = performance.now()): void {
    if (!this.reanchor) this.follow(this.last, now);
  }

  /**
   * The model's centre this frame. The camera's target eases (time constant FOLLOW_TAU, no jump)
   * towards `followTarget`: the target the view was set with, moved by as much as the centre has
   * left a dead zone of FOLLOW_ZONE model radii around where it was then — keeping its direction
   * and distance. A function of where the model is now, not of the path it took: a grab's wobble
   * that leaves the zone moves the view a little and, once the model is back, the view is back
   * too (before, the view followed each excursion and kept it: one grab on the mushroom moved
   * its target 0.15 m for good, four ~27 px on screen). Not while the user moves the camera or a
   * tool drags (`enabled` off): the view never moves under a grab.
   */
  follow(centre: THREE.Vector3, now = performance.now()): void {
    const dt = Math.min(0.25, Math.max(0, (now - this.followedAt) / 1000));
    this.followedAt = now;
    if (centre !== this.last) this.last.copy(centre);
    if (this.reanchor) { this.anchor.copy(centre); this.base.copy(this.target); this.reanchor = false; return; }
    if (this.moving || !this.controls.enabled) return;
    const away = followTarget(this.base, this.anchor, centre, FOLLOW_ZONE * this.radius, this.away).sub(this.target);
    // Closer than a millionth of the model's size: done (no endless sub-pixel redraws).
    if (!(away.length() > 1e-6 * this.radius)) return;
    away.multiplyScalar(1 - Math.exp(-dt / FOLLOW_TAU));
    this.target.add(away);
    this.camera.position.add(away);
    this.controls.update();
    this.changed();
  }

  private makeTrackball(): TrackballControls {
    const c = new TrackballControls(this.camera, this.dom);
    c.staticMoving = true; // no inertia: the view stops with the mouse
    c.rotateSpeed = 1.5;
    c.zoomSpeed = 1.2;
    c.panSpeed = 0.6;
    c.addEventListener('change', this.changed);
    c.addEventListener('start', this.started);
    c.addEventListener('end', this.ended);
    return c;
  }

  /** Turntable or free trackball; the view stays where it is (turntable levels the horizon). */
  setMode(mode: CameraMode): void {
    if (mode === this.mode) return;
    const target = this.target.clone();
    this.controls.enabled = false;
    if (mode === 'trackball') {
      this.trackball ??= this.makeTrackball();
      this.trackball.enabled = true;
    } else {
      this.camera.up.set(0, 1, 0);
      this.orbit.enabled = true;
    }
    this.mode = mode;
    this.controls.target.copy(target);
    this.limit();
    this.camera.lookAt(target);
    this.controls.update();
    this.changed();
    this.ended();
  }

  /** The model's bounding sphere changed (a new model): the zoom limits follow it. */
  setModel(centre: THREE.Vector3, radius: number): void {
    this.centre.copy(centre);
    this.reanchor = true;
    this.radius = Math.max(radius, 1e-6);
    this.limit();
  }

  private limit(): void {
    for (const c of [this.orbit, this.trackball]) {
      if (!c) continue;
      c.minDistance = MIN_DISTANCE_RADII * this.radius;
      c.maxDistance = MAX_DISTANCE_RADII * this.radius;
    }
    this.camera.near = Math.max(1e-4, 0.02 * this.radius);
    this.camera.far = 200 * this.radius;
    this.camera.updateProjectionMatrix();
  }

  /** The distance at which the model's bounding sphere fills the view's height with a margin. */
  private frameDistance(): number {
    const half = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const fit = this.radius / Math.sin(Math.min(half, Math.atan(Math.tan(half) * this.camera.aspect)));
    return Math.max(1.6 * fit, MIN_DISTANCE_RADII * this.radius);
  }

  /** Fit the model in the view from the current direction, level (V); around `centre` if given (where the model is now). */
  frame(centre?: THREE.Vector3): void {
    if (centre) this.centre.copy(centre);
    const dir = this.camera.position.clone().sub(this.target);
    if (dir.lengthSq() < 1e-12) dir.copy(HOME_DIRECTION);
    // Level: no roll, and not straight down or up (a turntable cannot turn from there).
    dir.normalize();
    dir.y = Math.max(0.15, Math.min(0.85, dir.y)); // from above, as the turntable allows
    dir.normalize();
    this.camera.up.set(0, 1, 0);
    this.controls.target.copy(this.centre);
    this.camera.position.copy(this.centre).addScaledVector(dir, this.frameDistance());
    this.camera.lookAt(this.centre);
    this.controls.update();
    this.changed();
    this.ended();
  }

  state(): CameraState { return { position: this.camera.position.toArray(), target: this.target.toArray(), mode: this.mode }; }

  restore(s: CameraState): void {
    this.setMode(s.mode);
    this.camera.position.fromArray(s.position);
    this.controls.target.fromArray(s.target);
    this.camera.lookAt(this.controls.target);
    this.controls.update();
    this.reanchor = true;
    this.changed();
  }

  resized(): void { this.trackball?.handleResize(); }
  update(): void { this.controls.update(); }
  dispose(): void { this.orbit.dispose(); this.trackball?.dispose(); }
}
