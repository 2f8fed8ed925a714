// glTF 2.0 and GLB through tinygltf (compiled privately: gltf_ext/src/tinygltf_unit.cpp): the positions and
// indices of every TRIANGLES (and TRIANGLE_STRIP / TRIANGLE_FAN) primitive of every mesh, placed by the node
// transforms of the default scene (meshes no node uses are read untransformed). Writing: one mesh, float
// positions, uint32 indices.
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh_io_internal.h"

namespace prm::io {
namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glTF

Mat4 identity() {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[static_cast<size_t>(k * 4 + rr)] * b[static_cast<size_t>(c * 4 + k)];
      r[static_cast<size_t>(c * 4 + rr)] = s;
    }
  return r;
}

Mat4 node_matrix(const prm_tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    Mat4 m;
    for (size_t i = 0; i < 16; ++i) m[i] = n.matrix[i];
    return m;
  }
  Mat4 t = identity(), r = identity(), s = identity();
  if (n.translation.size() == 3) {
    t[12] = n.translation[0];
    t[13] = n.translation[1];
    t[14] = n.translation[2];
  }
  if (n.rotation.size() == 4) {
    const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r = {1 - 2 * (y * y + z * z),
         2 * (x * y + z * w),
         2 * (x * z - y * w),
         0,
         2 * (x * y - z * w),
         1 - 2 * (x * x + z * z),
         2 * (y * z + x * w),
         0,
         2 * (x * z + y * w),
         2 * (y * z - x * w),
         1 - 2 * (x * x + y * y),
         0,
         0,
         0,
         0,
         1};
  }
  if (n.scale.size() == 3) {
    s[0] = n.scale[0];
    s[5] = n.scale[1];
    s[10] = n.scale[2];
  }
  return mul(t, mul(r, s));
}

// The bytes of accessor `index`, checked against its buffer.
struct View {
  const unsigned char* data = nullptr;
  size_t count = 0, stride = 0, elem = 0;
  int component = 0;
};

View accessor_view(const prm_tinygltf::Model& m, int index, const std::string& path, const char* what) {
  if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
    fail(path, std::string(what) + " accessor index out of range");
  const auto& a = m.accessors[static_cast<size_t>(index)];
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= m.bufferViews.size())
    fail(path,
         std::string(what) + " accessor has no buffer view (compressed or sparse data is not supported)");
  if (a.sparse.isSparse) fail(path, std::string(what) + " accessor is sparse (not supported)");
  const auto& bv = m.bufferViews[static_cast<size_t>(a.bufferView)];
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size())
    fail(path, "buffer index out of range");
  const auto& buf = m.buffers[static_cast<size_t>(bv.buffer)];
  View v;
  v.component = a.componentType;
  const int csize = prm_tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int ncomp = prm_tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (csize <= 0 || ncomp <= 0) fail(path, std::string(what) + " accessor has an invalid type");
  v.elem = static_cast<size_t>(csize) * static_cast<size_t>(ncomp);
  v.stride = bv.byteStride ? bv.byteStride : v.elem;
  v.count = a.count;
  // Without overflow: a hostile offset or count must not wrap round into an in-bounds size.
  const uint64_t size = buf.data.size();
  const bool view_ok = bv.byteOffset <= size && bv.byteLength <= size - bv.byteOffset;
  const uint64_t view_end = view_ok ? uint64_t{bv.byteOffset} + bv.byteLength : 0;
  const bool start_ok = view_ok && a.byteOffset <= bv.byteLength;
  const uint64_t start = start_ok ? uint64_t{bv.byteOffset} + a.byteOffset : 0;
  if (v.stride < v.elem || !start_ok ||
      (v.count > 0 && (view_end - start < v.elem || (v.count - 1) > (view_end - start - v.elem) / v.stride)))
    fail(path, std::string(what) + " accessor claims " + std::to_string(v.count) +
                   " elements, which reach past the end of its buffer view (" +
                   std::to_string(bv.byteLength) + " bytes; buffer " + std::to_string(buf.data.size()) +
                   " bytes)");
  v.data = buf.data.data() + start;
  return v;
}

uint32_t read_index(const View& v, size_t i) {
  const unsigned char* p = v.data + i * v.stride;
  switch (v.component) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, 2);
      return x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
  }
  return UINT32_MAX;
}

double read_position_component(const unsigned char* p, int component, bool normalized) {
  switch (component) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float x;
      std::memcpy(&x, p, 4);
      return x;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t x;
      std::memcpy(&x, p, 1);
      return normalized ? std::max(x / 127.0, -1.0) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t x;
      std::memcpy(&x, p, 2);
      return normalized ? std::max(x / 32767.0, -1.0) : x;
    }
    default: {  // UNSIGNED_SHORT
      uint16_t x;
      std::memcpy(&x, p, 2);
      return normalized ? x / 65535.0 : x;
    }
  }
}

