// Scene files in the modeler: open (with the mesh files a scene names), play the timed events,
// errors with the line, save and open again; and a screenshot of every shipped figure scene
// (scenes/screenshots/, shown in scenes/README.md).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { SHOTS, browserSuite, inspect, openModeler, steady } from './harness.mjs';

const SCENES = fileURLToPath(new URL('../../scenes/', import.meta.url));
const FIGURES = join(SCENES, 'screenshots');

const suite = browserSuite();

const sceneInput = (page) => page.locator('input[data-picker=scene]');
const sceneTime = (page) => inspect(page, () => window.softsculpt.scene()?.time ?? -1);

test('a scene opens with its mesh file and obstacle, and its events play in time', async () => {
  const { page, errors } = await openModeler(suite.browser, suite.server.url);
  const dir = join(tmpdir(), 'softsculpt-scene');
  mkdirSync(dir, { recursive: true });
  writeFileSync(join(dir, 'tent.obj'), 'v -3 0.05 -3\nv 3 0.05 -3\nv 3 0.05 3\nv -3 0.05 3\nf 1 3 2\nf 1 4 3\n');
  writeFileSync(join(dir, 'drop.toml'), `
[world]
dt = 0.001
duration = 3.0
ground = { height = 0.0 }

[[body]]
name = "ball"
model = "sphere"
scale = 0.5
translate = [0.0, 1.5, 0.0]
damping = 1.0
gas = { nrt = 10.0 }

[[body]]
name = "other"
model = "sphere"
scale = 0.4
translate = [1.5, 0.6, 0.0]
gas = { nrt = 10.0 }

[[obstacle]]
shape = "mesh"
mesh = "tent.obj"

[[event]]
time = 0.5
action = "set_gas"
body = "ball"
nrt = 40.0
`);
  await sceneInput(page).setInputFiles([join(dir, 'drop.toml'), join(dir, 'tent.obj')]);
  await page.waitForFunction(() => window.softsculpt.scene()?.bodies === 2);
  assert.match(await inspect(page, () => window.softsculpt.lastMessage()), /opened scene drop\.toml: 2 bodies/);
  // A scene opens paused at t = 0 (its first events are seen when one plays it), and the model
  // list names the scene after the built-ins. Its first frames drawn: play state and time steady.
  await steady(page, () => [window.softsculpt.playing(), window.softsculpt.scene()?.time]);
  assert.equal(await inspect(page, () => window.softsculpt.playing()), false);
  assert.equal(await sceneTime(page), 0);
  assert.equal(await inspect(page, () => window.softsculpt.banner()), 'Paused — Space to play');
  assert.equal((await page.locator('.lil-controller', { hasText: 'built-in' }).locator('.lil-display').textContent()).trim(), '(scene: drop.toml)');
  await page.keyboard.press('Space');
  // The gas law P V = nRT: 10 J at the start, 40 J once the event at 0.5 s has fired (the
  // volume itself swings as the ball lands, so it is the product that is checked).
  const pv = (st) => st.pressure * st.volume;
  const s0 = await inspect(page, () => ({ ...window.softsculpt.stats(), t: window.softsculpt.scene().time }));
  if (s0.t < 0.45) assert.ok(Math.abs(pv(s0) - 10) < 1e-6 * 10, `P V = ${pv(s0)} at ${s0.t} s`);
  await page.waitForFunction(() => window.softsculpt.scene().time > 2.0, null, { timeout: 30000 });
  const s = await inspect(page, () => window.softsculpt.stats());
  assert.ok(Math.abs(pv(s) - 40) < 1e-6 * 40, `P V = ${pv(s)} J after the event`);
  // It rests on the mesh floor (y = 0.05), not on the ground below it.
  const lowest = await inspect(page, () => Math.min(...window.softsculpt.positions().filter((_, k) => k % 3 === 1)));
  assert.ok(lowest > 0.05 - 1e-6, `lowest point ${lowest}: on the mesh floor`);
  await page.screenshot({ path: join(SHOTS, '20-scene-two-bodies.png') });
  // Undo goes back to the model before the scene.
  await page.keyboard.press('Control+z');
  await page.waitForFunction(() => window.softsculpt.scene() === null);
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), 362);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a bad scene file says which line and key, and keeps the model', async () => {
  const { page } = await openModeler(suite.browser, suite.server.url);
  const path = join(tmpdir(), 'bad-scene.toml');
  writeFileSync(path, '[world]\ndt = 0.001\n\n[[body]]\nmodel = "sphere"\nstifness = 10\n');
  await sceneInput(page).setInputFiles(path);
  await page.waitForFunction(() => /could not open/.test(window.softsculpt.lastMessage()));
  assert.match(await inspect(page, () => window.softsculpt.lastMessage()), /bad-scene\.toml: line 6: body\[0\]\.stifness: unknown field/);
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), 362, 'the model is untouched');
  assert.equal(await inspect(page, () => window.softsculpt.scene()), null);
  await page.context().close();
});

