// Importing a model file in the worker: the engine reads it (every format, one body per piece,
// into a scratch world), the page is asked what the file does not say (the up axis, which
// pieces), and the answer builds the model — at the file's own size, turned upright, standing on
// the ground, each piece a body, an open surface (cloth-like) without gas — as one undo step.

import { World, type DeltaScope } from '../engine/world';
import { FRAME_DT } from '../engine/models';
import { COARSE_VERTICES, headerText, needsAnswer, tooCoarse, place, question, sizeFactor, type ImportAnswer, type ImportFrame, type ImportQuestion, type Up } from '../io/import';
import { trial, verdict, worst } from './trial';
import type { MessageKind, Settings, Stats, UiState } from '../protocol';
import type { Imported } from './explain';

/** Brush radius (m) for the reference-size model (the mushroom); scaled with the model. */
/** The brush radius (m) of the built-in models, whose size is about 1 m: an import's is this × its size. */
export const BRUSH_RADIUS = 0.35;

/**
 * What the importer needs of the document it builds the model in (worker/document.ts's
 * `Document` is one, and owns the importer): declared here, below the document, so that the
 * importer does not import it (issue #39, no circles).
 */
export interface ImportTarget {
  /** An empty world's snapshot (the trial's scratch world, `trial.ts`). */
  readonly emptyWorld: Uint8Array;
  readonly world: World;
  readonly settings: Pick<Settings, 'opened' | 'frame'>;
  ui: UiState;
  /** The brush radius this import fitted (m), remembered for the next built-in (`docstate.ts`). */
  fittedRadius: number | null;
  /** The model is an import: what a stop soon after it names (explain.ts). */
  imported: Imported | undefined;
  /** Run `op` as one operation (one undo step when `undoable`); false if it failed. */
  edit(label: string, undoable: boolean, op: () => void, scope?: DeltaScope, failText?: (why: string) => string): boolean;
  /** A fresh world: no bodies, no scene, no obstacles, the table's defaults. */
  fresh(): void;
  /** A model built in the world (an import): its name, the settings from the world's dt, its file's frame. */
  adopt(model: string, frame: ImportFrame): void;
  remesh(): void;
  subdivide(): void;
  stats(): Pick<Stats, 'time'>;
  /** Tell the page new tool state (the brush radius fitted to an imported model). */
  hooksUi(ui: Partial<UiState>): void;
}

export interface ImporterHooks {
  message(text: string, kind?: MessageKind): void;
  progress(label: string | null): void;
  /** Ask the page (it answers with `Document.importAnswer`). */
  ask(q: ImportQuestion): void;
}

interface Pending { name: string; lists: Float64Array[]; triangles: Uint32Array[]; areas: number[]; warnings: string[]; question: ImportQuestion }

export class Importer {
  private pending: Pending | null = null;
  /** The files imported lately, with their answers, by the load they made (`settings.opened`; undo may bring an earlier one back): to turn one to another up axis. */
  private made = new Map<number, { p: Pending; a: ImportAnswer }>();

  constructor(private readonly doc: ImportTarget, private readonly hooks: ImporterHooks) {}

  /** The file waiting for the page's answer, if any. */
  get waiting(): ImportQuestion | null { return this.pending?.question ?? null; }

  /**
   * Read `data`; ask what the file does not say, or import it at once. `remembered`: the up axis
   * the user chose for files by name (io/upaxis.ts on the page), which settles this one's guess.
   */
  read(name: string, data: ArrayBuffer, remembered: Record<string, Up> = {}): void {
    this.pending = null;
    this.hooks.progress(`importing ${name}`);
    const scratch = World.create();
    try {
      const { first, report } = scratch.addFile(name, new Uint8Array(data), true);
      const bodies = report.pieces.map((_, k) => scratch.body(first + k));
      const lists = bodies.map((b) => b.positions.slice());
      // What the import's own message says anyway (pieces, an open surface) is not repeated.
      const warnings = report.warnings.filter((t) => !/separate pieces|surface is open/.test(t));
      const triangles = bodies.map((b) => b.triangles.slice());
      const q = question(name, report, lists, triangles, headerText(new Uint8Array(data)), remembered);
      const p: Pending = { name, lists, triangles, areas: report.pieces.map((x) => x.area), warnings, question: q };
      // What it will cost to simulate (trial.ts): built as the default answer would build it.
      const quality = worst(report.pieces.map((_, k) => scratch.quality(first + k)));
      this.hooks.progress(`importing ${name}: a trial run`);
      // Inflated, not frozen at rest: a body at rest costs nothing to step, the trial measures
      // what a moving one costs (the gas swelling it and its landing).
      const run = trial(this.doc.emptyWorld, (w) => { this.addPieces(w, p, { up: q.guessedUp, pieces: 'each', inflate: true }); });
      if (run) q.cost = verdict(quality, run.frames, run.msPerFrame);
      if (tooCoarse(q)) q.remeshed = this.remeshTrial(p);
      this.pending = p;
      if (needsAnswer(p.question)) this.hooks.ask(p.question);
      else this.answer({ up: p.question.guessedUp, pieces: 'each' });
    } catch (e) {
      this.hooks.message(`could not import ${name}: ${e instanceof Error ? e.message : String(e)} — the current model is unchanged`, 'error');
    } finally {
      scratch.free();
      this.hooks.progress(null);
    }
  }

