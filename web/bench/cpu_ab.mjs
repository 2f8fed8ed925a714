// node web/bench/cpu_ab.mjs ASSETS_DIR A B [BATCHES]: two builds of PRM's wasm decoder in one node process, on
// make_assets.sh's assets, alternating batches of 5 decodes after 30 warm-up decodes each, CPU time per decode: the
// fastest and the median batch of each (default 30 batches). Prints a Markdown table; fails if the two decode
// different vertex counts. A and B are each a .wasm file (loaded with this checkout's glue, so both must be
// glue-compatible builds) or a web/ directory (its own src/prm_decoder.js, dist/prm_decoder_wasm.{js,wasm}: any two
// revisions, e.g. `git worktree add /tmp/old REV && /tmp/old/web/build.sh`).
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { createDecoder } from '../src/prm_decoder.js';
const [assets, wa, wb, nb = '30'] = process.argv.slice(2);
if (!wb) { console.error('usage: node web/bench/cpu_ab.mjs ASSETS_DIR A B [BATCHES]  (A, B: .wasm files or web/ directories)'); process.exit(1); }
const load = async (x) => {
  if (fs.statSync(x).isDirectory()) {
    const mod = await import(pathToFileURL(path.join(x, 'src', 'prm_decoder.js')).href);
    return mod.createDecoder({ wasmBinary: fs.readFileSync(path.join(x, 'dist', 'prm_decoder_wasm.wasm')) });
  }
  return createDecoder({ wasmBinary: fs.readFileSync(x) });
};
const A = await load(wa);
const B = await load(wb);
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
