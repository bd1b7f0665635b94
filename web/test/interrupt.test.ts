// A step in progress makes way for a command (protocol.ts `interrupts`, the engine's
// `WorldSettings::interrupt`): the page counts interrupting commands into memory it shares with
// the worker, and the engine, asking between its solver's iterations, abandons the step with
// the world as it was. Here the page is another thread that sends its command while this one
// is inside a long implicit step.
import { beforeAll, expect, it } from 'vitest';
import { Worker } from 'node:worker_threads';
import { loadEngine, openedDocument } from './setup';
import { World } from '../src/engine/world';
import { tookInterrupt, useInterrupts } from '../src/engine/wasm';

beforeAll(loadEngine);

/** The standard workload at 10,242 vertices on implicit 1/60 s steps to 1e-9: a step of 0.2–0.35 s in wasm here (4 Newton iterations). */
function slowWorld(): World {
  const w = World.workload(5);
  w.setParam(0, 'integrator', 'implicit');
  w.setParam(0, 'dt', 1 / 60);
  w.setParam(0, 'tolerance', 1e-9);
  return w;
}

/** One 1/60 s frame under a real-time budget out of reach (every step converged): the interrupt is asked under a real-time budget. */
function frame(w: World): void {
  w.advance(1 / 60, 1e9);
}

/** A thread that, once told to go, waits `ms` and then sends an interrupting command (counts it, as client.ts does). */
function page(shared: SharedArrayBuffer, ms: number): Worker {
  return new Worker(`
    const { workerData } = require('node:worker_threads');
    const c = new Int32Array(workerData.shared);
    Atomics.wait(c, 2, 0);
    Atomics.wait(c, 3, 0, workerData.ms);
    Atomics.add(c, 0, 1);`, { eval: true, workerData: { shared, ms } });
}

it('a command sent during a long step ends it at once, the world as before the step; the steps then go on', async () => {
  const shared = new SharedArrayBuffer(16);
  const c = new Int32Array(shared);
  useInterrupts(shared);

  const a = slowWorld();
  let t0 = performance.now();
  frame(a);
  const whole = performance.now() - t0;

  const b = slowWorld();
  const before = b.snapshot();
  const thread = page(shared, whole / 10);
  await new Promise((r) => setTimeout(r, 100)); // the thread started and waits
  Atomics.store(c, 2, 1);
  Atomics.notify(c, 2);
  t0 = performance.now();
  let cause: unknown;
  try { frame(b); } catch (e) { cause = (e as { fields?: Record<string, unknown> }).fields?.cause; }
  const cut = performance.now() - t0;
  await thread.terminate();
  console.log(`whole step ${whole.toFixed(0)} ms, interrupted after ${cut.toFixed(0)} ms`);
  expect(cause).toBe('interrupted');
  // Asked between iterations (a conjugate-gradient iteration here is ~1 ms of the 0.2–0.35 s
  // step): it ends soon after the command, well before the step would have.
  expect(cut).toBeLessThan(whole / 2);
  expect(b.snapshot()).toEqual(before);

  // The worker takes the command; the next step is the step it would have been.
  tookInterrupt();
  frame(b);
  expect(b.snapshot()).toEqual(a.snapshot());
}, 120_000);

it('the document’s frame under a real-time budget makes way for a command: not paused, the world as before the step', async () => {
  // The page's path (`Document.advance` → the core's `World::advance` with the worker's
  // interrupt): the default mushroom subdivided twice (5,762 vertices), its tolerance at 1e-12
  // and every vertex shaken at up to 0.1 m/s (a step far from rest: many Newton iterations),
  // under a budget too long to stop the solve (1e6 s): only the command can end it.
  const shared = new SharedArrayBuffer(16);
  const c = new Int32Array(shared);
  useInterrupts(shared);
  const { doc } = openedDocument();
  doc.subdivide(); doc.subdivide();
  doc.setParam('tolerance', 1e-12);
  const v = doc.world.body(0).velocities;
  for (let k = 0; k < v.length; k++) v[k] = 0.1 * Math.sin(12.9898 * k);
  const dt = doc.settings.dt;
  const before = doc.world.snapshot();
  let t0 = performance.now();
  expect(doc.advance(dt, 1)).toBe(true); // converged, uninterrupted: how long the frame takes
  const whole = performance.now() - t0;
  doc.world.restore(before);

  const thread = page(shared, whole / 10);
  await new Promise((r) => setTimeout(r, 100));
  Atomics.store(c, 2, 1);
  Atomics.notify(c, 2);
  t0 = performance.now();
  const ok = doc.advance(dt, 1, 1e6);
  const cut = performance.now() - t0;
  await thread.terminate();
  console.log(`whole frame ${whole.toFixed(0)} ms, interrupted after ${cut.toFixed(0)} ms`);
  expect(ok).toBe(false);
  expect(doc.lastAdvance).toBeNull();
  // Interrupted, not failed: still playing, nothing to say, and the world as it was.
  expect(doc.settings.playing).toBe(true);
  expect(cut).toBeLessThan(whole / 2);
  expect(doc.world.snapshot()).toEqual(before);
  tookInterrupt();
  expect(doc.advance(dt, 1, 1e6)).toBe(true);
}, 300_000);
