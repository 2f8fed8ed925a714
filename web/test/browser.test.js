// The viewer in headless Chromium (Debian's /usr/bin/chromium through puppeteer-core; nothing downloads a browser).
// A multi-primitive scene built from the shared meshes (prm_gltf_make_scene: a mesh of two primitives with their
// materials, one with NORMAL, plus a textured primitive that stays uncompressed) is packed by `prm pack`; the viewer
// loads it and the decoded positions, indices and normals must equal those of the C++ decoder (`prm unpack`). Also:
// the main-thread decoder gives the same, the fallback is used without a decoder, a required extension without a
// decoder or with a corrupt stream fails with the problem named, and the canvas screenshot is not blank.
//   PRM=path/to/prm MAKE_SCENE=path/to/prm_gltf_make_scene WORK=dir node --test web/test/browser.test.js
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

import { accessorValues, fnv1a, readGlb } from './glb.js';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
for (const v of ['PRM', 'MAKE_SCENE', 'WORK'])
  if (!process.env[v]) throw new Error(`browser.test.js: set ${v} (web/CMakeLists.txt does)`);
const work = process.env.WORK;
fs.mkdirSync(work, { recursive: true });
const run = (cmd, args) => execFileSync(cmd, args, { cwd: work, stdio: ['ignore', 'pipe', 'inherit'] }).toString();

let server, browser, base;

// A static server: / is web/, /work/ the test's folder (the viewer needs http, not file://).
function serve() {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.glb': 'model/gltf-binary' };
  return http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const file = url.startsWith('/work/') ? path.join(work, url.slice(6)) : path.join(web, url);
    const resolved = url.endsWith('/') ? path.join(file, 'index.html') : file;
    fs.readFile(resolved, (err, data) => {
      if (err) { res.writeHead(404); res.end(); return; }
      res.writeHead(200, { 'Content-Type': types[path.extname(resolved)] || 'application/octet-stream' });
      res.end(data);
    });
  });
}

before(async () => {
  run(process.env.MAKE_SCENE, ['scene.glb', '--no-lines']);
  run(process.env.PRM, ['pack', 'scene.glb', '-o', 'packed.glb', '--grid-fraction', '0.05']);
  run(process.env.PRM, ['pack', 'scene.glb', '-o', 'packed_fallback.glb', '--grid-fraction', '0.05', '--fallback']);
  run(process.env.PRM, ['unpack', 'packed.glb', '-o', 'unpacked.glb']);
  // A copy of packed.glb with one byte of its first PRM stream flipped (the stream's CRC then fails).
  const glb = readGlb(path.join(work, 'packed.glb'));
  const ext = glb.json.meshes[0].primitives[0].extensions.PRM_mesh_compression;
  const view = glb.json.bufferViews[ext.bufferView];
  const corrupt = Buffer.from(glb.bytes);
  corrupt[glb.binOffset + (view.byteOffset || 0) + 40] ^= 0x10;
  fs.writeFileSync(path.join(work, 'corrupt.glb'), corrupt);

  server = serve();
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  base = `http://127.0.0.1:${server.address().port}`;
  browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=800,600'],
  });
});

after(async () => {
  if (browser) await browser.close();
  if (server) server.close();
});

// Opens the viewer on a file of the work folder; returns the page and the load's result with, per decoded primitive
// (in mesh then primitive order), the checksums of its geometry.
async function view(file, decoder) {
  const page = await browser.newPage();
  await page.setViewport({ width: 800, height: 600 });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${base}/viewer/?url=/work/${file}${decoder ? `&decoder=${decoder}` : ''}`);
  await page.waitForFunction(() => window.prmViewer && window.prmViewer.result, { timeout: 60000 });
  const result = await page.evaluate(() => {
    const fnv1a = (values) => {
      const words = values instanceof Float32Array ? new Uint32Array(values.buffer, values.byteOffset, values.length)
                                                   : Uint32Array.from(values);
      let h = 0x811c9dc5;
      for (const w of words) for (let k = 0; k < 32; k += 8) { h ^= (w >>> k) & 0xff; h = Math.imul(h, 0x01000193) >>> 0; }
      return h;
    };
    const r = window.prmViewer.result;
    const geometry = [];
    const meshes = [];
    window.prmViewer.scene.traverse((o) => {
      if (!o.isMesh) return;
      const g = o.geometry;
      const entry = { name: o.name, prm: o.userData.prm || null, vertices: g.attributes.position.count,
                      position: fnv1a(g.attributes.position.array), index: g.index ? fnv1a(g.index.array) : null,
                      normal: g.attributes.normal ? fnv1a(g.attributes.normal.array) : null,
                      material: o.material ? o.material.name : null };
      meshes.push(entry);
    });
    return { ok: r.ok, error: r.error, stats: r.stats, meshes, geometry };
  });
  return { page, result, problems };
}

// The C++ decoder's primitives (prm unpack): checksums per PRM primitive of packed.glb.
function reference() {
  const packed = readGlb(path.join(work, 'packed.glb'));
  const plain = readGlb(path.join(work, 'unpacked.glb'));
  const out = [];
  packed.json.meshes.forEach((mesh, m) => mesh.primitives.forEach((p, i) => {
    if (!p.extensions || !p.extensions.PRM_mesh_compression) return;
    const q = plain.json.meshes[m].primitives[i];
    const positions = accessorValues(plain, q.attributes.POSITION);
    out.push({ mesh: m, primitive: i, vertices: positions.length / 3, triangles: plain.json.accessors[q.indices].count / 3,
               position: fnv1a(positions), index: fnv1a(accessorValues(plain, q.indices)),
               normal: q.attributes.NORMAL !== undefined ? fnv1a(accessorValues(plain, q.attributes.NORMAL)) : null,
               material: packed.json.materials[p.material].name });
  }));
  return out;
}

function checkAgainstReference(result) {
  const ref = reference();
  assert.ok(ref.length >= 2, 'the packed scene has fewer than two PRM primitives');
  assert.ok(ref.some((r) => r.normal !== null) && ref.some((r) => r.normal === null), 'want primitives with and without NORMAL');
  assert.deepEqual(result.stats.map((s) => [s.mesh, s.primitive, s.vertices, s.triangles]),
                   ref.map((r) => [r.mesh, r.primitive, r.vertices, r.triangles]));
  // Every node instancing a mesh (the scene's nodes share meshes) shows the same decoded primitives.
  const decoded = result.meshes.filter((m) => m.prm);
  assert.equal(new Set(decoded.map((d) => `${d.prm.mesh}/${d.prm.primitive}`)).size, ref.length);
  for (const r of ref) {
    const instances = decoded.filter((d) => d.prm.mesh === r.mesh && d.prm.primitive === r.primitive);
    assert.ok(instances.length > 0, `meshes[${r.mesh}].primitives[${r.primitive}] is not in the page's scene`);
    for (const m of instances) checkPrimitive(m, r);
  }
  return ref;
}

