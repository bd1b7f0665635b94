// Largest mesh that runs in real time in Chromium at the modeler's default settings (implicit,
// dt = 1/60 s): import icospheres of growing size into the modeler and read how much of real
// time the simulation keeps up with, at each implicit tolerance asked for (set in the panel's
// field, as a user would), with the body's volume and height at the end (the result the
// tolerance buys).
//   node bench/realtime.mjs [levels=3,4,5] [configs=default|1e-3,1e-4,1e-6,symplectic,material:clay] [DIST…]
// env SETTLE, MEASURE: seconds before and of the measurement (default 2, 5).
// (a config is an implicit tolerance, or an explicit integrator's name chosen in the panel,
// which then takes the stable dt the modeler picks for it, or material:NAME, a material preset
// chosen in the panel's list)
// (needs web/dist built; several builds, e.g. `dist /tmp/softsculpt-main-dist` from
// bench/baseline.sh, are measured side by side, level by level, in one run)
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, openModeler, startServer } from '../e2e/harness.mjs';
import { writeIcosphere } from '../e2e/icosphere.mjs';

const levels = (process.argv[2] ?? '3,4,5').split(',').map(Number);
const tolerances = (process.argv[3] ?? 'default').split(',');
const dists = process.argv.length > 4 ? process.argv.slice(4) : ['dist'];
const dir = mkdtempSync(join(tmpdir(), 'ico-'));
const browser = await launch();
const servers = [];
for (const [k, dist] of dists.entries()) servers.push({ dist, ...(await startServer(Number(process.env.E2E_PORT ?? 5197) + k, dist)) });
console.log('build  vertices  integrator  dt (s)  tolerance  sim s per real s  fps  sim ms/frame  volume (m³)  height (m)');
for (const level of levels) {
  const file = writeIcosphere(dir, level);
  const n = 10 * 4 ** level + 2;
  for (const { dist, url } of servers) {
    for (const tol of tolerances) {
      // One page at a time (each its own context), so that the builds never run side by side.
      const { page, ctx } = await openModeler(browser, url);
      await page.locator('input[data-picker=import]').setInputFiles(file);
      // The import dialog (what was found, the choices): accept its defaults.
      await page.waitForSelector('.import-dialog', { timeout: 30000 });
      await page.keyboard.press('Enter');
      await page.waitForFunction((v) => window.softsculpt.vertexCount() === v && !window.softsculpt.busy?.(), n, { timeout: 120000 });
      if (tol.startsWith('material:')) {
        // A material preset chosen in the panel's list, as a user would (e.g. material:stiff_rubber).
        await page.locator('.lil-controller', { hasText: 'material' }).locator('select').selectOption({ label: tol.slice(9).replace('_', ' ') });
        await page.waitForFunction(() => !window.softsculpt.busy?.());
      } else if (/^[a-z]+$/.test(tol) && tol !== 'default') {
        await page.locator('.lil-controller', { hasText: 'integrator' }).locator('select').selectOption(tol);
        await page.waitForFunction((t) => window.softsculpt.param('integrator') === t, tol);
      } else if (tol !== 'default') {
        const field = page.locator('.lil-controller', { hasText: 'implicit tolerance' }).locator('input').first();
        await field.fill(tol);
        await field.press('Enter');
        await page.waitForFunction((t) => window.softsculpt.param('tolerance') === t, Number(tol));
      }
      // SETTLE and MEASURE (s of wall-clock time, default 2 and 5): when the measurement starts
      // after the import, and how long it runs (a long SETTLE measures the body at rest).
      await page.waitForTimeout(1000 * Number(process.env.SETTLE ?? 2));
      const t0 = await page.evaluate(() => [window.softsculpt.stats().time, performance.now()]);
      await page.waitForTimeout(1000 * Number(process.env.MEASURE ?? 5));
      const r = await page.evaluate(() => {
        const s = window.softsculpt, x = s.positions();
        let h = -Infinity;
        for (let i = 1; i < x.length; i += 3) h = Math.max(h, x[i]);
        return { t: s.stats().time, now: performance.now(), fps: s.fps(), simMs: s.simMs(), dt: s.settings().dt, integrator: s.param('integrator'), tol: s.param('tolerance'), volume: s.stats().volume, h };
      });
      const ratio = (r.t - t0[0]) / ((r.now - t0[1]) / 1000);
      console.log(`${dist}  ${String(n).padStart(8)}  ${r.integrator.padStart(10)}  ${r.dt.toPrecision(3)}  ${r.tol.toExponential(0).padStart(9)}  ${ratio.toFixed(3).padStart(16)}  ${r.fps.toFixed(0).padStart(3)}  ${r.simMs.toFixed(1).padStart(12)}  ${r.volume.toFixed(4).padStart(11)}  ${r.h.toFixed(4).padStart(10)}`);
      await ctx.close();
    }
  }
}
await browser.close();
for (const s of servers) s.stop();
