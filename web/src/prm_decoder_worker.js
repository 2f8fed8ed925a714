// web/src/prm_decoder_worker.js: the module worker behind createWorkerDecoder (prm_worker_client.js). Each message
// {id, bytes, options} is answered {id, mesh} or {id, error}; the mesh's arrays are transferred, not copied.
import { createDecoder } from './prm_decoder.js';

const decoderPromise = createDecoder();
self.onmessage = async (event) => {
  const { id, bytes, options } = event.data;
  try {
    const decoder = await decoderPromise;
    const t0 = performance.now();
    const mesh = decoder.decode(bytes, options);
    mesh.decodeMs = performance.now() - t0;
    const transfer = [mesh.positions.buffer, mesh.indices.buffer, mesh.quantized.buffer];
    if (mesh.normals) transfer.push(mesh.normals.buffer);
    self.postMessage({ id, mesh }, transfer);
  } catch (e) {
    self.postMessage({ id, error: { name: e.name, message: e.message, errorName: e.errorName,
                                    byteOffset: e.byteOffset, specSection: e.specSection } });
  }
};
