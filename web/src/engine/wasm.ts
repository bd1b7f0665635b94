// The only module that touches the WebAssembly engine (crates/softsculpt-wasm). It loads the
// module and reads its error and result slots; its raw exports' types come from the binding's
// table (./abi.ts, written from the Rust side). The calls are documented in one place: the crate
// documentation of crates/softsculpt-wasm/src/lib.rs (and web/README.md).
//
// Conventions: fallible calls return 0 / an index ≥ 0, or −1 on failure (then `errorJson()`);
// data comes back in the result slot (`resultBytes()`, `resultText()`). Any call may grow wasm
// memory, which replaces `memory.buffer`: typed arrays over it must be re-made after every call.

import type { RawEngine } from './abi';
import { loadThreaded } from './threads';

export type { RawEngine };

let engine: RawEngine | null = null;
/** Threads the engine steps on (`engineThreads`). */
let threadCount = 1;

/** The page's interrupting commands sent [0] and taken [1] (protocol.ts `interrupts`), if shared. */
let counters: Int32Array | null = null;
/** Let the engine abandon a step while an interrupting command waits (the worker, at init). */
export function useInterrupts(shared: SharedArrayBuffer): void { counters = new Int32Array(shared); }
/** The worker takes an interrupting command (the running steps need no longer make way). */
export function tookInterrupt(): void { if (counters) Atomics.add(counters, 1, 1); }
/** A command was lost on the way (it could not be read): count every one sent as taken, so no step is abandoned for it forever. */
export function settleInterrupts(): void { if (counters) Atomics.store(counters, 1, Atomics.load(counters, 0)); }

/**
 * What the engine imports: the clock its anytime steps' deadlines are read on (ms), and
 * whether a command is waiting that a step in progress should make way for.
 */
export const engineImports = {
  env: {
    ss_now: (): number => performance.now(),
    ss_interrupted: (): number => (counters && Atomics.load(counters, 0) !== Atomics.load(counters, 1) ? 1 : 0),
  },
};

/**
 * Load the engine from the wasm bytes or a URL (browser). Safe to call more than once. With
 * `threaded` (a URL of the threaded build, and the threads wanted) where memory can be shared,
 * that build on that many threads (./threads.ts); else, or if it cannot start, this one.
 */
export async function initEngine(source: BufferSource | string, threaded?: { url: string; threads: number }): Promise<RawEngine> {
  if (engine) return engine;
  const t = threaded ? await loadThreaded(threaded.url, threaded.threads, engineImports).catch((err: unknown) => { console.warn('SoftSculpt: the threaded engine failed to start', err); return null; }) : null;
  if (t) {
    // The threaded build imports its memory (shared); the calls read it here as `memory`.
    engine = { ...(t.instance.exports as object), memory: t.memory } as unknown as RawEngine;
    threadCount = t.threads;
    return engine;
  }
  const bytes = typeof source === 'string' ? await (await fetch(source)).arrayBuffer() : source;
  const { instance } = await WebAssembly.instantiate(bytes, engineImports);
  engine = instance.exports as unknown as RawEngine;
  threadCount = 1;
  return engine;
}

/** Threads the engine steps on (1: the one-thread build, or the threaded one on one thread). */
export function engineThreads(): number { return threadCount; }

export function raw(): RawEngine {
  if (!engine) throw new Error('the engine is not loaded yet (initEngine first)');
  return engine;
}

/** Views over wasm memory; made anew on each call, so a memory growth never leaves a stale one. */
export const view = {
  f64: (ptr: number, len: number) => new Float64Array(raw().memory.buffer, ptr, len),
  f32: (ptr: number, len: number) => new Float32Array(raw().memory.buffer, ptr, len),
  u32: (ptr: number, len: number) => new Uint32Array(raw().memory.buffer, ptr, len),
  u8: (ptr: number, len: number) => new Uint8Array(raw().memory.buffer, ptr, len),
};

/** The last error: `{kind, message, …}` (see the crate documentation). */
export function errorJson(): Record<string, unknown> {
  const e = raw();
  const text = new TextDecoder().decode(copyOut(e.ss_error_ptr(), e.ss_error_len()));
  try {
    return JSON.parse(text) as Record<string, unknown>;
  } catch {
    return { kind: 'usage', message: text || 'the engine gave no error' };
  }
}

/** A copy of `len` bytes at `ptr` (also what TextDecoder needs: it refuses views of shared memory, the threaded build's). */
function copyOut(ptr: number, len: number): Uint8Array {
  return new Uint8Array(raw().memory.buffer, ptr, len).slice();
}

/** A copy of the last result's bytes. */
export function resultBytes(): Uint8Array {
  const e = raw();
  return copyOut(e.ss_result_ptr(), e.ss_result_len());
}

/** The last result as text (JSON, TOML). */
export function resultText(): string {
  return new TextDecoder().decode(resultBytes());
}

/** Copy bytes into a temporary wasm buffer for the duration of `f`. */
export function withBytes<T>(bytes: Uint8Array, f: (ptr: number, len: number) => T): T {
  const e = raw();
  const ptr = e.ss_alloc(bytes.length);
  try {
    new Uint8Array(e.memory.buffer, ptr, bytes.length).set(bytes);
    return f(ptr, bytes.length);
  } finally {
    e.ss_dealloc(ptr, bytes.length);
  }
}

/** Copy typed arrays into temporary wasm buffers for the duration of `f`. */
export function withArrays<T>(arrays: (Float64Array | Float32Array | Uint32Array | Uint8Array)[], f: (...ptrs: number[]) => T): T {
  const e = raw();
  const blocks = arrays.map((a) => ({ a, len: a.byteLength, ptr: e.ss_alloc(a.byteLength) }));
  try {
    for (const b of blocks) new Uint8Array(e.memory.buffer, b.ptr, b.len).set(new Uint8Array(b.a.buffer, b.a.byteOffset, b.len));
    return f(...blocks.map((b) => b.ptr));
  } finally {
    for (const b of blocks) e.ss_dealloc(b.ptr, b.len);
  }
}
