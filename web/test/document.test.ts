// The worker's document over the engine world: undo by deltas, project files (version 2 and the
// migrated version 1, refusals that leave the work as it was), the autosave in IndexedDB
// (fake-indexeddb in Node) and the history's limits.
import 'fake-indexeddb/auto';
import { beforeAll, describe, expect, it } from 'vitest';
import { loadEngine } from './setup';
import { Document } from '../src/worker/document';
import { History, travel } from '../src/history';
import { parse, serialize, toBase64 } from '../src/project';
import { clearAutosave, loadAutosave, saveAutosave } from '../src/storage';

beforeAll(loadEngine);

/** A document on the default model, its messages collected. */
function opened(): { doc: Document; messages: string[] } {
  const messages: string[] = [];
  const doc = new Document({ message: (t) => messages.push(t), progress: () => {}, changed: () => {}, ui: () => {} });
  doc.open(null);
  return { doc, messages };
}

/** The world's whole state, to compare bit for bit. */
const state = (doc: Document) => Array.from(doc.world.snapshot());

/** An inflate stroke at the top of the body for `ticks` ticks of `dt` s, stepping between. */
function inflate(doc: Document, ticks = 5): void {
  const x = doc.world.body(0).positions;
  let top = 0;
  for (let i = 0; i < x.length / 3; i++) if (x[3 * i + 1] > x[3 * top + 1]) top = i;
  doc.strokeStart({ tool: 'inflate', point: [x[3 * top], x[3 * top + 1], x[3 * top + 2]], radius: 0.3, strength: 1, inverted: false });
  for (let t = 0; t < ticks; t++) {
    doc.updateStroke(0.01);
    doc.advance(doc.settings.dt, 10);
  }
  doc.strokeEnd();
}

describe('undo by deltas', () => {
  it('an inflate stroke undoes to the rest lengths before it, keeps the rest of the body moving, and redoes', () => {
    const { doc } = opened();
    const rest0 = doc.world.body(0).rest.slice();
    inflate(doc);
    const painted = doc.world.body(0).rest.slice();
    expect(painted.some((r, k) => r !== rest0[k])).toBe(true);
    expect(doc.history.sizes).toEqual([1, 0]);
    doc.undo();
    expect(Array.from(doc.world.body(0).rest)).toEqual(Array.from(rest0));
    doc.redo();
    expect(Array.from(doc.world.body(0).rest)).toEqual(Array.from(painted));
    // A brush stroke's entry holds what it touched: far less than the body's state.
    const snapshotBytes = doc.world.snapshot().length;
    expect(doc.history.bytes).toBeLessThan(snapshotBytes / 4);
  });

  it('subdivide, freeze and a parameter undo to the whole world as it was, in order', () => {
    const { doc } = opened();
    const s0 = state(doc);
    doc.subdivide();
    doc.freeze();
    doc.setParam('stiffness', 250);
    expect(doc.params().stiffness).toBe(250);
    doc.undo();
    expect(doc.params().stiffness).toBe(100);
    doc.undo(); doc.undo();
    expect(state(doc)).toEqual(s0);
    expect(doc.vertexCount).toBe(362);
  });

  it('undoing across a scene brings the scene back, with its names and events for saving', () => {
    const { doc } = opened();
    const text = '[[body]]\nname = "ball"\nmodel = "sphere"\n[[event]]\ntime = 0.5\naction = "freeze"\n';
    expect(doc.openScene('one.toml', text)).toBe(true);
    doc.loadBuiltin('octopus');
    expect(doc.sceneInfo).toBeNull();
    doc.undo();
    expect(doc.sceneInfo).toMatchObject({ name: 'one.toml', bodies: 1 });
    expect(doc.sceneText()).toMatch(/name = "ball"[\s\S]*action = "freeze"/);
    doc.undo();
    expect(doc.sceneInfo).toBeNull();
    expect(doc.vertexCount).toBe(362);
  });
});

