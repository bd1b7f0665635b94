// The camera's follow (view/camera.ts): a body that leaves for good stays in view, a grab's
// wobble does not move the view for good. The rig runs on a stub canvas element (no DOM in Node:
// the controls only register listeners on it).
import { describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { CameraRig, FOLLOW_TAU, FOLLOW_ZONE, followTarget } from '../src/view/camera';

function stubElement(): HTMLElement {
  const el: Record<string, unknown> = {
    style: {},
    addEventListener() {}, removeEventListener() {},
    setPointerCapture() {}, releasePointerCapture() {}, hasPointerCapture: () => false,
    getRootNode() { return el; },
    clientWidth: 800, clientHeight: 600,
    getBoundingClientRect: () => ({ left: 0, top: 0, width: 800, height: 600, right: 800, bottom: 600, x: 0, y: 0 }),
  };
  el.ownerDocument = el;
  return el as unknown as HTMLElement;
}

/** A rig on the mushroom's bounding sphere (centre (0, 0.92, 0), radius 1.2 m), its view set. */
function rig(): { r: CameraRig; centre: THREE.Vector3; radius: number; step: (c: THREE.Vector3, frames?: number) => void } {
  const camera = new THREE.PerspectiveCamera(45, 4 / 3, 0.01, 100);
  const r = new CameraRig(camera, stubElement(), () => {});
  const centre = new THREE.Vector3(0, 0.92, 0), radius = 1.2;
  r.setModel(centre, radius);
  r.frame();
  let now = 0;
  const step = (c: THREE.Vector3, frames = 1) => { for (let i = 0; i < frames; i++) { now += 1000 / 60; r.follow(c, now); } };
  step(centre);
  return { r, centre, radius, step };
}

describe('the camera follows a body that leaves, not a wobble', () => {
  it('a wobble after a grab, out of the dead zone and back, leaves the view where it was', () => {
    const { r, centre, radius, step } = rig();
    const target0 = r.target.clone(), position0 = r.camera.position.clone();
    // Four grabs: each pulls the centre 0.6 radii sideways (2.4× the dead zone) while the tool
    // holds the controls off, then the body swings back through its rest with a decaying
    // oscillation of 1 s period over 3 s (60 frames a second).
    for (let g = 0; g < 4; g++) {
      const dir = new THREE.Vector3(Math.cos(g), 0.3, Math.sin(g)).normalize();
      r.controls.enabled = false;
      step(centre.clone().addScaledVector(dir, 0.6 * radius), 30);
      r.controls.enabled = true;
      for (let i = 0; i < 180; i++) {
        const t = i / 60;
        step(centre.clone().addScaledVector(dir, 0.6 * radius * Math.exp(-t) * Math.cos(2 * Math.PI * t)));
      }
      step(centre, 120);
    }
    // At rest 2 s after the last wobble the view has eased back: within e^(−2/τ) of the largest
    // excursion (~0.42 m), i.e. 1e-9 m, and below the rig's stopping threshold 1e-6 R.
    expect(r.target.distanceTo(target0)).toBeLessThan(2e-6 * radius);
    expect(r.camera.position.distanceTo(position0)).toBeLessThan(2e-6 * radius);
  });

  it('a body that falls away stays within the dead zone of where the view keeps it, without a jump', () => {
    const { r, centre, radius, step } = rig();
    const offset = r.target.clone().sub(centre);
    const dist = r.camera.position.distanceTo(r.target);
    let last = r.target.clone(), most = 0;
    // Falling freely for 1 s from rest (y = −g t²/2: 4.9 m, ~4 radii), then lying there.
    for (let i = 1; i <= 60; i++) {
      const t = i / 60;
      step(centre.clone().add(new THREE.Vector3(0, -4.905 * t * t, 0)));
      most = Math.max(most, r.target.distanceTo(last));
      last = r.target.clone();
    }
    const fallen = centre.clone().add(new THREE.Vector3(0, -4.905, 0));
    step(fallen, 120);
    // Where the view keeps the model (target less the set offset) ends on the dead zone's edge,
    // to within the rig's stopping threshold (1e-6 R; e^(−2 s/τ) of the fall is far less); direction and distance kept.
    const kept = r.target.clone().sub(offset);
    expect(Math.abs(kept.distanceTo(fallen) - FOLLOW_ZONE * radius)).toBeLessThan(2e-6 * radius);
    expect(Math.abs(r.camera.position.distanceTo(r.target) - dist)).toBeLessThan(1e-9);
    // No jump: per frame, at most the body's own speed at the end of the fall (g · 1 s / 60).
    expect(most).toBeLessThan(9.81 / 60);
    expect(FOLLOW_TAU).toBeGreaterThan(0);
  });

  it('the target sought is the set one inside the zone and trails by the zone outside it', () => {
    const base = new THREE.Vector3(1, 2, 3), anchor = new THREE.Vector3(0, 1, 0);
    expect(followTarget(base, anchor, new THREE.Vector3(0.2, 1, 0), 0.3).distanceTo(base)).toBe(0);
    const far = followTarget(base, anchor, new THREE.Vector3(0, 1, 2), 0.5);
    expect(far.distanceTo(new THREE.Vector3(1, 2, 4.5))).toBeLessThan(1e-12);
  });
});

describe('framing (V)', () => {
  it('frames the model where it is now, not where it arrived', () => {
    const { r, centre, radius } = rig();
    const lying = centre.clone().add(new THREE.Vector3(0.3, -0.6, -0.1));
    const direction = r.camera.position.clone().sub(r.target).normalize();
    r.frame(lying);
    expect(r.target.distanceTo(lying)).toBeLessThan(1e-12);
    // From the same direction, at the framing distance (outside the model).
    expect(r.camera.position.clone().sub(r.target).normalize().distanceTo(direction)).toBeLessThan(1e-9);
    expect(r.camera.position.distanceTo(lying)).toBeGreaterThan(radius);
  });
});
