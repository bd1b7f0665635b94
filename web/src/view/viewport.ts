// The 3D view: renderer, camera and its controls (view/camera.ts), ground grid, the body's surface
// and springs. The surface draws the positions of the simulation's frames (transferred buffers)
// without copying.

import * as THREE from 'three';
import { CameraRig } from './camera';
import { SceneExtras } from './extras';
import { lengthUnit } from '../tools/scale';

/** The wind arrow's middle, as a share of the view's half height above its target (`placeWind`). */
const WIND_ARROW_HIGH = 0.7;
/** The wind arrow's length as a share of the view's half height: at calm, and at 20 m/s and above. */
const WIND_ARROW_LENGTH = [0.2, 0.5] as const;

export class Viewport {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(45, 1, 0.01, 200);
  /** Turntable (default) or trackball, zoom limits from the model's size, framing (V). */
  readonly rig: CameraRig;
  readonly surface: THREE.Mesh<THREE.BufferGeometry, THREE.MeshStandardMaterial>;
  readonly springs: THREE.LineSegments<THREE.BufferGeometry, THREE.LineBasicMaterial>;
  readonly grid = new THREE.GridHelper(20, 40, 0x667788, 0x3a4450);
  readonly groundPlane: THREE.Mesh;
  readonly windArrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 2.5, 0), 1, 0x44aaff, 0.25, 0.15);
  /** A scene's other bodies and obstacles. */
  readonly extras = new SceneExtras();
  private colors = new Float32Array(0);
  /** Something changed since the last render (a new frame, the camera, the overlay…). */
  private dirty = true;
  /** WebGL runs in software here (no GPU): drawn without multisampling and within SOFTWARE_PIXELS (unless `fullResolution`). */
  readonly software = isSoftwareRenderer();
  /** Draw at the screen's full resolution even on a software renderer (the panel's View folder). */
  private full = false;

  constructor(readonly canvas: HTMLCanvasElement) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: !this.software, preserveDrawingBuffer: true });
    this.scene.background = new THREE.Color(0x20252c);
    this.scene.add(new THREE.HemisphereLight(0xdde8ff, 0x303030, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.rig = new CameraRig(this.camera, canvas, () => this.invalidate());

    const geometry = new THREE.BufferGeometry();
    this.surface = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: 0xd9a066, roughness: 0.55, metalness: 0.05, vertexColors: false, side: THREE.DoubleSide }));
    this.springs = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x202020, transparent: true, opacity: 0.45 }));
    this.springs.visible = false;
    this.surface.frustumCulled = false;
    this.springs.frustumCulled = false;
    this.groundPlane = new THREE.Mesh(new THREE.PlaneGeometry(20, 20), new THREE.MeshStandardMaterial({ color: 0x2c343d, roughness: 1 }));
    this.groundPlane.rotation.x = -Math.PI / 2;
    this.groundPlane.position.y = -0.001;
    this.scene.add(this.surface, this.springs, this.grid, this.groundPlane, this.windArrow, this.extras.group);
    this.windArrow.visible = false;
    this.resize();
    window.addEventListener('resize', () => this.resize());
  }

  resize(): void {
    const w = this.canvas.clientWidth || window.innerWidth;
    const h = this.canvas.clientHeight || window.innerHeight;
    this.renderer.setPixelRatio(pixelRatio(this.software && !this.full, window.devicePixelRatio, w, h));
    this.renderer.setSize(w, h, false);
    this.invalidate();
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.rig.resized();
  }

  /** The active camera controls (the tools switch them off while they drag). */
  get controls() { return this.rig.controls; }

  /**
   * Fit the model in the view, level (V): around where it is now (a model that fell over or was
   * blown away is framed where it lies, not where it arrived).
   */
  resetView(): void {
    const g = this.surface.geometry;
    g.computeBoundingSphere();
    const sphere = g.boundingSphere;
    this.rig.frame(sphere && Number.isFinite(sphere.radius) ? sphere.center : undefined);
  }

  /** The model's bounding sphere (from the drawn positions): zoom limits follow it. */
  /** The bounding-sphere radius (m) of the model when it was last measured. */
  modelRadius = 0;

  measureModel(): void {
    const g = this.surface.geometry;
    g.computeBoundingSphere();
    if (g.boundingSphere && Number.isFinite(g.boundingSphere.radius)) this.rig.setModel(g.boundingSphere.center, g.boundingSphere.radius);
    // The ground grid follows the model's size (imports keep their units): 20 × 20 squares
    // of a power of ten metres near the model's diameter / 2.5 (1 m for the built-in models),
    // the brush's length unit too (tools/scale.ts).
    this.modelRadius = g.boundingSphere?.radius ?? 0;
    const grid = lengthUnit(this.modelRadius);
    this.grid.scale.setScalar(grid);
    this.groundPlane.scale.setScalar(grid);
  }

  /** Point the surface and the springs at a (new) mesh: its triangles, springs and positions. */
  attach(triangles: Uint32Array, springs: Uint32Array, positions: Float32Array): void {
    const g = this.surface.geometry;
    g.setIndex(new THREE.BufferAttribute(triangles, 1));
    const position = new THREE.BufferAttribute(positions, 3);
    position.setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', position);
    this.colors = new Float32Array(positions.length).fill(1);
    g.setAttribute('color', new THREE.BufferAttribute(this.colors, 3));
    const s = this.springs.geometry;
    s.setIndex(new THREE.BufferAttribute(springs, 1));
    s.setAttribute('position', position);
    this.update(positions);
    // The material's shader may have been built before the surface had vertex normals (the page
    // draws before the worker's first frame): without this it keeps shading flat, by facets.
    this.surface.material.needsUpdate = true;
  }

  /** New positions (a frame's buffer, same length): drawn as they are, no copy. */
  update(positions: Float32Array): void {
    const position = this.surface.geometry.getAttribute('position') as THREE.BufferAttribute;
    (position as any).array = positions;
    position.needsUpdate = true;
    this.invalidate();
    this.surface.geometry.computeVertexNormals();
    this.surface.geometry.computeBoundingSphere();
    const sphere = this.surface.geometry.boundingSphere;
    if (sphere && Number.isFinite(sphere.radius)) this.rig.follow(sphere.center);
  }

  /** Per-vertex colours (rgb in [0, 1]) or null for the plain material. */
  setColors(fill: ((colors: Float32Array) => void) | null): void {
    this.invalidate();
    const m = this.surface.material;
    if (!fill) {
      if (m.vertexColors) { m.vertexColors = false; m.color.set(0xd9a066); m.needsUpdate = true; }
      return;
    }
    fill(this.colors);
    this.surface.geometry.getAttribute('color').needsUpdate = true;
    if (!m.vertexColors) { m.vertexColors = true; m.color.set(0xffffff); m.needsUpdate = true; }
  }

  setGround(on: boolean, height: number): void {
    this.invalidate();
    this.groundPlane.visible = on;
    this.grid.position.y = height;
    this.groundPlane.position.y = height - 0.001;
  }

  /** The wind (m/s) the arrow shows; placed in the view whenever it is drawn (`placeWind`). */
  private wind = new THREE.Vector3();
  /** Scratch for `placeWind` (called on every draw while the wind blows: no allocation). */
  private readonly windDir = new THREE.Vector3();
  private readonly windUp = new THREE.Vector3();
  setWind(w: [number, number, number]): void {
    this.invalidate();
    this.wind.set(...w);
    this.windArrow.visible = this.wind.lengthSq() > 0;
  }

  /**
   * The wind arrow inside the view, whatever the camera: its middle on the vertical through the
   * view's target, WIND_ARROW_HIGH of the way from the centre to the top edge (the view's half
   * height at the target's distance, h = dist · tan(fov / 2)), its length a share of h growing
   * with the speed (WIND_ARROW_LENGTH: 0.2 h at calm to 0.5 h at 20 m/s). Before, it stood 1.2 m
   * above and 2 m upwind of the target in metres: above the top of the view for the mushroom.
   */
  private placeWind(): void {
    const len = this.wind.length();
    if (!(len > 0)) return;
    const d = this.windDir.copy(this.wind).divideScalar(len);
    const dist = this.camera.position.distanceTo(this.rig.target);
    const h = dist * Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    const length = h * (WIND_ARROW_LENGTH[0] + (WIND_ARROW_LENGTH[1] - WIND_ARROW_LENGTH[0]) * Math.min(len, 20) / 20);
    // The camera's up (its local y): the arrow's middle WIND_ARROW_HIGH h above the target, the tail half its length upwind.
    const up = this.windUp.set(0, 1, 0).applyQuaternion(this.camera.quaternion);
    this.windArrow.setDirection(d);
    this.windArrow.setLength(length, 0.25 * length, 0.15 * length);
    this.windArrow.position.copy(this.rig.target).addScaledVector(up, WIND_ARROW_HIGH * h).addScaledVector(d, -length / 2);
  }

  /** The view needs drawing again. */
  invalidate(): void { this.dirty = true; }

  /**
   * Draw, if anything changed since the last time: an unchanged view is not drawn again (a
   * paused or loading model costs nothing per frame, which matters where drawing is slow).
   */
  render(): void {
    this.rig.update();
    this.rig.ease();
    if (!this.dirty) return;
    this.dirty = false;
    if (this.windArrow.visible) this.placeWind();
    this.renderer.render(this.scene, this.camera);
  }

  /** The surface point under a pointer event, or null. */
  pick(ev: { clientX: number; clientY: number }): THREE.Intersection | null {
    const ray = this.rayAt(ev);
    this.surface.geometry.computeBoundingSphere();
    return ray.intersectObject(this.surface, false)[0] ?? null;
  }

  rayAt(ev: { clientX: number; clientY: number }): THREE.Raycaster {
    const r = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    return ray;
  }

  /** Whether the view is drawn at the screen's full resolution (always, with a GPU). */
  get fullResolution(): boolean { return !this.software || this.full; }
  set fullResolution(on: boolean) {
    this.full = on;
    this.resize();
  }

  /** The drawing buffer's size as a fraction of the canvas's CSS size (1 with a GPU on a standard screen). */
  get resolution(): number { return this.renderer.getPixelRatio(); }

  /** Renders so far (three.js counts them). */
  get renders(): number { return this.renderer.info.render.frame; }

  dispose(): void {
    this.rig.dispose();
    this.renderer.dispose();
  }
}

