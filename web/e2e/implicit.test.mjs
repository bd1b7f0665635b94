// The modeler on implicit steps (issue 9): one 1/60 s backward-Euler step per frame, the grab
// and the press as target springs inside the step, subdivision keeping dt. Driven with the
// mouse at default settings; effects read through `window.softsculpt`.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { browserSuite, shot, dist, drag, inspect, openModeler, settle, simulate, topVertex, vertex } from './harness.mjs';
import { writeIcosphere } from './icosphere.mjs';

const suite = browserSuite();

/** Load a built-in model from the panel's list and wait until it is drawn and settled. */
async function load(page, name) {
  if ((await inspect(page, () => window.softsculpt.settings().model)) !== name) {
    await page.locator('.lil-controller', { hasText: 'built-in' }).locator('select').selectOption(name);
    await page.waitForFunction((n) => window.softsculpt.settings().model === n && !window.softsculpt.busy(), name, { timeout: 60000 });
  }
  // Half a second of simulation first: a model just loaded is still (it has not started falling).
  await simulate(page, 0.5);
  await settle(page, 0.05, 30000);
}

/** Set the active tool's strength through its panel field (as a user types it). */
async function setStrength(page, label, value) {
  const field = page.locator('.lil-controller', { hasText: label }).locator('input').first();
  await field.fill(String(value));
  await field.press('Enter');
}

/** Highest point (m) of the body. */
const height = (page) => inspect(page, () => { const x = window.softsculpt.positions(); let h = -Infinity; for (let i = 1; i < x.length; i += 3) h = Math.max(h, x[i]); return h; });

/** Height (m) of the body: highest minus lowest point. */
const extent = (page) => inspect(page, () => { const x = window.softsculpt.positions(); let lo = Infinity, hi = -Infinity; for (let i = 1; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); } return hi - lo; });

/**
 * The highest vertex of the side facing the camera (its direction from the centre of mass within
 * 60° of the camera's): on a sphere the top vertex itself sits on the outline, where a click can
 * miss the surface.
 */
const upperFront = (page) => inspect(page, () => {
  const s = window.softsculpt, x = s.positions(), c = s.stats().centerOfMass, e = s.camera();
  const unit = (v) => { const l = Math.hypot(...v); return v.map((a) => a / l); };
  const d = unit([e[0] - c[0], e[1] - c[1], e[2] - c[2]]);
  let best = -1;
  for (let i = 0; i < x.length / 3; i++) {
    const n = unit([x[3 * i] - c[0], x[3 * i + 1] - c[1], x[3 * i + 2] - c[2]]);
    if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] >= 0.5 && (best < 0 || x[3 * i + 1] > x[3 * best + 1])) best = i;
  }
  return best;
});

/**
 * Hold the grab on vertex `i`'s screen point, 3 px towards the body's centre of mass on screen
 * (a top vertex sits on the outline, where the press can miss the surface and turn the camera
 * instead), and drag by (dx, dy) px, then hold it there `holdS` seconds of simulated time (a loaded
 * machine or a fine mesh runs below real time: the wall clock would give the body less time to
 * follow the cursor); returns the cursor.
 */
async function grabAndHold(page, i, dx, dy, holdS) {
  const from = await inspect(page, (j) => {
    const s = window.softsculpt, v = s.screenOf(j), c = s.screenOfPoint(s.stats().centerOfMass);
    const l = Math.hypot(c.x - v.x, c.y - v.y) || 1;
    return { x: v.x + (3 * (c.x - v.x)) / l, y: v.y + (3 * (c.y - v.y)) / l };
  }, i);
  const to = { x: from.x + dx, y: from.y + dy };
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let k = 1; k <= 15; k++) {
    await page.mouse.move(from.x + (dx * k) / 15, from.y + (dy * k) / 15);
    await page.waitForTimeout(30); // paces the drag's moves, as a hand does
  }
  await simulate(page, holdS, 120000);
  return to;
}

test('the modeler steps implicitly, one 1/60 s step per frame, by default', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  assert.equal(await inspect(page, () => window.softsculpt.param('integrator')), 'implicit');
  assert.ok(Math.abs((await inspect(page, () => window.softsculpt.settings().dt)) - 1 / 60) < 1e-12);
  assert.deepEqual(errors, []);
  await page.context().close();
});

