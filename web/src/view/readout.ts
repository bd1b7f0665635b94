// The HUD's readout, as text: how fast the simulation goes (view/pace.ts) and the drawing's rate,
// the mesh's sizes and the tool, the time, volume, pressure and speed, the wind as seen from the
// camera, and the open scene.

import { Vector3, type Camera } from 'three';
import { sig3, volumeText } from '../format';
import type { Mirror } from '../mirror';
import { sceneLine } from './hud';
import { paceText, viewText } from './pace';

/** What the readout says besides the mirror's state. */
export interface ReadoutInput {
  /** A long operation is under way in the worker. */
  busy: boolean;
  /** Milliseconds since the last frame arrived (the pace says when steps stall). */
  sinceFrameMs: number;
  /** The drawing's frames and shapes per second (view/hud.ts). */
  fps: number;
  shapesPerSecond: number;
  toolLabel: string;
  /** The wind velocity (m/s) and the camera it is seen from. */
  wind: [number, number, number];
  camera: Camera;
}

/** The readout's lines. */
export function readoutLines(m: Mirror, r: ReadoutInput): string[] {
  const s = m.stats;
  // How fast the simulation goes comes first (the drawing's fps can be high while it crawls).
  const pace = paceText({ playing: m.settings.playing, busy: r.busy, slowMotion: m.slowMotion, realTimeFraction: m.realTimeFraction, accuracy: m.accuracy, sinceFrameMs: r.sinceFrameMs });
  return [
    `simulation: ${pace}   ${m.simMs.toFixed(1)} ms of steps/frame${m.threads > 1 ? ` on ${m.threads} threads` : ''}   ${viewText(r.fps, r.shapesPerSecond, m.slowMotion)}` +
      (m.recording ? `   ● REC ${m.recording.frames} frames, ${m.recording.seconds.toFixed(1)} s` : ''),
    `${m.vertexCount} vertices   ${m.springCount} springs   ${m.faceCount} faces   tool: ${r.toolLabel}`,
    `t ${s.time.toFixed(2)} s   ${volumeText(s.volume, m.closed)}   P ${sig3(s.pressure)} Pa   max speed ${sig3(s.maxSpeed)} m/s`,
    ...(Math.hypot(...r.wind) > 0 ? [windLine(r.wind, r.camera)] : []),
    ...(m.scene ? [sceneLine(m.scene)] : []),
  ];
}

/**
 * The wind as seen from the camera (its 3D arrow is end-on when it blows along the view, as
 * Wind › blow from view makes it): speed, an arrow for its direction across the screen, and
 * whether it blows away from or towards the viewer.
 */
export function windLine(w: [number, number, number], camera: Camera): string {
  const v = new Vector3(...w);
  const speed = v.length();
  v.transformDirection(camera.matrixWorldInverse);
  const across = Math.hypot(v.x, v.y);
  const arrows = ['→', '↗', '↑', '↖', '←', '↙', '↓', '↘'];
  const arrow = across > 0.2 ? arrows[(Math.round(Math.atan2(v.y, v.x) / (Math.PI / 4)) + 8) % 8] : '';
  const depth = v.z < -0.5 ? ' away from you' : v.z > 0.5 ? ' towards you' : '';
  return `wind ${sig3(speed)} m/s ${arrow}${arrow && depth ? ' and' : ''}${depth}`;
}
