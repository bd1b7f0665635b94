// What the modeler says when the simulation stops: once, in the user's terms — what happened, at
// which simulated time (3 significant digits, never an internal step count or a raw float), the
// likely cause, and one thing to do. The engine's error (engine/world.ts `EngineError`) gives
// `cause` (non_finite, collapsed, not_converged), `time` and `rolled_back_to`; the document gives
// the settings and the parameters the user changed shortly before.

import { EngineError } from '../engine/world';
import { sig3 } from '../format';

/** A parameter the user changed, and the simulated time (s) when. */
export interface Change { id: string; value: unknown; time: number }

export interface StopContext {
  integrator: string;
  dt: number;
  /** The largest stable step of an explicit integrator here (s), if known. */
  stableDt?: number;
  /** Recent parameter changes, the latest last. */
  changes: Change[];
  /** Whether part of the body was below the ground when the ground was last switched on. */
  groundUnderBody?: boolean;
  /** The simulated time (s) the document went back to, the last state known good (the core's world/rewind.rs), if it did. */
  rewoundTo?: number;
  /** The model is an import (worker/importer.ts): its file, pieces, smallest angle (°) and the simulated time (s) it was built at. */
  imported?: Imported;
}

/** What the stop message says of an import. */
export interface Imported { name: string; pieces: number; minAngle: number; time: number }

/** A stop within this much simulated time after an import is put down to the import (s). */
export const IMPORT_WINDOW = 1;
/** Triangles with an angle below this (°) are named as thin in that message (meshing.md: slivers below 10°). */
const THIN_DEG = 10;

/** A change within this much simulated time before the failure is named as its likely cause (s). */
export const CAUSE_WINDOW = 3;

const LABELS: Record<string, string> = {
  ground: 'the ground', gravity: 'gravity', 'gas.amount': 'the gas amount', 'gas.temperature': 'the temperature',
  stiffness: 'the stiffness', bending: 'the bending stiffness', rigidity: 'the flexural rigidity', damping: 'the damping', spring_damping: 'the spring damping',
  wind: 'the wind', mass: 'the mass', dt: 'the time step', integrator: 'the integrator', self_collision: 'self-collision',
};

function describeChange(c: Change): string {
  const name = LABELS[c.id] ?? c.id;
  if (c.id === 'ground') return c.value ? 'switching the ground on' : 'switching the ground off';
  if (typeof c.value === 'boolean') return `switching ${name} ${c.value ? 'on' : 'off'}`;
  if (typeof c.value === 'number') return `setting ${name} to ${sig3(c.value)}`;
  if (typeof c.value === 'string') return `switching ${name} to ${c.value}`;
  return `changing ${name}`;
}

/**
 * The one message for a simulation that stopped on `e` (the world already rolled back by the
 * engine and paused by the document). Ends with what the user can do.
 */
export function explainStop(e: unknown, ctx: StopContext): string {
  if (!(e instanceof EngineError) || e.kind !== 'step') return `The simulation stopped: ${e instanceof Error ? e.message : String(e)}. Paused.`;
  const cause = String(e.fields.cause ?? '');
  const t = e.time !== undefined ? ` at t = ${sig3(e.time)} s` : '';
  const back = ctx.rewoundTo !== undefined ? ` It was put back to t = ${sig3(ctx.rewoundTo)} s, the last moment it was sound, and paused.`
    : e.rolledBackTo !== undefined ? ` It was put back to t = ${sig3(e.rolledBackTo)} s and paused.` : ' Paused.';
  const what = cause === 'collapsed' ? `The body turned inside out${t} (its volume fell to zero).`
    : cause === 'not_converged' ? `The implicit solver could not finish a step${t}, even split into 8.`
    : `The simulation blew up${t}.`;
  // The likeliest cause: a change the user made shortly before, else the step.
  const recent = ctx.changes.filter((c) => e.time === undefined || (e.time - c.time >= -1e-9 && e.time - c.time <= CAUSE_WINDOW));
  const last = recent[recent.length - 1];
  let why: string;
  const im = ctx.imported;
  const since = im && e.time !== undefined ? e.time - im.time : NaN;
  if (im && since >= -1e-9 && since <= IMPORT_WINDOW && !recent.some((c) => c.time >= im.time - 1e-9)) {
    // The user did nothing since the import: not the gas (a new user's teddy stopped at
    // t = 0.0123 s with "likely cause: too little gas") but the file as it came.
    const thin = im.minAngle < THIN_DEG ? `, triangles as thin as ${sig3(im.minAngle)}°` : '';
    const pieces = im.pieces > 1 ? `${im.pieces} pieces` : 'one piece';
    const remedy = im.pieces > 1 ? 'Model › Remesh evens the triangles; importing it again with "the largest piece only" leaves the other pieces out.' : 'Model › Remesh evens the triangles.';
    why = `Likely cause: the imported ${im.name} as it came (${pieces}${thin}), ${sig3(Math.max(0, since))} s after the import. ${remedy}`;
  } else if (last?.id === 'ground' && last.value === true && ctx.groundUnderBody) {
    why = 'Likely cause: the ground was switched on with part of the body below it. Undo (Ctrl+Z) it, or raise the model first.';
  } else if (ctx.integrator !== 'implicit' && ctx.stableDt !== undefined && ctx.dt > ctx.stableDt) {
    why = `Likely cause: the time step ${sig3(ctx.dt)} s is larger than the ${ctx.integrator} integrator's stable step (${sig3(ctx.stableDt)} s) here. Choose the implicit integrator, or a smaller dt.`;
  } else if (last) {
    why = `Likely cause: ${describeChange(last)}, ${sig3(Math.max(0, (e.time ?? last.time) - last.time))} s before. Undo it with Ctrl+Z, then Space to play.`;
  } else if (ctx.integrator !== 'implicit') {
    why = 'Likely cause: a force too strong for the explicit integrator at this step. The implicit integrator (the default) is stable at any step.';
  } else if (cause === 'collapsed') {
    why = 'Likely cause: too little gas for the load it carries. Add gas, or stiffen the springs, then Space to play.';
  } else {
    why = 'Likely cause: a force too strong for this step. A smaller dt or more damping avoids it; Space plays on.';
  }
  return `${what}${back} ${why}`;
}
