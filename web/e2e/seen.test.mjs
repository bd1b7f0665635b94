// What the page shows can be seen: W's wind leans the model across the view (not along the line
// of sight), every line of the HUD's readout stays clear of the panel and the window's edges, and
// the "Press ?" hint stays where it is when the readout or the messages change. Mouse and keys at
// default settings, in Chromium.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { animationFrames, browserSuite, drag, inspect, openModeler, settle, shot, simulate, topVertex } from './harness.mjs';

const suite = browserSuite();

/** The rim of the mushroom's cap: the vertices within a tenth of the height of its widest ring. */
const rimOf = (page) => inspect(page, () => {
  const x = window.softsculpt.positions();
  let top = -Infinity, wide = 0, wideY = 0;
  for (let i = 0; i < x.length; i += 3) top = Math.max(top, x[i + 1]);
  for (let i = 0; i < x.length; i += 3) { const r = Math.hypot(x[i], x[i + 2]); if (r > wide) { wide = r; wideY = x[i + 1]; } }
  const rim = [];
  for (let i = 0; i < x.length; i += 3) if (Math.abs(x[i + 1] - wideY) < 0.1 * top) rim.push(i / 3);
  return rim;
});
/** The centre of vertices `ids` (m) and where it shows on the page (px), with the view as it is now. */
const seenCentre = (page, ids) => inspect(page, (ids) => {
  const x = window.softsculpt.positions(), c = [0, 0, 0];
  for (const i of ids) for (let d = 0; d < 3; d++) c[d] += x[3 * i + d] / ids.length;
  return { position: c, screen: window.softsculpt.screenOfPoint(c) };
}, ids);
/** The camera's right on the ground (unit, m), as the view is now. */
const groundRight = (page) => inspect(page, () => {
  const r = window.softsculpt.view().right, n = Math.hypot(r[0], r[2]);
  return [r[0] / n, 0, r[2] / n];
});

test('W leans the mushroom across the view: its cap sways sideways on screen, not along the line of sight', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await settle(page, 0.05, 30000);
  const rim = await rimOf(page);
  const before = await seenCentre(page, rim);
  await page.mouse.move(100, 700);
  await page.keyboard.press('w');
  await page.waitForFunction(() => window.softsculpt.param('wind').some((c) => c !== 0), null, { timeout: 10000 });
  const wind = await inspect(page, () => window.softsculpt.param('wind'));
  const right = await groundRight(page);
  const speed = Math.hypot(...wind);
  await simulate(page, 3); // three seconds of simulated time in the wind
  const after = await seenCentre(page, rim);
  const moved = after.position.map((v, d) => v - before.position[d]);
  const sideways = moved[0] * right[0] + moved[2] * right[2];
  const px = Math.hypot(after.screen.x - before.screen.x, after.screen.y - before.screen.y);
  await shot(page, 'seen-01-wind-across');
  console.log(`rim: ${(100 * sideways).toFixed(1)} cm sideways, ${(100 * Math.hypot(...moved)).toFixed(1)} cm in all, ${px.toFixed(1)} px on screen, wind ${JSON.stringify(wind)} (${speed.toFixed(2)} m/s)`);
  // Horizontal, from the screen's left to its right.
  assert.equal(wind[1], 0, `the wind ${JSON.stringify(wind)} is horizontal`);
  assert.ok((wind[0] * right[0] + wind[2] * right[2]) / speed > 0.999, `the wind ${JSON.stringify(wind)} blows towards the view's right ${JSON.stringify(right)}`);
  assert.ok(sideways >= 0.05, `the cap's rim moved ${(100 * sideways).toFixed(1)} cm sideways (moved ${JSON.stringify(moved)}) in the wind ${JSON.stringify(wind)}`);
  assert.ok(px >= 15, `the cap's rim moved ${px.toFixed(1)} px on screen (${JSON.stringify(before.screen)} → ${JSON.stringify(after.screen)})`);
  // The arrow that shows the wind is in the view.
  await animationFrames(page);
  const a = await inspect(page, () => window.softsculpt.windArrow());
  for (const [name, p] of [['tail', a.tail], ['tip', a.tip]]) assert.ok(p.x > 0 && p.x < 1280 && p.y > 0 && p.y < 800, `the arrow's ${name} ${JSON.stringify(p)} in the view`);
  // Shift+W calms it.
  await page.keyboard.press('Shift+W');
  await page.waitForFunction(() => window.softsculpt.param('wind').every((c) => c === 0), null, { timeout: 10000 });
  assert.deepEqual(errors, []);
  await page.context().close();
});