test('save scene downloads a file that opens again as the same body', async () => {
  const { page } = await openModeler(suite.browser, suite.server.url);
  await sceneInput(page).setInputFiles(join(SCENES, 'fig4a_mushroom_press_wind.toml'));
  await page.waitForFunction(() => window.softsculpt.scene() !== null);
  await page.keyboard.press('Space');
  await page.waitForFunction(() => window.softsculpt.scene().time > 0.5, null, { timeout: 30000 });
  const button = page.locator('#panel button', { hasText: 'Save scene' });
  const [download] = await Promise.all([page.waitForEvent('download'), button.click()]);
  const path = join(tmpdir(), 'saved-scene.toml');
  await download.saveAs(path);
  const text = readFileSync(path, 'utf8');
  assert.match(text, /\[\[body\]\]/);
  assert.match(text, /\[\[event\]\]/, 'the events are kept');
  await sceneInput(page).setInputFiles(path);
  await page.waitForFunction(() => /opened scene saved-scene\.toml/.test(window.softsculpt.lastMessage()));
  assert.equal(await inspect(page, () => window.softsculpt.vertexCount()), 362);
  await page.context().close();
});

// One screenshot per shipped scene — the figures of the paper — at the end of its run, or where
// the figure shows it: Fig. 4b while pushed, Fig. 7 at the end of the push with the mass brush's
// overlay showing the painted masses (dark: heavy).
const MOMENT = { 'fig4b_sphere_push.toml': 2.5, 'fig7_kangaroo.toml': 0.4, 'fig7_local_deformation.toml': 0.4 };
const KEYS = { 'fig7_kangaroo.toml': 'm', 'fig7_local_deformation.toml': 'm' };
for (const file of readdirSync(SCENES).filter((f) => f.endsWith('.toml')).sort()) {
  test(`figure scene ${file} plays to its end in the modeler`, async () => {
    const { page, errors } = await openModeler(suite.browser, suite.server.url);
    await sceneInput(page).setInputFiles(join(SCENES, file));
    await page.waitForFunction(() => window.softsculpt.scene() !== null);
    await page.keyboard.press('Space');
    if (KEYS[file]) await page.keyboard.press(KEYS[file]);
    const { duration } = await inspect(page, () => window.softsculpt.scene());
    const at = MOMENT[file] ?? duration;
    await page.waitForFunction((t) => window.softsculpt.scene().time >= t, at, { timeout: 120000, polling: 50 });
    await page.keyboard.press(' ');
    // A frame stepped before the worker took the pause may still come: wait until the drawn time stops.
    await steady(page, () => window.softsculpt.scene()?.time);
    mkdirSync(FIGURES, { recursive: true });
    await page.screenshot({ path: join(FIGURES, file.replace('.toml', '.png')) });
    assert.ok((await sceneTime(page)) >= at);
    await page.keyboard.press(' ');
    await page.waitForFunction((d) => window.softsculpt.scene().time >= d, duration, { timeout: 120000, polling: 200 });
    assert.deepEqual(errors, []);
    await page.context().close();
  });
}
