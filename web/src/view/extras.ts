// What a scene adds to the view: its other bodies (read from the engine's f32 positions, like
// the main surface) and its rigid obstacles (sphere, box, capsule, triangle mesh).

import * as THREE from 'three';
import type { SoftBody } from '../engine/softbody';
import type { Obstacle } from '../engine/scene';

const BODY_COLORS = [0x7fb0d9, 0x9ccf7f, 0xd98fb0, 0xc9c26b];

export class SceneExtras {
  readonly group = new THREE.Group();
  private bodies: { body: SoftBody; mesh: THREE.Mesh }[] = [];
  private obstacles: THREE.Object3D[] = [];
  private readonly obstacleMaterial = new THREE.MeshStandardMaterial({ color: 0x8a8f96, roughness: 0.8, metalness: 0.1, side: THREE.DoubleSide });

  /** The bodies besides the active one (each drawn with its own colour). */
  setBodies(bodies: SoftBody[]): void {
    for (const b of this.bodies) { this.group.remove(b.mesh); b.mesh.geometry.dispose(); (b.mesh.material as THREE.Material).dispose(); }
    this.bodies = bodies.map((body, k) => {
      const g = new THREE.BufferGeometry();
      g.setIndex(new THREE.BufferAttribute(body.triangles().slice(), 1));
      g.setAttribute('position', new THREE.BufferAttribute(body.syncRender(), 3));
      const mesh = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: BODY_COLORS[k % BODY_COLORS.length], roughness: 0.55, side: THREE.DoubleSide }));
      mesh.frustumCulled = false;
      this.group.add(mesh);
      return { body, mesh };
    });
    this.update();
  }

  /** New positions from the engine (fresh views, no copies). */
  update(): void {
    for (const { body, mesh } of this.bodies) {
      if (!body.alive) continue;
      const p = mesh.geometry.getAttribute('position') as THREE.BufferAttribute;
      (p as any).array = body.syncRender();
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