/** Open folder `title` of the panel (closed ones are rarely used). */
async function openFolder(page, title) {
  const t = page.locator('.lil-title', { hasText: title }).first();
  if ((await t.getAttribute('aria-expanded')) === 'false') await t.click();
}
/** Type `value` into the panel's number field `name` and press Enter, as a user sets it. */
async function typeInto(page, name, value) {
  const field = page.locator('.lil-controller', { hasText: name }).locator('input').first();
  await field.fill(String(value));
  await field.press('Enter');
}
/**
 * The readout's lines as laid out (each line box of its text, page px), the panel's and the hint's
 * boxes (null: hidden), and the window's size.
 */
const layout = (page) => page.evaluate(() => {
  const box = (e) => (e && !e.hidden ? e.getBoundingClientRect().toJSON() : null);
  const readout = document.querySelector('#hud .readout');
  const range = document.createRange();
  range.selectNodeContents(readout);
  const lines = [...range.getClientRects()].filter((r) => r.width > 0).map((r) => r.toJSON());
  return { lines, text: readout.textContent, panel: box(document.getElementById('panel')), hint: box(document.querySelector('#hud .hint')), width: innerWidth, height: innerHeight };
});
const overlaps = (a, b) => !!a && !!b && a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
/** Every line of the readout inside the window and clear of the panel and the hint. */
function assertReadoutClear(l, when) {
  assert.ok(l.lines.length >= 3, `${when}: the readout's lines ${JSON.stringify(l.lines)}`);
  for (const r of l.lines) {
    const where = `${when}: a readout line ${JSON.stringify(r)} of ${JSON.stringify(l.text)}`;
    assert.ok(r.top >= 0 && r.left >= 0 && r.right <= l.width && r.bottom <= l.height, `${where} inside the window ${l.width} × ${l.height}`);
    assert.ok(!overlaps(r, l.panel), `${where} clear of the panel ${JSON.stringify(l.panel)}`);
    assert.ok(!overlaps(r, l.hint), `${where} clear of the hint ${JSON.stringify(l.hint)}`);
  }
}

test('in slow motion every line of the readout shows, clear of the panel and the ? hint', async () => {
  const ctx = await suite.browser.newContext({ viewport: { width: 1000, height: 700 } });
  const { page, errors } = await openModeler(suite.browser, suite.server.url, ctx);
  await openFolder(page, 'Simulation');
  await typeInto(page, 'dt (s)', '0.000001');
  // Its first line grows: "… % of real time (slow motion) … new shape …/s".
  await page.waitForFunction(() => /slow motion\)/.test(document.querySelector('#hud .readout')?.textContent ?? ''), null, { timeout: 30000 });
  await animationFrames(page);
  const first = await layout(page);
  await shot(page, 'seen-02-slow-motion-readout');
  assertReadoutClear(first, 'first visit, with the hint');
  // Once help has been seen the hint is gone: the readout may reach the panel, not under it.
  await page.keyboard.press('?');
  await page.keyboard.press('Escape');
  await page.waitForFunction(() => /slow motion\)/.test(document.querySelector('#hud .readout')?.textContent ?? ''), null, { timeout: 30000 });
  await animationFrames(page);
  const later = await layout(page);
  assert.equal(later.hint, null, 'the hint is gone');
  assertReadoutClear(later, 'after help');
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('the ? hint stays where it is through a grab, whatever the readout and the messages say', async () => {
  const ctx = await suite.browser.newContext({ viewport: { width: 1280, height: 800 } });
  const { page, errors } = await openModeler(suite.browser, suite.server.url, ctx);
  await settle(page, 0.05, 30000);
  const hint = () => page.evaluate(() => document.querySelector('#hud .hint').getBoundingClientRect().toJSON());
  const before = await hint();
  // Where the hint is in every drawn frame from here on.
  await page.evaluate(() => {
    const seen = (window.__hintTops = new Set());
    const f = () => { const h = document.querySelector('#hud .hint'); if (!h.hidden) seen.add(Math.round(h.getBoundingClientRect().top)); requestAnimationFrame(f); };
    requestAnimationFrame(f);
  });
  const top = await topVertex(page);
  await page.keyboard.press('g');
  await drag(page, top.screen, { x: top.screen.x + 120, y: top.screen.y - 60 }, 20, 1.5);
  await page.mouse.up();
  await simulate(page, 1);
  await shot(page, 'seen-03-hint-after-grab');
  const after = await hint();
  const tops = await page.evaluate(() => [...window.__hintTops]);
  assert.equal(await inspect(page, () => window.softsculpt.hintVisible()), true, 'first visit: the hint shows');
  assert.deepEqual(after, before, `the hint's box before the grab ${JSON.stringify(before)}, after ${JSON.stringify(after)}`);
  assert.deepEqual(tops, [Math.round(before.top)], `the hint's top in every frame: ${tops}`);
  assertReadoutClear(await layout(page), 'after the grab');
  assert.deepEqual(errors, []);
  await ctx.close();
});
