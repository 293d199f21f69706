// Measures the studio's live update end to end in the browser (docs/benchmarks.md):
//   node latency.mjs MEANDER_BINARY MESH_FILE [--previews] [--spacing SLIDER] [MODE:LEVELS ...]
// With --spacing, the spacing is on at that position of its slider (0 to 100: 1/300 to 1/10
// of the diagonal) first. For each mode (default: all, levels 0 and 1 for the variable ones), changes the seed three times for a full
// result (not with --previews) and three times for a preview (what the page asks while a
// slider moves) and prints the median of the page's own figure: from the request leaving
// to the new geometry in the scene (make + view.bin + decoding + the first frame drawn),
// and the server's share.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [binary, meshFile, ...args] = process.argv.slice(2);
const previewsOnly = args.includes('--previews');
const spacingAt = args.indexOf('--spacing');
const spacing = spacingAt >= 0 ? args[spacingAt + 1] : null;
const chosen = args.filter((a, i) => a !== '--previews' && i !== spacingAt && i !== spacingAt + 1);
const modes = chosen.length ? chosen.map((m) => m.split(':')).map(([mode, levels]) => [mode, Number(levels ?? 1)])
  : [['curve', 1], ['constant-ribbon', 1], ['constant-wire', 1], ['variable-ribbon', 0], ['variable-wire', 0],
    ['variable-ribbon', 1], ['variable-wire', 1], ['duotone', 0]];
const server = spawn(binary, ['serve', '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
// Whatever fails below, the server goes with this process.
process.on('exit', () => server.kill('SIGTERM'));
const url = await new Promise((resolve) => server.stdout.on('data', (c) => { const m = `${c}`.match(/(http:\/\/\S+)/); if (m) resolve(m[1]); }));
const profile = mkdtempSync(path.join(tmpdir(), 'meander-latency-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = browser.pages()[0] ?? await browser.newPage();
  await page.goto(url);
  const idle = (after) => page.waitForFunction((r) => window.studio.idle() && window.studio.state.revision > r, after, { timeout: 600000 });
  await page.setInputFiles('#file', { name: path.basename(meshFile), mimeType: 'application/octet-stream', buffer: readFileSync(meshFile) });
  await idle(0);
  const set = (id, value) => page.evaluate(([i, v]) => { const e = document.getElementById(i); e.value = v; e.dispatchEvent(new Event('input', { bubbles: true })); }, [id, value]);
  if (spacing !== null) {
    const revision = await page.evaluate(() => window.studio.state.revision);
    await page.evaluate(() => { const e = document.getElementById('spacing-on'); e.checked = true; e.dispatchEvent(new Event('input', { bubbles: true })); });
    await set('spacing', spacing);
    await idle(revision);
    console.log(`spacing ${await page.evaluate(() => document.getElementById('spacing-value').textContent)}`);
  }
  for (const [mode, levels] of modes) {
    await set(mode === 'duotone' ? 'subdivide' : 'levels', String(levels));
    let revision = await page.evaluate(() => window.studio.state.revision);
    await set('mode', mode);
    await idle(revision);
    for (const preview of previewsOnly ? [true] : [true, false]) {
      const runs = [];
      for (let seed = 2; seed <= 4; ++seed)
        runs.push(await page.evaluate(async ([s, p]) => {
          document.getElementById('seed').value = s;
          await window.studio.make(p);
          const { lastUpdateMs, stats, phases } = window.studio.state;
          return { total: lastUpdateMs, server: stats.seconds * 1000, triangles: stats.triangles, preview: stats.preview, phases };
        }, [String(seed + (preview ? 10 : 0)), preview]));
      runs.sort((a, b) => a.total - b.total);
      const m = runs[1];
      console.log(`${mode} levels ${levels} ${m.preview ? 'preview' : 'full'}: ${m.triangles} triangles, end to end ${m.total.toFixed(0)} ms (server ${m.server.toFixed(0)} ms; ${Object.entries(m.phases).map(([k, v]) => `${k} ${v.toFixed(0)}`).join(', ')})`);
    }
  }
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(profile, { recursive: true, force: true });
}
