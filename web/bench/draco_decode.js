// web/bench/draco_decode.js: one decode with Draco's wasm decoder (the module of draco_wasm_wrapper.js), as three.js's
// DRACOLoader does it: positions as a Float32Array and indices as a Uint32Array, copied out of the heap. Shared by the
// page (bench.js) and the node bench (cpu_bench.mjs).
export function dracoDecode(draco, bytes) {
  const decoder = new draco.Decoder();
  const mesh = new draco.Mesh();
  try {
    const status = decoder.DecodeArrayToMesh(bytes, bytes.byteLength, mesh);
    if (!status.ok() || mesh.ptr === 0) throw new Error(`Draco: ${status.error_msg()}`);
    const numIndices = mesh.num_faces() * 3;
    let ptr = draco._malloc(numIndices * 4);
    decoder.GetTrianglesUInt32Array(mesh, numIndices * 4, ptr);
    const indices = new Uint32Array(draco.HEAPF32.buffer, ptr, numIndices).slice();
    draco._free(ptr);
    const attribute = decoder.GetAttribute(mesh, decoder.GetAttributeId(mesh, draco.POSITION));
    const n = mesh.num_points() * 3;
    ptr = draco._malloc(n * 4);
    decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, draco.DT_FLOAT32, n * 4, ptr);
    const positions = new Float32Array(draco.HEAPF32.buffer, ptr, n).slice();
    draco._free(ptr);
    return { positions, indices };
  } finally {
    draco.destroy(mesh);
    draco.destroy(decoder);
  }
}