function checkPrimitive(m, r) {
  assert.equal(m.position, r.position, `positions of meshes[${r.mesh}].primitives[${r.primitive}]`);
  assert.equal(m.index, r.index, `indices of meshes[${r.mesh}].primitives[${r.primitive}]`);
  assert.equal(m.normal, r.normal, `normals of meshes[${r.mesh}].primitives[${r.primitive}]`);
  assert.equal(m.material, r.material, `material of meshes[${r.mesh}].primitives[${r.primitive}]`);
}

test('the viewer (Web Worker decoder) shows the packed scene as the C++ decoder decodes it, not blank', async () => {
  const { page, result, problems } = await view('packed.glb');
  try {
    assert.equal(result.ok, true, result.error);
    assert.deepEqual(problems, []);
    checkAgainstReference(result);
    // The uncompressed textured primitive is there too.
    assert.ok(result.meshes.some((m) => !m.prm && m.material === 'painted'), 'the uncompressed primitive is missing');
    for (const s of result.stats) assert.ok(s.decodeMs >= 0 && s.streamBytes > 0);
    // Two frames later, the canvas's screenshot (the stats panel hidden: only the rendering counts): not one flat colour.
    await page.evaluate(() => {
      document.getElementById('panel').style.visibility = 'hidden';
      return new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    });
    const canvas = await page.$('#view canvas');
    const png = await canvas.screenshot({ path: path.join(work, 'viewer.png') });
    const pixels = await page.evaluate(async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width; c.height = img.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(img, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      let sum = 0, sum2 = 0, differ = 0;
      const n = d.length / 4;
      for (let i = 0; i < d.length; i += 4) {
        const y = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
        sum += y; sum2 += y * y;
        if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 24) ++differ;
      }
      const mean = sum / n;
      return { width: c.width, height: c.height, variance: sum2 / n - mean * mean, coverage: differ / n };
    }, png.toString('base64'));
    assert.equal(pixels.width, 800);
    assert.ok(pixels.variance > 50, `screenshot variance ${pixels.variance.toFixed(1)}: blank`);
    assert.ok(pixels.coverage > 0.02, `only ${(100 * pixels.coverage).toFixed(2)}% of the pixels differ from the background`);
  } finally {
    await page.close();
  }
});

test('the main-thread decoder gives the same geometry', async () => {
  const { page, result } = await view('packed.glb', 'main');
  try {
    assert.equal(result.ok, true, result.error);
    checkAgainstReference(result);
  } finally {
    await page.close();
  }
});

test('with the extension not required, the decoder is used, and without a decoder the fallback (the same mesh)', async () => {
  const withDecoder = await view('packed_fallback.glb');
  await withDecoder.page.close();
  assert.equal(withDecoder.result.ok, true, withDecoder.result.error);
  checkAgainstReference(withDecoder.result);
  const without = await view('packed_fallback.glb', 'none');
  await without.page.close();
  assert.equal(without.result.ok, true, without.result.error);
  assert.deepEqual(without.result.stats, []);  // nothing decoded
  const ref = reference();
  const plain = without.result.meshes;
  for (const r of ref) assert.ok(plain.some((m) => m.position === r.position && m.index === r.index && m.normal === r.normal),
                                 `fallback of meshes[${r.mesh}].primitives[${r.primitive}] is not the decoded mesh`);
});

test('a required extension without a decoder fails the load, naming the primitive', async () => {
  const { page, result } = await view('packed.glb', 'none');
  await page.close();
  assert.equal(result.ok, false);
  assert.match(result.error, /PRM_mesh_compression: meshes\[0\]\.primitives\[0\]: no PRM decoder/);
});

test('a corrupt stream fails the load with its §4.4 error name and byte offset', async () => {
  for (const decoder of ['worker', 'main']) {
    const { page, result } = await view('corrupt.glb', decoder);
    await page.close();
    assert.equal(result.ok, false, decoder);
    assert.match(result.error, /PRM_mesh_compression: meshes\[0\]\.primitives\[0\]: PRM stream does not decode: crc_mismatch at byte \d+/);
  }
});
