// node validate.js [--allow CODE]... FILE...: the Khronos glTF-Validator on each file. Prints one summary line per
// file and every message it does not allow; exits 1 if any file has an error, a warning, or an Info other than
// UNSUPPORTED_EXTENSION (the validator does not know PRM_mesh_compression) and UNUSED_OBJECT on a bufferView that
// only a PRM_mesh_compression object uses (the validator cannot see that use). --allow CODE also allows that
// Info code (for infos a test's input already has).
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

function gltfJson(bytes) {
  if (bytes.length >= 20 && bytes.readUInt32LE(0) === 0x46546C67) {
    const n = bytes.readUInt32LE(12);
    return JSON.parse(bytes.subarray(20, 20 + n).toString('utf8'));
  }
  return JSON.parse(bytes.toString('utf8'));
}

function prmBufferViews(json) {
  const views = new Set();
  for (const mesh of json.meshes || [])
    for (const prim of mesh.primitives || []) {
      const ext = prim.extensions && prim.extensions.PRM_mesh_compression;
      if (ext && Number.isInteger(ext.bufferView)) views.add(`/bufferViews/${ext.bufferView}`);
    }
  return views;
}

async function main(args) {
  const allowed = new Set(['UNSUPPORTED_EXTENSION']);
  const files = [];
  for (let i = 0; i < args.length; ++i) {
    if (args[i] === '--allow') allowed.add(args[++i]);
    else files.push(args[i]);
  }
  let failed = false;
  for (const f of files) {
    const bytes = fs.readFileSync(f);
    const streams = prmBufferViews(gltfJson(bytes));
    const r = await validator.validateBytes(new Uint8Array(bytes), {
      uri: path.basename(f), maxIssues: 1000,
      externalResourceFunction: () => Promise.reject(new Error('no external resources')),
    });
    const i = r.issues;
    const ok = (m) => m.severity === 2 && (allowed.has(m.code) || (m.code === 'UNUSED_OBJECT' && streams.has(m.pointer)));
    const bad = i.messages.filter((m) => m.severity < 3 && !ok(m));
    const infos = [...new Set(i.messages.filter((m) => m.severity === 2).map((m) => m.code))];
    console.log(`${f}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos` +
                (infos.length ? ` (${infos.join(', ')})` : '') + `, ${i.numHints} hints`);
    for (const m of bad) console.log(`  ${['Error', 'Warning', 'Info', 'Hint'][m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
    if (bad.length || i.truncated) failed = true;
  }
  process.exit(failed ? 1 : 0);
}

main(process.argv.slice(2)).catch((e) => { console.error(e); process.exit(2); });
