// web/viewer/viewer.js: the viewer page's logic (index.html). Loads a glTF with GLTFLoader and the
// PRM_mesh_compression plugin, shows it, and lists file bytes, PRM vertices / triangles and decode milliseconds per
// decoded primitive. window.prmViewer holds the last load's result (the browser test reads it).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

import { createDecoder } from '../src/prm_decoder.js';
import { createWorkerDecoder } from '../src/prm_worker_client.js';
import { PrmMeshCompressionPlugin } from '../src/prm_gltf_plugin.js';

const params = new URLSearchParams(location.search);
// ?decoder=main: on the main thread; ?decoder=none: no decoder (the plugin then uses the fallback, or fails when
// the extension is required); default: a Web Worker.
const decoderKind = params.get('decoder') || 'worker';
const decoder = { main: () => createDecoder(), none: () => null, worker: () => createWorkerDecoder() }[decoderKind]();

const view = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20232a);
scene.add(new THREE.HemisphereLight(0xffffff, 0x444455, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
let model = null;

function resize() {
  renderer.setSize(view.clientWidth, view.clientHeight);
  camera.aspect = view.clientWidth / Math.max(1, view.clientHeight);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();
renderer.setAnimationLoop(() => { controls.update(); renderer.render(scene, camera); });

const status = (text) => { document.getElementById('status').textContent = text; };
const showError = (text) => { document.getElementById('error').textContent = text; };

function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  const size = box.getSize(new THREE.Vector3()).length() || 1;
  const center = box.getCenter(new THREE.Vector3());
  camera.near = size / 1000;
  camera.far = size * 100;
  camera.position.copy(center).add(new THREE.Vector3(0.6, 0.4, 1).normalize().multiplyScalar(size * 1.1));
  camera.updateProjectionMatrix();
  controls.target.copy(center);
}

function showStats(fileName, bytes, stats) {
  const rows = [`<tr><th>${fileName}</th><th colspan="4">${bytes.toLocaleString('en')} B</th></tr>`,
    '<tr><th>primitive</th><th>stream B</th><th>vertices</th><th>triangles</th><th>decode ms</th></tr>'];
  for (const s of stats) {
    rows.push(`<tr><td>mesh ${s.mesh} / ${s.primitive}</td><td>${s.streamBytes.toLocaleString('en')}</td>` +
      `<td>${s.vertices.toLocaleString('en')}</td><td>${s.triangles.toLocaleString('en')}</td><td>${s.decodeMs.toFixed(2)}</td></tr>`);
  }
  const sum = (k) => stats.reduce((a, s) => a + s[k], 0);
  if (stats.length > 1) {
    rows.push(`<tr><th>total</th><th>${sum('streamBytes').toLocaleString('en')}</th><th>${sum('vertices').toLocaleString('en')}</th>` +
      `<th>${sum('triangles').toLocaleString('en')}</th><th>${sum('decodeMs').toFixed(2)}</th></tr>`);
  }
  if (stats.length === 0) rows.push('<tr><td colspan="5">no PRM_mesh_compression primitive</td></tr>');
  document.getElementById('stats').innerHTML = rows.join('');
}

// Loads a .glb/.gltf from its bytes; resolves to the result window.prmViewer.result also holds.
export async function loadBytes(fileName, buffer) {
  showError('');
  status(`loading ${fileName} …`);
  const loader = new GLTFLoader();
  let plugin = null;
  loader.register((parser) => (plugin = new PrmMeshCompressionPlugin(parser, { decoder })));
  const t0 = performance.now();
  try {
    const gltf = await loader.parseAsync(buffer, '');
    const loadMs = performance.now() - t0;
    if (model) scene.remove(model);
    model = gltf.scene;
    scene.add(model);
    frame(model);
    showStats(fileName, buffer.byteLength, plugin.stats);
    status(`${fileName}: loaded in ${loadMs.toFixed(1)} ms`);
    const prmMeshes = [];
    model.traverse((o) => { if (o.userData.prm) prmMeshes.push(o); });
    const result = { ok: true, fileName, fileBytes: buffer.byteLength, loadMs, stats: plugin.stats.slice(), prmMeshes };
    window.prmViewer.result = result;
    return result;
  } catch (e) {
    status(`${fileName}: not loaded`);
    showError(e.message);
    console.error(e);
    window.prmViewer.result = { ok: false, fileName, error: e.message };
    return window.prmViewer.result;
  }
}

async function loadFile(file) { return loadBytes(file.name, await file.arrayBuffer()); }
document.getElementById('file').addEventListener('change', (e) => { if (e.target.files[0]) loadFile(e.target.files[0]); });
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  if (e.dataTransfer.files[0]) loadFile(e.dataTransfer.files[0]);
});

window.prmViewer = { result: null, scene, renderer, loadBytes };
if (params.get('url')) {
  const url = params.get('url');
  fetch(url).then((r) => {
    if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
    return r.arrayBuffer();
  }).then((b) => loadBytes(url.split('/').pop(), b))
    .catch((e) => { showError(e.message); window.prmViewer.result = { ok: false, fileName: url, error: e.message }; });
}