void add_primitive(const prm_tinygltf::Model& m, const prm_tinygltf::Primitive& prim, const Mat4& xf,
                   const std::string& path, RawMesh& raw, uint64_t max_vertices) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    raw.notes.push_back("a primitive that is not made of triangles (points or lines) was skipped");
    return;
  }
  const auto it = prim.attributes.find("POSITION");
  if (it == prim.attributes.end()) fail(path, "a triangle primitive has no POSITION attribute");
  const View pv = accessor_view(m, it->second, path, "POSITION");
  // Float, or integers (KHR_mesh_quantization: normalized or not, placed by the node transforms).
  const int csize = prm_tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(pv.component));
  if (csize <= 0 || pv.elem != static_cast<size_t>(3 * csize) || pv.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(path, "POSITION must be VEC3 of float, or of (unsigned) bytes or shorts (KHR_mesh_quantization)");
  const bool normalized = m.accessors[static_cast<size_t>(it->second)].normalized;
  if (raw.positions.size() + uint64_t{pv.count} > max_vertices)
    fail(path, "the nodes instance the meshes into more than " + std::to_string(max_vertices) +
                   " vertices (far more than the file stores)");
  const uint32_t base = static_cast<uint32_t>(raw.positions.size());
  for (size_t i = 0; i < pv.count; ++i) {
    double p[3];
    for (size_t c = 0; c < 3; ++c) p[c] = read_position_component(pv.data + i * pv.stride + c * static_cast<size_t>(csize), pv.component, normalized);
    Vec3 q;
    for (size_t r = 0; r < 3; ++r) q[r] = xf[r] * p[0] + xf[4 + r] * p[1] + xf[8 + r] * p[2] + xf[12 + r];
    raw.positions.push_back(q);
  }
  std::vector<uint32_t> idx;
  if (prim.indices >= 0) {
    const View iv = accessor_view(m, prim.indices, path, "indices");
    if (iv.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        iv.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        iv.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(path, "indices must be unsigned byte, short or int");
    idx.resize(iv.count);
    for (size_t i = 0; i < iv.count; ++i) {
      idx[i] = read_index(iv, i);
      if (idx[i] >= pv.count)
        fail(path, "index " + std::to_string(idx[i]) + " is out of range (" + std::to_string(pv.count) +
                       " vertices)");
    }
  } else {
    idx.resize(pv.count);
    for (size_t i = 0; i < pv.count; ++i) idx[i] = static_cast<uint32_t>(i);
  }
  // A negative determinant mirrors the mesh: flip the triangles to keep them outward.
  const double det = xf[0] * (xf[5] * xf[10] - xf[9] * xf[6]) - xf[4] * (xf[1] * xf[10] - xf[9] * xf[2]) +
                     xf[8] * (xf[1] * xf[6] - xf[5] * xf[2]);
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    uint32_t t[3] = {base + a, base + b, base + c};
    if (det < 0) std::swap(t[1], t[2]);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return;
    raw.add_polygon(t, 3);
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < idx.size(); i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < idx.size(); ++i)
      if (i % 2)
        add(idx[i + 1], idx[i], idx[i + 2]);
      else
        add(idx[i], idx[i + 1], idx[i + 2]);
  } else {
    for (size_t i = 1; i + 1 < idx.size(); ++i) add(idx[0], idx[i], idx[i + 1]);
  }
}

// External buffers (a .gltf's "uri") are read only from regular files: a hostile file must not make the
// reader block on a FIFO or a device.
bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& file,
                       void* user) {
  struct stat st;
  if (::stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    if (err) *err += "the buffer file '" + file + "' is not a regular file\n";
    return false;
  }
  return prm_tinygltf::ReadWholeFile(out, err, file, user);
}

// Images are not decoded (only geometry is read); without a callback tinygltf refuses every textured asset.
bool skip_image(prm_tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                void*) {
  return true;
}

}  // namespace

