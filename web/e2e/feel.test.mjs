// The modeler as a user meets it (issue 10): keys after panel clicks, a calm turntable camera,
// stops explained once, tools that say when they cannot act, the brush ring and its keys, mirror
// symmetry, the strain view, the first-visit hint. Each test was written against the page before
// these changes and failed there. Driven with the mouse and keys at default settings.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { animationFrames, browserSuite, dist, drag, inspect, openModeler, settle, shot, simulate, steady, topVertex, until, vertex } from './harness.mjs';

const suite = browserSuite();

const modelList = (page) => page.locator('.lil-controller', { hasText: 'built-in' }).locator('select');
async function load(page, name) {
  await modelList(page).selectOption(name);
  await page.waitForFunction((n) => window.softsculpt.settings().model === n && !window.softsculpt.busy(), name, { timeout: 60000 });
  // A model arrives at rest: half a simulated second lets it start moving before it is seen to settle.
  await simulate(page, 0.5);
  await settle(page, 0.05, 30000);
}
/** The material list's value as shown (lil-gui's select named "material"). */
const materialShown = (page, value) => until(page, (v) => [...document.querySelectorAll('.lil-controller')].find((c) => c.querySelector('.lil-name')?.textContent === 'material')?.querySelector('select')?.value === v, value, 15000);
const view = (page) => inspect(page, () => window.softsculpt.view());
/** The camera's azimuth about the vertical through its target (degrees). */
const azimuth = (v) => (Math.atan2(v.position[2] - v.target[2], v.position[0] - v.target[0]) * 180) / Math.PI;
const range = (v) => Math.hypot(...v.position.map((p, i) => p - v.target[i]));
/** On screen: the vertex nearest the camera at 60 % of the model's height (the mushroom's cap front). */
const capFront = (page) => inspect(page, () => {
  const S = window.softsculpt, x = S.positions(), cam = S.view().position;
  let lo = Infinity, hi = -Infinity;
  for (let i = 1; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); }
  let best = -1, bd = Infinity;
  for (let i = 0; i < x.length / 3; i++) {
    if (Math.abs(x[3 * i + 1] - (lo + 0.6 * (hi - lo))) > 0.08 * (hi - lo)) continue;
    const d = Math.hypot(x[3 * i] - cam[0], x[3 * i + 1] - cam[1], x[3 * i + 2] - cam[2]);
    if (d < bd) { bd = d; best = i; }
  }
  return S.screenOf(best);
});

