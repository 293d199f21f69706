// The page is served by `meander serve` from studio/dist (no CDN at run time), with
// relative asset URLs so it works under any host and port.
import { defineConfig } from 'vite';

export default defineConfig({
  base: './',
  build: { outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1000 },
  server: { proxy: { '/api': 'http://127.0.0.1:8080' } },
});
