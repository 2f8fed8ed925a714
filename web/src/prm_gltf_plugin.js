// web/src/prm_gltf_plugin.js: a three.js GLTFLoader plugin for PRM_mesh_compression
// (spec/PRM_mesh_compression/README.md).
//
//   import { PrmMeshCompressionPlugin } from './src/prm_gltf_plugin.js';
//   loader.register((parser) => new PrmMeshCompressionPlugin(parser, { decoder: createDecoder() }));
//
// GLTFLoader has no per-primitive hook for a third-party compression extension (Draco's is built in), so the plugin
// implements loadMesh for every mesh that has a primitive with the extension: those primitives are decoded from their
// PRM stream, the others go through GLTFLoader's own loadGeometries. A stream that cannot be used (the decoder did
// not load, an invalid extension object, a stream that does not decode, counts that differ from the accessors') makes
// the load fail naming the mesh, the primitive and the problem when the extension is required, and otherwise falls back
// to the primitive's accessors with a console warning ("Loader behaviour" 5). Decode statistics go to
// plugin.stats and to each three.js mesh's userData.prm.
import { BufferAttribute, BufferGeometry, Group, Line, LineLoop, LineSegments, Mesh, MeshStandardMaterial, Points }
  from 'three';

export const EXTENSION_NAME = 'PRM_mesh_compression';
const POINTS = 0, LINES = 1, LINE_LOOP = 2, LINE_STRIP = 3, TRIANGLES = 4, TRIANGLE_STRIP = 5, TRIANGLE_FAN = 6;

export class PrmMeshCompressionPlugin {
  // options.decoder: a decoder or a promise of one ({decode(bytes, {normals})}, prm_decoder.js's createDecoder or
  // prm_worker_client.js's createWorkerDecoder); without one, or if it fails to load, the fallback is used.
  constructor(parser, options = {}) {
    this.name = EXTENSION_NAME;
    this.parser = parser;
    this.decoder = options.decoder ? Promise.resolve(options.decoder) : null;
    this.stats = [];  // one {mesh, primitive, streamBytes, vertices, triangles, decodeMs} per decoded primitive
  }

  loadMesh(meshIndex) {
    const json = this.parser.json;
    const meshDef = json.meshes[meshIndex];
    if (!meshDef.primitives.some((p) => p.extensions && p.extensions[EXTENSION_NAME])) return null;
    const required = (json.extensionsRequired || []).includes(EXTENSION_NAME);
    const parser = this.parser;
    const pending = meshDef.primitives.map((primitive, i) => Promise.all([
      primitive.material === undefined ? defaultMaterial(parser) : parser.getDependency('material', primitive.material),
      this.loadGeometry(meshIndex, i, primitive, required),
    ]));
    return Promise.all(pending).then((results) => {
      const meshes = results.map(([material, geometry], i) => {
        const primitive = meshDef.primitives[i];
        const object = makeObject(primitive.mode, geometry, material);
        object.name = parser.createUniqueName(meshDef.name || `mesh_${meshIndex}`);
        if (geometry.userData.prm) object.userData.prm = geometry.userData.prm;
        if (meshDef.extras && typeof meshDef.extras === 'object') Object.assign(object.userData, meshDef.extras);
        parser.assignFinalMaterial(object);
        parser.associations.set(object, { meshes: meshIndex, primitives: i });
        return object;
      });
      if (meshes.length === 1) return meshes[0];
      const group = new Group();
      parser.associations.set(group, { meshes: meshIndex });
      for (const m of meshes) group.add(m);
      return group;
    });
  }

  // The primitive's BufferGeometry: decoded when it has the extension and the decoder is there, else GLTFLoader's.
  async loadGeometry(meshIndex, primitiveIndex, primitive, required) {
    const ext = primitive.extensions && primitive.extensions[EXTENSION_NAME];
    const fallback = () => this.parser.loadGeometries([primitive]).then((g) => g[0]);
    if (!ext) return fallback();
    const where = `meshes[${meshIndex}].primitives[${primitiveIndex}]`;
    try {
      return await this.decodePrimitive(meshIndex, primitiveIndex, primitive, ext);
    } catch (e) {
      const message = `${EXTENSION_NAME}: ${where}: ${e.message}`;
      if (required) {
        const error = new Error(message);
        error.cause = e;
        throw error;
      }
      console.warn(`${message}; using the fallback accessors`);
      return fallback();
    }
  }

