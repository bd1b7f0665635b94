// Project files: a body's whole state (engine/state.ts) and the page's state, as JSON text.

import type { BodyState } from './engine/state';

export type { BodyState };

export const PROJECT_FORMAT = 'softsculpt-project';

export interface Project {
  name: string;
  state: BodyState;
  ui: Record<string, unknown>;
}

const F64 = ['positions', 'velocities', 'restLengths', 'masses', 'frozenPositions', 'frozenRestLengths', 'prestress', 'frozenPrestress', 'bendingRestLengths', 'frozenBendingRestLengths'] as const;

/** Project file text (JSON; numbers print in shortest round-trip form, so they load back exactly). */
export function serialize(p: Project): string {
  const s = p.state;
  const body: Record<string, unknown> = { triangles: Array.from(s.triangles), pinned: Array.from(s.pinned), gas: s.gas, frozenGas: s.frozenGas, params: s.params };
  for (const k of F64) body[k] = Array.from(s[k]);
  return JSON.stringify({ format: PROJECT_FORMAT, version: 1, name: p.name, body, ui: p.ui });
}

function numbers(v: unknown, what: string): number[] {
  if (!Array.isArray(v) || v.some((x) => typeof x !== 'number' || !Number.isFinite(x))) throw new Error(`project: '${what}' must be a list of finite numbers`);
  return v as number[];
}

/** Parse a project file; throws an Error saying what is wrong. */
export function parse(text: string): Project {
  let j: any;
  try {
    j = JSON.parse(text);
  } catch {
    throw new Error('not a SoftSculpt project (not JSON)');
  }
  if (!j || j.format !== PROJECT_FORMAT) throw new Error('not a SoftSculpt project (no "format": "softsculpt-project")');
  if (j.version !== 1) throw new Error(`project version ${j.version} is not supported (this modeler reads version 1)`);
  const b = j.body ?? {};
  const arr = Object.fromEntries(F64.map((k) => [k, new Float64Array(numbers(b[k], k))])) as Record<(typeof F64)[number], Float64Array>;
  const triangles = new Uint32Array(numbers(b.triangles, 'triangles'));
  const n = arr.positions.length / 3;
  if (!Number.isInteger(n) || n === 0 || triangles.length % 3 !== 0 || triangles.some((i) => i >= n)) throw new Error('project: the mesh is malformed');
  for (const k of ['velocities', 'frozenPositions', 'prestress', 'frozenPrestress'] as const) if (arr[k].length !== 3 * n) throw new Error(`project: '${k}' has the wrong length`);
  if (arr.masses.length !== n) throw new Error("project: 'masses' has the wrong length");
  const params: Record<string, number> = {};
  for (const [k, v] of Object.entries(b.params ?? {})) if (typeof v === 'number') params[k] = v;
  return {
    name: typeof j.name === 'string' ? j.name : 'project',
    state: {
      ...arr,
      triangles,
      pinned: new Uint8Array(numbers(b.pinned, 'pinned')),
      gas: numbers(b.gas, 'gas') as [number, number],
      frozenGas: numbers(b.frozenGas, 'frozenGas') as [number, number],
      params,
    },
    ui: typeof j.ui === 'object' && j.ui ? j.ui : {},
  };
}

/** A file name's base for downloads: 'bunny.obj' → 'bunny', 'x.softsculpt.json' → 'x'. */
export function baseName(name: string): string {
  return name.replace(/\.[^.]*$/, '').replace(/\.softsculpt$/, '') || 'softsculpt';
}
