import { beforeAll, describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { loadEngine } from './setup';
import { guessUp, isClosed, needsAnswer, place, question, REFERENCE_DIAGONAL, sizeFactor, toFile } from '../src/io/import';
import { exportShape, shapeMesh } from '../src/io/export';
import { animationGlb, World } from '../src/engine/world';

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
