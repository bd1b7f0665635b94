import { beforeAll, describe, expect, it } from 'vitest';
import * as THREE from 'three';
import { STLExporter } from 'three/examples/jsm/exporters/STLExporter.js';
import { loadEngine } from './setup';
import { importModel, mergeMeshes } from '../src/io/import';
import { exportShape, shapeMesh } from '../src/io/export';
import { World } from '../src/engine/world';

beforeAll(loadEngine);

const enc = (s: string) => new TextEncoder().encode(s).buffer as ArrayBuffer;

/** An icosphere (closed) as a three.js mesh, non-indexed like most loaders return. */
function ball(): THREE.Mesh {
  return new THREE.Mesh(new THREE.IcosahedronGeometry(1, 2));
}

describe('import', () => {
  it('STL (unindexed triangles) comes in as one mesh the engine welds closed', async () => {
    const stl = new STLExporter().parse(ball(), { binary: true }) as unknown as DataView;
    const imported = await importModel('ball.stl', stl.buffer as ArrayBuffer);
    if (imported.kind !== 'mesh') throw new Error('expected a mesh');
    expect(imported.indices.length % 3).toBe(0);
    const w = World.create();
    w.addMesh(imported.positions, imported.indices);
    expect(w.warnings.join('\n')).toMatch(/welded/);
    expect(w.body(0).vertexCount).toBe(92); // three's detail 2 splits each edge in 3: 10·3² + 2
    w.setParam(0, 'gas.amount', 0.001); // closed: gas is accepted
    w.free();
  });

  it('PLY comes in through the three.js loader', async () => {
    // A tetrahedron in ASCII PLY.
    const text = 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n' +
      'element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n';
    const imported = await importModel('tetra.ply', enc(text));
    if (imported.kind !== 'mesh') throw new Error('expected a mesh');
    expect(imported.positions.length).toBe(12);
    expect(Array.from(imported.indices)).toEqual([0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3]);
  });

  it('OBJ goes to the engine reader, which names the bad line', async () => {
    const imported = await importModel('bad.obj', enc('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n'));
    if (imported.kind !== 'obj') throw new Error('expected obj bytes');
    const w = World.create();
    expect(() => w.addObj(imported.bytes)).toThrow(/line 4: face refers to vertex 9/);
    w.free();
  });

  it('refuses empty files, unknown types and files without triangles', async () => {
    await expect(importModel('x.obj', new ArrayBuffer(0))).rejects.toThrow(/empty/);
    await expect(importModel('x.fbx', enc('data'))).rejects.toThrow(/unsupported file type '.fbx'/);
    await expect(importModel('x.stl', enc('solid x\nendsolid x\n'))).rejects.toThrow(/x\.stl: /);
    expect(() => mergeMeshes(new THREE.Group())).toThrow(/no triangles/);
  });

  it('merging applies each mesh’s world transform', () => {
    const g = new THREE.Group();
    const a = new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2));
    a.position.set(10, 0, 0);
    g.add(a);
    const { positions } = mergeMeshes(g);
    let minX = Infinity;
    for (let i = 0; i < positions.length; i += 3) minX = Math.min(minX, positions[i]);
    expect(minX).toBe(9);
  });
});

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
