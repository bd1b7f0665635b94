// A body's whole state as plain arrays: captured for undo and project files, restored exactly
// into a new engine body.

import { SoftBody } from './softbody';
import { EDITABLE, type ParamName } from './params';

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