for (const model of ['mushroom', 'sphere', 'octopus', 'bunny']) {
  test(`a grab on the ${model} keeps the grabbed point on the cursor, and the strongest grab stays finite`, async () => {
    const { page, errors } = await openModeler(suite.browser, suite.server.url);
    await load(page, model);
    const top = await topVertex(page);
    // Up and to the right, 120 px in all (about 0.4 m here), held 2 s to let it come to rest.
    const cursor = await grabAndHold(page, top.index, 70, -100, 2);
    const at = await inspect(page, (j) => window.softsculpt.screenOf(j), top.index);
    await shot(page, `20-grab-${model}`);
    await page.mouse.up();
    // The grabbed vertex's target is the cursor's point plus its offset from the click point,
    // 3 px (the press is 3 px inside the vertex) or a fraction of an edge; the target spring
    // (ω = 600 1/s) holds it there against the body (k = 100 N/m springs): within 8 px.
    const off = Math.hypot(at.x - cursor.x, at.y - cursor.y);
    assert.ok(off < 8, `the grabbed point is ${off.toFixed(1)} px from the cursor`);

    // Strongest pull, a fast long drag: stays finite, and the body comes back after release.
    await page.keyboard.press('g');
    await setStrength(page, 'pull ω', 3000);
    await settle(page, 0.05, 30000);
    const again = await topVertex(page);
    await grabAndHold(page, again.index, -200, -150, 1);
    await shot(page, `21-grab-strongest-${model}`);
    await page.mouse.up();
    await simulate(page, 0.3); // the release taken (held, it can be slower than the threshold)
    await settle(page, 0.05, 30000);
    const x = await inspect(page, () => window.softsculpt.positions());
    assert.ok(x.every(Number.isFinite), 'positions finite');
    assert.ok(await inspect(page, () => window.softsculpt.playing()), 'still playing (no blow-up)');
    assert.deepEqual(errors, []);
    await page.context().close();
  });
}

test('the press dents the mushroom cap, which comes back upright after release', async () => {
  const { page } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.02, 30000);
  const top = await topVertex(page);
  const c0 = (await inspect(page, () => window.softsculpt.stats())).centerOfMass;
  await page.keyboard.press('p');
  await page.mouse.move(top.screen.x, top.screen.y);
  await page.mouse.down();
  await simulate(page, 2.5); // the default press held 2.5 s of simulation (what toppled it before)
  const pressed = await vertex(page, top.index);
  await shot(page, '22-press-mushroom');
  await page.mouse.up();
  // Default depth 0.15 m at the centre: the cap's top goes down by more than 5 cm.
  assert.ok(top.position[1] - pressed[1] > 0.05, `the top went down by ${top.position[1] - pressed[1]} m while pressed`);
  await simulate(page, 0.3);
  await settle(page, 0.02, 30000);
  // Released and settled: upright again. The cap centre within 5 cm of where it was and the
  // centre of mass within 3 cm (the stem foot is pinned; toppling moves both by ~1 m).
  const back = await vertex(page, top.index);
  const c1 = (await inspect(page, () => window.softsculpt.stats())).centerOfMass;
  await shot(page, '23-press-released');
  assert.ok(dist(back, top.position) < 0.05, `the cap's top is ${dist(back, top.position)} m from where it was`);
  assert.ok(dist(c1, c0) < 0.03, `the centre of mass moved ${dist(c1, c0)} m`);
  await page.context().close();
});

test('subdivide keeps dt at 1/60 s and the mushroom keeps its height', async () => {
  const { page } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.02, 30000);
  const h0 = await height(page);
  await page.keyboard.press('u');
  await page.waitForFunction(() => window.softsculpt.vertexCount() > 362 && !window.softsculpt.busy(), null, { timeout: 60000 });
  // (Loop subdivision itself moves the surface a little: 1.832 -> 1.830 m for the mushroom.)
  assert.ok(Math.abs((await inspect(page, () => window.softsculpt.settings().dt)) - 1 / 60) < 1e-12, 'dt stays 1/60 s');
  await simulate(page, 2, 60000);
  const h1 = await height(page);
  await shot(page, '24-subdivided');
  // Within 3 % (5 cm of 1.8 m): the finer mesh has the same material, so the same shape.
  assert.ok(Math.abs(h1 - h0) < 0.03 * h0, `height ${h0.toFixed(3)} -> ${h1.toFixed(3)} m after 2 s`);
  await page.context().close();
});

/** The 10,242-vertex icosphere as a user brings it, through the import dialog (Enter: the guessed answers). */
async function importedSphere() {
  const file = writeIcosphere(mkdtempSync(join(tmpdir(), 'ico-')), 5);
  const opened = await openModeler(suite.browser, suite.server.url);
  const page = opened.page;
  await page.locator('input[data-picker=import]').setInputFiles(file);
  await page.waitForSelector('.import-dialog', { timeout: 30000 });
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => window.softsculpt.vertexCount() === 10242 && !window.softsculpt.busy(), null, { timeout: 120000 });
  return opened;
}