  async decodePrimitive(meshIndex, primitiveIndex, primitive, ext) {
    const json = this.parser.json;
    checkExtension(json, primitive, ext);
    if (!this.decoder) throw new Error('no PRM decoder was given to the plugin');
    let decoder;
    try {
      decoder = await this.decoder;
    } catch (e) {
      throw new Error(`the PRM decoder did not load (${e.message})`);
    }
    const view = await this.parser.getDependency('bufferView', ext.bufferView);
    const bytes = new Uint8Array(view);
    const wantNormals = primitive.attributes.NORMAL !== undefined;
    const t0 = performance.now();
    const mesh = await decoder.decode(bytes, { normals: wantNormals });
    const decodeMs = performance.now() - t0;
    // "Loader behaviour" 4: the decoded counts are the accessors'.
    const count = (id) => json.accessors[id].count;
    if (count(primitive.attributes.POSITION) !== mesh.vertices)
      throw new Error(`the stream decodes to ${mesh.vertices} vertices, accessors[${primitive.attributes.POSITION}].count is ${count(primitive.attributes.POSITION)}`);
    if (wantNormals && count(primitive.attributes.NORMAL) !== mesh.vertices)
      throw new Error(`accessors[${primitive.attributes.NORMAL}] (NORMAL) count ${count(primitive.attributes.NORMAL)} is not the ${mesh.vertices} decoded vertices`);
    if (count(primitive.indices) !== 3 * mesh.triangles)
      throw new Error(`the stream decodes to ${mesh.triangles} triangles, accessors[${primitive.indices}].count is ${count(primitive.indices)}`);
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(mesh.positions, 3));
    if (wantNormals) geometry.setAttribute('normal', new BufferAttribute(mesh.normals, 3));
    geometry.setIndex(new BufferAttribute(mesh.indices, 1));
    geometry.computeBoundingBox();
    geometry.computeBoundingSphere();
    const stats = { mesh: meshIndex, primitive: primitiveIndex, streamBytes: bytes.length, vertices: mesh.vertices,
                    triangles: mesh.triangles, decodeMs: mesh.decodeMs ?? decodeMs };
    geometry.userData.prm = stats;
    this.stats.push(stats);
    return geometry;
  }
}

// "Loader behaviour" 1 and 2, and the constraints on the primitive.
function checkExtension(json, primitive, ext) {
  const views = json.bufferViews || [];
  if (!Number.isInteger(ext.bufferView)) throw new Error('PRM_mesh_compression.bufferView is missing or not an integer');
  if (ext.bufferView < 0 || ext.bufferView >= views.length)
    throw new Error(`PRM_mesh_compression.bufferView: ${ext.bufferView} is not a bufferView`);
  const view = views[ext.bufferView];
  const buffer = (json.buffers || [])[view.buffer];
  if (!buffer || (view.byteOffset || 0) + view.byteLength > buffer.byteLength)
    throw new Error(`bufferViews[${ext.bufferView}] reaches past the end of its buffer`);
  const attrs = ext.attributes;
  if (!attrs || typeof attrs !== 'object' || Object.keys(attrs).length !== 1 || attrs.POSITION !== 0)
    throw new Error('PRM_mesh_compression.attributes must be {"POSITION": 0}');
  if (ext.version !== 1) throw new Error(`PRM_mesh_compression.version ${ext.version} is not supported (1 is)`);
  if (primitive.mode !== undefined && primitive.mode !== TRIANGLES)
    throw new Error(`mode ${primitive.mode} is not TRIANGLES`);
  const names = Object.keys(primitive.attributes);
  if (!names.includes('POSITION') || names.some((n) => n !== 'POSITION' && n !== 'NORMAL'))
    throw new Error(`attributes ${names.join(', ')}: only POSITION and NORMAL may be compressed`);
  if (primitive.indices === undefined) throw new Error('the primitive has no indices');
}

function makeObject(mode, geometry, material) {
  switch (mode === undefined ? TRIANGLES : mode) {
    case TRIANGLES: case TRIANGLE_STRIP: case TRIANGLE_FAN: return new Mesh(geometry, material);  // (strips and fans
                                                                             // made triangles by loadGeometries)
    case LINES: return new LineSegments(geometry, material);
    case LINE_STRIP: return new Line(geometry, material);
    case LINE_LOOP: return new LineLoop(geometry, material);
    case POINTS: return new Points(geometry, material);
    default: throw new Error(`primitive mode ${mode} is not supported by this plugin`);
  }
}

// glTF 2.0's default material (§3.9.6), once per parser, as GLTFLoader makes it.
function defaultMaterial(parser) {
  if (!parser.cache.get('PrmDefaultMaterial')) {
    parser.cache.add('PrmDefaultMaterial', new MeshStandardMaterial({ color: 0xffffff, emissive: 0x000000,
      metalness: 1, roughness: 1, transparent: false, depthTest: true, side: 0 }));
  }
  return parser.cache.get('PrmDefaultMaterial');
}
