// No circles between the page's modules (issue #39): every web/src/**/*.ts file's relative
// imports (`import … from './x'`, `import type …`, `export … from`, `import './x'`,
// `import('./x')`) form a graph without cycles, so each file can be read knowing only the files
// below it. A file that needs something of one above it declares what it needs as a small
// interface of its own, which the file above implements (worker/importer.ts's `ImportTarget`,
// worker/stepper.ts's `Stepped`: before, both imported worker/document.ts, which imports the
// importer, which imports the trial, which imports the stepper).
import { readdirSync, readFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const SRC = fileURLToPath(new URL('../src', import.meta.url));

/**
 * Cycles known and not yet broken, each as the sorted files of its strongly connected component
 * (paths under web/src). Empty: none is known; a new cycle fails the test.
 */
const KNOWN: string[][] = [];

/** Every `.ts` file under `dir`, sorted. */
function tsFiles(dir: string): string[] {
  return readdirSync(dir, { withFileTypes: true })
    .flatMap((e) => (e.isDirectory() ? tsFiles(join(dir, e.name)) : e.name.endsWith('.ts') ? [join(dir, e.name)] : []))
    .sort();
}

/** The relative module specifiers a file's code imports (static, type-only, re-exports, side effects, dynamic). */
function relativeImports(text: string): string[] {
  const found: string[] = [];
  const patterns = [
    /^\s*(?:import|export)\b[^;'"`]*?\bfrom\s*['"](\.{1,2}\/[^'"]+)['"]/gm,
    /^\s*import\s*['"](\.{1,2}\/[^'"]+)['"]/gm,
    /\bimport\(\s*['"](\.{1,2}\/[^'"]+)['"]\s*\)/g,
  ];
  for (const p of patterns) for (const m of text.matchAll(p)) found.push(m[1]);
  return found;
}

/** The import graph: file → the files it imports (paths under `src`; non-TypeScript imports such as `./style.css` left out). */
function importGraph(src: string): Map<string, string[]> {
  const files = tsFiles(src);
  const known = new Set(files);
  const graph = new Map<string, string[]>();
  for (const f of files) {
    const deps = new Set<string>();
    for (const spec of relativeImports(readFileSync(f, 'utf8'))) {
      const base = resolve(dirname(f), spec.replace(/\.js$/, ''));
      const target = [base, `${base}.ts`, join(base, 'index.ts')].find((c) => known.has(c));
      if (target) deps.add(relative(src, target));
    }
    graph.set(relative(src, f), [...deps].sort());
  }
  return graph;
}

/** The graph's cycles: its strongly connected components of more than one file (or a file importing itself), each sorted. */
function cycles(graph: Map<string, string[]>): string[][] {
  let next = 0;
  const index = new Map<string, number>(), low = new Map<string, number>(), stack: string[] = [], onStack = new Set<string>();
  const out: string[][] = [];
  const visit = (v: string) => {
    index.set(v, next); low.set(v, next); next++;
    stack.push(v); onStack.add(v);
    for (const w of graph.get(v) ?? []) {
      if (!index.has(w)) { visit(w); low.set(v, Math.min(low.get(v)!, low.get(w)!)); }
      else if (onStack.has(w)) low.set(v, Math.min(low.get(v)!, index.get(w)!));
    }
    if (low.get(v) === index.get(v)) {
      const c: string[] = [];
      let w: string;
      do { w = stack.pop()!; onStack.delete(w); c.push(w); } while (w !== v);
      if (c.length > 1 || (graph.get(v) ?? []).includes(v)) out.push(c.sort());
    }
  };
  for (const v of graph.keys()) if (!index.has(v)) visit(v);
  return out.sort((a, b) => a[0].localeCompare(b[0]));
}

/** The shortest closed path through `start` inside a cycle's files (`a.ts → b.ts → a.ts`), to name it. */
function pathThrough(graph: Map<string, string[]>, cycle: string[], start = cycle[0]): string {
  const inCycle = new Set(cycle);
  // Breadth first from the start back to it, inside the cycle: the shortest loop through it.
  const from = new Map<string, string>();
  const queue = [start];
  while (queue.length) {
    const v = queue.shift()!;
    for (const w of graph.get(v) ?? []) {
      if (!inCycle.has(w)) continue;
      if (w === start) {
        const between: string[] = [];
        for (let u = v; u !== start; u = from.get(u)!) between.unshift(u);
        return [start, ...between, start].join(' → ');
      }
      if (!from.has(w)) { from.set(w, v); queue.push(w); }
    }
  }
  return cycle.join(', ');
}

/** A cycle named by its files and the shortest loop through each of them (a loop once, from its first file in order). */
function describeCycle(graph: Map<string, string[]>, cycle: string[]): string {
  const loops = cycle.map((f) => {
    const files = pathThrough(graph, cycle, f).split(' → ').slice(0, -1);
    const k = files.indexOf([...files].sort()[0]);
    const turned = [...files.slice(k), ...files.slice(0, k)];
    return [...turned, turned[0]].join(' → ');
  });
  return `${cycle.join(', ')}: ${[...new Set(loops)].join('; ')}`;
}

describe('imports (web/src)', () => {
  it('form no cycle', () => {
    const graph = importGraph(SRC);
    expect(graph.size).toBeGreaterThan(40);
    expect(graph.get('worker/document.ts')).toContain('worker/importer.ts');
    const known = new Set(KNOWN.map((c) => [...c].sort().join(' ')));
    const found = cycles(graph);
    const fresh = found.filter((c) => !known.has(c.join(' ')));
    expect(fresh.map((c) => describeCycle(graph, c)), 'import cycles under web/src (break them: see test/imports.test.ts)').toEqual([]);
    // A known cycle that is gone leaves the list.
    const gone = [...known].filter((k) => !found.some((c) => c.join(' ') === k));
    expect(gone, 'cycles in KNOWN that no longer exist: remove them').toEqual([]);
  });

  it('reads every kind of relative import, and finds cycles of any length', () => {
    const text = [
      "import { a } from './a';",
      "import type { B } from '../b';",
      'import {',
      '  c,',
      '  type C,',
      "} from './c';",
      "export { d } from './d';",
      "export * from './e.js';",
      "import './f';",
      "const g = await import('./g');",
      "import * as THREE from 'three';",
      "// import { h } from './h';",
    ].join('\n');
    expect(relativeImports(text).sort()).toEqual(['../b', './a', './c', './d', './e.js', './f', './g']);
    const g = (arrows: [string, string][]) => {
      const m = new Map<string, string[]>();
      for (const [a, b] of arrows) { m.set(a, [...(m.get(a) ?? []), b]); if (!m.has(b)) m.set(b, []); }
      return m;
    };
    expect(cycles(g([['a', 'b'], ['b', 'c']]))).toEqual([]);
    const loop = g([['doc', 'imp'], ['imp', 'trial'], ['trial', 'step'], ['step', 'doc'], ['doc', 'x']]);
    expect(cycles(loop)).toEqual([['doc', 'imp', 'step', 'trial']]);
    expect(pathThrough(loop, cycles(loop)[0])).toBe('doc → imp → trial → step → doc');
    const two = g([['doc', 'imp'], ['imp', 'doc'], ['imp', 'trial'], ['trial', 'step'], ['step', 'doc']]);
    expect(describeCycle(two, cycles(two)[0])).toBe('doc, imp, step, trial: doc → imp → doc; doc → imp → trial → step → doc');
  });
});
