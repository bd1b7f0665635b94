// Entry point: build the modeler (it starts the simulation worker), wire keys, file pickers and
// drag-and-drop.

import './style.css';
import { App } from './app';
import { buildPanel } from './panel';
import { IMPORT_EXTENSIONS } from './io/import';
import { inspector } from './inspect';
import { viewWindSpeed } from './tools/wind';

const HELP = `<h2>SoftSculpt</h2>
<p>Shape a soft body with the mouse, a pen (pressure sets the strength) or a finger. Drag on empty space to turn the view (right button: pan, wheel: zoom; two fingers: turn and pinch-zoom).</p>
<table>
<tr><td>G</td><td>Grab: drag the surface, it follows the mouse on a spring</td></tr>
<tr><td>P</td><td>Press: push the faces under the brush inward</td></tr>
<tr><td>I</td><td>Inflate brush (Shift: deflate)</td></tr>
<tr><td>M</td><td>Mass brush: heavier (Shift: lighter) — heavy parts move less</td></tr>
<tr><td>N</td><td>Pin brush (Shift: unpin)</td></tr>
<tr><td>K</td><td>Sketch: draw a closed outline on the view; it becomes a balloon inflated by gas (replaces the model)</td></tr>
<tr><td>[ ] / { }</td><td>Brush radius / strength smaller, larger (shown on the ring under the cursor)</td></tr>
<tr><td>B / Shift+B</td><td>Set the radius / strength by moving the mouse; click or Enter sets it, Esc puts it back</td></tr>
<tr><td>Tool › mirror X Y Z</td><td>Symmetry: every tool also acts on the mirror image (X on for symmetric models)</td></tr>
<tr><td>F / R</td><td>Freeze the shape as the rest shape / reset to the last frozen shape</td></tr>
<tr><td>U</td><td>Subdivide (Loop)</td></tr>
<tr><td>W / Shift+W</td><td>Wind across the view, from the left of the screen to the right / calm (Wind › blow from view: along the view)</td></tr>
<tr><td>Space / .</td><td>Play-pause / single step</td></tr>
<tr><td>X / V</td><td>Springs wireframe / frame the model (level horizon)</td></tr>
<tr><td>Ctrl+Z / Ctrl+Shift+Z</td><td>Undo / redo</td></tr>
<tr><td>Ctrl+S / Ctrl+O / Ctrl+I / E</td><td>Save project / open project / import / export OBJ</td></tr>
<tr><td>Files › Open scene…</td><td>A scene file (.toml) with its mesh files: bodies, obstacles, timed events (or drop them on the page)</td></tr>
<tr><td>?</td><td>This help</td></tr>
</table><p>Your work is saved in this browser after every operation and restored on reload.</p>`;

function picker(name: string, accept: string, onFile: (f: File) => void): () => void {
  return multiPicker(name, accept, false, (fs) => onFile(fs[0]));
}

function multiPicker(name: string, accept: string, multiple: boolean, onFiles: (f: File[]) => void): () => void {
  const input = document.createElement('input');
  input.type = 'file';
  input.accept = accept;
  input.multiple = multiple;
  input.dataset.picker = name;
  input.style.display = 'none';
  document.body.appendChild(input);
  input.addEventListener('change', () => {
    const fs = Array.from(input.files ?? []);
    if (fs.length > 0) onFiles(fs);
    input.value = '';
  });
  return () => input.click();
}

/** A scene file among `files` opened with the others as the mesh files it may name. */
async function openSceneFiles(app: App, files: File[]): Promise<void> {
  const scene = files.find((f) => f.name.endsWith('.toml'));
  if (!scene) { app.message('choose a scene file (.toml), with the mesh files it names', 'warn'); return; }
  const meshes = new Map<string, Uint8Array>();
  for (const f of files) if (f !== scene) meshes.set(f.name, new Uint8Array(await f.arrayBuffer()));
  app.openScene(scene.name, await scene.text(), meshes);
}