RawMesh read_gltf(const std::string& path) {
  prm_tinygltf::TinyGLTF loader;
  prm_tinygltf::FsCallbacks fs = {&prm_tinygltf::FileExists, &prm_tinygltf::ExpandFilePath,
                                  &read_regular_file, &prm_tinygltf::WriteWholeFile, nullptr};
  loader.SetFsCallbacks(fs);
  loader.SetImageLoader(&skip_image, nullptr);
  prm_tinygltf::Model model;
  std::string err, warn;
  const std::vector<char> head = read_file(path);  // also reports a missing file as IoError
  if (head.empty()) fail(path, "the file is empty");
  const bool binary = head.size() >= 4 && std::memcmp(head.data(), "glTF", 4) == 0;
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {  // nlohmann-json can throw on malformed JSON inside tinygltf
    err = e.what();
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n')) err.pop_back();
    fail(path, "malformed glTF: " + (err.empty() ? std::string("tinygltf failed") : err));
  }
  RawMesh raw;
  // Nodes may place one mesh many times; a small file must not expand without bound.
  uint64_t buffer_bytes = 0;
  for (const auto& b : model.buffers) buffer_bytes += b.data.size();
  const uint64_t max_vertices =
      std::min<uint64_t>(kMaxElements, 16 * (buffer_bytes / 12) + (uint64_t{1} << 20));
  std::vector<uint8_t> used(model.meshes.size(), 0);
  const int scene = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
  if (scene >= 0 && static_cast<size_t>(scene) < model.scenes.size()) {
    // Depth-first over the node hierarchy; a depth limit guards against cycles in a broken file.
    struct Item {
      int node;
      Mat4 parent;
      int depth;
    };
    std::vector<Item> stack;
    for (int n : model.scenes[static_cast<size_t>(scene)].nodes) stack.push_back({n, identity(), 0});
    size_t visits = 0;
    while (!stack.empty()) {
      const Item it = stack.back();
      stack.pop_back();
      if (it.node < 0 || static_cast<size_t>(it.node) >= model.nodes.size())
        fail(path, "node index out of range");
      if (it.depth > 64 || ++visits > 1000000) fail(path, "the node hierarchy is cyclic or too deep");
      const auto& node = model.nodes[static_cast<size_t>(it.node)];
      const Mat4 xf = mul(it.parent, node_matrix(node));
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= model.meshes.size()) fail(path, "mesh index out of range");
        used[static_cast<size_t>(node.mesh)] = 1;
        for (const auto& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives)
          add_primitive(model, prim, xf, path, raw, max_vertices);
      }
      for (int c : node.children) stack.push_back({c, xf, it.depth + 1});
    }
  }
  for (size_t m = 0; m < model.meshes.size(); ++m)
    if (!used[m])
      for (const auto& prim : model.meshes[m].primitives)
        add_primitive(model, prim, identity(), path, raw, max_vertices);
  raw.file_vertices = raw.positions.size();
  raw.file_faces = raw.num_polygons();
  if (!warn.empty()) raw.notes.push_back("tinygltf: " + warn.substr(0, warn.find('\n')));
  return raw;
}

void write_glb(const Mesh& mesh, const std::string& path, bool binary) {
  prm_tinygltf::Model model;
  prm_tinygltf::Buffer buffer;
  const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  buffer.data.resize(nv * 12 + nt * 12);
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (size_t v = 0; v < nv; ++v) {
    float p[3] = {static_cast<float>(mesh.positions[v][0]), static_cast<float>(mesh.positions[v][1]),
                  static_cast<float>(mesh.positions[v][2])};
    std::memcpy(buffer.data.data() + 12 * v, p, 12);
    for (int a = 0; a < 3; ++a) {
      lo[a] = v ? std::min(lo[a], p[a]) : p[a];
      hi[a] = v ? std::max(hi[a], p[a]) : p[a];
    }
  }
  for (size_t t = 0; t < nt; ++t)
    std::memcpy(buffer.data.data() + 12 * nv + 12 * t, mesh.triangles[t].data(), 12);
  model.buffers.push_back(std::move(buffer));
  prm_tinygltf::BufferView pv, iv;
  pv.buffer = 0;
  pv.byteOffset = 0;
  pv.byteLength = 12 * nv;
  pv.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  iv.buffer = 0;
  iv.byteOffset = 12 * nv;
  iv.byteLength = 12 * nt;
  iv.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  model.bufferViews = {pv, iv};
  prm_tinygltf::Accessor pa, ia;
  pa.bufferView = 0;
  pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pa.type = TINYGLTF_TYPE_VEC3;
  pa.count = nv;
  pa.minValues = {lo[0], lo[1], lo[2]};
  pa.maxValues = {hi[0], hi[1], hi[2]};
  ia.bufferView = 1;
  ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  ia.type = TINYGLTF_TYPE_SCALAR;
  ia.count = 3 * nt;
  model.accessors = {pa, ia};
  prm_tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prm_tinygltf::Mesh m;
  m.primitives.push_back(prim);
  model.meshes.push_back(m);
  prm_tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  prm_tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.asset.version = "2.0";
  model.asset.generator = "prm";
  prm_tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, true, true, !binary, binary))
    throw IoError(path + ": cannot write the glTF file");
}

}  // namespace prm::io
