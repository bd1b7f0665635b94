// A body's whole state: captured for undo, saved to a project file, restored exactly.

import { SoftBody } from './engine/softbody';
import { EDITABLE, type ParamName } from './engine/params';

export interface BodyState {
  positions: Float64Array;
  velocities: Float64Array;
  triangles: Uint32Array;
  restLengths: Float64Array;
  masses: Float64Array;
  pinned: Uint8Array;
  frozenPositions: Float64Array;
  frozenRestLengths: Float64Array;
  /** Rest lengths of the bending springs (m), now and frozen. */
  bendingRestLengths: Float64Array;
  frozenBendingRestLengths: Float64Array;
  /** Load kept by a freeze under load (N, xyz per vertex), now and at the last freeze. */
  prestress: Float64Array;
  frozenPrestress: Float64Array;
  /** Gas reference now and at the last freeze: surroundings' pressure (Pa), volume V0 (m³). */
  gas: [number, number];
  frozenGas: [number, number];
  params: Partial<Record<ParamName, number>>;
}

export function capture(body: SoftBody): BodyState {
  const params: Partial<Record<ParamName, number>> = {};
  for (const p of EDITABLE) params[p] = body.get(p);
  return {
    positions: body.positions().slice(),
    velocities: body.velocities().slice(),
    triangles: body.triangles().slice(),
    restLengths: body.restLengths().slice(),
    masses: body.masses().slice(),
    pinned: body.pinned().slice(),
    frozenPositions: body.frozenPositions().slice(),
    frozenRestLengths: body.frozenRestLengths().slice(),
    bendingRestLengths: body.bendingRestLengths().slice(),
    frozenBendingRestLengths: body.frozenBendingRestLengths().slice(),
    prestress: body.prestress().slice(),
    frozenPrestress: body.frozenPrestress().slice(),
    gas: [body.get('ambientPressure'), body.get('referenceVolume')],
    frozenGas: [body.get('frozenAmbientPressure'), body.get('frozenReferenceVolume')],
    params,
  };
}

/** A new body in exactly the captured state. */
export function restore(s: BodyState): SoftBody {
  const total = s.masses.reduce((a, b) => a + b, 0);
  const body = SoftBody.fromMesh(s.frozenPositions, s.triangles, total, false);
  try {
    if (body.springCount !== s.restLengths.length) throw new Error('the saved rest lengths do not match the mesh');
    body.setRestLengths(s.restLengths);
    body.setMasses(s.masses);
    s.pinned.forEach((p, i) => { if (p) body.setPinned(i, true); });
    body.setState(s.positions, s.velocities);
    for (const p of EDITABLE) {
      const v = s.params[p];
      if (v !== undefined && p !== 'gasAmount') body.set(p, v);
    }
    if (s.params.gasAmount !== undefined) body.set('gasAmount', s.params.gasAmount);
    body.set('ambientPressure', s.gas[0]);
    body.set('referenceVolume', s.gas[1]);
    body.setFrozen(s.frozenPositions, s.frozenRestLengths, s.frozenGas[0], s.frozenGas[1]);
    body.setPrestress(s.prestress, s.frozenPrestress);
    if (body.bendingCount !== s.bendingRestLengths.length) throw new Error('the saved bending rest lengths do not match the mesh');
    body.setBendingRest(s.bendingRestLengths, s.frozenBendingRestLengths);
    return body;
  } catch (e) {
    body.free();
    throw e;
  }
}

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
