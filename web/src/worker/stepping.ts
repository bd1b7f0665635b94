// The document's steps: `advance` runs the world for a tick as the core's `World::advance` takes
// it (split steps, the relaxed retry, a wall-clock budget), moves a grab's anchors along, and
// turns a failure into a pause and one message (explain.ts); what the steps met is counted and
// said once (relaxed hinges, split steps) or kept for the HUD (accuracy).

import { precision3 as fmt } from '../format';
import type { DocState } from './docstate';
import { explainStop } from './explain';
import { setDt } from './parameters';
import { strokeBody } from './stroking';

/** Frames with split steps before the modeler says so (once per model). */
export const SPLIT_NOTICE = 10;
/**
 * Halvings of a step the implicit solver refuses before the refusal stands (dt/8): the core's
 * `world::SPLITS`, which `World::advance` takes (`crates/softsculpt/src/world/advance.rs`).
 */
export const SPLITS = 3;

/**
 * `n` steps of `dt` (s) of the world, contacts and scene events included, as the core's
 * `World::advance` takes them: a step the implicit solver refuses split up to SPLITS times,
 * the relaxed retry before a refusal, and under a wall-clock budget of `seconds` (> 0; 0:
 * every step to the tolerance) each implicit step accepted at its deadline once within the
 * minimum accuracy, explicit steps only while the budget lasts (`lastAdvance.simulated` says
 * how far it got). A grab's anchors move towards the cursor over the steps' simulated time
 * (`anchorpath.ts`). On a blow-up the engine goes back to the last state known good since the
 * user's last change (the core's `world/rewind.rs`); the document pauses and says so. False
 * then, or when a waiting command interrupted a step (the world as before that step).
 */
export function advance(d: DocState, dt: number, n: number, seconds = 0): boolean {
  d.lastAdvance = null;
  try {
    if (dt !== d.settings.dt) setDt(d, dt);
    const anchors = d.stroke?.path(strokeBody(d)) ?? null;
    anchors?.aim(dt * n);
    const a = d.world.advance(dt * n, seconds, 0, SPLITS, true, true);
    d.lastAdvance = a;
    anchors?.took(a.simulated);
    anchors?.stepped(newtonIterations(d), a.splits > 0);
    // The frame's largest residual is an early step's when any was stopped at its deadline (a
    // converged step's is below the tolerance, an early one's above it).
    if (a.early > 0) d.accuracy = Math.max(d.accuracy, a.residual);
    noteRelaxed(d);
    if (a.splits > 0) splitFrame(d, a.splits);
    return true;
  } catch (e) {
    // A command is waiting (protocol.ts `interrupts`): the engine abandoned the step, the world
    // as before it; the command comes next and the steps go on after it.
    if ((e as { fields?: Record<string, unknown> } | null)?.fields?.cause === 'interrupted') return false;
    d.settings.playing = false;
    d.pausedByError = true;
    // The engine went back to the last state known good (its rewind points), or where it had
    // none to the start of the failing step.
    const back = (e as { fields?: Record<string, unknown> } | null)?.fields?.rewound_to;
    const rewoundTo = typeof back === 'number' ? back : undefined;
    if (rewoundTo !== undefined) d.bodyVersion++;
    d.stroke?.rebase(strokeBody(d));
    const integrator = String(d.world.params(0).integrator);
    d.hooks.message(explainStop(e, {
      integrator, dt: d.settings.dt, changes: d.changes, groundUnderBody: d.groundUnderBody, imported: d.imported,
      stableDt: integrator === 'implicit' ? undefined : d.world.stableDt(integrator), rewoundTo,
    }), 'error');
    return false;
  }
}

/** The largest residual an implicit step stopped by its deadline was accepted at (0: every step converged); starts again. */
export function takeAccuracy(d: DocState): number {
  const a = d.accuracy;
  d.accuracy = 0;
  return a;
}

/** Newton iterations of the last step, the most over the bodies. */
function newtonIterations(d: DocState): number {
  return Math.max(0, ...d.everyBody.map((b) => d.world.newtonIterations(b)));
}

/** After steps that may have been relaxed (the core's relaxed retry): count it, and say so once. */
function noteRelaxed(d: DocState): void {
  const r = Math.max(0, ...d.everyBody.map((b) => d.world.relaxed(b)));
  if (r === 0 || ++d.relaxedSteps !== 1) return;
  d.synced();
  d.hooks.message(`a step at t = ${fmt(d.world.body(0).stats.time)} s could not be finished with the surface's bending where faces are crushed flat; ` +
    `it was taken with ${r === 1 ? "those faces' bending" : 'all hinge bending'} let go for that step, so the simulation goes on (a crushed fold may keep its crease).`, 'warn');
}

/** A frame's step was split: after SPLIT_NOTICE such frames, say so once. */
function splitFrame(d: DocState, splits: number): void {
  if (++d.splitFrames !== SPLIT_NOTICE) return;
  d.hooks.message(`implicit steps of ${fmt(d.settings.dt)} s did not converge in ${SPLIT_NOTICE} frames (the last split in ${splits + 1}); ` +
    'those frames ran as shorter steps. More damping, a looser tolerance or a smaller dt avoids it.', 'warn');
}
