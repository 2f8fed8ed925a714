// web/bench/cpu_bench.mjs ASSETS_DIR: the same decoders as run_bench.mjs (PRM's wasm, Draco's wasm as npm three ships
// it) in node's V8, the engine of Chromium, timed as the process's CPU time instead of wall time: on a shared machine
// the page's wall-clock medians carry the other jobs' delays, CPU time far less. Batches of 5 decodes, PRM and Draco
// alternating, 10 batches each after 20 warm-up decodes; the fastest batch per decode. Prints a Markdown table.
//   node web/bench/cpu_bench.mjs /tmp/assets
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { createDecoder } from '../src/prm_decoder.js';
import { dracoDecode } from './draco_decode.js';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const [assets] = process.argv.slice(2);
if (!assets) { console.error('usage: node web/bench/cpu_bench.mjs ASSETS_DIR'); process.exit(1); }
const dracoDir = path.join(web, 'node_modules/three/examples/jsm/libs/draco');
// draco_wasm_wrapper.js is a classic script (CommonJS under node); three's package is an ES module one, so it is
// evaluated here rather than required.
const wrapper = { exports: {} };
new Function('module', 'exports', 'require', '__dirname', fs.readFileSync(path.join(dracoDir, 'draco_wasm_wrapper.js'), 'utf8'))(
  wrapper, wrapper.exports, createRequire(import.meta.url), dracoDir);
const draco = await wrapper.exports({ wasmBinary: fs.readFileSync(path.join(dracoDir, 'draco_decoder.wasm')) });
const prm = await createDecoder({ wasmBinary: fs.readFileSync(path.join(web, 'dist/prm_decoder_wasm.wasm')) });

const cpuMs = (f, n) => {
  const c0 = process.cpuUsage();
  for (let i = 0; i < n; ++i) f();
  const c = process.cpuUsage(c0);
  return (c.user + c.system) / 1000 / n;
};
console.log('| asset | PRM v | Draco v | PRM CPU ms | Draco CPU ms | PRM / Draco | PRM ns/v | Draco ns/v |');
console.log('|---|---:|---:|---:|---:|---:|---:|---:|');
for (const a of JSON.parse(fs.readFileSync(path.join(assets, 'assets.json'), 'utf8'))) {
  const p = new Uint8Array(fs.readFileSync(path.join(assets, a.prm)));
  const d = new Int8Array(fs.readFileSync(path.join(assets, a.drc)));
  const pv = prm.decode(p).vertices, dv = dracoDecode(draco, d).positions.length / 3;
  for (let i = 0; i < 20; ++i) { prm.decode(p); dracoDecode(draco, d); }
  let bp = Infinity, bd = Infinity;
  for (let b = 0; b < 10; ++b) {
    bp = Math.min(bp, cpuMs(() => prm.decode(p), 5));
    bd = Math.min(bd, cpuMs(() => dracoDecode(draco, d), 5));
  }
  console.log(`| ${a.name} | ${pv} | ${dv} | ${bp.toFixed(2)} | ${bd.toFixed(2)} | ${(bp / bd).toFixed(2)} | ` +
              `${(1e6 * bp / pv).toFixed(0)} | ${(1e6 * bd / dv).toFixed(0)} |`);
}