describe('history limits', () => {
  it('keeps at most `limit` steps and `maxBytes` bytes, dropping the oldest first', () => {
    const h = new History<Uint8Array>({ limit: 100, maxBytes: 1000, size: (b) => b.length });
    for (let i = 0; i < 150; i++) h.push(`s${i}`, new Uint8Array(5));
    expect(h.sizes).toEqual([100, 0]);
    expect(h.bytes).toBe(500);
    h.push('big', new Uint8Array(900)); // over 1000 bytes: the oldest go
    expect(h.bytes).toBeLessThanOrEqual(1000);
    expect(h.undoLabel).toBe('big');
    h.push('huge', new Uint8Array(5000)); // alone over the limit: kept (the newest always is)
    expect(h.sizes).toEqual([1, 0]);
    expect(h.bytes).toBe(5000);
  });

  it('a step that cannot be applied stays where it was', () => {
    const h = new History<number>(10);
    h.push('a', 1);
    expect(() => travel(h, 'undo', () => { throw new Error('no'); })).toThrow('no');
    expect(h.sizes).toEqual([1, 0]);
  });
});

describe('project files', () => {
  it('version 2 round-trips the whole world and the page state', () => {
    const { doc } = opened();
    inflate(doc);
    doc.ui = { brush: { radius: 0.5 }, tool: 'press', strengths: { press: 9 } };
    const text = doc.projectText();
    expect(JSON.parse(text)).toMatchObject({ format: 'softsculpt-project', version: 2, name: 'mushroom' });
    const s = state(doc);
    const other = opened().doc;
    other.openProjectText(text);
    expect(state(other)).toEqual(s);
    expect(other.ui.tool).toBe('press');
    other.undo(); // opening is one undo step
    expect(other.vertexCount).toBe(362);
  });

  it('a version-1 file opens, migrated, where it was saved', () => {
    const { doc } = opened();
    const w = doc.world, b = w.body(0);
    const arr = (x: ArrayLike<number>) => Array.from(x);
    w.sync();
    const v1 = JSON.stringify({
      format: 'softsculpt-project', version: 1, name: 'old.obj',
      body: {
        triangles: arr(b.triangles), pinned: arr(b.pinned), gas: [0, 1], frozenGas: [0, 1],
        params: { stiffness: 321, gasAmount: 0.01, groundOn: 1, groundHeight: 0 },
        positions: arr(b.positions), velocities: arr(b.velocities), restLengths: arr(b.rest), masses: arr(b.masses),
        frozenPositions: arr(b.positions), frozenRestLengths: arr(b.rest), prestress: arr(new Float64Array(b.positions.length)),
        frozenPrestress: arr(new Float64Array(b.positions.length)), bendingRestLengths: arr(b.bendingRest), frozenBendingRestLengths: arr(b.bendingRest),
      },
      ui: { dt: 0.0005, tool: 'pin' },
    });
    const positions = b.positions.slice();
    doc.loadBuiltin('sphere');
    doc.openProject('old.softsculpt.json', v1);
    expect(doc.vertexCount).toBe(362);
    expect(Array.from(doc.world.body(0).positions)).toEqual(Array.from(positions));
    expect(doc.params()).toMatchObject({ stiffness: 321, ground: true, dt: 0.0005 });
    expect(doc.ui.tool).toBe('pin');
  });

  it('a truncated, corrupted or newer-version file is refused with one message and the work stays', () => {
    const { doc, messages } = opened();
    inflate(doc);
    const good = doc.projectText();
    const s = state(doc), sizes = doc.history.sizes;
    const snapshot = doc.world.snapshot();
    const flipped = snapshot.slice(); flipped[flipped.length - 3] ^= 0x40;
    const cases: [string, RegExp][] = [
      [good.slice(0, good.length / 2), /the project file is truncated/],
      ['', /the project file is empty/],
      ['{"format":"softsculpt-project","version":3,"snapshot":""}', /project version 3 is newer than this modeler reads \(≤ 2\)/],
      ['{"format":"nope","version":2}', /not a SoftSculpt project/],
      [serialize({ name: 'x', ui: {}, snapshot: snapshot.slice(0, 200) }), /the snapshot is truncated: 200 of \d+ bytes/],
      [serialize({ name: 'x', ui: {}, snapshot: flipped }), /the snapshot is corrupted: checksum mismatch/],
      [JSON.stringify({ format: 'softsculpt-project', version: 2, name: 'x', ui: {}, snapshot: '%%%' }), /not valid base64/],
      [JSON.stringify({ format: 'softsculpt-project', version: 1, body: { positions: [1, 2] } }), /project: /],
    ];
    for (const [text, why] of cases) {
      const n = messages.length;
      doc.openProject('p.softsculpt.json', text);
      expect(messages.slice(n)).toHaveLength(1);
      expect(messages.at(-1)).toMatch(why);
      expect(messages.at(-1)).toMatch(/could not open p\.softsculpt\.json: .*the current model is unchanged/);
      expect(state(doc)).toEqual(s);
      expect(doc.history.sizes).toEqual(sizes);
    }
    expect(parse(good).version).toBe(2);
    expect(toBase64(new Uint8Array([0, 255, 1]))).toBe('AP8B');
  });
});

