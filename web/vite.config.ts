import { defineConfig } from 'vite';

// Cross-origin isolation (COOP + COEP), so the page may share memory with its worker: the
// worker then abandons a running step the moment a command such as Undo is sent
// (src/protocol.ts, `interrupts`). Any static host serving web/dist should send the same two
// headers (README, "The modeler"); without them the modeler works the same, a slow step is only
// not interrupted.
const isolated = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' };

export default defineConfig({
  build: { target: 'es2022', chunkSizeWarningLimit: 2000 },
  server: { headers: isolated },
  preview: { headers: isolated },
  test: { include: ['test/**/*.test.ts'], environment: 'node', testTimeout: 30000 },
} as any);
