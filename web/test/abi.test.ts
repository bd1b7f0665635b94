// The binding's table (src/engine/abi.ts, written from crates/softsculpt-wasm's `exports!`
// blocks) against the modules built from it: every export the page is typed for is there with
// the number of arguments the table says, and the modules export no call the table lacks.
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { EXPORTS } from '../src/engine/abi';
import { engineImports } from '../src/engine/wasm';

const file = (name: string) => fileURLToPath(new URL(`../public/${name}`, import.meta.url));
const calls = (m: WebAssembly.Module) => WebAssembly.Module.exports(m).filter((e) => e.kind === 'function' && e.name.startsWith('ss_')).map((e) => e.name);

describe('the binding table', () => {
  it('names every call of the one-thread build, each with its number of arguments', async () => {
    const module = await WebAssembly.compile(readFileSync(file('softsculpt.wasm')));
    expect(calls(module).sort()).toEqual(Object.keys(EXPORTS).sort());
    const exports = (await WebAssembly.instantiate(module, engineImports)).exports as Record<string, unknown>;
    for (const [name, args] of Object.entries(EXPORTS)) expect((exports[name] as (...a: number[]) => unknown).length, name).toBe(args);
  });

  it.skipIf(!existsSync(file('softsculpt-threads.wasm')))('names every call of the threaded build', async () => {
    const module = await WebAssembly.compile(readFileSync(file('softsculpt-threads.wasm')));
    expect(calls(module).sort()).toEqual(Object.keys(EXPORTS).sort());
  });
});
