// The engine's parameter table (ids, scopes, units, defaults, ranges) for the page's types.
// Generated from crates/softsculpt/src/params/table.rs: do not edit. A test fails when it is
// stale; regenerate it with `UPDATE_DOCS=1 cargo test -p softsculpt --release --test parameters`.

/** Ideal gas constant R (J/(mol·K)): gas as nRT (J) is n = nRT / (R T) mol. */
export const GAS_CONSTANT = 8.314462618;

/** A body's parameter (each body has its own). */
export type BodyParamId =
  | 'mass'
  | 'stiffness'
  | 'spring_damping'
  | 'bending'
  | 'rigidity'
  | 'damping'
  | 'gas.amount'
  | 'gas.temperature'
  | 'gas.nrt'
  | 'gas.volume'
  | 'gas.ambient'
  | 'yield'
  | 'flow'
  | 'self_collision';

/** A world's parameter (every body shares it). */
export type WorldParamId =
  | 'dt'
  | 'integrator'
  | 'tolerance'
  | 'newton_iterations'
  | 'gravity'
  | 'wind'
  | 'wind_drag'
  | 'ground'
  | 'ground.height'
  | 'ground.friction'
  | 'ground.restitution'
  | 'contact_thickness'
  | 'contact_friction';

/** Every parameter of the table (scene and obstacle ones exist only in scene files). */
export type ParamId = BodyParamId | WorldParamId
  | 'duration'
  | 'obstacle.friction';

/** A row of the table: valid numbers (each component of a vector) are min ≤ v ≤ max (min < v when minOpen; null: unbounded). */
export interface ParamRow {
  id: ParamId;
  scope: 'body' | 'world' | 'scene' | 'obstacle';
  unit: string;
  default: number | boolean | string | readonly [number, number, number];
  min: number | null;
  max: number | null;
  minOpen: boolean;
}

/** The table's rows, in its order. */
export const PARAMS = [
  { id: 'mass', scope: 'body', unit: 'kg', default: 1, min: 0, max: null, minOpen: true },
  { id: 'stiffness', scope: 'body', unit: 'N/m', default: 100, min: 0, max: null, minOpen: false },
  { id: 'spring_damping', scope: 'body', unit: 'N·s/m', default: 0.1, min: 0, max: null, minOpen: false },
  { id: 'bending', scope: 'body', unit: 'N/m', default: 0, min: 0, max: null, minOpen: false },
  { id: 'rigidity', scope: 'body', unit: 'J', default: 0, min: 0, max: null, minOpen: false },
  { id: 'damping', scope: 'body', unit: '1/s', default: 0, min: 0, max: null, minOpen: false },
  { id: 'gas.amount', scope: 'body', unit: 'mol', default: 0, min: 0, max: null, minOpen: false },
  { id: 'gas.temperature', scope: 'body', unit: 'K', default: 300, min: 0, max: null, minOpen: true },
  { id: 'gas.nrt', scope: 'body', unit: 'J', default: 0, min: 0, max: null, minOpen: false },
  { id: 'gas.volume', scope: 'body', unit: '', default: 'exact', min: null, max: null, minOpen: false },
  { id: 'gas.ambient', scope: 'body', unit: 'Pa', default: 0, min: 0, max: null, minOpen: false },
  { id: 'yield', scope: 'body', unit: '', default: 0, min: 0, max: null, minOpen: false },
  { id: 'flow', scope: 'body', unit: '1/s', default: 0, min: 0, max: null, minOpen: false },
  { id: 'self_collision', scope: 'body', unit: '', default: false, min: null, max: null, minOpen: false },
  { id: 'dt', scope: 'world', unit: 's', default: 0.001, min: 0, max: null, minOpen: true },
  { id: 'integrator', scope: 'world', unit: '', default: 'symplectic', min: null, max: null, minOpen: false },
  { id: 'tolerance', scope: 'world', unit: '', default: 0.000001, min: 0, max: null, minOpen: true },
  { id: 'newton_iterations', scope: 'world', unit: '', default: 100, min: 1, max: 1000, minOpen: false },
  { id: 'gravity', scope: 'world', unit: 'm/s²', default: 9.81, min: null, max: null, minOpen: false },
  { id: 'wind', scope: 'world', unit: 'm/s', default: [0, 0, 0], min: null, max: null, minOpen: false },
  { id: 'wind_drag', scope: 'world', unit: 'N·s/m³', default: 1, min: 0, max: null, minOpen: false },
  { id: 'ground', scope: 'world', unit: '', default: false, min: null, max: null, minOpen: false },
  { id: 'ground.height', scope: 'world', unit: 'm', default: 0, min: null, max: null, minOpen: false },
  { id: 'ground.friction', scope: 'world', unit: '', default: 0.5, min: 0, max: null, minOpen: false },
  { id: 'ground.restitution', scope: 'world', unit: '', default: 0, min: 0, max: 1, minOpen: false },
  { id: 'contact_thickness', scope: 'world', unit: 'm', default: 0.005, min: 0, max: null, minOpen: false },
  { id: 'contact_friction', scope: 'world', unit: '', default: 0.5, min: 0, max: null, minOpen: false },
  { id: 'duration', scope: 'scene', unit: 's', default: 1, min: 0, max: null, minOpen: true },
  { id: 'obstacle.friction', scope: 'obstacle', unit: '', default: 0.5, min: 0, max: null, minOpen: false },
] as const satisfies readonly ParamRow[];
