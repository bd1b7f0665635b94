// Engine parameters: ids (as in crates/softsculpt-wasm/src/lib.rs `param`), units, ranges.

export const Param = {
  stiffness: 0,
  springDamping: 1,
  damping: 2,
  gravity: 3,
  gasAmount: 4,
  temperature: 5,
  volumeMode: 6,
  windX: 7,
  windY: 8,
  windZ: 9,
  windDrag: 10,
  groundOn: 11,
  groundHeight: 12,
  friction: 13,
  integrator: 14,
  totalMass: 15,
  ambientPressure: 16,
  referenceVolume: 17,
  frozenAmbientPressure: 18,
  frozenReferenceVolume: 19,
  bendingStiffness: 20,
  /** 0/1: the body collides with itself (in a scene's world). */
  selfCollision: 21,
} as const;

export type ParamName = keyof typeof Param;

/** Parameters a project saves and the panel edits (the gas reference is saved separately). */
export const EDITABLE: ParamName[] = [
  'stiffness', 'springDamping', 'bendingStiffness', 'damping', 'gravity', 'gasAmount', 'temperature', 'volumeMode',
  'windX', 'windY', 'windZ', 'windDrag', 'groundOn', 'groundHeight', 'friction', 'integrator', 'selfCollision',
];

export const INTEGRATORS = ['euler', 'midpoint', 'rk4', 'symplectic'] as const;
export const VOLUME_MODES = ['exact', 'box', 'sphere'] as const;

/** R (J/(mol·K)). */
export const GAS_CONSTANT = 8.314462618;
