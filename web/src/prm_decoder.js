// web/src/prm_decoder.js: the PRM decoder (spec/prm-format.md) in WebAssembly, as an ES module.
//
//   import { createDecoder, decode } from './src/prm_decoder.js';
//   const { positions, indices } = await decode(bytes);          // positions Float32Array, indices Uint32Array
//   const decoder = await createDecoder(); decoder.decode(bytes, { normals: true });   // synchronous after loading
//
// A stream that does not decode throws a PrmDecodeError carrying the §4.4 error name and the byte offset.
import createPrmModule from '../dist/prm_decoder_wasm.js';

// The §4.4 error of a stream that does not decode.
export class PrmDecodeError extends Error {
  constructor(errorName, byteOffset, specSection, detail) {
    super(`PRM stream does not decode: ${errorName} at byte ${byteOffset}` +
          (specSection ? ` (§${specSection})` : '') + (detail ? `: ${detail}` : ''));
    this.name = 'PrmDecodeError';
    this.errorName = errorName;     // e.g. "crc_mismatch", normative (§4.4)
    this.byteOffset = byteOffset;   // where the decoder detected it (informative)
    this.specSection = specSection; // the rule broken, e.g. "3.5"; '' if none
  }
}

// PRM_mesh_compression "Normals": per vertex the normalized sum of (p_b - p_a) x (p_c - p_a) over its triangles
// (corner order), (0, 0, 1) when that sum is zero; computed in binary64 from the binary64 positions origin + q * step
// (§10.5), as the writer does, then rounded to binary32.
export function regenerateNormals(quantized, indices, frame) {
  const n = quantized.length;
  const p = new Float64Array(n);
  for (let i = 0; i < n; i += 3)
    for (let k = 0; k < 3; ++k) p[i + k] = frame.origin[k] + quantized[i + k] * frame.step;
  const s = new Float64Array(n);
  for (let t = 0; t + 2 < indices.length; t += 3) {
    const a = 3 * indices[t], b = 3 * indices[t + 1], c = 3 * indices[t + 2];
    const u0 = p[b] - p[a], u1 = p[b + 1] - p[a + 1], u2 = p[b + 2] - p[a + 2];
    const v0 = p[c] - p[a], v1 = p[c + 1] - p[a + 1], v2 = p[c + 2] - p[a + 2];
    const n0 = u1 * v2 - u2 * v1, n1 = u2 * v0 - u0 * v2, n2 = u0 * v1 - u1 * v0;
    for (const corner of [a, b, c]) { s[corner] += n0; s[corner + 1] += n1; s[corner + 2] += n2; }
  }
  const out = new Float32Array(n);
  for (let i = 0; i < n; i += 3) {
    const len = Math.sqrt(s[i] * s[i] + s[i + 1] * s[i + 1] + s[i + 2] * s[i + 2]);
    if (len > 0) { out[i] = s[i] / len; out[i + 1] = s[i + 1] / len; out[i + 2] = s[i + 2] / len; }
    else { out[i] = 0; out[i + 1] = 0; out[i + 2] = 1; }
  }
  return out;
}

// Loads the WebAssembly module. options.wasmBinary: the .wasm bytes (node, where the loader must not fetch);
// otherwise the .wasm is fetched from beside dist/prm_decoder_wasm.js.
export async function createDecoder(options = {}) {
  const moduleOptions = {};
  if (options.wasmBinary) moduleOptions.wasmBinary = options.wasmBinary;
  else moduleOptions.locateFile = (file) => new URL(`../dist/${file}`, import.meta.url).href;
  const m = await createPrmModule(moduleOptions);
  return { decode: (bytes, decodeOptions) => decodeWith(m, bytes, decodeOptions) };
}

let shared = null;
// decode(Uint8Array, {normals, maxVertices, maxTriangles}) with a module loaded once per realm.
export async function decode(bytes, options) {
  if (!shared) shared = createDecoder();
  return (await shared).decode(bytes, options);
}

// Decodes one stream (spec §2). Returns {positions, indices, quantized, frame, vertices, triangles[, normals]}:
// positions origin + q * step as binary32 (§10.5), indices 3 per triangle in the stream's order (§6.6), quantized the
// exact coordinates (§10.4), frame {bits, origin, step} (§10.1). options.normals adds the extension's normals;
// options.maxVertices / maxTriangles are the caller limits of §4.1 (default those of the C API).
function decodeWith(m, bytes, options = {}) {
  if (!(bytes instanceof Uint8Array)) throw new TypeError('decode: expected a Uint8Array');
  const data = m._malloc(Math.max(bytes.length, 1));
  const err = m._prm_wasm_error_new();
  let mesh = 0;
  try {
    m.HEAPU8.set(bytes, data);
    mesh = m._prm_wasm_decode(data, bytes.length, options.maxVertices || 0, options.maxTriangles || 0, err);
    if (!mesh) {
      throw new PrmDecodeError(m.UTF8ToString(m._prm_wasm_error_name(err)), m._prm_wasm_error_offset(err),
                               m.UTF8ToString(m._prm_wasm_error_section(err)),
                               m.UTF8ToString(m._prm_wasm_error_message(err)));
    }
    const vertices = m._prm_wasm_mesh_vertices(mesh) >>> 0, triangles = m._prm_wasm_mesh_triangles(mesh) >>> 0;
    // Copies out of the heap (a later allocation may grow and move it).
    const positions = new Float32Array(m.HEAPF32.buffer, m._prm_wasm_mesh_positions(mesh), 3 * vertices).slice();
    const quantized = new Uint32Array(m.HEAPU32.buffer, m._prm_wasm_mesh_quantized(mesh), 3 * vertices).slice();
    const indices = new Uint32Array(m.HEAPU32.buffer, m._prm_wasm_mesh_indices(mesh), 3 * triangles).slice();
    const frame = { bits: m._prm_wasm_mesh_bits(mesh),
                    origin: [0, 1, 2].map((k) => m._prm_wasm_mesh_origin(mesh, k)),
                    step: m._prm_wasm_mesh_step(mesh) };
    const out = { positions, indices, quantized, frame, vertices, triangles };
    if (options.normals) out.normals = regenerateNormals(quantized, indices, frame);
    return out;
  } finally {
    if (mesh) m._prm_wasm_mesh_free(mesh);
    m._prm_wasm_error_free(err);
    m._free(data);
  }
}
