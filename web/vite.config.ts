import { defineConfig } from 'vite';

export default defineConfig({
  build: { target: 'es2022', chunkSizeWarningLimit: 2000 },
  test: { include: ['test/**/*.test.ts'], environment: 'node', testTimeout: 30000 },
} as any);