describe('autosave', () => {
  it('keeps the last complete record: a new one replaces it only once written whole', async () => {
    await clearAutosave();
    expect(await loadAutosave()).toBeNull();
    const { doc } = opened();
    await saveAutosave(doc.autosaveRecord(1));
    inflate(doc);
    const second = doc.autosaveRecord(2);
    await saveAutosave(second);
    const got = await loadAutosave();
    expect(got && 'record' in got && got.record.savedAt).toBe(2);
    // A write that fails mid-way (the record cannot be stored) leaves the last one readable.
    const bad = { ...doc.autosaveRecord(3), ui: { oops: () => 0 } } as never;
    await expect(saveAutosave(bad)).rejects.toBeTruthy();
    const still = await loadAutosave();
    expect(still && 'record' in still && Array.from(still.record.snapshot)).toEqual(Array.from(second.snapshot));
    // And it reopens the world as it was.
    const again = opened().doc;
    again.open(still);
    expect(state(again)).toEqual(Array.from(second.snapshot));
  });

  it('a corrupted autosave is reported and the default model opens', () => {
    const { doc } = opened();
    const record = doc.autosaveRecord(1);
    record.snapshot = record.snapshot.slice(0, 100);
    const messages: string[] = [];
    const fresh = new Document({ message: (t) => messages.push(t), progress: () => {}, changed: () => {}, ui: () => {} });
    fresh.open({ record });
    expect(messages[0]).toMatch(/the autosave could not be read \(.*truncated.*\); opened the default model instead/);
    expect(fresh.vertexCount).toBe(362);
    expect(fresh.history.sizes).toEqual([0, 0]);
  });

  it('an implicit step that cannot converge is split, then pauses with the reason, the state untouched', () => {
    const { doc, messages } = opened();
    // One Newton iteration to a relative residual of 1e-12: no step of any length gets there.
    doc.world.setParam(0, 'newton_iterations', 1);
    doc.world.setParam(0, 'tolerance', 1e-12);
    const before = state(doc);
    expect(doc.advance(1 / 60, 1)).toBe(false);
    expect(doc.settings.playing).toBe(false);
    expect(messages.at(-1)).toMatch(/could not finish a step at t = [0-9.]+ s, even split into 8\. .*paused/);
    // Rolled back by the engine at every try; the world's dt is the settings' again.
    expect(state(doc)).toEqual(before);
    expect(doc.world.params(0).dt).toBe(1 / 60);
  });
});


describe('the time step', () => {
  it('an implicit dt far below 1/60 s says it runs in slow motion and why; 1/60 s and an explicit dt say nothing of it', () => {
    const { doc, messages } = opened();
    expect(doc.world.params(0).integrator).toBe('implicit');
    doc.setParam('dt', 1e-6);
    // 1/60 s in steps of 1 µs: round(16,666.7) = 16,667 solves a frame.
    expect(messages.at(-1)).toMatch(/16,667 implicit steps for each 1\/60 s frame, so expect slow motion; the implicit integrator is stable at dt = 1\/60 s/);
    const said = messages.length;
    doc.setParam('dt', 1 / 60);
    doc.setParam('dt', 1 / 240); // four steps a frame: not yet
    expect(messages.slice(said).some((t) => /slow motion/.test(t))).toBe(false);
    doc.setParam('integrator', 'symplectic');
    doc.setParam('dt', 1e-6);
    expect(messages.slice(said).some((t) => /slow motion/.test(t))).toBe(false);
  });
});
