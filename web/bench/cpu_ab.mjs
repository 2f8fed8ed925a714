// node web/bench/cpu_ab.mjs ASSETS_DIR A.wasm B.wasm [BATCHES]: two builds of PRM's wasm decoder (e.g. a revision's
// web/build.sh output against another's) in one node process, on make_assets.sh's assets, alternating batches of
// 5 decodes after 30 warm-up decodes each, CPU time per decode: the fastest and the median batch of each (default 30
// batches). Prints a Markdown table; fails if the two decode different vertex counts.
import fs from 'node:fs';
import path from 'node:path';
import { createDecoder } from '../src/prm_decoder.js';
const [assets, wa, wb, nb = '30'] = process.argv.slice(2);
if (!wb) { console.error('usage: node web/bench/cpu_ab.mjs ASSETS_DIR A.wasm B.wasm [BATCHES]'); process.exit(1); }
const A = await createDecoder({ wasmBinary: fs.readFileSync(wa) });
const B = await createDecoder({ wasmBinary: fs.readFileSync(wb) });
const cpuMs = (f, n) => { const c0 = process.cpuUsage(); for (let i = 0; i < n; ++i) f(); const c = process.cpuUsage(c0); return (c.user + c.system) / 1000 / n; };
const med = (x) => { const s = [...x].sort((p, q) => p - q); return s[Math.floor(s.length / 2)]; };
console.log('| asset | V | A fastest ms | B fastest ms | B/A fastest | A median ms | B median ms | B/A median |');
console.log('|---|---:|---:|---:|---:|---:|---:|---:|');
for (const a of JSON.parse(fs.readFileSync(path.join(assets, 'assets.json'), 'utf8'))) {
  const p = new Uint8Array(fs.readFileSync(path.join(assets, a.prm)));
  const v = A.decode(p).vertices;
  if (B.decode(p).vertices !== v) throw new Error('vertex counts differ');
  for (let i = 0; i < 30; ++i) { A.decode(p); B.decode(p); }
  const ta = [], tb = [];
  for (let b = 0; b < Number(nb); ++b) { ta.push(cpuMs(() => A.decode(p), 5)); tb.push(cpuMs(() => B.decode(p), 5)); }
  const fa = Math.min(...ta), fb = Math.min(...tb), ma = med(ta), mb = med(tb);
  console.log(`| ${a.name} | ${v} | ${fa.toFixed(3)} | ${fb.toFixed(3)} | ${(fb / fa).toFixed(3)} | ${ma.toFixed(3)} | ${mb.toFixed(3)} | ${(mb / ma).toFixed(3)} |`);
}
