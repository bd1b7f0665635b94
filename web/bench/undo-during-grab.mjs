// Undo pressed right after a grab on a large model, as a user would, in Chromium at the
// modeler's defaults: the mushroom subdivided SUB times (U), its top dragged with the mouse and
// let go; at once, while the body still swings back (the page ignores Undo while the mouse
// drags: app.ts), Ctrl+Z. Prints the wall-clock ms from the key to the undo being seen (the
// history's undo count falls) and whether the page is cross-origin isolated (the worker
// abandons a running step only then: src/protocol.ts `interrupts`).
//   node bench/undo-during-grab.mjs [SUB=3] [DIST=dist]
import { launch, openModeler, startServer, topVertex } from '../e2e/harness.mjs';

const sub = Number(process.argv[2] ?? 3);
const dist = process.argv[3] ?? 'dist';
const browser = await launch();
const { url, stop } = await startServer(Number(process.env.E2E_PORT ?? 5189), dist);
const { page, ctx } = await openModeler(browser, url);
for (let s = 0; s < sub; s++) {
  const n = await page.evaluate(() => window.softsculpt.vertexCount());
  await page.keyboard.press('u');
  await page.waitForFunction((m) => window.softsculpt.vertexCount() > m && !window.softsculpt.busy(), n, { timeout: 300000 });
}
const nv = await page.evaluate(() => window.softsculpt.vertexCount());
const isolated = await page.evaluate(() => globalThis.crossOriginIsolated === true);
await page.waitForTimeout(3000);
const top = await topVertex(page);
const from = top.screen;
await page.mouse.move(from.x, from.y);
await page.mouse.down();
for (let i = 1; i <= 10; i++) { await page.mouse.move(from.x + 15 * i, from.y - 10 * i); await page.waitForTimeout(50); }
// The grab becomes an undo step when the worker takes the mouse's release.
const before = await page.evaluate(() => window.softsculpt.history()[0]);
await page.mouse.up();
await page.waitForFunction((u) => window.softsculpt.history()[0] > u, before, { timeout: 300000, polling: 10 });
const undos = await page.evaluate(() => window.softsculpt.history()[0]);
const t0 = Date.now();
await page.keyboard.press('Control+z');
await page.waitForFunction((u) => window.softsculpt.history()[0] < u, undos, { timeout: 300000, polling: 10 });
const ms = Date.now() - t0;
console.log(`${dist}: ${nv} vertices, cross-origin isolated ${isolated}: undo seen ${ms} ms after the key`);
await ctx.close();
await browser.close();
stop();
process.exit(0);
