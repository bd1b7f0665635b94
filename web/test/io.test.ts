import { beforeAll, describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { OBJExporter } from 'three/examples/jsm/exporters/OBJExporter.js';
import { loadEngine } from './setup';
import { guessUp, headerText, isClosed, needsAnswer, place, question, REFERENCE_DIAGONAL, sizeFactor, toFile, tooCoarse, type ImportFrame, type Up } from '../src/io/import';
import { dialogHtml } from '../src/io/dialog';
import { exportHeader, exportShape, shapeMesh } from '../src/io/export';
import { animationGlb, World } from '../src/engine/world';
import { addModel } from '../src/engine/models';
import { SLOW_FRAME_MS, verdict } from '../src/worker/trial';

beforeAll(loadEngine);

const enc = (s: string) => new TextEncoder().encode(s).buffer as ArrayBuffer;

/** An icosphere (closed) as a three.js mesh, non-indexed like most loaders return. */
function ball(): THREE.Mesh {
  return new THREE.Mesh(new THREE.IcosahedronGeometry(1, 2));
}

describe('import', () => {
  it('STL (unindexed triangles) is read by the engine and welded closed', async () => {
    const stl = new STLExporter().parse(ball(), { binary: true }) as unknown as DataView;
    const w = World.create();
    const { report } = w.addFile('ball.stl', new Uint8Array(stl.buffer as ArrayBuffer), true);
    expect(report.format).toBe('STL');
    expect(report.up_axis).toBe('unknown');
    expect(w.body(0).vertexCount).toBe(92); // three's detail 2 splits each edge in 3: 10·3² + 2
    expect(report.pieces).toEqual([expect.objectContaining({ vertices: 92, closed: true, boundary_edges: 0 })]);
    w.setParam(0, 'gas.amount', 0.001); // closed: gas is accepted
    w.free();
  });

  it('PLY comes in through the engine reader, glTF declares Y up', async () => {
    const text = 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n' +
      'element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n';
    const w = World.create();
    const { report } = w.addFile('tetra.ply', new Uint8Array(enc(text)), true);
    expect(report.format).toBe('PLY');
    expect(w.body(0).vertexCount).toBe(4);
    // A GLB (the recording's writer, one frame) reads back, Y-up by specification.
    const glb = animationGlb(new Float64Array([0]), [{ triangles: w.body(0).triangles.slice(), frames: [Float32Array.from(w.body(0).positions)] }]);
    const g = w.addFile('tetra.glb', glb, true);
    expect(g.report.up_axis).toBe('y');
    expect(w.body(g.first).vertexCount).toBe(4);
    w.free();
  });

  it('a bad OBJ names the line; unknown and empty files say what is wrong', () => {
    const w = World.create();
    expect(() => w.addFile('bad.obj', new Uint8Array(enc('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n')), true)).toThrow(/line 4.*vertex 9/);
    expect(() => w.addFile('x.fbx', new Uint8Array(enc('data')), true)).toThrow(/cannot tell the file's format/);
    expect(() => w.addFile('x.stl', new Uint8Array(enc('solid x\nendsolid x\n')), true)).toThrow(/./);
    expect(w.bodyCount).toBe(0);
    w.free();
  });

  it('two shells come as two bodies, the larger first; the question says so', () => {
    const small = icosphereObj(0.5, -3), big = icosphereObj(1, 3);
    const w = World.create();
    const { report } = w.addFile('two.obj', new Uint8Array(enc(joinObj(small, big))), true);
    expect(w.bodyCount).toBe(2);
    expect(report.pieces.map((p) => p.vertices)).toEqual([42, 42]);
    expect(report.pieces[0].area / report.pieces[1].area).toBeCloseTo(4, 10); // area ∝ size²
    const q = question('two.obj', report, [w.body(0).positions.slice(), w.body(1).positions.slice()]);
    expect(q.pieces.length).toBe(2);
    expect(needsAnswer(q)).toBe(true);
    w.free();
  });

  it('the up axis is guessed from the plane a model rests on, else by format', () => {
    const onZ = [0, 0, 0, 1, 1, 2, -1, -1, 1];
    expect(guessUp('OBJ', [onZ]).up).toBe('z');
    expect(guessUp('STL', [[0, 0, 0, 1, 2, 1, -1, 1, -1]]).up).toBe('y');
    expect(guessUp('STL', [[0, -1, -1, 1, 1, 1]]).up).toBe('z');
    expect(guessUp('PLY', [[0, -1, -1, 1, 1, 1]]).up).toBe('y');
  });

  it('the import frame turns Z-up upright, stands the model on the ground, and exports go back exactly', () => {
    const file = new Float64Array([0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 3, 5, 5, 5]);
    const { positions, frame } = place([file], 'z');
    const p = positions[0];
    // Z was up: the model is 3 tall in y now, from 0.
    let lo = Infinity, hi = -Infinity;
    for (let i = 1; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); }
    expect([lo, hi]).toEqual([0, 5]);
    expect(Array.from(toFile(p, frame), (x) => x + 0)).toEqual(Array.from(file)); // sums and swaps only: exact (+0 folds −0)
    // Unchanged size: nothing is rescaled.
    expect(sizeFactor(positions)).toBeCloseTo(Math.hypot(5, 5, 5) / REFERENCE_DIAGONAL, 12);
  });

  it('closed and open surfaces are told apart', () => {
    expect(isClosed([0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3])).toBe(true);
    expect(isClosed([0, 2, 1, 0, 1, 3, 1, 2, 3])).toBe(false);
  });
});

/** An icosahedron (12 vertices) subdivided once: 42 vertices of radius r at x = dx, as OBJ lines. */
function icosphereObj(r: number, dx: number): { v: number[][]; f: number[][] } {
  const g = new THREE.IcosahedronGeometry(r, 1);
  const w = World.create();
  const p = g.getAttribute('position');
  const pos = new Float64Array(p.count * 3);
  for (let i = 0; i < p.count; i++) { pos[3 * i] = p.getX(i) + dx; pos[3 * i + 1] = p.getY(i); pos[3 * i + 2] = p.getZ(i); }
  w.addMesh(pos, Uint32Array.from({ length: p.count }, (_, i) => i));
  const b = w.body(0);
  const x = b.positions, t = b.triangles;
  const out = { v: [] as number[][], f: [] as number[][] };
  for (let i = 0; i < b.vertexCount; i++) out.v.push([x[3 * i], x[3 * i + 1], x[3 * i + 2]]);
  for (let i = 0; i < t.length; i += 3) out.f.push([t[i], t[i + 1], t[i + 2]]);
  w.free();
  return out;
}
function joinObj(...parts: { v: number[][]; f: number[][] }[]): string {
  let text = '', base = 1;
  for (const m of parts) {
    for (const v of m.v) text += `v ${v.join(' ')}\n`;
    for (const f of m.f) text += `f ${f.map((i) => i + base).join(' ')}\n`;
    base += m.v.length;
  }
  return text;
}

describe('export', () => {
  it('OBJ has every vertex and face of the shape', async () => {
    const w = World.create();
    w.addBuiltin('octopus');
    const body = w.body(0);
    const blob = await exportShape('obj', body.positions.slice(), body.triangles.slice());
    const text = await blob.text();
    expect(text.split('\n').filter((l) => l.startsWith('v ')).length).toBe(body.vertexCount);
    expect(text.split('\n').filter((l) => l.startsWith('f ')).length).toBe(body.faceCount);
    w.free();
  });

  it('STL is binary with one record per face', async () => {
    const w = World.create();
    w.addBuiltin('sphere');
    const body = w.body(0);
    const blob = await exportShape('stl', body.positions.slice(), body.triangles.slice());
    // 80-byte header + 4-byte count + 50 bytes per triangle.
    expect(blob.size).toBe(84 + 50 * body.faceCount);
    w.free();
  });

  it('the export mesh reads the engine positions', () => {
    const m = shapeMesh([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 2]);
    expect(m.geometry.getAttribute('position').count).toBe(3);
  });
});

// ----- our STL and OBJ say which axis is up -------------------------------------------------------

/**
 * A file read back as the worker reads it (worker/importer.ts `read`, then `build` with the
 * guessed axis): the engine's pieces, the question from the file's first bytes, and the pieces
 * placed (turned upright if Z-up, standing on the ground) with their frame.
 */
function readBack(name: string, data: Uint8Array) {
  const w = World.create();
  try {
    const { first, report } = w.addFile(name, data, true);
    const bodies = report.pieces.map((_, k) => w.body(first + k));
    const lists = bodies.map((b) => b.positions.slice()), triangles = bodies.map((b) => b.triangles.slice());
    const q = question(name, report, lists, triangles, headerText(data));
    return { q, lists, triangles, ...place(lists, q.guessedUp) };
  } finally {
    w.free();
  }
}

/**
 * How far the points of `a` are from the same points in `b` (as many; the reader may weld and
 * reorder them): the largest distance from a point of `a` to its nearest in `b`.
 */
function farthest(a: ArrayLike<number>, b: ArrayLike<number>): number {
  expect(a.length).toBe(b.length);
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) {
    let best = Infinity;
    for (let j = 0; j < b.length; j += 3) best = Math.min(best, Math.hypot(a[i] - b[j], a[i + 1] - b[j + 1], a[i + 2] - b[j + 2]));
    worst = Math.max(worst, best);
  }
  return worst;
}

