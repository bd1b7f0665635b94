// Re-importing an export gives back the shape that was exported (issue #37, "files as users
// have them"): an import of a closed mesh rests at its own shape — the gas amount the modeler's
// preset gives it, then frozen under load so the shape in the file is an equilibrium
// (worker/importer.ts `addPieces`, docs/meshing.md) — unless the import dialog's "inflate it"
// is checked, which keeps the old behaviour (the gas swells it).
import { beforeAll, describe, expect, it } from 'vitest';
import { loadEngine, openedDocument } from './setup';
import { exportShape } from '../src/io/export';
import type { ImportAnswer } from '../src/io/import';

beforeAll(loadEngine);

/** The lowest and highest y and the volume of body 0, after a sync. */
function shape(doc: ReturnType<typeof openedDocument>['doc']) {
  doc.world.sync();
  const x = doc.world.body(0).positions;
  let lo = Infinity, hi = -Infinity;
  for (let i = 1; i < x.length; i += 3) { lo = Math.min(lo, x[i]); hi = Math.max(hi, x[i]); }
  return { height: hi - lo, volume: doc.world.body(0).stats.volume };
}

/** The default mushroom (at rest after the load's settling) exported as STL, as the page exports it. */
async function exportedMushroom() {
  const { doc } = openedDocument();
  const b = doc.world.body(0);
  const data = new Uint8Array(await (await exportShape('stl', [{ positions: b.positions.slice(), triangles: b.triangles.slice() }], undefined, null)).arrayBuffer());
  return { data, before: shape(doc) };
}

/** `data` imported into a new document (answered as the dialog's defaults, `inflate` as given) and run 5 s. */
function reimported(data: Uint8Array, inflate: boolean) {
  const { doc, messages } = openedDocument();
  doc.importFile('mushroom.stl', data.slice().buffer as ArrayBuffer);
  const importer = (doc as unknown as { importer: { waiting: unknown; made: Map<number, { p: unknown; a: ImportAnswer }>; build(p: unknown, a: ImportAnswer): boolean } }).importer;
  if (importer.waiting !== null) doc.importAnswer({ up: 'y', pieces: 'each', inflate });
  else if (inflate) {
    // Our own export declares its up axis, so nothing was asked: built again as the dialog's
    // "inflate it" would have built it.
    const l = importer.made.get(doc.settings.opened ?? -1)!;
    importer.build(l.p, { ...l.a, inflate: true });
  }
  const start = shape(doc);
  const dt = doc.settings.dt;
  for (let i = 0; i < Math.round(5 / dt); i++) expect(doc.advance(dt, 1)).toBe(true);
  return { doc, messages, start, end: shape(doc) };
}

describe('re-importing an export', () => {
  it('gives back the exported mushroom: its volume and height within 0.2 % after 5 s, and says it rests at the file\'s shape', async () => {
    const { data, before } = await exportedMushroom();
    const { messages, start, end } = reimported(data, false);
    // The file's shape is where it starts (the export writes float32: ~1e-7 relative).
    expect(Math.abs(start.volume / before.volume - 1)).toBeLessThan(1e-5);
    // And where it stays: the freeze makes the shape the rest shape (no spring or net gas
    // force) with the weight carried onto the ground, so what could move it is the float32
    // rounding of the file and the contact settling into the ground's penalty. Measured: both
    // within 5e-5. Before this import rule the gas
    // swelled it by 15 % in volume and 7 % in height (2.45 → 2.83 m³, 1.84 → 1.97 m, the next
    // test): 2e-3 leaves a margin of 40 over the measured and separates the two by 35.
    expect(Math.abs(end.volume / before.volume - 1)).toBeLessThan(2e-3);
    expect(Math.abs(end.height / before.height - 1)).toBeLessThan(2e-3);
    expect(messages.some((m) => /at rest at the shape in the file/.test(m))).toBe(true);
    console.log(`re-imported: volume ${before.volume.toFixed(4)} → ${end.volume.toFixed(4)} m³, height ${before.height.toFixed(4)} → ${end.height.toFixed(4)} m`);
  }, 300_000);

  it('"inflate it" swells it by its gas, as imports did before', async () => {
    const { data, before } = await exportedMushroom();
    const { messages, end } = reimported(data, true);
    // The preset's gas against a slack skin: the volume grows by more than the 1 % above (15 %
    // measured before the rule; the exact figure is the preset's, not this test's).
    console.log(`inflated: volume ${before.volume.toFixed(4)} → ${end.volume.toFixed(4)} m³, height ${before.height.toFixed(4)} → ${end.height.toFixed(4)} m`);
    expect(end.volume / before.volume - 1).toBeGreaterThan(0.05);
    expect(messages.some((m) => /inflated by its gas/.test(m))).toBe(true);
  }, 300_000);
});
