// web/bench/run_bench.mjs ASSETS_DIR [RUNS]: PRM's wasm decoder against Draco's in one headless Chromium page
// (Debian's /usr/bin/chromium), on the assets of make_assets.sh; prints a Markdown table of median decode ms.
//   web/bench/make_assets.sh build/tools/prm/prm /tmp/assets ../shared/meshes/spot.obj ...
//   node web/bench/run_bench.mjs /tmp/assets 21
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const [assets, runsText = '21'] = process.argv.slice(2);
if (!assets) { console.error('usage: node web/bench/run_bench.mjs ASSETS_DIR [RUNS]'); process.exit(1); }
const runs = Number(runsText);
if (!Number.isInteger(runs) || runs < 10) { console.error('run_bench: RUNS must be an integer of at least 10'); process.exit(1); }

const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.json': 'application/json' };
const server = http.createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  const file = url.startsWith('/assets/') ? path.join(assets, url.slice(8)) : path.join(web, url);
  fs.readFile(file, (err, data) => {
    if (err) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    res.end(data);
  });
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const browser = await puppeteer.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
                                         args: ['--no-sandbox'] });
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.error(`page: ${e.message}`));
  await page.goto(`http://127.0.0.1:${server.address().port}/bench/index.html`);
  await page.waitForFunction(() => typeof window.runBench === 'function');
  const rows = await page.evaluate((r) => window.runBench('/assets/assets.json', r), runs);
  console.log(`| asset | PRM B | PRM v / t | PRM RMS | Draco -qp | Draco B | Draco v / t | Draco RMS | PRM ms | Draco ms | PRM / Draco | ` +
              `PRM min ms | Draco min ms | PRM µs/v (min) | Draco µs/v (min) |`);
  console.log('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|');
  for (const r of rows) {
    console.log(`| ${r.name} | ${r.prm_bytes} | ${r.prm_vertices} / ${r.prm_triangles} | ${r.prm_rms.toExponential(2)} | ${r.draco_qp} | ` +
      `${r.drc_bytes} | ${r.drc_vertices} / ${r.drc_triangles} | ${r.drc_rms.toExponential(2)} | ${r.prm_ms.toFixed(2)} | ` +
      `${r.drc_ms.toFixed(2)} | ${(r.prm_ms / r.drc_ms).toFixed(2)} | ${r.prm_min_ms.toFixed(2)} | ${r.drc_min_ms.toFixed(2)} | ` +
      `${(1e3 * r.prm_min_ms / r.prm_vertices).toFixed(2)} | ${(1e3 * r.drc_min_ms / r.drc_vertices).toFixed(2)} |`);
  }
  console.log(`\nmedian (and fastest) of ${runs} decodes each, alternating, in one page; RMS: symmetric RMS distance to the input as a fraction of its bounding-box diagonal (prm compare)`);
} finally {
  await browser.close();
  server.close();
}