  /**
   * The vertices Remesh would give a model too coarse to shape, tried on a scratch copy built
   * as the default answer builds it (0 if the core refuses): an even coarse mesh stays as coarse
   * at its mean edge, a box is remeshed finer to keep its shape (meshops.ts `remesh`).
   */
  private remeshTrial(p: Pending): number {
    const w = World.create();
    try {
      w.restore(this.doc.emptyWorld);
      const { chosen } = this.addPieces(w, p, { up: p.question.guessedUp, pieces: 'each' });
      const underLoad = w.params(0).gravity !== 0;
      return chosen.reduce((n, _, b) => {
        w.remeshReporting(b, w.quality(b).edge_mean, underLoad);
        return n + w.body(b).vertexCount;
      }, 0);
    } catch {
      return 0;
    } finally {
      w.free();
    }
  }

  /** The page's answer (null: cancelled). */
  answer(a: ImportAnswer | null): void {
    const p = this.pending;
    this.pending = null;
    if (!p) { this.hooks.message('no import is waiting for an answer', 'warn'); return; }
    if (!a) { this.hooks.message(`import of ${p.name} cancelled — the current model is unchanged`); return; }
    if (!this.build(p, a)) return;
    if (a.remesh) this.doc.remesh();
    else if (a.subdivide) this.doc.subdivide();
  }

  /**
   * The imported model turned to the other up axis (Model › up axis, to fix a wrong guess): built
   * again from the file as read, with the same pieces, as one undo step (what was done to it since
   * the import is replaced; Undo brings it back).
   */
  reorient(up: Up): void {
    const l = this.made.get(this.doc.settings.opened ?? -1);
    if (!l || !this.doc.settings.frame) {
      this.hooks.message('the up axis applies to an imported model (OBJ, PLY, STL, glTF): import one first', 'warn');
      return;
    }
    if (l.a.up === up) return;
    // (The file as read, so without a remesh chosen at import: Model › Remesh gives it again.)
    this.build(l.p, { ...l.a, up, remesh: false }, `turned ${up === 'z' ? 'from Z-up' : 'back to Y-up as in the file'}`);
  }

  /**
   * The chosen pieces of `p` into world `w` as `a` says, each a body under the modeler's preset
   * at the model's size; returns how many are open surfaces (no gas), the size and the frame.
   */
  private addPieces(w: World, p: Pending, a: ImportAnswer) {
    const chosen = a.pieces === 'largest' ? [0] : p.lists.map((_, k) => k);
    const { positions, frame } = place(chosen.map((k) => p.lists[k]), a.up);
    frame.format = p.question.format;
    frame.file = p.name;
    const size = sizeFactor(positions);
    const area = chosen.reduce((s, k) => s + p.areas[k], 0);
    let gasless = 0;
    chosen.forEach((k, i) => {
      const b = w.addMesh(positions[i], p.triangles[k], 1, false);
      const open = w.applyPresetScaled(b, 'modeler', size).length > 0;
      if (open) gasless++;
      // The mass the preset gives the whole model (1 kg at the reference size, × size³),
      // shared by area: the same surface density on every piece.
      w.setParam(b, 'mass', (w.params(b).mass as number) * (chosen.length > 1 ? p.areas[k] / area : 1));
      // A closed piece rests at the file's shape unless asked to inflate: the freeze under load
      // (`World::freeze`, body/freeze.rs) makes the shape in the file the rest shape — rest
      // lengths the current ones, the surroundings' pressure the gas's, the weight carried onto
      // the ground — so it is an equilibrium at every resolution (before, the preset's gas
      // swelled a re-imported export of the mushroom from 2.45 to 2.83 m³). Not keeping the
      // tension: from a slack import that is the least-tension field, unstable on fine meshes
      // (the 10,242-vertex sphere's first step: 26 m/s, 130 Newton iterations, hinges let go;
      // docs/model.md, "Freeze keeping the tension", limits).
      if (!open && !a.inflate) {
        w.freeze(b, true, false);
      }
    });
    // Pieces that overlap or touch where they join take no contact with each other until they
    // part (`world/overlaps.rs`): pushed apart, urdf_000's five pieces flew off and jittered.
    if (chosen.length > 1) w.letOverlappingBe();
    return { chosen, gasless, size, frame };
  }

