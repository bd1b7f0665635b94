// Run the end-to-end tests with Node's test runner (TAP output, counted by scripts/test_summary.py).
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
const dir = fileURLToPath(new URL('.', import.meta.url));
const r = spawnSync(process.execPath, ['--test', '--test-reporter=tap', '--test-concurrency=1', `${dir}modeler.test.mjs`], { stdio: 'inherit' });
process.exit(r.status ?? 1);
