// A minimal GLB reader for the tests (the GLB container of glTF 2.0): the JSON and the BIN chunk, an accessor's
// values.
import fs from 'node:fs';

export function readGlb(file) {
  const b = fs.readFileSync(file);
  if (b.readUInt32LE(0) !== 0x46546c67) throw new Error(`${file}: not a GLB`);
  const jsonLength = b.readUInt32LE(12);
  const json = JSON.parse(b.subarray(20, 20 + jsonLength).toString('utf8'));
  const binStart = 20 + jsonLength;
  const bin = binStart + 8 <= b.length ? b.subarray(binStart + 8, binStart + 8 + b.readUInt32LE(binStart)) : null;
  return { json, bin, bytes: b, binOffset: binStart + 8 };
}

const componentArrays = { 5121: Uint8Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
const componentsPer = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

// The values of a tightly packed, non-sparse accessor (what `prm unpack` writes), as a typed array.
export function accessorValues(glb, index) {
  const a = glb.json.accessors[index];
  const view = glb.json.bufferViews[a.bufferView];
  const Type = componentArrays[a.componentType];
  const n = a.count * componentsPer[a.type];
  const start = (view.byteOffset || 0) + (a.byteOffset || 0);
  const copy = new Uint8Array(glb.bin.subarray(start, start + n * Type.BYTES_PER_ELEMENT));
  return new Type(copy.buffer, 0, n);
}

// FNV-1a 32 over the bytes of a Float32Array's values, or over a list of integers as little-endian uint32 words; the
// page computes the same (browser.test.js).
export function fnv1a(values) {
  const words = values instanceof Float32Array ? new Uint32Array(values.buffer, values.byteOffset, values.length)
                                               : Uint32Array.from(values);
  let h = 0x811c9dc5;
  for (const w of words) {
    for (let k = 0; k < 32; k += 8) { h ^= (w >>> k) & 0xff; h = Math.imul(h, 0x01000193) >>> 0; }
  }
  return h;
}
