// web/src/prm_worker_client.js: the decoder in a Web Worker, so that decoding does not block the page.
//   const decoder = createWorkerDecoder();
//   const { positions, indices, decodeMs } = await decoder.decode(bytes, { normals: true });   // rejects with a
//   decoder.terminate();                                                                       // PrmDecodeError
import { PrmDecodeError } from './prm_decoder.js';

export function createWorkerDecoder() {
  const worker = new Worker(new URL('./prm_decoder_worker.js', import.meta.url), { type: 'module' });
  const pending = new Map();
  let nextId = 0;
  worker.onmessage = (event) => {
    const { id, mesh, error } = event.data;
    const p = pending.get(id);
    pending.delete(id);
    if (!error) return p.resolve(mesh);
    if (error.name === 'PrmDecodeError') {
      p.reject(new PrmDecodeError(error.errorName, error.byteOffset, error.specSection,
                                  error.message.replace(/^.*?: [a-z_]+ at byte \d+( \(§[^)]*\))?: ?/, '')));
    } else {
      p.reject(new Error(`PRM decoder worker: ${error.message}`));
    }
  };
  worker.onerror = (event) => {
    const e = new Error(`PRM decoder worker failed: ${event.message || 'could not load'}`);
    for (const p of pending.values()) p.reject(e);
    pending.clear();
  };
  return {
    // The bytes are copied to the worker (the caller keeps its buffer).
    decode(bytes, options = {}) {
      return new Promise((resolve, reject) => {
        const id = nextId++;
        pending.set(id, { resolve, reject });
        worker.postMessage({ id, bytes, options });
      });
    },
    terminate() { worker.terminate(); },
  };
}
