// What a scene adds to the view: its other bodies (drawn from the frame's positions, like the
// main surface) and its rigid obstacles (sphere, box, capsule, triangle mesh).

import * as THREE from 'three';
import type { Obstacle } from '../protocol';

const BODY_COLORS = [0x7fb0d9, 0x9ccf7f, 0xd98fb0, 0xc9c26b];

export class SceneExtras {
  readonly group = new THREE.Group();
  private bodies: { count: number; mesh: THREE.Mesh }[] = [];
  private obstacles: THREE.Object3D[] = [];
  private readonly obstacleMaterial = new THREE.MeshStandardMaterial({ color: 0x8a8f96, roughness: 0.8, metalness: 0.1, side: THREE.DoubleSide });

  /** The bodies besides the active one (each drawn with its own colour). */
  setBodies(bodies: { vertexCount: number; triangles: Uint32Array }[]): void {
    for (const b of this.bodies) { this.group.remove(b.mesh); b.mesh.geometry.dispose(); (b.mesh.material as THREE.Material).dispose(); }
    this.bodies = bodies.map((body, k) => {
      const g = new THREE.BufferGeometry();
      g.setIndex(new THREE.BufferAttribute(body.triangles, 1));
      g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * body.vertexCount), 3));
      const mesh = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: BODY_COLORS[k % BODY_COLORS.length], roughness: 0.55, side: THREE.DoubleSide }));
      mesh.frustumCulled = false;
      mesh.userData.body = k + 1; // picked by the tools (tools/pick.ts)
      this.group.add(mesh);
      return { count: body.vertexCount, mesh };
    });
  }

  /** New positions: the frame's buffer, the other bodies' xyz from `start` on, in order (views, no copies). */
  update(all: Float32Array, start: number): void {
    let at = start;
    for (const { count, mesh } of this.bodies) {
      const p = mesh.geometry.getAttribute('position') as THREE.BufferAttribute;
      (p as any).array = all.subarray(at, at + 3 * count);
      at += 3 * count;
      p.needsUpdate = true;
      mesh.geometry.computeVertexNormals();
    }
  }

  setObstacles(list: Obstacle[]): void {
    for (const o of this.obstacles) { this.group.remove(o); if (o instanceof THREE.Mesh) o.geometry.dispose(); }
    this.obstacles = list.map((o) => {
      let mesh: THREE.Mesh;
      if (o.kind === 'sphere') {
        mesh = new THREE.Mesh(new THREE.SphereGeometry(o.radius, 48, 24), this.obstacleMaterial);
        mesh.position.set(o.center[0], o.center[1], o.center[2]);
      } else if (o.kind === 'box') {
        mesh = new THREE.Mesh(new THREE.BoxGeometry(2 * o.half[0], 2 * o.half[1], 2 * o.half[2]), this.obstacleMaterial);
        const [x, y, z] = o.axes.map((a) => new THREE.Vector3(a[0], a[1], a[2]));
        mesh.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(x, y, z));
        mesh.position.set(o.center[0], o.center[1], o.center[2]);
      } else if (o.kind === 'capsule') {
        const a = new THREE.Vector3(...o.a), b = new THREE.Vector3(...o.b);
        mesh = new THREE.Mesh(new THREE.CapsuleGeometry(o.radius, a.distanceTo(b), 8, 24), this.obstacleMaterial);
        mesh.position.copy(a).add(b).multiplyScalar(0.5);
        if (a.distanceTo(b) > 0) mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), b.clone().sub(a).normalize());
      } else {
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(o.positions), 3));
        g.setIndex(new THREE.BufferAttribute(o.indices, 1));
        g.computeVertexNormals();
        mesh = new THREE.Mesh(g, this.obstacleMaterial);
      }
      this.group.add(mesh);
      return mesh;
    });
  }

  clear(): void {
    this.setBodies([]);
    this.setObstacles([]);
  }
}
