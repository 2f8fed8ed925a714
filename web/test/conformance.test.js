// The WebAssembly decoder against the conformance vectors (conformance/README.md), the bar the C++ decoder meets
// (conformance/conformance_test.cpp): every stream of vectors/ decodes to exactly its expected.txt (comment lines
// aside), every stream of invalid/ is rejected with exactly the §4.4 error its vector.json names.
//   node --test web/test/   (needs web/dist/, built by web/build.sh)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { createDecoder, PrmDecodeError } from '../src/prm_decoder.js';
import { formatG17 } from './format_g17.js';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const conformance = path.join(path.dirname(web), 'conformance');
const decoder = await createDecoder({ wasmBinary: fs.readFileSync(path.join(web, 'dist', 'prm_decoder_wasm.wasm')) });

function listVectors(folder) {
  const dir = path.join(conformance, folder);
  return fs.readdirSync(dir).filter((n) => fs.existsSync(path.join(dir, n, 'stream.prm'))).sort()
    .map((n) => path.join(dir, n));
}

// The decoded mesh printed as expected.txt is, without its comment line.
function printMesh(r) {
  const lines = [`frame bits ${r.frame.bits} origin ${r.frame.origin.map(formatG17).join(' ')} step ${formatG17(r.frame.step)}`];
  for (let i = 0; i < r.quantized.length; i += 3) lines.push(`v ${r.quantized[i]} ${r.quantized[i + 1]} ${r.quantized[i + 2]}`);
  for (let i = 0; i < r.indices.length; i += 3) lines.push(`f ${r.indices[i]} ${r.indices[i + 1]} ${r.indices[i + 2]}`);
  return lines.join('\n') + '\n';
}

const valid = listVectors('vectors');
const invalid = listVectors('invalid');

test('the vector folders are there', () => {
  assert.ok(valid.length >= 16, `only ${valid.length} vectors in conformance/vectors`);
  assert.ok(invalid.length >= 50, `only ${invalid.length} vectors in conformance/invalid`);
});

test('formatG17 prints as printf("%.17g") does (conformance/README.md examples)', () => {
  assert.equal(formatG17(0), '0');
  assert.equal(formatG17(1), '1');
  assert.equal(formatG17(-0), '-0');
  assert.equal(formatG17(1 / 4095), '0.0002442002442002442');
  assert.equal(formatG17(-0.471552), '-0.47155200000000003');
  assert.equal(formatG17(1.6566056166056168e-05), '1.6566056166056168e-05');
  assert.equal(formatG17(1e17), '1e+17');
  assert.equal(formatG17(123456.5), '123456.5');
});

for (const dir of valid) {
  test(`decodes ${path.basename(dir)} to exactly expected.txt`, () => {
    const bytes = new Uint8Array(fs.readFileSync(path.join(dir, 'stream.prm')));
    const r = decoder.decode(bytes);
    const expected = fs.readFileSync(path.join(dir, 'expected.txt'), 'utf8').split('\n')
      .filter((l) => !l.startsWith('#')).join('\n');
    assert.equal(printMesh(r), expected);
    // The positions are origin + q * step rounded to binary32 (§10.5).
    for (let i = 0; i < r.quantized.length; ++i)
      assert.equal(r.positions[i], Math.fround(r.frame.origin[i % 3] + r.quantized[i] * r.frame.step));
  });
}

for (const dir of invalid) {
  test(`rejects ${path.basename(dir)} with its error name`, () => {
    const want = JSON.parse(fs.readFileSync(path.join(dir, 'vector.json'), 'utf8'));
    const limits = want.limits || {};
    const bytes = new Uint8Array(fs.readFileSync(path.join(dir, 'stream.prm')));
    assert.throws(() => decoder.decode(bytes, { maxVertices: limits.max_vertices, maxTriangles: limits.max_triangles }),
      (e) => {
        assert.ok(e instanceof PrmDecodeError, `not a PrmDecodeError: ${e}`);
        assert.equal(e.errorName, want.error);
        assert.ok(Number.isInteger(e.byteOffset) && e.byteOffset >= 0 && e.byteOffset <= bytes.length,
                  `byte offset ${e.byteOffset} outside the ${bytes.length}-byte stream`);
        assert.match(e.message, new RegExp(`${want.error} at byte ${e.byteOffset}`));
        return true;
      });
  });
}

test('a non-Uint8Array argument is a TypeError', () => {
  assert.throws(() => decoder.decode('not bytes'), TypeError);
});