  /** Build the model from `p` as `a` says (one undo step); returns whether it was built. */
  private build(p: Pending, a: ImportAnswer, why?: string): boolean {
    const w = this.doc.world;
    let made = null as ReturnType<Importer['addPieces']> | null;
    this.hooks.progress(`importing ${p.name}`);
    const ok = this.doc.edit(why ? `up axis ${a.up.toUpperCase()}` : `import ${p.name}`, true, () => {
      this.doc.fresh();
      made = this.addPieces(w, p, a);
      this.doc.adopt(p.name, made.frame);
    }, 'all', (why) => `could not import ${p.name}: ${why} — the current model is unchanged`);
    if (!ok || !made) return false;
    const { chosen, gasless, size } = made;
    this.made.set(this.doc.settings.opened ?? -1, { p, a });
    // A stop soon after this names the file, not the gas (explain.ts).
    const qualities = chosen.map((_, b) => w.quality(b));
    this.doc.imported = { name: p.name, pieces: chosen.length, minAngle: Math.min(...qualities.map((q) => q.min_angle_deg)), time: this.doc.stats().time };
    // The newest few (each holds its file's pieces).
    for (const k of this.made.keys()) if (this.made.size > 4) this.made.delete(k);
    // Three significant digits: the panel shows the number as it is (0.485, not 0.4849744…).
    const radius = Number((BRUSH_RADIUS * size).toPrecision(3));
    this.doc.ui = { ...this.doc.ui, brush: { radius } };
    this.doc.fittedRadius = radius;
    this.doc.hooksUi({ brush: { radius } });
    const q = p.question, n = chosen.length;
    const v = chosen.reduce((s, k) => s + q.pieces[k].vertices, 0), f = chosen.reduce((s, k) => s + q.pieces[k].faces, 0);
    const dims = q.size.map((x) => x.toPrecision(3)).join(' × ');
    // The up axis, and why, when the page did not ask it (a guess sure enough: the dialog, if
    // shown for something else, only says it; a wrong guess is fixed in Model › up axis).
    const upWhy = !q.declaredUp && q.upSure === true && a.up === q.guessedUp ? ` (${q.guessReason}; Model › up axis changes it)` : '';
    const parts = [
      why ? `${p.name} ${why}: re-built from the file (Undo brings the model back as it was)` : `imported ${p.name}: ${v} vertices, ${f} faces, ${dims} m as in the file`,
      a.up === 'z' ? `turned from Z-up to Y-up${upWhy}` : upWhy ? `Y-up${upWhy}` : '',
      q.pieces.length > 1 ? (n > 1 ? `${n} pieces as ${n} bodies` : `the largest of ${q.pieces.length} pieces`) : '',
      gasless ? `${gasless === n ? '' : `${gasless} of ${n} bodies `}cloth-like (an open surface): no gas` : '',
      gasless < n ? (a.inflate ? 'inflated by its gas' : 'at rest at the shape in the file (more Gas › amount n swells it)') : '',
      (w.params(0).dt as number) < FRAME_DT / 1.5 ? `steps of ${(w.params(0).dt as number).toPrecision(2)} s (finer for its small size)` : '',
    ];
    // Too few vertices for the brushes to shape: say what gives them more.
    if (v < COARSE_VERTICES && !a.remesh && !a.subdivide) parts.push(`only ${v} vertices: Subdivide (U) or Model › Remesh gives the tools more to shape`);
    // Long thin triangles make poor springs: say so, and what evens them.
    // (Not when the answer remeshes it: that says what it did.)
    const cost = p.question.cost;
    const quality = qualities[0];
    // The trial's reason, or (no trial: interrupted) the core's poor-triangles verdict.
    const uneven = cost?.why || (quality.poor ? `uneven triangles (${Math.round(100 * quality.small_angle_share)} % of angles below 25°)` : '');
    if (!a.remesh && uneven) parts.push(`${uneven}: Model › Remesh evens them`);
    this.hooks.message(parts.filter(Boolean).join('; '));
    // The file's warnings were said when it was imported, not again when it is turned.
    if (p.warnings.length && !why) this.hooks.message(p.warnings.join('\n'), 'warn');
    return true;
  }
}
