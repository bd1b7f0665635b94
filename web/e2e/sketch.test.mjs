// The sketch tool: an outline drawn with the mouse becomes a closed balloon inflated by gas.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite, shot, inspect, openModeler } from './harness.mjs';

const suite = browserSuite();

/** Press, move through `points` (page pixels) and release: one stroke. */
async function stroke(page, points) {
  await page.mouse.move(points[0].x, points[0].y);
  await page.mouse.down();
  for (const p of points.slice(1)) await page.mouse.move(p.x, p.y, { steps: 4 });
  await page.mouse.up();
}

/** A five-pointed star of `r` px about (cx, cy), closed back to its first point. */
function star(cx, cy, r) {
  const pts = [];
  for (let k = 0; k <= 10; k++) {
    const a = -Math.PI / 2 + (Math.PI * k) / 5, rr = k % 2 === 0 ? r : 0.45 * r;
    pts.push({ x: cx + rr * Math.cos(a), y: cy + rr * Math.sin(a) });
  }
  return pts;
}

test('a star drawn with the sketch tool becomes a closed inflated balloon, undoable', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  await page.waitForFunction(() => window.softsculpt.ready);
  const before = await inspect(page, () => window.softsculpt.vertexCount());
  await page.keyboard.press('k');
  assert.equal(await inspect(page, () => window.softsculpt.tool()), 'sketch');
  await stroke(page, star(330, 330, 160));
  await page.waitForFunction(() => /sketched a balloon/.test(window.softsculpt.lastMessage()), null, { timeout: 60000 });
  await page.waitForFunction((n) => window.softsculpt.vertexCount() !== n, before, { timeout: 10000 });
  const v = await inspect(page, () => window.softsculpt.vertexCount());
  const f = await inspect(page, () => window.softsculpt.faceCount());
  const s = await inspect(page, () => window.softsculpt.stats());
  // A closed surface of a sphere's topology: F = 2V − 4 (Euler: V − E + F = 2, E = 3F/2).
  assert.equal(f, 2 * v - 4, `${v} vertices, ${f} faces`);
  assert.ok(s.volume > 0 && s.pressure > 0, `volume ${s.volume}, pressure ${s.pressure}: inflated`);
  await page.waitForTimeout(500);
  await shot(page, 'sketch-star-balloon');
  // Undo brings the mushroom back.
  await page.keyboard.press('Control+z');
  await page.waitForFunction((n) => window.softsculpt.vertexCount() === n, before, { timeout: 10000 });
  // A bow tie crosses itself: one clear message, the model unchanged.
  await stroke(page, [{ x: 250, y: 250 }, { x: 450, y: 450 }, { x: 450, y: 250 }, { x: 250, y: 450 }, { x: 250, y: 260 }]);
  await page.waitForFunction(() => /crosses itself/.test(window.softsculpt.lastMessage()), null, { timeout: 20000 });
  // In the user's terms: what to draw, not the crossing edges' numbers and coordinates (the CLI's).
  const said = await inspect(page, () => window.softsculpt.lastMessage());
  assert.match(said, /draw it without crossing/);
  assert.doesNotMatch(said, /edge \d|\(-?\d/, said);
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), before);
  assert.deepEqual(errors, []);
  await page.context().close();
});