/**
 * Pixels of the drawing buffer at most on a software renderer. There the drawing runs on the
 * CPU cores the simulation's worker and the page's own thread need: in Chromium here
 * (SwiftShader, 2 cores, 1280 × 800) its two threads took ~1 core while a body landed, and the
 * page answered the mouse late. Measured (BENCHMARKS.md, "The view on a software renderer"),
 * the mushroom subdivided twice, a 25-step mouse drag of its top: 2.7 s for the page to take
 * it with multisampling at full resolution (the renderer had not been recognised as software),
 * 1.3–1.8 s without multisampling, 1.0–1.1 s at this budget as well; the simulation's own rate
 * about even. ~0.3 Mpx is a little less than 640 × 480: the outline stays clear, if
 * stair-stepped. (A window above 4.8 Mpx, where the ratio would drop below 1/4, is drawn at 1/4.)
 */
export const SOFTWARE_PIXELS = 300_000;

/**
 * The renderer's pixel ratio: the screen's (at most 2), or on a software renderer (`capped`) at
 * most what keeps a w × h CSS-pixel canvas within SOFTWARE_PIXELS (and at least 1/4).
 */
export function pixelRatio(capped: boolean, devicePixelRatio: number, w: number, h: number): number {
  const screen = Math.min(devicePixelRatio || 1, 2);
  if (!capped || !(w > 0 && h > 0)) return screen;
  return Math.max(0.25, Math.min(screen, Math.sqrt(SOFTWARE_PIXELS / (w * h))));
}

/**
 * Whether WebGL runs without a GPU (SwiftShader, llvmpipe): a context that refuses a major
 * performance caveat cannot be had, or the renderer's name says so (Chromium's SwiftShader
 * enabled by --enable-unsafe-swiftshader reports no caveat; Windows' WARP is the "Microsoft
 * Basic Render Driver"). Without WEBGL_debug_renderer_info the masked name may not tell.
 */
function isSoftwareRenderer(): boolean {
  const probe = document.createElement('canvas');
  const gl = probe.getContext('webgl2', { failIfMajorPerformanceCaveat: true });
  if (!gl) return true;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER));
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software|basic render driver/i.test(name);
}
