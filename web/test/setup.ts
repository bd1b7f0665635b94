// Load the real engine (public/softsculpt.wasm, built by `make wasm`) into Node for the tests.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { initEngine } from '../src/engine/wasm';

export async function loadEngine(): Promise<void> {
  const path = fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url));
  await initEngine(readFileSync(path));
}
