// The tools' drags on the document: a stroke begins on the body under the cursor, follows the
// cursor, acts for each tick's simulated time before the steps, and ends as one undo step. A
// brush keeps what it painted and the state of those vertices ('touched'); a grab or press moves
// everything ('all'). The strokes themselves: worker/strokes.ts.

import type { Vec3 } from '../protocol';
import { makeStroke, type StrokeBody, type StrokeStart } from './strokes';
import type { DocState } from './docstate';

export function strokeStart(d: DocState, s: StrokeStart): void {
  if (d.stroke) strokeEnd(d);
  const b = s.body ?? 0;
  if (!Number.isInteger(b) || b < 0 || b >= d.world.bodyCount) { d.hooks.message(`there is no body ${b} to shape`, 'warn'); return; }
  d.strokeOn = b;
  d.world.forgetRewind();
  d.world.mark();
  d.stroke = makeStroke(s);
  // A brush keeps what it painted and the state of those vertices; a drag moves everything.
  d.strokeScope = s.tool === 'grab' || s.tool === 'press' ? 'all' : 'touched';
  d.stroke.start(strokeBody(d));
  if (d.stroke.paintsBodyData) d.bodyVersion++;
}

export function strokeMove(d: DocState, point: Vec3 | null, inverted: boolean, pressure?: number): void {
  d.stroke?.press(pressure);
  d.stroke?.move(point, inverted, strokeBody(d));
}

export function strokeEnd(d: DocState): void {
  if (!d.stroke) return;
  const stroke = d.stroke;
  d.stroke = null;
  stroke.end(strokeBody(d));
  d.history.push(stroke.label, { delta: d.world.delta(d.strokeScope), settings: { ...d.settings }, scene: d.session });
  d.hooks.changed();
}

/** The stroke acts for `dt` simulated seconds (before the steps of a tick). */
export function updateStroke(d: DocState, dt: number): void {
  if (!d.stroke) return;
  d.stroke.update(strokeBody(d), dt, d.settings.dt);
  if (d.stroke.paintsBodyData) d.bodyVersion++;
}

/** The stroke's body as the strokes see it. */
export function strokeBody(d: DocState): StrokeBody {
  const w = d.world, b = d.strokeOn;
  return {
    get view() { return w.body(b); },
    applyLoads: () => w.applyLoads(b),
    scaleRest: (f) => w.scaleRest(b, f),
    setMasses: (m) => w.setMasses(b, m),
    setPins: () => w.setPins(b),
    setTargets: (r) => w.setTargets(b, r),
  };
}