function main(): void {
  const status = document.getElementById('status')!;
  const app = new App(
    document.getElementById('view') as HTMLCanvasElement,
    document.getElementById('plots') as HTMLCanvasElement,
    document.getElementById('hud')!,
    HELP,
    new URL('/softsculpt.wasm', window.location.href).href,
  );
  (window as any).softsculpt = inspector(app);
  // The engine starts in its worker; the page draws meanwhile and shows the model when it comes.
  app.start(() => status.remove());
  const loop = () => { app.frame(); requestAnimationFrame(loop); };
  requestAnimationFrame(loop);

  const importFile = picker('import', IMPORT_EXTENSIONS.join(','), async (f) => app.importFile(f.name, await f.arrayBuffer()));
  const openProject = picker('project', '.json,.softsculpt.json', async (f) => app.openProjectFile(f.name, await f.text()));
  const openScene = multiPicker('scene', '.toml,.obj', true, (fs) => void openSceneFiles(app, fs));
  const gui = buildPanel(app, { importFile, openProject, openScene });
  gui.domElement.id = 'panel';

  // The panel keeps no keyboard focus after a click (a checkbox, a button, a list): the shortcuts
  // work at once, and letter keys never change a list or Space a checkbox. Text and number
  // fields keep it while the user types in them.
  const release = (ev: Event) => {
    const t = ev.target as HTMLElement;
    if (!isTextField(t)) queueMicrotask(() => t.blur?.());
  };
  gui.domElement.addEventListener('change', release);
  gui.domElement.addEventListener('click', (ev) => {
    // Not a list: a click opens its menu, which a blur would close.
    if (!(ev.target as HTMLElement).closest?.('select')) release(ev);
  });

  window.addEventListener('keydown', (ev) => {
    if (isTextField(ev.target as HTMLElement)) {
      // Escape leaves a panel field (what was typed stays, as with Enter), so that the next
      // keys are shortcuts again (before, a "g" after Escape was typed into the field).
      if (ev.key === 'Escape' && gui.domElement.contains(ev.target as Node)) { ev.preventDefault(); (ev.target as HTMLElement).blur(); }
      return;
    }
    // A question on screen (the import dialog) has the keys: nothing acts behind it.
    if (document.querySelector('.import-dialog')) return;
    // Anything else focused (a list, a checkbox, a button): the key is a shortcut, not for it.
    if ((ev.target as HTMLElement).closest?.('input, select, button') && !ev.ctrlKey && !ev.metaKey && ev.key !== 'Tab') {
      ev.preventDefault();
      (ev.target as HTMLElement).blur();
    }
    const key = ev.key.toLowerCase();
    const ctrl = ev.ctrlKey || ev.metaKey;
    if (ctrl && key === 'z') { ev.preventDefault(); if (ev.shiftKey) app.redo(); else app.undo(); return; }
    if (ctrl && key === 'y') { ev.preventDefault(); app.redo(); return; }
    if (ctrl && key === 's') { ev.preventDefault(); app.saveProject(); return; }
    if (ctrl && key === 'o') { ev.preventDefault(); openProject(); return; }
    if (ctrl && key === 'i') { ev.preventDefault(); importFile(); return; }
    if (ctrl || ev.altKey) return;
    const tool = app.tools.tools.find((t) => t.key === key);
    if (tool) { app.tools.select(tool.name); return; }
    switch (ev.key) {
      case 'f': case 'F': app.freeze(); break;
      case 'r': case 'R': app.reset(); break;
      case 'u': case 'U': app.subdivide(); break;
      case ' ': ev.preventDefault(); app.togglePlaying(); break;
      case '.': app.step(); break;
      case 'x': case 'X': app.wireframe = !app.wireframe; app.syncScene(); break;
      case 'v': case 'V': app.viewport.resetView(); break;
      case 'e': case 'E': void app.export('obj'); break;
      // W: wind across the view, left to right (from calm at a speed made for the body,
      // tools/wind.ts); Shift+W: calm.
      case 'w': case 'W': if (ev.shiftKey) app.windAcrossView(0); else app.windAcrossView(app.windStrength > 0 ? app.windStrength : viewWindSpeed(app)); break;
      case '[': app.scaleRadius(1 / 1.2); break;
      case ']': app.scaleRadius(1.2); break;
      case '{': app.scaleStrength(1 / 1.2); break;
      case '}': app.scaleStrength(1.2); break;
      case 'b': app.cursor.startAdjust('radius'); break;
      case 'B': app.cursor.startAdjust('strength'); break;
      case 'Enter': app.cursor.finishAdjust(true); break;
      case '?': case 'h': case 'H': app.hud.toggleHelp(); break;
      case 'Escape': if (app.cursor.adjusting) app.cursor.finishAdjust(false); else app.hud.toggleHelp(false); break;
      default: return;
    }
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  }, { capture: true }); // before the panel's controllers, which stop keys from reaching the page

  // Drag and drop: model files import, project files open, a scene file (with its meshes) opens.
  window.addEventListener('dragover', (ev) => { ev.preventDefault(); document.body.classList.add('dropping'); });
  window.addEventListener('dragleave', () => document.body.classList.remove('dropping'));
  window.addEventListener('drop', async (ev) => {
    ev.preventDefault();
    document.body.classList.remove('dropping');
    const all = Array.from(ev.dataTransfer?.files ?? []);
    if (all.some((x) => x.name.endsWith('.toml'))) { await openSceneFiles(app, all); return; }
    const f = all[0];
    if (!f) return;
    if (f.name.endsWith('.json')) app.openProjectFile(f.name, await f.text());
    else app.importFile(f.name, await f.arrayBuffer());
  });

}

/** Where keys are text the user types (a number or text field), not shortcuts. */
function isTextField(t: HTMLElement | null): boolean {
  if (!t || !t.closest) return false;
  if (t.closest('textarea, [contenteditable="true"]')) return true;
  const input = t.closest('input') as HTMLInputElement | null;
  return !!input && !['checkbox', 'radio', 'button', 'range', 'color', 'file'].includes(input.type);
}

main();
