// What the page shows can be seen: W's wind leans the model across the view (not along the line
// of sight). Mouse and keys at default settings, in Chromium.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { animationFrames, browserSuite, inspect, openModeler, settle, shot, simulate } from './harness.mjs';

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

