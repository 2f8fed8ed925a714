// web/bench/bench.js: decode each asset with PRM's wasm and with Draco's, alternating, `runs` times each; the
// median and the fastest milliseconds (on a shared machine the fastest run is the one least delayed by other jobs).
// Both decode to a positions Float32Array and a Uint32Array of indices copied out of the heap, as the PRM plugin and
// DRACOLoader hand them to three.js.
import { createDecoder } from '../src/prm_decoder.js';
import { dracoDecode } from './draco_decode.js';

const dracoWasmUrl = '../node_modules/three/examples/jsm/libs/draco/draco_decoder.wasm';

const median = (a) => { const s = [...a].sort((x, y) => x - y); const m = s.length >> 1; return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2; };

window.runBench = async (assetsUrl, runs) => {
  const base = new URL(assetsUrl, location.href);
  const assets = await (await fetch(base)).json();
  const prm = await createDecoder();
  const dracoWasm = await (await fetch(dracoWasmUrl)).arrayBuffer();
  const draco = await DracoDecoderModule({ wasmBinary: dracoWasm });  // eslint-disable-line no-undef
  const files = [];
  for (const a of assets) {
    files.push([new Uint8Array(await (await fetch(new URL(a.prm, base))).arrayBuffer()),
                new Int8Array(await (await fetch(new URL(a.drc, base))).arrayBuffer())]);
  }
  // Warm-up: every asset decoded 5 times by both before any timing, so that both modules run optimized code.
  for (let i = 0; i < 5; ++i) for (const [p, d] of files) { prm.decode(p); dracoDecode(draco, d); }
  const rows = [];
  for (const [k, a] of assets.entries()) {
    const [prmBytes, drcBytes] = files[k];
    const p = prm.decode(prmBytes), d = dracoDecode(draco, drcBytes);  // the counts
    const tp = [], td = [];
    for (let i = 0; i < runs; ++i) {
      let t = performance.now(); prm.decode(prmBytes); tp.push(performance.now() - t);
      t = performance.now(); dracoDecode(draco, drcBytes); td.push(performance.now() - t);
    }
    rows.push({ ...a, prm_bytes: prmBytes.length, drc_bytes: drcBytes.length, prm_vertices: p.positions.length / 3,
                prm_triangles: p.indices.length / 3, drc_vertices: d.positions.length / 3,
                drc_triangles: d.indices.length / 3, prm_ms: median(tp), drc_ms: median(td),
                prm_min_ms: Math.min(...tp), drc_min_ms: Math.min(...td), runs });
  }
  document.getElementById('out').textContent = JSON.stringify(rows, null, 1);
  return rows;
};
document.getElementById('out').textContent = 'ready';
