// Split steps: an implicit step that does not converge (the engine's step error with
// `converged: false`; the engine rolled the world back, state untouched) is taken again as two
// steps of dt/2, each split again if it also fails, at most `depth` times (dt/8 by default).
// Any other failure, or one at the smallest split, is thrown as it came.

/**
 * Steps `n` of `dt` (s) or none: throws the engine's error and leaves the state as it was.
 * `last`: no shorter split follows if this fails (the engine should not give up early then:
 * `pace.ts`, NEWTON_STALLED).
 */
export type StepFn = (dt: number, n: number, last: boolean) => void;

/** Whether `e` is an implicit step that did not converge (and may succeed with a smaller dt). */
export function notConverged(e: unknown): boolean {
  const f = (e as { kind?: string; fields?: Record<string, unknown> } | null);
  return f?.kind === 'step' && f.fields?.converged === false;
}

/**
 * `n` steps of `dt`, splitting any step that does not converge; returns how many splits it
 * took (0: none). If the `n` steps at once fail, they are taken one at a time (the failed batch
 * was rolled back whole), so only the steps that need it are split.
 */
export function stepSplitting(step: StepFn, dt: number, n: number, depth = 3): number {
  try {
    step(dt, n, depth <= 0);
    return 0;
  } catch (e) {
    if (!notConverged(e) || depth <= 0) throw e;
  }
  let splits = 0;
  if (n > 1) {
    for (let i = 0; i < n; i++) splits += stepSplitting(step, dt, 1, depth);
    return splits;
  }
  splits = 1;
  for (let half = 0; half < 2; half++) splits += stepSplitting(step, dt / 2, 1, depth - 1);
  return splits;
}