test('shortcuts work after clicking the panel, and letter keys never change the model list', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // A checkbox clicked with the mouse, then P: the press tool (before: the key went to the checkbox).
  await page.locator('.lil-controller', { hasText: 'mirror Y' }).locator('input').click();
  await page.keyboard.press('p');
  assert.equal(await inspect(page, () => window.softsculpt.tool()), 'press');
  // The sphere chosen in the list, then M (the mass tool): before, M switched the list to mushroom.
  await load(page, 'sphere');
  await modelList(page).focus();
  await page.keyboard.press('m');
  await until(page, () => window.softsculpt.tool() === 'mass');
  // Had the list taken the key, its load would be handled by the worker before these steps.
  await simulate(page, 0.3);
  assert.equal(await inspect(page, () => window.softsculpt.tool()), 'mass');
  assert.equal(await inspect(page, () => window.softsculpt.settings().model), 'sphere');
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), 642);
  // Space after a button click plays or pauses; it does not click the button again.
  const undoSizes = await inspect(page, () => window.softsculpt.history());
  await page.locator('#panel button', { hasText: 'Undo' }).click();
  // The worker takes commands between its ticks, in order: frames simulated after the click carry the undo's history.
  await simulate(page, 0.2);
  const afterUndo = await inspect(page, () => window.softsculpt.history());
  await page.keyboard.press('Space');
  await until(page, () => window.softsculpt.playing() === false);
  assert.equal(await inspect(page, () => window.softsculpt.playing()), false);
  // Paused, the worker sends nothing to wait on: Space again plays (had Space clicked the button,
  // it would undo once more each time), and the frames simulated then carry any undo sent before.
  await page.keyboard.press('Space');
  await simulate(page, 0.2);
  assert.deepEqual(await inspect(page, () => window.softsculpt.history()), afterUndo, `one undo only (before: ${undoSizes})`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the camera turns as a turntable, stops with the mouse, keeps the horizon level, stays outside the model; V frames it', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  const v0 = await view(page);
  assert.equal(v0.mode, 'turntable');
  // A 60 px drag on empty space (the lower left, off the model).
  await page.mouse.move(150, 500);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) { await page.mouse.move(150 + 6 * i, 500); await page.waitForTimeout(16); } // paces the moves, as a hand does
  await page.mouse.up();
  const v1 = await view(page);
  const turned = Math.abs(azimuth(v1) - azimuth(v0));
  // 0.8 turns per view height: 0.8 · 360° · 60 / 800 ≈ 21.6°; before, the trackball turned ~60°.
  assert.ok(turned > 10 && turned < 35, `turned ${turned}° for 60 px`);
  // Inertia (damped per frame) or an ease (per page second) would show within 90 frames (1.5 s at 60 fps, longer on a slow page).
  await animationFrames(page, 90);
  const v2 = await view(page);
  assert.ok(dist(v1.position, v2.position) < 1e-9, 'no drift after the mouse stops');
  // Dragged far up and down: never under the floor (the ground would hide the model).
  for (const dy of [500, -500]) {
    await page.mouse.move(150, dy > 0 ? 150 : 700);
    await page.mouse.down();
    await page.mouse.move(150, dy > 0 ? 650 : 200, { steps: 10 });
    await page.mouse.up();
    const v = await view(page);
    assert.ok(v.position[1] > v.target[1], `camera at y ${v.position[1]}, target ${v.target[1]}`);
  }
  // A level horizon: the camera's right axis stays horizontal.
  assert.ok(Math.abs(v1.right[1]) < 1e-9, `horizon tilt ${v1.right[1]}`);
  // Twenty wheel clicks inward: the camera stops outside the model's bounding sphere.
  await page.mouse.move(640, 400);
  for (let i = 0; i < 20; i++) { await page.mouse.wheel(0, -200); await page.waitForTimeout(30); } // paces the clicks, as a hand does
  await animationFrames(page);
  const radius = await inspect(page, () => {
    const x = window.softsculpt.positions(), c = window.softsculpt.view().target;
    let r = 0;
    for (let i = 0; i < x.length; i += 3) r = Math.max(r, Math.hypot(x[i] - c[0], x[i + 1] - c[1], x[i + 2] - c[2]));
    return r;
  });
  const near = await view(page);
  assert.ok(range(near) > radius, `camera ${range(near)} m from the centre, model radius ${radius} m`);
  // Pan away, then V: the model is back in the middle of the view at the framing distance.
  await page.mouse.move(300, 300);
  await page.mouse.down({ button: 'right' });
  await page.mouse.move(500, 450, { steps: 8 });
  await page.mouse.up({ button: 'right' });
  await page.keyboard.press('v');
  await animationFrames(page); // V sets the view at once (camera.ts frame)
  const framed = await view(page);
  assert.ok(range(framed) > 2 * radius && range(framed) < 6 * radius, `framed at ${range(framed)} m for radius ${radius} m`);
  const centre = await inspect(page, () => {
    const x = window.softsculpt.positions();
    let best = 0, lo = Infinity, hi = -Infinity;
    for (let i = 1; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); }
    for (let i = 0; i < x.length / 3; i++) if (Math.abs(x[3 * i + 1] - (lo + hi) / 2) < Math.abs(x[3 * best + 1] - (lo + hi) / 2)) best = i;
    return window.softsculpt.screenOf(best);
  });
  assert.ok(Math.abs(centre.y - 400) < 120, `model's middle at y = ${centre.y} px of 800`);
  await shot(page, '40-framed');
  // The trackball stays selectable.
  await page.locator('.lil-title', { hasText: 'View' }).click();
  await page.locator('.lil-controller', { hasText: 'camera' }).locator('select').selectOption('free trackball');
  assert.equal((await view(page)).mode, 'trackball');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('raising the ground lifts the rooted mushroom with it: it stands on the plane, whole, and keeps playing', async () => {
  // A new-user trial: the ground at 0.1 m buried the mushroom's pinned foot and crushed its
  // stem; at 0.5 m the step failed and the page paused.
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  const span = () => inspect(page, () => { const x = window.softsculpt.positions(); let lo = Infinity, hi = -Infinity; for (let i = 1; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); } return [lo, hi]; });
  const [lo0, hi0] = await span();
  await page.locator('.lil-title', { hasText: 'Gravity & ground' }).click();
  const height = page.locator('.lil-controller', { hasText: 'ground height' }).locator('input').first();
  await height.fill('0.5');
  await height.press('Enter');
  // The plane is raised with the next frame; 2.5 simulated seconds show the mushroom resting there and still playing.
  await simulate(page, 2.5);
  const [lo1, hi1] = await span();
  // On the raised plane to rounding (its pinned foot moved with it), and as tall as before: the
  // mushroom was resting, and a translation changes no force (1 cm: the settle's own wobble).
  assert.ok(Math.abs(lo1 - 0.5) < 1e-6, `lowest vertex at ${lo1} m`);
  assert.ok(Math.abs((hi1 - lo1) - (hi0 - lo0)) < 0.01, `height ${hi1 - lo1} m, was ${hi0 - lo0} m`);
  assert.equal(await inspect(page, () => window.softsculpt.playing()), true);
  assert.deepEqual((await inspect(page, () => window.softsculpt.messages())).filter((m) => m.kind === 'error'), []);
  await shot(page, '49-ground-raised');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a blow-up is said once in the user\'s terms, the view frames the model put back, and loading a model plays again', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  // An explicit integrator at the panel's largest step blows the mushroom up.
  await page.locator('.lil-title', { hasText: 'Simulation' }).click();
  await page.locator('.lil-controller', { hasText: 'integrator' }).locator('select').selectOption('symplectic');
  const dt = page.locator('.lil-controller', { hasText: 'dt (s)' }).locator('input').first();
  await dt.fill('0.02');
  await dt.press('Enter');
  await page.waitForFunction(() => window.softsculpt.playing() === false, null, { timeout: 30000 });
  // Said in the tick that paused (worker/document.ts); the ticks after it do not step, so nothing more is said.
  await until(page, () => window.softsculpt.messages().some((m) => m.kind === 'error'));
  const errorsShown = (await inspect(page, () => window.softsculpt.messages())).filter((m) => m.kind === 'error');
  assert.equal(errorsShown.length, 1, JSON.stringify(errorsShown));
  const text = errorsShown[0].text;
  assert.match(text, /blew up at t = \d+(\.\d{1,2})? s|turned inside out at t = \d+(\.\d{1,2})? s/, text);
  assert.doesNotMatch(text, /step \d{2,}|\d[eE][+-]?\d|\d{5,}/, `no step counts or raw floats: ${text}`);
  assert.match(text, /Likely cause: (setting the time step|the time step)/, text);
  assert.equal(text.match(/smaller dt/g)?.length ?? 0, text.includes('smaller dt') ? 1 : 0, 'advice once');
  // The readout stays readable: the message does not cover it.
  const [readout, message] = await Promise.all(['.readout', '.message.error'].map((s) => page.locator(s).boundingBox()));
  assert.ok(message.y > readout.y + readout.height || message.x > readout.x + readout.width, 'the message is clear of the readout');
  // The view shows the model as it was put back (the camera follows where the model is, not the
  // path it took: the blow-up's excursion is undone with it), and the plots start again at the
  // time it was put back to.
  // The view eases back (FOLLOW_TAU) on the page's clock (nothing simulates while paused): wait
  // for the vertices to be on screen, then check them.
  // Times are said to three significant digits (format.ts sig3: 7.6 s, 7.74 s, 10.2 s). The frame
  // put back may come after the message: wait until the time drawn is the one said.
  const sig3 = (t) => String(Number(t.toPrecision(3)));
  const said = text.match(/put back to t = ([\d.]+) s/)?.[1];
  await until(page, (t) => String(Number(window.softsculpt.stats().time.toPrecision(3))) === t, said);
  const canvas = await page.locator('#view').boundingBox();
  const shown = [(await topVertex(page)).index, 0];
  await page.waitForFunction(([c, is]) => is.every((i) => { const p = window.softsculpt.screenOf(i); return p.x > c.x && p.x < c.x + c.width && p.y > c.y && p.y < c.y + c.height; }), [canvas, shown], { timeout: 10000 }).catch(() => {});
  for (const i of shown) {
    const p = await inspect(page, (j) => window.softsculpt.screenOf(j), i);
    assert.ok(p.x > canvas.x && p.x < canvas.x + canvas.width && p.y > canvas.y && p.y < canvas.y + canvas.height, `vertex ${i} on screen at ${p.x}, ${p.y}`);
  }
  const back = await inspect(page, () => window.softsculpt.stats().time);
  assert.ok((await inspect(page, () => window.softsculpt.plots())).every((s) => s.values.length <= 2), 'the plots restarted at the time put back to');
  assert.equal(said, sig3(back), `put back to t = ${back} s: ${text}`);
  await shot(page, '41-blow-up-message');
  // Another model: plays again, the old notes go; the error is not cleared by it (it goes by
  // itself after its reading time, at least 10 s: view/hud.ts messageLifetime).
  await modelList(page).selectOption('sphere');
  await page.waitForFunction(() => window.softsculpt.settings().model === 'sphere' && !window.softsculpt.busy(), null, { timeout: 60000 });
  assert.equal(await inspect(page, () => window.softsculpt.playing()), true);
  assert.equal((await inspect(page, () => window.softsculpt.messages())).filter((m) => /blew up|inside out/.test(m.text)).length, 1, 'the error stays with the new model');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a grab while paused says why nothing happens and adds no undo step', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  await page.keyboard.press('Space');
  await page.waitForFunction(() => window.softsculpt.playing() === false);
  assert.equal(await inspect(page, () => window.softsculpt.banner()), 'Paused — Space to play');
  const before = await inspect(page, () => window.softsculpt.history());
  const top = await topVertex(page);
  await page.mouse.move(top.screen.x, top.screen.y + 20);
  await page.mouse.down();
  await page.mouse.move(top.screen.x + 40, top.screen.y - 60, { steps: 6 });
  await page.mouse.up();
  // The page refuses the stroke itself (app.ts: ACTS_WHILE_PLAYING): nothing goes to the worker.
  await until(page, () => /paused: the grab acts while the simulation plays/.test(window.softsculpt.lastMessage()));
  assert.deepEqual(await inspect(page, () => window.softsculpt.history()), before);
  assert.match(await inspect(page, () => window.softsculpt.lastMessage()), /paused: the grab acts while the simulation plays/);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('without a GPU the view is drawn within its pixel budget, the model sharp enough to see; "full resolution" draws every pixel', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  const buffer = () => inspect(page, () => {
    const c = document.querySelector('#view');
    return { w: c.width, h: c.height, cssW: c.clientWidth, cssH: c.clientHeight, ...window.softsculpt.drawing(), colours: window.softsculpt.pixels() };
  });
  const low = await buffer();
  // Chromium here draws WebGL with SwiftShader (--enable-unsafe-swiftshader), which reports no
  // performance caveat: the renderer's name must give it away.
  assert.equal(low.software, true, 'SwiftShader is recognised as a software renderer');
  // SOFTWARE_PIXELS (viewport.ts) is 300,000; the buffer's sides are rounded down to whole pixels.
  assert.ok(low.w * low.h <= 300000 && low.w * low.h > 280000, `drawn at ${low.w} × ${low.h} for a ${low.cssW} × ${low.cssH} canvas`);
  assert.ok(Math.abs(low.w / low.h - low.cssW / low.cssH) < 0.01, 'the same aspect as the canvas');
  // The shaded body, the ground and the grid: many colours, not a blank or a flat fill.
  assert.ok(low.colours > 50, `the view shows the model: ${low.colours} colours in a 64 × 64 sample`);
  await shot(page, '50-software-budget');
  // Paused, the view redraws only when something changes: the toggle must draw it again itself.
  await page.keyboard.press('Space');
  await page.waitForFunction(() => window.softsculpt.playing() === false);
  await page.locator('.lil-title', { hasText: 'View' }).click();
  // The frames stepped before the pause are drawn: the count of renders stops.
  await steady(page, () => window.softsculpt.drawing().renders);
  const still = await buffer();
  await animationFrames(page, 30);
  assert.equal((await buffer()).renders, still.renders, 'paused and untouched, the view is not redrawn');
  await page.locator('.lil-controller', { hasText: 'full resolution' }).locator('input').click();
  await page.waitForFunction(() => window.softsculpt.drawing().full === true);
  await until(page, (r) => window.softsculpt.drawing().renders > r, still.renders);
  const full = await buffer();
  assert.equal(full.pixelRatio, 1);
  assert.deepEqual([full.w, full.h], [full.cssW, full.cssH], 'every CSS pixel drawn');
  assert.ok(full.renders > still.renders, 'drawn again at full resolution');
  assert.ok(full.colours > 50, `${full.colours} colours`);
  await shot(page, '51-software-full');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the ? hint never covers the readout, in a narrow window too', async () => {
  // At 1000 px the hint (top right, left of the panel) starts where the readout's first line
  // ends; a slow-motion line is longer still (the 12th and 13th sessions' trials: cut off).
  const ctx = await suite.browser.newContext({ viewport: { width: 1000, height: 700 } });
  const { page, errors } = await openModeler(suite.browser, suite.server.url, ctx);
  // The readout's lines (pace, slow motion) come with the frames: a simulated second of them.
  await simulate(page, 1);
  const rects = await page.evaluate(() => ['readout', 'hint'].map((c) => document.querySelector(`#hud .${c}`).getBoundingClientRect().toJSON()));
  const [r, h] = rects;
  assert.equal(await inspect(page, () => window.softsculpt.hintVisible()), true, 'first visit: the ? hint');
  const overlap = r.left < h.right && h.left < r.right && r.top < h.bottom && h.top < r.bottom;
  await shot(page, '41-hint-narrow');
  assert.ok(!overlap, JSON.stringify(rects));
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('the brush ring shows the radius and strength under the cursor; keys and B set them', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  assert.equal(await inspect(page, () => window.softsculpt.hintVisible()), true, 'first visit: the ? hint');
  const top = await topVertex(page);
  await page.mouse.move(top.screen.x, top.screen.y + 30);
  await until(page, () => window.softsculpt.ring() !== null);
  let ring = await inspect(page, () => window.softsculpt.ring());
  assert.ok(ring && Math.abs(ring.radius - 0.35) < 1e-12, JSON.stringify(ring));
  await shot(page, '42-brush-ring');
  await page.keyboard.press(']');
  await until(page, (r) => window.softsculpt.ring()?.radius > r, ring.radius);
  ring = await inspect(page, () => window.softsculpt.ring());
  assert.ok(Math.abs(ring.radius - 0.35 * 1.2) < 1e-9, `] grows the ring: ${ring.radius}`);
  const f0 = ring.fraction;
  await page.keyboard.press('}');
  await until(page, (f) => window.softsculpt.ring()?.fraction > f, f0);
  ring = await inspect(page, () => window.softsculpt.ring());
  assert.ok(ring.fraction > f0, 'a stronger pull shows on the ring');
  assert.ok(Math.abs((await inspect(page, () => window.softsculpt.brush())).strength - 600 * 1.2) < 1e-9);
  // B: the radius follows the mouse; Esc puts it back, a click sets it.
  const r0 = (await inspect(page, () => window.softsculpt.brush())).radius;
  await page.keyboard.press('b');
  await page.mouse.move(top.screen.x + 150, top.screen.y + 30, { steps: 5 });
  const grown = (await inspect(page, () => window.softsculpt.brush())).radius;
  assert.ok(Math.abs(grown / r0 - Math.E) < 0.05, `150 px right: ×e (${grown / r0})`);
  assert.match(await inspect(page, () => window.softsculpt.banner()), /brush radius .* m/);
  await page.keyboard.press('Escape');
  assert.equal((await inspect(page, () => window.softsculpt.brush())).radius, r0);
  await page.keyboard.press('b');
  await page.mouse.move(top.screen.x, top.screen.y + 30, { steps: 5 });
  const history = await inspect(page, () => window.softsculpt.history());
  await page.mouse.click(top.screen.x, top.screen.y + 30);
  // A stroke would reach the worker and come back in the history of the frames simulated after it.
  await simulate(page, 0.3);
  assert.deepEqual(await inspect(page, () => window.softsculpt.history()), history, 'the setting click is not a stroke');
  assert.equal(await inspect(page, () => window.softsculpt.banner()), null, 'the click set it: the banner is gone');
  await page.keyboard.press('?');
  assert.equal(await inspect(page, () => window.softsculpt.hintVisible()), false);
  // The panel fits the window.
  const panel = await page.locator('#panel').boundingBox();
  assert.ok(panel.y + panel.height <= 800, `panel bottom at ${panel.y + panel.height} px`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('mirror X: a press on one side of the sphere dents its mirror image as much', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await load(page, 'sphere');
  assert.deepEqual(await inspect(page, () => window.softsculpt.symmetry()), [true, false, false], 'X on for a symmetric model');
  await load(page, 'bunny');
  assert.deepEqual(await inspect(page, () => window.softsculpt.symmetry()), [false, false, false], 'off for the bunny');
  await load(page, 'sphere');
  // The vertex facing the camera most on the +x side, and the vertex nearest its mirror image.
  const pick = await inspect(page, () => {
    const x = window.softsculpt.positions(), n = x.length / 3, cam = window.softsculpt.view().position;
    let cx = 0;
    for (let i = 0; i < n; i++) cx += x[3 * i] / n;
    let a = -1, best = Infinity;
    for (let i = 0; i < n; i++) {
      if (x[3 * i] < cx + 0.3) continue;
      const d = Math.hypot(x[3 * i] - cam[0], x[3 * i + 1] - cam[1], x[3 * i + 2] - cam[2]);
      if (d < best) { best = d; a = i; }
    }
    const m = [2 * cx - x[3 * a], x[3 * a + 1], x[3 * a + 2]];
    let b = 0;
    for (let i = 0; i < n; i++) if (Math.hypot(x[3 * i] - m[0], x[3 * i + 1] - m[1], x[3 * i + 2] - m[2]) < Math.hypot(x[3 * b] - m[0], x[3 * b + 1] - m[1], x[3 * b + 2] - m[2])) b = i;
    return { a, b, screen: window.softsculpt.screenOf(a) };
  });
  const [a0, b0] = [await vertex(page, pick.a), await vertex(page, pick.b)];
  await page.keyboard.press('p');
  await page.mouse.move(pick.screen.x, pick.screen.y);
  await page.mouse.down();
  await simulate(page, 1.5);
  const [a1, b1] = [await vertex(page, pick.a), await vertex(page, pick.b)];
  await page.mouse.up();
  const da = dist(a0, a1), db = dist(b0, b1);
  assert.ok(da > 0.03, `the pressed side moved ${da} m`);
  // The mirror image is pressed by the same brush at the mirrored point: the same dent up to the
  // nearest-vertex mismatch of the tessellation (the sphere is exactly symmetric: 25 %).
  assert.ok(Math.abs(da - db) < 0.25 * da, `mirror moved ${db} m vs ${da} m`);
  await shot(page, '43-mirror-press');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the strain view colours the stretch of a grab and fades back to white', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  await page.locator('.lil-title', { hasText: 'View' }).click();
  await page.locator('.lil-controller', { hasText: 'strain view' }).locator('input').click();
  await page.waitForFunction(() => window.softsculpt.strain().length === window.softsculpt.vertexCount());
  const top = await topVertex(page);
  await page.mouse.move(top.screen.x, top.screen.y + 10);
  await page.mouse.down();
  await page.mouse.move(top.screen.x, top.screen.y - 120, { steps: 10 });
  await simulate(page, 1.2);
  const held = await inspect(page, () => Math.max(...window.softsculpt.strain()));
  await shot(page, '44-strain-view');
  await page.mouse.up();
  assert.ok(held > 0.02, `the pulled springs are stretched: ${held}`);
  await simulate(page, 3);
  const released = await inspect(page, () => Math.max(...window.softsculpt.strain().map(Math.abs)));
  assert.ok(released < held / 2, `released, the stretch springs back: ${released} (held ${held})`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a pen\'s pressure scales the press: a light touch dents less than a firm one', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await load(page, 'sphere');
  await page.keyboard.press('p');
  const top = await topVertex(page);
  const at = { x: top.screen.x, y: top.screen.y + 40 };
  /** Press with a pen at `pressure` for 1.5 simulated seconds: how far the vertex under it went in (m). */
  const press = async (pressure) => {
    await settle(page, 0.02, 30000);
    const i = await inspect(page, (p) => {
      const x = window.softsculpt.positions();
      let best = 0, d = Infinity;
      for (let k = 0; k < x.length / 3; k++) {
        const s = window.softsculpt.screenOf(k);
        const e = Math.hypot(s.x - p.x, s.y - p.y) + (x[3 * k + 2] < 0 ? 1e6 : 0); // the front side
        if (e < d) { d = e; best = k; }
      }
      return best;
    }, at);
    const before = await vertex(page, i);
    const pen = (type, extra = {}) => page.evaluate(({ type, at, extra }) => {
      const target = type === 'pointerdown' ? document.getElementById('view') : window;
      target.dispatchEvent(new PointerEvent(type, { pointerType: 'pen', pointerId: 7, isPrimary: true, button: 0, buttons: 1, clientX: at.x, clientY: at.y, bubbles: true, ...extra }));
    }, { type, at, extra });
    await pen('pointerdown', { pressure });
    await pen('pointermove', { pressure });
    await simulate(page, 1.5);
    const during = await vertex(page, i);
    await pen('pointerup', { pressure: 0, buttons: 0 });
    return dist(before, during);
  };
  const light = await press(0.2);
  const firm = await press(1);
  // The depth is the strength × the pressure: 0.2 of the firm dent, up to what the body's own
  // springs add (the dent is held by target springs of finite stiffness): between 0.1 and 0.45.
  assert.ok(firm > 0.05, `a firm press dents ${firm} m`);
  assert.ok(light / firm > 0.1 && light / firm < 0.45, `light ${light} m vs firm ${firm} m`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the kangaroo stands on its pinned feet, and a material preset keeps a frozen body\'s shape', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await load(page, 'kangaroo');
  await simulate(page, 2);
  const extent = await inspect(page, () => {
    const x = window.softsculpt.positions(), lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < x.length; i++) { lo[i % 3] = Math.min(lo[i % 3], x[i]); hi[i % 3] = Math.max(hi[i % 3], x[i]); }
    return hi.map((h, d) => h - lo[d]);
  });
  // Sketched from a side view (2.5 m long, 1.2 m tall, 0.55 m thick): standing, its height is
  // its outline's; lying on its side (before) it was 0.55 m.
  assert.ok(extent[1] > 1.0, `the kangaroo is ${extent.map((e) => e.toFixed(2)).join(' × ')} m (x × y × z)`);
  await shot(page, '45-kangaroo-standing');
  // Jelly has less gas than the modeler's mushroom: on a frozen body the pressure difference the
  // springs carry is kept, so it does not shrink (before: 2.51 → 1.71 m³).
  await load(page, 'mushroom');
  await page.keyboard.press('f');
  await until(page, () => /frozen/.test(window.softsculpt.lastMessage()));
  const v0 = (await inspect(page, () => window.softsculpt.stats())).volume;
  await page.locator('.lil-controller', { hasText: 'material' }).locator('select').selectOption('jelly');
  await simulate(page, 3);
  const v1 = (await inspect(page, () => window.softsculpt.stats())).volume;
  assert.ok(Math.abs(v1 / v0 - 1) < 0.1, `volume ${v0} → ${v1} m³ with jelly`);
  // Clay on the mushroom as it stands: it keeps its height (before: it slumped into an egg,
  // 1.83 → 1.2 m, its stem yielding under the cap's weight), and a press leaves a dent.
  await load(page, 'mushroom');
  const height = () => inspect(page, () => Math.max(...window.softsculpt.positions().filter((_, k) => k % 3 === 1)));
  const h0 = await height();
  await page.locator('.lil-controller', { hasText: 'material' }).locator('select').selectOption('clay');
  await simulate(page, 3);
  const h1 = await height();
  assert.ok(h1 > 0.97 * h0, `clay: height ${h0} → ${h1} m`);
  // Another model starts with the modeler's own material: the list forgets "clay" and names it.
  await load(page, 'sphere');
  const shown = await page.locator('.lil-controller', { hasText: 'material' }).locator('select').evaluate((s) => s.options[s.selectedIndex]?.text);
  assert.equal(shown, 'modeler\'s own', 'a fresh model shows the modeler\'s material');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('clay keeps the shape a mirrored grab pulls and the gas in it: the body does not collapse afterwards', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await load(page, 'mushroom');
  await page.locator('.lil-controller', { hasText: 'material' }).locator('select').selectOption('clay');
  await simulate(page, 2);
  const v0 = (await inspect(page, () => window.softsculpt.stats())).volume;
  // The front of the cap at 60 % of the height (mirror X is on for the mushroom: its image on
  // the other side is pulled too), dragged 150 px up and out, held 2 simulated seconds, let go.
  const front = await capFront(page);
  await page.keyboard.press('g');
  await drag(page, front, { x: front.x + 106, y: front.y - 106 }, 15, 2);
  await page.mouse.up();
  await simulate(page, 3);
  const v1 = (await inspect(page, () => window.softsculpt.stats())).volume;
  await shot(page, '46-clay-after-a-mirrored-pull');
  // Before, every flow of the pulled springs raised the gas's reference pressure until it sucked
  // the body in: 2.46 → 0.008 m³. The pull itself may squeeze the body (natively an elastic one
  // under such a pull keeps 62 % of its volume at least; measured here after the fix: 93 %).
  assert.ok(v1 > 0.6 * v0, `clay after a mirrored pull: volume ${v0} → ${v1} m³`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a subdivided model keeps its shape: the octopus keeps standing, the mushroom\'s cap keeps its volume under a grab', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  const height = () => inspect(page, () => { const y = window.softsculpt.positions().filter((_, k) => k % 3 === 1); return Math.max(...y) - Math.min(...y); });
  await load(page, 'octopus');
  await simulate(page, 1.5);
  const h0 = await height();
  await page.keyboard.press('u');
  await page.waitForFunction(() => window.softsculpt.positions().length > 3000 && !window.softsculpt.busy(), null, { timeout: 60000 });
  await simulate(page, 3);
  const h1 = await height();
  await shot(page, '47-octopus-subdivided-standing');
  // Loop subdivision lifted the tentacle tips off the ground (6.4 mm), so the freeze under load
  // found no support and the octopus sagged 1.76 → 1.33 m within a second, its tentacles
  // splayed; Loop's smoothing itself changes the height by a centimetre.
  assert.ok(h1 > 0.97 * h0, `the subdivided octopus: height ${h0} → ${h1} m`);
  // The mushroom subdivided once, its cap pulled 150 px out (mirror X: both sides) and held: with
  // bending springs alone, 4× weaker in flexure per subdivision, it took 5.4 % of the volume and
  // creased the cap (the unsubdivided one 0.3 %); the hinges' rigidity does not depend on the mesh.
  await load(page, 'mushroom');
  await page.keyboard.press('u');
  await page.waitForFunction(() => window.softsculpt.positions().length > 3000 && !window.softsculpt.busy(), null, { timeout: 60000 });
  await simulate(page, 2);
  const v0 = (await inspect(page, () => window.softsculpt.stats())).volume;
  const front = await capFront(page);
  await page.keyboard.press('g');
  await drag(page, front, { x: front.x + 106, y: front.y - 106 }, 15, 2);
  const held = (await inspect(page, () => window.softsculpt.stats())).volume;
  await shot(page, '48-subdivided-mushroom-grabbed');
  // Let go, and wait 2.5 simulated seconds: the cap swings back within them (sooner, it was still
  // swinging: 1.3 % over its volume).
  const tUp = (await inspect(page, () => window.softsculpt.stats())).time;
  await page.mouse.up();
  await page.waitForFunction((t) => window.softsculpt.stats().time >= t + 2.5, tUp, { timeout: 90000 });
  const after = (await inspect(page, () => window.softsculpt.stats())).volume;
  // Measured with the real engine in Node: 0.7 % lost while held (5.4 % without hinges) and
  // all of it back after; a browser's drag differs in its path, so 2 % and 1 %.
  assert.ok(held > 0.98 * v0, `the subdivided mushroom's volume under the grab: ${v0} → ${held} m³`);
  assert.ok(Math.abs(after / v0 - 1) < 0.01, `after letting go: ${v0} → ${after} m³`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the view does not creep: after three grabs and the wobbles that follow, the camera is back where it was', async () => {
  // Before: the camera followed each wobble that left its dead zone (a quarter of the model's
  // radius) and kept what it had followed — the new-user trial saw the target move 0.15 m over
  // one grab and ~27 px over four (view/camera.ts). Now it seeks the set view moved only by what
  // the model's centre is beyond the zone, so once the model is back, so is the view.
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.01, 30000);
  const v0 = await view(page);
  let moved = 0;
  for (const [dx, dy] of [[-220, -60], [200, -120], [0, -200]]) {
    const p = await capFront(page);
    await drag(page, p, { x: p.x + dx, y: p.y + dy }, 20, 0.7);
    await page.mouse.up();
    // The wobble after the release (1.5 simulated seconds): the view may follow it for a moment.
    for (let i = 0; i < 6; i++) {
      await simulate(page, 0.25);
      moved = Math.max(moved, dist((await view(page)).target, v0.target));
    }
  }
  // Held still by the grab, it can be slower than the threshold: let the release take effect first.
  await simulate(page, 0.3);
  await settle(page, 0.005, 60000);
  // The view eases back with τ = 0.1 s of the page's clock and stops within a millionth of the
  // model's size (camera.ts follow): wait until it has stopped, to 10 µm.
  await steady(page, () => window.softsculpt.view().position.concat(window.softsculpt.view().target).map((c) => Math.round(c * 1e5)), null, { timeout: 60000 });
  const v1 = await view(page);
  await shot(page, 'feel-no-creep');
  // The model's centre at rest comes back to within millimetres (the rest shape is the same;
  // friction on the ground can leave it a few mm off), so does the view: within 1 cm of 1.2 m
  // (under 2 px at this distance), against 0.15 m before.
  assert.ok(dist(v1.target, v0.target) < 0.01, `target moved ${dist(v1.target, v0.target)} m (at most ${moved} m during the wobbles)`);
  assert.ok(dist(v1.position, v0.position) < 0.01, `camera moved ${dist(v1.position, v0.position)} m`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('V frames the model where it lies now: a sphere pulled across the ground is centred, not where it arrived', async () => {
  // Before: V framed the centre measured when the model arrived (a new-user trial: a kangaroo
  // that fell on its side was framed 0.6 m above and beside where it lay).
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await load(page, 'sphere');
  const box = () => inspect(page, () => {
    const x = window.softsculpt.positions(), lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < x.length; i++) { lo[i % 3] = Math.min(lo[i % 3], x[i]); hi[i % 3] = Math.max(hi[i % 3], x[i]); }
    return lo.map((l, d) => (l + hi[d]) / 2);
  });
  const c0 = await box();
  // Dragged sideways by its top for 2 simulated seconds: it rolls and slides along the ground.
  const p = await capFront(page);
  await drag(page, p, { x: p.x + 330, y: p.y }, 30, 2);
  await page.mouse.up();
  await simulate(page, 0.3); // the release takes effect (held, it can be slower than the threshold)
  await settle(page, 0.01, 60000);
  // Paused, so what V frames is exactly what is measured (settled is below 1 cm/s, not still:
  // a full run once measured the sphere 1 mm lower by the time V was pressed).
  await page.keyboard.press('Space');
  await page.waitForFunction(() => !window.softsculpt.playing());
  // A frame stepped before the worker took the pause may still come: wait until the drawn time stops.
  await steady(page, () => window.softsculpt.stats().time);
  const c1 = await box();
  assert.ok(dist(c1, c0) > 0.3, `the sphere moved ${dist(c1, c0)} m`);
  await page.keyboard.press('v');
  await animationFrames(page); // V sets the view at once (camera.ts frame)
  const v = await view(page);
  // The target is the bounding sphere's centre (three.js: the bounding box's centre) of the
  // positions drawn; the body is at rest, so within a millimetre.
  assert.ok(dist(v.target, c1) < 1e-3, `framed ${v.target.map((t) => t.toFixed(3))}, the sphere at ${c1.map((t) => t.toFixed(3))}`);
  await shot(page, 'feel-frame-where-it-lies');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('an opened project names its material, in a browser that has never seen it', async () => {
  // A new-user trial: clay chosen, the project saved, opened in a fresh browser — the list said
  // "modeler's own" (it names materials by values learned in this browser's storage).
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  const materialList = (p) => p.locator('.lil-controller:has(.lil-name:text-is("material")) select');
  await materialList(page).selectOption('clay');
  await page.waitForFunction(() => /material: clay/.test(window.softsculpt.lastMessage()), null, { timeout: 15000 });
  await materialShown(page, 'clay');
  assert.equal(await materialList(page).inputValue(), 'clay');
  const stiffness = await inspect(page, () => window.softsculpt.param('stiffness'));
  const [download] = await Promise.all([page.waitForEvent('download'), page.keyboard.press('Control+s')]);
  // The message comes from the worker in a message of its own after the download's: waited for,
  // not read at once (CI's fresh clone read the clay message still showing).
  await page.waitForFunction(() => /^saved the project .*in your downloads/.test(window.softsculpt.lastMessage()), null, { timeout: 15000 });
  const path = join(tmpdir(), 'clay.softsculpt.json');
  await download.saveAs(path);
  await page.context().close();
  const fresh = await openModeler(suite.browser, suite.server.url);
  assert.equal(await materialList(fresh.page).inputValue(), 'modeler\'s own');
  await fresh.page.locator('input[data-picker=project]').setInputFiles(path);
  await fresh.page.waitForFunction((k) => window.softsculpt.param('stiffness') === k, stiffness, { timeout: 15000 });
  await materialShown(fresh.page, 'clay');
  assert.equal(await materialList(fresh.page).inputValue(), 'clay');
  await shot(fresh.page, 'feel-project-material');
  assert.deepEqual([...errors, ...fresh.errors], []);
  await fresh.page.context().close();
});

test('the mirrored brush ring sits on the surface, not off it', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  // Mirror X is on for the symmetric mushroom: the ring under the cursor and its mirror image.
  const top = await topVertex(page);
  await page.mouse.move(top.screen.x + 70, top.screen.y + 40);
  await page.waitForFunction(() => window.softsculpt.ring()?.copies === 2, null, { timeout: 5000 });
  // Each centre's distance to the surface (the nearest point of any triangle, Ericson's
  // closest-point test): the one under the cursor is a picked point (0 up to rounding), the
  // mirror image was off by the asymmetry of the mesh and its motion (before: 1.9 mm here);
  // on the surface it is within 1 mm (the ray's hit, in float32 positions).
  const off = await inspect(page, () => {
    const s = window.softsculpt, x = s.positions(), t = s.triangles();
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]], dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const closest = (p, a, b, c) => {
      const ab = sub(b, a), ac = sub(c, a), ap = sub(p, a), d1 = dot(ab, ap), d2 = dot(ac, ap);
      if (d1 <= 0 && d2 <= 0) return a;
      const bp = sub(p, b), d3 = dot(ab, bp), d4 = dot(ac, bp);
      if (d3 >= 0 && d4 <= d3) return b;
      const vc = d1 * d4 - d3 * d2;
      if (vc <= 0 && d1 >= 0 && d3 <= 0) { const v = d1 / (d1 - d3); return [a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]]; }
      const cp = sub(p, c), d5 = dot(ab, cp), d6 = dot(ac, cp);
      if (d6 >= 0 && d5 <= d6) return c;
      const vb = d5 * d2 - d1 * d6;
      if (vb <= 0 && d2 >= 0 && d6 <= 0) { const w = d2 / (d2 - d6); return [a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]]; }
      const va = d3 * d6 - d5 * d4;
      if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) { const w = (d4 - d3) / (d4 - d3 + (d5 - d6)); return [b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])]; }
      const den = 1 / (va + vb + vc), v = vb * den, w = vc * den;
      return [a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w];
    };
    const at = (i) => [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
    return s.ring().centres.map((p) => {
      let best = Infinity;
      for (let f = 0; f < t.length; f += 3) { const q = closest(p, at(t[f]), at(t[f + 1]), at(t[f + 2])); best = Math.min(best, Math.hypot(...sub(p, q))); }
      return best;
    });
  });
  assert.ok(off.every((d) => d < 1e-3), `ring centres ${off.map((d) => (1000 * d).toFixed(2)).join(', ')} mm off the surface`);
  assert.deepEqual(errors, []);
  await page.context().close();
});
