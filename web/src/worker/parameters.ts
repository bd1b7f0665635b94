// The document's parameters as the panel changes them: one by its table id (undoable), the mass,
// the wind, a material preset at the model's size, and the time step; with what each change
// says (slow motion ahead, playing again after a stop).

import type { ParamValue } from '../engine/world';
import { dtFor, stepsPerFrame } from '../engine/models';
import { precision3 as fmt } from '../format';
import { isClosed, sizeFactor } from '../io/import';
import type { Vec3 } from '../protocol';
import { errorText, type DocState } from './docstate';
import { edit } from './editing';
import type { ParamId } from '../engine/params';

/** Implicit steps per 1/60 s frame past which a smaller dt is said to run in slow motion: each is
 * a Newton solve, where the modeler's default (dt = 1/60 s) takes one a frame. */
const SLOW_IMPLICIT_STEPS = 4;

/** Change a parameter by its table id (undoable); a refused value is reported and leaves the old one. */
export function setParam(d: DocState, id: ParamId, value: ParamValue): boolean {
  if (id === 'ground' && value === true) d.groundUnderBody = belowGround(d);
  // The ground's height moves the plane with what stands on it (the core's `move_ground`): a
  // rooted mushroom rises with it instead of being buried at its pinned foot (a new-user
  // trial: at 0.5 m the step failed). Undo takes the whole world back ('whole'): a delta of
  // what the move changed holds only the y coordinates, and applied after the body has moved
  // on it would mix old heights with new x and z.
  const ok = id === 'ground.height' && typeof value === 'number'
    ? edit(d, `set ${id}`, true, () => d.world.moveGround(value), 'whole')
    : edit(d, `set ${id}`, true, () => d.world.setParam(0, id, value), 'none');
  if (ok) d.changes = [...d.changes.slice(-7), { id, value, time: d.stats().time }];
  if (ok && id === 'dt') {
    d.settings.dt = value as number;
    sayIfSlow(d);
  }
  // Another integrator gets a step it is stable at: 1/60 s implicit, else the explicit limit.
  if (ok && id === 'integrator') {
    setDt(d, dtFor(d.world, value as string));
    d.settings.substeps = stepsPerFrame(d.settings.dt);
    d.hooks.message(`${value}: dt = ${fmt(d.settings.dt)} s`);
  }
  // After a stop, another integrator or dt is the remedy the stop's message names: play again
  // (if it was not, the next step stops and says so again). A new-user trial switched back to
  // implicit after an explicit blow-up and found the page still paused, its grab doing nothing.
  if (ok && d.pausedByError && (id === 'integrator' || id === 'dt')) {
    d.pausedByError = false;
    d.settings.playing = true;
    d.hooks.message(`playing again with ${id === 'dt' ? `dt = ${fmt(d.settings.dt)} s` : `the ${value} integrator`}`);
  }
  return ok;
}

/**
 * A material preset of the core on the active body (undoable), at the model's size: an
 * imported model keeps its units, so the preset is scaled by the core's similarity rules
 * (params/similarity.rs) as the modeler preset was on import.
 */
export function materialPreset(d: DocState, name: string): void {
  const size = d.settings.frame ? sizeFactor(Array.from({ length: d.world.bodyCount }, (_, i) => d.world.body(i).positions)) : 1;
  // A new material changes how the body responds, not its shape at once. Under gravity the
  // shape as it is becomes the rest shape first, carrying its weight (freeze under load), so a
  // softer or plastic material (clay) does not slump from where it stands; the gas keeps the
  // pressure difference P − P_ref it had (a frozen body's springs balance that), so a preset
  // with less gas does not crush a frozen body. P_ref ≥ 0: with no gas (cloth) it is 0.
  // Except a closed body that the preset leaves without gas (cloth on the mushroom): its
  // weight carried by the freeze held it exactly where it stood, an unstable equilibrium of a
  // gasless shell, so it did not move until touched and then collapsed at once (a new-user
  // trial: 3 s at speed 0, then a small grab took its volume from 2.45 to 1.11 m³). It is
  // frozen plainly instead (the weight no longer carried), so it sags and drapes at once, as
  // the message says. Undo takes the whole world back to before the preset ('whole'), the
  // shape as it stood included: undoing cloth after it folded brought the gas back into the
  // folded shell, which then would not step (a new-user trial: "waiting for a step").
  if (edit(d, `material ${name}`, true, () => {
    const gravity = d.world.params(0).gravity !== 0;
    if (gravity) d.world.freeze(0, true, false);
    const before = d.stats().pressure - (d.world.params(0)['gas.ambient'] as number);
    d.world.applyPresetScaled(0, name, size);
    if (gravity && d.world.params(0)['gas.amount'] === 0 && isClosed(d.world.body(0).triangles)) d.world.freeze(0, false, false);
    d.world.setParam(0, 'gas.ambient', Math.max(0, d.stats().pressure - before));
  }, 'whole')) {
    const gasless = d.world.params(0)['gas.amount'] === 0;
    d.hooks.message(`material: ${name.replace('_', ' ')}${gasless ? ' — no gas: a closed body sags under its weight (it suits open surfaces)' : ''}`);
  }
}

/** Whether some vertex of the active body is below the ground's height. */
function belowGround(d: DocState): boolean {
  const h = d.world.params(0)['ground.height'];
  const x = d.world.body(0).positions;
  if (typeof h !== 'number') return false;
  for (let i = 1; i < x.length; i += 3) if (x[i] < h - 1e-9) return true;
  return false;
}

/** Wind along `direction` at `strength` m/s (0: calm); undoable. */
export function wind(d: DocState, direction: Vec3, strength: number): void {
  setParam(d, 'wind', [direction[0] * strength, direction[1] * strength, direction[2] * strength]);
}

/** The time step (s), from the panel (not an undo step). */
export function setDt(d: DocState, dt: number): void {
  try {
    d.world.setParam(0, 'dt', dt);
    d.settings.dt = dt;
    sayIfSlow(d);
  } catch (e) {
    d.hooks.message(errorText(e), 'error');
  }
}

/**
 * An implicit dt below 1/60 s buys no stability (backward Euler is stable at 1/60 s) and costs
 * a solve per step: say what to expect (a new-user trial ran dt = 1e-6 s at 0.4 % of real
 * time, 16,667 steps a frame, with no word).
 */
function sayIfSlow(d: DocState): void {
  const dt = d.settings.dt, n = stepsPerFrame(dt);
  if (n > SLOW_IMPLICIT_STEPS && String(d.world.params(0).integrator) === 'implicit') {
    d.hooks.message(`dt = ${Number(dt.toPrecision(3))} s is ${n.toLocaleString('en-US')} implicit steps for each 1/60 s frame, so expect slow motion; the implicit integrator is stable at dt = 1/60 s`, 'warn');
  }
}
