// The sketch tool: an outline drawn with the mouse becomes a closed balloon inflated by gas.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite, shot, inspect, openModeler, simulate } from './harness.mjs';

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
  await simulate(page, 0.5); // the balloon as it stands half a simulated second later
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

test('a balloon sketched on a view tilted down stands upright as drawn, not lying on the ground', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  // Tilt the view down (a drag down on empty space above the model turns the camera over it).
  await page.mouse.move(300, 120);
  await page.mouse.down();
  await page.mouse.move(300, 180, { steps: 10 });
  await page.mouse.up();
  const cam = await inspect(page, () => { const c = window.softsculpt.camera(); return c; });
  const target = await inspect(page, () => window.softsculpt.stats().centerOfMass);
  const d = [cam[0] - target[0], cam[1] - target[1], cam[2] - target[2]];
  const tilt = Math.atan2(d[1], Math.hypot(d[0], d[2])) * 180 / Math.PI;
  assert.ok(tilt > 35 && tilt < 80, `the view looks down at ${tilt.toFixed(0)}° (straight down, an outline lies as drawn)`);
  await page.keyboard.press('k');
  // Paused: the balloon as placed (a tall, narrow one standing on its end then falls over, as it should).
  await page.keyboard.press('Space');
  await page.waitForFunction(() => window.softsculpt.playing() === false);
  const before = await inspect(page, () => window.softsculpt.vertexCount());
  // A tall, narrow ellipse (80 × 320 px): its long axis up the screen.
  const ellipse = Array.from({ length: 25 }, (_, k) => ({ x: 330 + 40 * Math.cos((2 * Math.PI * k) / 24), y: 380 + 160 * Math.sin((2 * Math.PI * k) / 24) }));
  await stroke(page, ellipse);
  await page.waitForFunction(() => /sketched a balloon/.test(window.softsculpt.lastMessage()), null, { timeout: 60000 });
  await page.waitForFunction((n) => window.softsculpt.vertexCount() !== n, before, { timeout: 10000 });
  const x = await inspect(page, () => window.softsculpt.positions());
  const ext = [0, 1, 2].map((k) => { let lo = Infinity, hi = -Infinity; for (let i = k; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); } return hi - lo; });
  // Upright, the ellipse's long axis (4 times its short one) is the balloon's height: at least
  // twice its width or depth. On the view plane tilted down by θ the long axis ran cos θ up and
  // sin θ along the ground, as deep as tall at 45°.
  assert.ok(ext[1] > 2 * Math.max(ext[0], ext[2]), `${ext.map((e) => e.toFixed(2)).join(' × ')} m (x × y × z)`);
  await shot(page, 'sketch-tilted-upright');
  assert.deepEqual(errors, []);
  await page.context().close();
});