test('an imported 10,242-vertex sphere rests where it stands; a grab keeps its point on the cursor and the sphere comes back', async () => {
  // The size the issue asks to run in real time at the defaults (the multigrid preconditioner
  // works from 8,000 vertices); the sphere as a user brings it, through the import dialog.
  const { page, errors } = await importedSphere();
  // Frozen under load at the import (worker/importer.ts): at rest at its own shape on the
  // ground from the start, below 5 mm/s (before, the preset's gas swelled it and it bounced).
  await settle(page, 0.005, 150000);
  const v0 = (await inspect(page, () => window.softsculpt.stats())).volume;
  const h0 = await extent(page);
  const top = await upperFront(page);
  // Held 2.5 s of simulated time (2.3–5.1 px at real time): a hold measured on the wall clock
  // would give a slower machine less simulated time to follow the cursor.
  const cursor = await grabAndHold(page, top, 40, -60, 2.5);
  const at = await inspect(page, (j) => window.softsculpt.screenOf(j), top);
  await shot(page, '25-grab-imported-10242');
  await page.mouse.up();
  // As for the built-ins above: the target spring holds the grabbed vertex within 8 px.
  const off = Math.hypot(at.x - cursor.x, at.y - cursor.y);
  assert.ok(off < 8, `the grabbed point is ${off.toFixed(1)} px from the cursor`);
  await simulate(page, 0.3);
  await settle(page, 0.005, 150000);
  // Released and settled: the shape holds (it may have rolled: the grab pulled sideways). The gas
  // (nRT fixed) and the springs set the volume at rest: within 1 % of before the grab (measured
  // 0.1–0.3 %). The height within 5 %: friction can hold the bottom sheared where it landed
  // again (measured 0.3–0.8 %, 3.8 % once on a loaded machine, where the grab ran in slow
  // motion); a stretched, crumpled or collapsed skin is far outside both.
  const v1 = (await inspect(page, () => window.softsculpt.stats())).volume;
  const h1 = await extent(page);
  console.log(`10,242 vertices: grab ${off.toFixed(1)} px off; volume ${v0.toFixed(4)} -> ${v1.toFixed(4)} m³; height ${h0.toFixed(4)} -> ${h1.toFixed(4)} m`);
  assert.ok(Math.abs(v1 - v0) < 0.01 * v0, `volume ${v0.toFixed(4)} -> ${v1.toFixed(4)} m³`);
  assert.ok(Math.abs(h1 - h0) < 0.05 * h0, `height ${h0.toFixed(4)} -> ${h1.toFixed(4)} m`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('stiff rubber at 10,242 vertices: a lift keeps moving towards the cursor, frame after frame, instead of stalling', async () => {
  // The imported sphere in the stiffest material, the grab's defaults. Before the split steps
  // and the anchors' travel per step (the core's World::advance, anchorpath.ts) the first
  // grabbed step from rest did not converge (3 x 100 Newton iterations, then a split) and each
  // slow step let the cursor run further ahead: this test on that build waited 13.7 s for a
  // step. Now: a frame every 1-2 s here (4 substeps of ~17 Newton iterations; longest wait
  // 2.6 s), the point 10 px from the cursor within the 20 s.
  const { page, errors } = await importedSphere();
  await settle(page, 0.005, 150000);
  await page.locator('.lil-controller', { hasText: 'material' }).locator('select').selectOption({ label: 'stiff rubber' });
  await page.waitForFunction(() => /material: stiff rubber/.test(window.softsculpt.lastMessage()), null, { timeout: 60000 });
  await simulate(page, 0.1, 150000); // frames of the new material (a settle on the old one's would pass at once)
  await settle(page, 0.005, 150000);
  const top = await topVertex(page);
  const from = { x: top.screen.x, y: top.screen.y + 3 }, to = { x: top.screen.x, y: top.screen.y + 3 - 160 };
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 16; i++) await page.mouse.move(from.x, from.y - 10 * i);
  // 20 s of wall clock: the longest wait between two new simulated times, and how close the
  // grabbed point came to the cursor.
  const watch = await page.evaluate(async ({ j, to }) => {
    let last = window.softsculpt.stats().time, since = performance.now(), longest = 0, closest = Infinity;
    const t0 = performance.now();
    while (performance.now() - t0 < 20000) {
      await new Promise((r) => setTimeout(r, 100));
      const t = window.softsculpt.stats().time, now = performance.now();
      if (t !== last) { longest = Math.max(longest, now - since); last = t; since = now; }
      const p = window.softsculpt.screenOf(j);
      closest = Math.min(closest, Math.hypot(p.x - to.x, p.y - to.y));
    }
    return { longest: Math.max(longest, performance.now() - since), closest };
  }, { j: top.index, to });
  await shot(page, '26-stiff-rubber-lift-10242');
  await page.mouse.up();
  console.log(`stiff rubber, 10,242 vertices, lifted 160 px: longest wait for a step ${(watch.longest / 1000).toFixed(1)} s; closest ${watch.closest.toFixed(0)} px`);
  // Frames keep coming: at most 8 s between two (2.6 s here, 13.7 s before; a loaded CI machine
  // may double the good case); the point comes at least half way (80 px) to the cursor.
  assert.ok(watch.longest < 8000, `no new step for ${(watch.longest / 1000).toFixed(1)} s`);
  assert.ok(watch.closest < 80, `the grabbed point came no closer than ${watch.closest.toFixed(0)} px to the cursor`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the page steps on both cores where it is cross-origin isolated, on one with ?threads=1, and the model rests the same', async () => {
  // The threaded build needs shared memory (COOP + COEP from `vite preview`) and a second core.
  // Without the threaded build (`make web` could not install the nightly toolchain) the page
  // runs on one thread: that is what is checked then.
  const [cores, built] = await (async () => {
    const { page, ctx } = await openModeler(suite.browser, suite.server.url);
    const r = await inspect(page, async () => [navigator.hardwareConcurrency, await fetch('/softsculpt-threads.wasm', { method: 'HEAD' }).then((r) => r.ok && r.headers.get('content-type') === 'application/wasm')]);
    await ctx.close();
    return r;
  })();
  if (!built) console.log('# no threaded build in dist: the page is checked on one thread');
  const rest = {};
  for (const [query, want] of [['', built ? Math.min(4, cores) : 1], ['?threads=1', 1]]) {
    const { page, ctx, errors } = await openModeler(suite.browser, suite.server.url + query);
    assert.equal(await inspect(page, () => window.softsculpt.threads()), want, `threads with '${query}'`);
    assert.equal(await inspect(page, () => crossOriginIsolated), true);
    if (want > 1) assert.match(await page.locator('#hud').innerText(), new RegExp(`on ${want} threads`));
    // The default mushroom settled on the ground: its height, on simulated time.
    await settle(page, 0.02, 60000);
    rest[query] = await extent(page);
    assert.deepEqual(errors, []);
    await ctx.close();
  }
  // The same model and steps: the converged rest shape does not depend on the thread count (the
  // implicit solve gives the same bits on any count; the frames' budgets may stop different
  // iterates on the way, and the rest is where the residual vanishes): 1 mm of its 1.8 m.
  assert.ok(Math.abs(rest[''] - rest['?threads=1']) < 1e-3, `rest heights ${rest['']} and ${rest['?threads=1']} m`);
});

test('the mushroom subdivided twice (5,762 vertices) follows a mouse grab within 10 px, and a released grab is taken back', async () => {
  const { page, ctx, errors } = await openModeler(suite.browser, suite.server.url);
  for (const n of [1442, 5762]) {
    await page.keyboard.press('u');
    await page.waitForFunction((m) => window.softsculpt.vertexCount() === m && !window.softsculpt.busy(), n, { timeout: 120000 });
  }
  await settle(page, 0.05, 120000);
  const top = await topVertex(page);
  const from = top.screen, to = { x: from.x + 150, y: from.y - 100 };
  await drag(page, from, to, 25);
  // Held for 1 s of simulated time (the grab's pull, ω = 600/s, reaches the cursor in ~10 ms;
  // the cap's inertia and the gas take a few tenths): the grabbed vertex under the cursor.
  await simulate(page, 1, 120000);
  const seen = await inspect(page, (i) => window.softsculpt.screenOf(i), top.index);
  const gap = Math.hypot(seen.x - to.x, seen.y - to.y);
  await shot(page, 'implicit-5762-grab-held');
  await page.mouse.up();
  assert.ok(gap < 10, `the grabbed vertex is ${gap.toFixed(1)} px from the cursor`);
  // Let go: the cap springs back towards its rest within 2 s of simulated time (a third of the
  // pull's 0.6 m on screen at most left).
  await simulate(page, 2, 120000);
  const after = await inspect(page, (i) => window.softsculpt.screenOf(i), top.index);
  assert.ok(Math.hypot(after.x - from.x, after.y - from.y) < Math.hypot(to.x - from.x, to.y - from.y) / 3, `back to ${after.x.toFixed(0)}, ${after.y.toFixed(0)} from ${from.x.toFixed(0)}, ${from.y.toFixed(0)}`);
  assert.deepEqual(errors, []);
  await ctx.close();
});
