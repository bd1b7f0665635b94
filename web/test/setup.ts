// Load the real engine (public/softsculpt.wasm, built by `make wasm`) into Node for the tests.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { initEngine } from '../src/engine/wasm';
import { Document } from '../src/worker/document';

export async function loadEngine(): Promise<void> {
  const path = fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url));
  await initEngine(readFileSync(path));
}

/** A document on the default model (the engine loaded), and the messages it says. */
export function openedDocument(): { doc: Document; messages: string[] } {
  const messages: string[] = [];
  const doc = new Document({ message: (t) => messages.push(t), progress: () => {}, changed: () => {}, ui: () => {}, ask: () => {} });
  doc.open(null);
  return { doc, messages };
}
