// Largest mesh that runs in real time in Chromium at default settings: import icospheres of
// growing size into the modeler and read how much of real time the simulation keeps up with.
//   node bench/realtime.mjs [levels=3,4,5] [DIST…]   (needs web/dist built; several builds, e.g.
//   `dist /tmp/softsculpt-main-dist` from bench/baseline.sh, are measured side by side, level by
//   level, in one run)
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, openModeler, startServer } from '../e2e/harness.mjs';
import { writeIcosphere } from '../e2e/icosphere.mjs';

const levels = (process.argv[2] ?? '3,4,5').split(',').map(Number);
const dists = process.argv.length > 3 ? process.argv.slice(3) : ['dist'];
const dir = mkdtempSync(join(tmpdir(), 'ico-'));
const browser = await launch();
const servers = [];
for (const [k, dist] of dists.entries()) servers.push({ dist, ...(await startServer(5197 + k, dist)) });
console.log('build  vertices  dt (s)  sim s per real s  fps  sim ms/frame');
for (const level of levels) {
  const file = writeIcosphere(dir, level);
  const n = 10 * 4 ** level + 2;
  for (const { dist, url } of servers) {
    // One page at a time (each its own context), so that the builds never run side by side.
    const { page, ctx } = await openModeler(browser, url);
    await page.locator('input[data-picker=import]').setInputFiles(file);
    await page.waitForFunction((v) => window.softsculpt.vertexCount() === v && !window.softsculpt.busy?.(), n, { timeout: 120000 });
    await page.waitForTimeout(2000);
    const t0 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now()]);
    await page.waitForTimeout(5000);
    const t1 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now(), window.softsculpt.fps(), window.softsculpt.simMs(), window.softsculpt.settings().dt]);
    const ratio = (t1[0] - t0[0]) / ((t1[1] - t0[1]) / 1000);
    console.log(`${dist}  ${String(n).padStart(8)}  ${t1[4].toExponential(0)}  ${ratio.toFixed(3).padStart(16)}  ${t1[2].toFixed(0).padStart(3)}  ${t1[3].toFixed(1).padStart(12)}`);
    await ctx.close();
  }
}
await browser.close();
for (const s of servers) s.stop();
