// An open scene in the modeler: the engine scene, the file it came from (to restart it), and
// what the modeler does with it — which body the tools shape, world parameters shared by all
// bodies.

import { Scene } from './scene';
import type { SoftBody } from './softbody';
import type { ParamName } from './params';

/** What a scene was opened from, to restart it. */
export interface SceneSource { name: string; text: string; files: Map<string, Uint8Array> }

/** Parameters of the world rather than of one body: a scene's bodies share them. */
export const WORLD_PARAMS: ParamName[] = ['gravity', 'windX', 'windY', 'windZ', 'windDrag', 'groundOn', 'groundHeight', 'friction', 'integrator'];

export class SceneSession {
  private constructor(readonly scene: Scene, readonly source: SceneSource) {}

  /** Open a scene file; throws the engine's error (line and key) if it is bad. */
  static open(source: SceneSource): SceneSession {
    return new SceneSession(Scene.open(source.text, source.files), source);
  }

  /** The body the tools shape (the scene's first). */
  get active(): SoftBody { return this.scene.bodies[0]; }
  get others(): SoftBody[] { return this.scene.bodies.slice(1); }

  /** The active body was replaced (undo, subdivide): a note if its pending events were dropped. */
  adopt(body: SoftBody): string {
    return this.scene.replaceBody(0, body);
  }

  /** Give the other bodies `from`'s value of each world parameter in `names`. */
  shareWorld(from: SoftBody, names: ParamName[]): void {
    for (const name of names.filter((n) => WORLD_PARAMS.includes(n))) {
      for (const b of this.scene.bodies) if (b !== from) b.set(name, from.get(name));
    }
  }

  get info(): { name: string; time: number; duration: number; bodies: number } {
    return { name: this.source.name, time: this.scene.time, duration: this.scene.duration, bodies: this.scene.bodies.length };
  }


  /** Free the scene and its other bodies (the active one stays with the modeler). */
  close(): void {
    for (const b of this.others) b.free();
    this.scene.free();
  }
}
