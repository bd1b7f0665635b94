// Largest mesh that runs in real time in Chromium at default settings: import icospheres of
// growing size into the modeler and read how much of real time the simulation keeps up with.
//   node bench/realtime.mjs [levels=3,4,5]   (needs web/dist built and python3)
import { execFileSync } from 'node:child_process';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launch, openModeler, startServer } from '../e2e/harness.mjs';

const levels = (process.argv[2] ?? '3,4,5').split(',');
const dir = mkdtempSync(join(tmpdir(), 'ico-'));
const gen = fileURLToPath(new URL('../../../shared/bench/gen_icosphere.py', import.meta.url));
execFileSync('python3', [gen, dir, ...levels]);
const server = await startServer(5197);
const browser = await launch();
const { page } = await openModeler(browser, server.url);
console.log('vertices  dt (s)  sim s per real s  fps  sim ms/frame');
for (const level of levels) {
  const file = join(dir, `icosphere_L${level}.obj`);
  await page.locator('input[type=file][accept*=".obj"]').setInputFiles(file);
  await page.waitForFunction((l) => window.softsculpt.vertexCount() === 10 * 4 ** l + 2, Number(level), { timeout: 120000 });
  await page.waitForTimeout(2000);
  const t0 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now()]);
  await page.waitForTimeout(5000);
  const t1 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now(), window.softsculpt.fps(), window.softsculpt.simMs(), window.softsculpt.settings().dt]);
  const ratio = (t1[0] - t0[0]) / ((t1[1] - t0[1]) / 1000);
  console.log(`${String(10 * 4 ** level + 2).padStart(8)}  ${t1[4].toExponential(0)}  ${ratio.toFixed(2).padStart(16)}  ${t1[2].toFixed(0).padStart(3)}  ${t1[3].toFixed(1).padStart(12)}`);
}
await browser.close();
server.stop();
