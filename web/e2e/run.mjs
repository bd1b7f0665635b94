// Run the end-to-end tests with Node's test runner (TAP output, counted by scripts/test_summary.py).
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
const dir = fileURLToPath(new URL('.', import.meta.url));
// A hard limit, so a hung browser can never hold CI past its budget.
const r = spawnSync(process.execPath, ['--test', '--test-reporter=tap', '--test-concurrency=1', `${dir}modeler.test.mjs`, `${dir}implicit.test.mjs`, `${dir}scenes.test.mjs`, `${dir}responsive.test.mjs`, `${dir}feel.test.mjs`, `${dir}import.test.mjs`, `${dir}sketch.test.mjs`, `${dir}freeze.test.mjs`, `${dir}leftovers.test.mjs`, `${dir}pieces.test.mjs`, `${dir}details.test.mjs`], {
  stdio: 'inherit',
  timeout: 25 * 60 * 1000,
  killSignal: 'SIGKILL',
});
if (r.error) console.log(`# fail 1\n# e2e runner stopped: ${r.error.message}`);
process.exit(r.status ?? 1);
