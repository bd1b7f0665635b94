// The import dialog: what the engine found in a file (format, size in the file's units, pieces,
// open surfaces) and the questions the file leaves open — which way is up (offered first: what
// the format declares, else a guess with its reason) and, for a file of several pieces, one body
// per piece or the largest only — and what its triangles will cost to simulate (a trial run,
// worker/trial.ts), with Remesh checked where they would make it slow — and, for a closed model
// too coarse to shape (an 8-vertex box), Remesh (recommended where it adds vertices, else
// Subdivide), Subdivide or keep it as it is.
// Enter imports, Escape cancels.

import { coarseRemedy, tooCoarse, type ImportAnswer, type ImportQuestion } from './import';

const CSS = `
/* Above the lil-gui panel (its z-index is 1001): the question is modal, the panel waits (a new-user trial remeshed the model behind the dialog). */
.import-dialog { position: fixed; inset: 0; display: flex; align-items: center; justify-content: center; background: rgba(10, 12, 16, 0.55); z-index: 2000; }
.import-dialog form { background: #2a3039; color: #e8ecf0; font: 13px/1.45 system-ui, sans-serif; padding: 16px 20px; border-radius: 8px; width: min(440px, 92vw); box-shadow: 0 8px 32px rgba(0,0,0,0.5); }
.import-dialog h2 { margin: 0 0 6px; font-size: 15px; }
.import-dialog fieldset { border: 1px solid #47505c; border-radius: 6px; margin: 10px 0; padding: 6px 10px; }
.import-dialog legend { padding: 0 4px; color: #aeb8c4; }
.import-dialog label { display: block; margin: 3px 0; }
.import-dialog .why, .import-dialog .note { color: #aeb8c4; font-size: 12px; }
.import-dialog .note { margin: 6px 0; }
.import-dialog .buttons { display: flex; justify-content: flex-end; gap: 8px; margin-top: 12px; }
.import-dialog button { font: inherit; padding: 4px 14px; border-radius: 4px; border: 1px solid #5a6572; background: #39414c; color: inherit; cursor: pointer; }
.import-dialog button[type=submit] { background: #3d6fb0; border-color: #5088d0; }
`;

const esc = (s: string) => s.replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]!);
const num = (x: number) => x.toPrecision(3);