const bytesOf = async (blob: Blob) => new Uint8Array(await blob.arrayBuffer());
/** A model's size: its bounding-box diagonal. */
const diagonal = (x: ArrayLike<number>) => Math.hypot(...bounds3(x));
/** A model's extents in x, y and z. */
function bounds3(x: ArrayLike<number>): [number, number, number] {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < x.length; i += 3) for (let d = 0; d < 3; d++) { lo[d] = Math.min(lo[d], x[i + d]); hi[d] = Math.max(hi[d], x[i + d]); }
  return [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
}

describe('exports say which axis is up, and come back as they were', () => {
  // A new-user trial: our STL of a Y-up model came back lying on its side (STL declares no up
  // axis; the guess for STL is Z-up, unsure, unless the shape tells).
  it('a built-in (Y-up) model exported as STL and OBJ is read back Y-up for sure, upright', async () => {
    const w = World.create();
    addModel(w, 'octopus');
    const x = w.body(0).positions.slice(), t = w.body(0).triangles.slice();
    w.free();
    // Lifted off the ground (as a grab leaves it, or mid-bounce): the shape no longer says Y-up.
    for (let i = 1; i < x.length; i += 3) x[i] += 0.3;
    expect(guessUp('STL', [x], [t]).sure).toBe(false);
    // As the page exports it: no import frame, the engine's own coordinates.
    const upright = place([x], 'y').positions[0];
    for (const format of ['stl', 'obj'] as const) {
      const data = await bytesOf(await exportShape(format, x, t));
      const r = readBack(`octopus.${format}`, data);
      // The header text is what we wrote (and the STL's header is its first 80 bytes).
      expect(exportHeader(null)).toBe('SoftSculpt export, Y-up, metres');
      expect(headerText(data, format === 'stl' ? 80 : 34).trim()).toBe(format === 'stl' ? exportHeader(null) : `# ${exportHeader(null)}`);
      expect(r.q).toMatchObject({ guessedUp: 'y', upSure: true, guessReason: 'written by SoftSculpt as Y-up' });
      expect(needsAnswer(r.q)).toBe(false);
      // Upright: the same positions as before, within float32 rounding.
      expect(r.positions[0].length).toBe(x.length);
      expect(farthest(r.positions[0], upright)).toBeLessThan(1e-6 * diagonal(x));
    }
  });

  it('an imported Z-up STL and a Y-up OBJ off the ground, exported as STL and OBJ, come back as they were', async () => {
    // A tall ellipsoid (3 m along its up axis, centred at the origin: nothing rests on a plane).
    const g = new THREE.IcosahedronGeometry(1, 3);
    const ball = Float64Array.from(g.getAttribute('position').array);
    const files: { name: string; up: Up; data: Uint8Array }[] = [];
    const tall = (up: Up) => { const p = ball.slice(); for (let i = 0; i < p.length; i += 3) p[i + (up === 'z' ? 2 : 1)] *= 1.5; return p; };
    // Written by three.js (zeroed STL header, no OBJ comment): the guess is unsure, the user answers.
    files.push({ name: 'tall.stl', up: 'z', data: new Uint8Array((new STLExporter().parse(new THREE.Mesh(geometryOf(tall('z'))), { binary: true }) as unknown as DataView).buffer as ArrayBuffer) });
    files.push({ name: 'tall.obj', up: 'y', data: new Uint8Array(enc(new OBJExporter().parse(new THREE.Mesh(geometryOf(tall('y')))))) });
    for (const f of files) {
      const first = readBack(f.name, f.data);
      expect(first.q.upSure).toBe(false);
      // The user's answer builds it: upright in the engine, the file's frame kept for exports.
      const { positions, frame } = place(first.lists, f.up);
      frame.format = first.q.format;
      const engine = positions[0];
      expect(bounds3(engine)[1]).toBeCloseTo(3, 5);
      for (const format of ['stl', 'obj'] as const) {
        const data = await bytesOf(await exportShape(format, [{ positions: engine, triangles: first.triangles[0] }], undefined, frame));
        const header = exportHeader(frame);
        expect(header).toBe(`SoftSculpt export, ${f.up.toUpperCase()}-up, units as in the imported ${first.q.format} file`);
        expect(headerText(data, 4096).startsWith(format === 'stl' ? header : `# ${header}`)).toBe(true);
        const r = readBack(`again.${format}`, data);
        expect(r.q).toMatchObject({ guessedUp: f.up, upSure: true, guessReason: `written by SoftSculpt as ${f.up.toUpperCase()}-up` });
        expect(needsAnswer(r.q)).toBe(false);
        // As it was: the same file coordinates and the same upright model in the engine.
        expect(farthest(r.lists[0], first.lists[0])).toBeLessThan(1e-6 * 3);
        expect(farthest(r.positions[0], engine)).toBeLessThan(1e-6 * 3);
        expect(r.frame.offset.every((o, d) => Math.abs(o - frame.offset[d]) < 1e-6)).toBe(true);
      }
    }
  });

  it('the header keeps the binary STL as it was: 80 bytes, the triangle count at byte 80, never "solid"', async () => {
    const w = World.create();
    w.addBuiltin('sphere');
    const b = w.body(0);
    const frames: (ImportFrame | null)[] = [null, { up: 'z', offset: [0, 0, 0], format: 'STL' }, { up: 'y', offset: [0, 0, 0], format: 'glTF' }];
    for (const frame of frames) {
      const data = await bytesOf(await exportShape('stl', [{ positions: b.positions.slice(), triangles: b.triangles.slice() }], undefined, frame));
      expect(data.length).toBe(84 + 50 * b.faceCount);
      expect(new DataView(data.buffer).getUint32(80, true)).toBe(b.faceCount);
      expect(exportHeader(frame).length).toBeLessThanOrEqual(80);
      expect(new TextDecoder().decode(data.subarray(0, 5))).not.toBe('solid');
      // The rest of the file is three's, byte for byte.
      const plain = new Uint8Array((new STLExporter().parse(shapeMesh(toFile(b.positions, frame ?? { up: 'y', offset: [0, 0, 0] }), b.triangles), { binary: true }) as unknown as DataView).buffer as ArrayBuffer);
      expect(data.subarray(80)).toEqual(plain.subarray(80));
    }
    expect(exportHeader({ up: 'y', offset: [0, 0, 0], format: 'glTF' })).toBe('SoftSculpt export, Y-up, metres');
    // OBJ: the comment line, then three's statements unchanged.
    const obj = await (await exportShape('obj', b.positions.slice(), b.triangles.slice())).text();
    const [first, ...rest] = obj.split('\n');
    expect(first).toBe('# SoftSculpt export, Y-up, metres');
    expect(rest.join('\n')).toBe(new OBJExporter().parse(shapeMesh(b.positions, b.triangles)));
    w.free();
  });

  it("other programs' headers are read as before; a SoftSculpt command-line header states no axis", () => {
    const far = [[0, -1, -1, 1, 1, 1]];
    expect(guessUp('STL', far, [], 'Exported from Blender-3.4').up).toBe('z');
    expect(guessUp('OBJ', far, [], '# Blender 3.4 OBJ File').up).toBe('y');
    expect(guessUp('STL', far, [], 'SoftSculpt export, Z-up, metres')).toEqual({ up: 'z', reason: 'written by SoftSculpt as Z-up', sure: true });
    expect(guessUp('OBJ', far, [], '# SoftSculpt export, Y-up, metres o softsculpt v 0 0 0')).toEqual({ up: 'y', reason: 'written by SoftSculpt as Y-up', sure: true });
    // The CLI writes in the input's own frame and says nothing of an axis: unsure, as before.
    expect(guessUp('STL', far, [], 'SoftSculpt remesh in.stl --edge 0.1').sure).toBe(false);
    // We write no PLY: a PLY's header is not taken for ours.
    expect(guessUp('PLY', far, [], 'SoftSculpt export, Z-up').sure).toBe(false);
  });
});

