// Load the real engine (public/softsculpt.wasm, built by `make wasm`) into Node for the tests.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { initEngine } from '../src/engine/wasm';
import { Document } from '../src/worker/document';
import type { Vec3 } from '../src/protocol';

export async function loadEngine(): Promise<void> {
  await loadEngineFrom(fileURLToPath(new URL('../public/softsculpt.wasm', import.meta.url)));
}

/** The engine built elsewhere (a bench's or a branch's `.wasm`). */
export async function loadEngineFrom(path: string): Promise<void> {
  await initEngine(readFileSync(path));
}

/** The highest vertex (largest y) of flat xyz positions `x`. */
export function topVertex(x: ArrayLike<number>): number {
  let top = 0;
  for (let i = 0; i < x.length / 3; i++) if (x[3 * i + 1] > x[3 * top + 1]) top = i;
  return top;
}

/** Vertex `i` of flat xyz positions `x`. */
export function vertexAt(x: ArrayLike<number>, i: number): Vec3 {
  return [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
}

/** A document on the default model (the engine loaded), and the messages it says. */
export function openedDocument(): { doc: Document; messages: string[] } {
  const messages: string[] = [];
  const doc = new Document({ message: (t) => messages.push(t), progress: () => {}, changed: () => {}, ui: () => {}, ask: () => {} });
  doc.open(null);
  return { doc, messages };
}