/** The dialog's HTML for `q` (a form with radio groups `up`, `pieces` and, for a model too coarse to shape, `refine`; `inflate` and `remesh` checkboxes). */
export function dialogHtml(q: ImportQuestion): string {
  const p = q.pieces, n = p.length;
  const vertices = p.reduce((s, x) => s + x.vertices, 0), faces = p.reduce((s, x) => s + x.faces, 0);
  const open = p.filter((x) => !x.closed).length;
  const radio = (group: string, value: string, checked: boolean, label: string, why = '') =>
    `<label><input type="radio" name="${group}" value="${value}"${checked ? ' checked' : ''}> ${label}${why ? ` <span class="why">— ${esc(why)}</span>` : ''}</label>`;
  // Declared by the format, or a guess sure enough not to ask (asked here for another reason): said, not asked.
  const sureUp = q.declaredUp ?? (q.upSure ? q.guessedUp : null);
  const up = sureUp
    ? `<p class="note">Up axis: ${sureUp.toUpperCase()} — ${esc(q.guessReason)}${q.declaredUp ? '' : ' (Model › up axis changes it)'}.</p><input type="hidden" name="up" value="${sureUp}">`
    : `<fieldset><legend>Which way is up? (${esc(q.format)} does not say)</legend>
        ${radio('up', 'y', q.guessedUp === 'y', 'Y is up', q.guessedUp === 'y' ? q.guessReason : '')}
        ${radio('up', 'z', q.guessedUp === 'z', 'Z is up (Blender, CAD): turned upright', q.guessedUp === 'z' ? q.guessReason : '')}
      </fieldset>`;
  const largest = n > 1 ? `${p[0].vertices} vertices${p[0].closed ? '' : ', open'}` : '';
  const pieces = n > 1
    ? `<fieldset><legend>The file is ${n} separate pieces</legend>
        ${radio('pieces', 'each', true, `one body per piece (${n} bodies)`)}
        ${radio('pieces', 'largest', false, `the largest piece only (${largest})`)}
      </fieldset>`
    : '<input type="hidden" name="pieces" value="each">';
  const cloth = open
    ? `<p class="note">${open === n ? (n === 1 ? 'The surface is' : 'Every piece is') : `${open} of ${n} pieces are`} open (cloth-like): no gas inside ${open === 1 ? 'it' : 'them'}; it hangs and drapes on its springs.</p>`
    : '';
  const closed = n - open;
  const gas = closed
    ? `<fieldset><legend>Gas</legend>
        <label><input type="checkbox" name="inflate"> Inflate it <span class="why">— the gas swells ${closed === 1 ? 'it' : 'the closed pieces'} like a balloon; unchecked, ${closed === 1 ? 'it rests' : 'they rest'} at the shape in the file</span></label>
      </fieldset>`
    : '';
  // Too coarse to shape: what gives the tools more vertices, Remesh recommended (it keeps the shape).
  const coarse = tooCoarse(q), remedy = coarseRemedy(q);
  const refine = coarse
    ? `<fieldset><legend>Only ${vertices} vertices: too coarse to shape</legend>
        <p class="note">A grab takes a whole corner, and a brush between corners finds no vertex.</p>
        ${radio('refine', 'remesh', remedy === 'remesh', `Remesh to even triangles${remedy === 'remesh' ? ' (recommended)' : ''}`, remedy === 'remesh' ? `${q.remeshed ? `${q.remeshed} vertices, ` : 'more vertices, '}the shape and its sharp edges kept` : 'its triangles are even already: about as many vertices as now')}
        ${radio('refine', 'subdivide', remedy === 'subdivide', `Subdivide${remedy === 'subdivide' ? ' (recommended)' : ''}`, 'about four times the vertices, smoothed: a box comes out rounded')}
        ${radio('refine', 'keep', false, `Keep the file's ${vertices} vertices`, 'Model › Remesh or Subdivide (U) later')}
      </fieldset>`
    : '';
  const c = q.cost;
  const trial = c ? (c.frames > 0 ? `a trial frame took ${c.msPerFrame.toFixed(0)} ms` : `a trial frame did not finish in ${(c.msPerFrame / 1000).toFixed(1)} s`) : '';
  const mesh = c
    ? `<fieldset><legend>Triangles</legend>
        <p class="note">Smallest angle ${c.minAngle.toFixed(1)}°, shortest edge ${(100 * c.shortest).toFixed(0)} % of the mean, ${(100 * c.smallShare).toFixed(0)} % of angles below 25°; ${trial} (real time: 16.7 ms a frame).</p>
        ${coarse ? '' : `<label><input type="checkbox" name="remesh"${c.remesh ? ' checked' : ''}> Remesh to even triangles${c.remesh ? ' (recommended)' : ''} <span class="why">— ${esc(c.remesh ? c.reason : c.why || 'not needed: the triangles are even enough')}; Undo brings the file's triangles back</span></label>`}
      </fieldset>`
    : '';
  return `<form method="dialog">
    <h2>Import ${esc(q.name)}</h2>
    <div class="note">${esc(q.format)}: ${vertices} vertices, ${faces} faces, ${q.size.map(num).join(' × ')} in the file's units, kept as metres (the view is fitted to it).</div>
    ${up}${pieces}${cloth}${refine}${gas}${mesh}
    <div class="buttons"><button type="button" value="cancel">Cancel</button><button type="submit" value="import">Import</button></div>
  </form>`;
}

/** Show the dialog for `q`; resolves with the answers, or null if cancelled. */
export function askImport(q: ImportQuestion): Promise<ImportAnswer | null> {
  if (!document.getElementById('import-dialog-css')) {
    const style = document.createElement('style');
    style.id = 'import-dialog-css';
    style.textContent = CSS;
    document.head.appendChild(style);
  }
  document.querySelector('.import-dialog')?.remove();
  const root = document.createElement('div');
  root.className = 'import-dialog';
  root.setAttribute('role', 'dialog');
  root.innerHTML = dialogHtml(q);
  document.body.appendChild(root);
  const form = root.querySelector('form')!;
  return new Promise((resolve) => {
    const close = (a: ImportAnswer | null) => {
      root.remove();
      window.removeEventListener('keydown', onKey, true);
      resolve(a);
    };
    // Keys go to the dialog only: the modeler's shortcuts wait until it is closed.
    const onKey = (ev: KeyboardEvent) => {
      ev.stopPropagation();
      if (ev.key === 'Escape') { ev.preventDefault(); close(null); }
      if (ev.key === 'Enter') { ev.preventDefault(); form.requestSubmit(); }
    };
    window.addEventListener('keydown', onKey, true);
    form.addEventListener('submit', (ev) => {
      ev.preventDefault();
      const d = new FormData(form);
      close({ up: d.get('up') === 'z' ? 'z' : 'y', pieces: d.get('pieces') === 'largest' ? 'largest' : 'each', remesh: d.get('remesh') === 'on' || d.get('refine') === 'remesh', subdivide: d.get('refine') === 'subdivide', inflate: d.get('inflate') === 'on' });
    });
    root.querySelector('button[value=cancel]')!.addEventListener('click', () => close(null));
    (form.querySelector('button[type=submit]') as HTMLButtonElement).focus();
  });
}