/** A three.js geometry of xyz positions (unindexed triangles). */
function geometryOf(p: Float64Array): THREE.BufferGeometry {
  const geo = new THREE.BufferGeometry();
  geo.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(p), 3));
  return geo;
}

describe('the import trial (worker/trial.ts)', () => {
  const even = { minAngle: 40, smallShare: 0, shortest: 0.6, poor: false };
  const slivers = { minAngle: 0.8, smallShare: 0.06, shortest: 0.03, poor: false };
  it('recommends Remesh for slivers that made the trial slow, with the reason, and not for a large even mesh', () => {
    const v = verdict(slivers, 1, 4 * SLOW_FRAME_MS);
    expect(v.remesh).toBe(true);
    expect(v.why).toMatch(/took \d+ ms .*long thin triangles \(smallest angle 0\.8°, shortest edge 3 % of the mean\)/);
    expect(verdict(slivers, 0, 500).why).toMatch(/did not finish/);
    // Slivers that cost nothing (the trial fast), or an even mesh that is merely large: no.
    expect(verdict(slivers, 6, SLOW_FRAME_MS / 4).remesh).toBe(false);
    expect(verdict(even, 0, 500).remesh).toBe(false);
    // Triangles the core calls poor (many small angles): offered when slow, only named when fast.
    expect(verdict({ ...even, poor: true, smallShare: 0.3 }, 0, 500)).toMatchObject({ remesh: true, reason: 'uneven triangles make uneven, slow springs' });
    expect(verdict({ ...even, poor: true, smallShare: 0.3 }, 6, 1)).toMatchObject({ remesh: false, why: 'uneven triangles (30 % of angles below 25°)' });
  });
  it('asks about a file whose only open question is Remesh', () => {
    const q = { name: 'a.obj', format: 'OBJ', declaredUp: null, guessedUp: 'y' as Up, guessReason: '', upSure: true, pieces: [{ vertices: 642, faces: 1280, closed: true }], size: [1, 1, 1] as [number, number, number] };
    expect(needsAnswer(q)).toBe(false);
    expect(needsAnswer({ ...q, cost: verdict(slivers, 0, 500) })).toBe(true);
    expect(needsAnswer({ ...q, cost: verdict(even, 0, 500) })).toBe(false);
  });
  it('asks about a closed model too coarse to shape, recommending Remesh where it adds vertices, else Subdivide; not about a coarse open sheet', () => {
    const box = { name: 'box.obj', format: 'OBJ', declaredUp: null, guessedUp: 'y' as Up, guessReason: 'it rests on the plane y = 0', upSure: true, pieces: [{ vertices: 8, faces: 12, closed: true }], size: [1, 1, 1] as [number, number, number], cost: verdict(even, 6, 1) };
    expect(tooCoarse(box)).toBe(true);
    expect(needsAnswer(box)).toBe(true);
    const html = dialogHtml(box);
    expect(html).toMatch(/Only 8 vertices: too coarse to shape/);
    expect(html).toMatch(/<input type="radio" name="refine" value="remesh" checked> Remesh to even triangles \(recommended\)/);
    expect(html).toMatch(/name="refine" value="subdivide"/);
    // The sure up axis is said, not asked.
    expect(html).not.toMatch(/Which way is up/);
    expect(html).toMatch(/<input type="hidden" name="up" value="y">/);
    // Two 42-vertex icospheres that Remesh leaves at 84 vertices: Subdivide is recommended.
    const icospheres = dialogHtml({ ...box, pieces: [{ vertices: 42, faces: 80, closed: true }, { vertices: 42, faces: 80, closed: true }], remeshed: 84 });
    expect(icospheres).toMatch(/<input type="radio" name="refine" value="subdivide" checked> Subdivide \(recommended\)/);
    expect(icospheres).not.toMatch(/value="remesh" checked/);
    expect(needsAnswer({ ...box, pieces: [{ vertices: 100, faces: 196, closed: true }] })).toBe(false);
    expect(needsAnswer({ ...box, pieces: [{ vertices: 9, faces: 8, closed: false }] })).toBe(false);
  });
});
