// Reading and writing a glTF asset's JSON and buffers (GLB container: glTF 2.0 §4.4; data: URIs: RFC 2397).
#include "prm/gltf/document.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "prm/error.h"

namespace prm::gltf {
namespace {

using nlohmann::json;

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr size_t kAlignment = 4;             // bufferView offsets and GLB chunks

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

std::vector<uint8_t> read_bytes(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) throw IoError("cannot open '" + path + "'");
  if (!S_ISREG(st.st_mode)) throw InputError("'" + path + "' is not a regular file");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError("cannot open '" + path + "'");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw IoError("cannot read '" + path + "'");
  return bytes;
}

uint32_t u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  uint8_t b[4];
  std::memcpy(b, &v, 4);
  out.insert(out.end(), b, b + 4);
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;
  if (c == '/' || c == '_') return 63;
  return -1;
}

bool base64_decode(const std::string& text, size_t begin, std::vector<uint8_t>& out) {
  uint32_t acc = 0;
  int bits = 0;
  for (size_t i = begin; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '=') break;
    const int v = base64_value(c);
    if (v < 0) return false;
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>((acc >> bits) & 0xFF));
    }
  }
  return true;
}

std::string base64_encode(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                   b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[v & 63] : '=';
  }
  return out;
}

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// The bytes of buffer i from its uri: a data: URI, or a relative file in the asset's folder or below it.
std::vector<uint8_t> buffer_from_uri(const std::string& path, size_t i, const std::string& uri) {
  const std::string where = "buffers[" + std::to_string(i) + "].uri";
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.substr(0, comma).find(";base64") == std::string::npos)
      fail(path, where + " is a data: URI that is not base64");
    std::vector<uint8_t> out;
    if (!base64_decode(uri, comma + 1, out)) fail(path, where + " has a character that is not base64");
    return out;
  }
  if (uri.empty() || uri[0] == '/' || uri.find("..") != std::string::npos || uri.find(':') != std::string::npos)
    fail(path, where + " '" + uri + "' is not a relative path inside the asset's folder");
  return read_bytes(folder_of(path) + uri);
}

const json& array_or_empty(const json& j, const char* key) {
  static const json empty = json::array();
  const auto it = j.find(key);
  return it != j.end() && it->is_array() ? *it : empty;
}

uint64_t get_uint(const json& obj, const char* key, uint64_t fallback, const std::string& path,
                  const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) return fallback;
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<int64_t>() >= 0))
    fail(path, where + "." + key + " must be a non-negative integer");
  return it->get<uint64_t>();
}

void check_buffer_views(const Document& doc) {
  const json& views = array_or_empty(doc.json, "bufferViews");
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string where = "bufferViews[" + std::to_string(i) + "]";
    if (!views[i].is_object()) fail(doc.path, where + " is not an object");
    const uint64_t b = get_uint(views[i], "buffer", UINT64_MAX, doc.path, where);
    if (b >= doc.buffers.size())
      fail(doc.path, where + ".buffer is " + (b == UINT64_MAX ? std::string("missing") : std::to_string(b)) +
                         " (the asset has " + std::to_string(doc.buffers.size()) + " buffers)");
    const uint64_t off = get_uint(views[i], "byteOffset", 0, doc.path, where);
    const uint64_t len = get_uint(views[i], "byteLength", UINT64_MAX, doc.path, where);
    if (len == UINT64_MAX) fail(doc.path, where + ".byteLength is missing");
    const uint64_t size = doc.buffers[b].size();
    const bool placeholder = size == 0 && views[i].contains("extensions");  // e.g. an EXT_meshopt fallback
    if (!placeholder && (off > size || len > size - off))
      fail(doc.path, where + " (byteOffset " + std::to_string(off) + ", byteLength " + std::to_string(len) +
                         ") reaches past the end of buffers[" + std::to_string(b) + "] (" + std::to_string(size) +
                         " bytes)");
  }
}

// The members the commands read as typed values (glTF 2.0 §5 and its JSON schema): a value of another type is refused
// here, by name, instead of throwing nlohmann's type_error deep inside `prm info` or `prm unpack` (the CLI's
// "internal error"). Elements of the top-level arrays are objects, their names strings; extensionsUsed and
// extensionsRequired list strings; a primitive's attributes and extensions are objects, its mode, indices, material and attribute values integers; an
// accessor's (and its sparse parts') indices, offsets, component type and count are integers, its type a string and
// normalized a boolean; a bufferView's byteStride and target are integers.
void check_member_types(const Document& doc) {
  const json& j = doc.json;
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (!j.contains(key)) continue;
    if (!j[key].is_array()) fail(doc.path, std::string(key) + " is not an array");
    for (size_t i = 0; i < j[key].size(); ++i)
      if (!j[key][i].is_string()) fail(doc.path, std::string(key) + "[" + std::to_string(i) + "] is not a string");
  }
  for (const char* key : {"buffers", "bufferViews", "accessors", "meshes", "nodes", "images"}) {
    const json& list = array_or_empty(j, key);
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string where = key + ("[" + std::to_string(i) + "]");
      if (!list[i].is_object()) fail(doc.path, where + " is not an object");
      if (list[i].contains("name") && !list[i]["name"].is_string()) fail(doc.path, where + ".name is not a string");
    }
  }
  const auto integers = [&](const json& obj, std::initializer_list<const char*> keys, const std::string& where) {
    for (const char* key : keys)
      if (obj.contains(key) && !obj[key].is_number_integer()) fail(doc.path, where + "." + key + " is not an integer");
  };
  const json& views = array_or_empty(j, "bufferViews");
  for (size_t i = 0; i < views.size(); ++i) integers(views[i], {"byteStride", "target"}, "bufferViews[" + std::to_string(i) + "]");
  const json& accessors = array_or_empty(j, "accessors");
  for (size_t i = 0; i < accessors.size(); ++i) {
    const json& a = accessors[i];
    const std::string where = "accessors[" + std::to_string(i) + "]";
    integers(a, {"bufferView", "byteOffset", "componentType", "count"}, where);
    if (a.contains("type") && !a["type"].is_string()) fail(doc.path, where + ".type is not a string");
    if (a.contains("normalized") && !a["normalized"].is_boolean()) fail(doc.path, where + ".normalized is not a boolean");
    if (!a.contains("sparse")) continue;
    const json& sp = a["sparse"];
    if (!sp.is_object()) fail(doc.path, where + ".sparse is not an object");
    integers(sp, {"count"}, where + ".sparse");
    for (const char* part : {"indices", "values"}) {
      if (!sp.contains(part)) continue;
      const std::string pw = where + ".sparse." + part;
      if (!sp[part].is_object()) fail(doc.path, pw + " is not an object");
      integers(sp[part], {"bufferView", "byteOffset", "componentType"}, pw);
    }
  }
  const json& meshes = array_or_empty(j, "meshes");
  for (size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].contains("primitives")) continue;
    const json& prims = meshes[m]["primitives"];
    if (!prims.is_array()) fail(doc.path, "meshes[" + std::to_string(m) + "].primitives is not an array");
    for (size_t p = 0; p < prims.size(); ++p) {
      const std::string where = primitive_name(m, p);
      if (!prims[p].is_object()) fail(doc.path, where + " is not an object");
      for (const char* key : {"attributes", "extensions"})
        if (prims[p].contains(key) && !prims[p][key].is_object())
          fail(doc.path, where + "." + key + " is not an object");
      integers(prims[p], {"mode", "indices", "material"}, where);
      if (prims[p].contains("attributes"))
        for (const auto& [name, index] : prims[p]["attributes"].items())
          if (!index.is_number_integer()) fail(doc.path, where + ".attributes." + name + " is not an integer");
    }
  }
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == "glb" || ext == "gltf";
}

std::string primitive_name(size_t mesh, size_t primitive) {
  return "meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(primitive) + "]";
}

Document read_document(const std::string& path) {
  Document doc;
  doc.path = path;
  const std::vector<uint8_t> bytes = read_bytes(path);
  std::vector<uint8_t> bin;
  bool has_bin = false;
  std::string text;
  if (bytes.size() >= 4 && u32(bytes.data()) == kGlbMagic) {
    if (bytes.size() < 20) fail(path, "GLB shorter than its 12-byte header and one chunk header");
    if (u32(bytes.data() + 4) != 2) fail(path, "GLB version " + std::to_string(u32(bytes.data() + 4)) + " (only 2)");
    const uint64_t length = u32(bytes.data() + 8);
    if (length > bytes.size())
      fail(path, "GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(bytes.size()));
    size_t at = 12;
    int chunk = 0;
    while (at + 8 <= length) {
      const uint64_t clen = u32(bytes.data() + at), type = u32(bytes.data() + at + 4);
      if (clen > length - at - 8)
        fail(path, "GLB chunk " + std::to_string(chunk) + " (" + std::to_string(clen) + " bytes) reaches past the end");
      const uint8_t* data = bytes.data() + at + 8;
      if (chunk == 0) {
        if (type != kChunkJson) fail(path, "the first GLB chunk is not JSON");
        text.assign(reinterpret_cast<const char*>(data), clen);
      } else if (chunk == 1 && type == kChunkBin) {
        bin.assign(data, data + clen);
        has_bin = true;
      }
      at += 8 + clen;
      ++chunk;
    }
    if (chunk == 0) fail(path, "GLB without a JSON chunk");
  } else {
    text.assign(bytes.begin(), bytes.end());
  }
  try {
    doc.json = json::parse(text);
  } catch (const json::exception& e) {
    fail(path, std::string("the glTF JSON does not parse: ") + e.what());
  }
  if (!doc.json.is_object()) fail(path, "the glTF JSON is not an object");
  const auto asset = doc.json.find("asset");
  if (asset == doc.json.end() || !asset->is_object() || !asset->contains("version") ||
      !(*asset)["version"].is_string() || (*asset)["version"].get<std::string>().rfind("2.", 0) != 0)
    fail(path, "asset.version is missing or not 2.x (only glTF 2.0 is read)");
  for (const char* key : {"buffers", "bufferViews", "accessors", "meshes", "nodes", "images"})
    if (doc.json.contains(key) && !doc.json[key].is_array()) fail(path, std::string(key) + " is not an array");
  const json& buffers = array_or_empty(doc.json, "buffers");
  for (size_t i = 0; i < buffers.size(); ++i) {
    const std::string where = "buffers[" + std::to_string(i) + "]";
    if (!buffers[i].is_object()) fail(path, where + " is not an object");
    const uint64_t len = get_uint(buffers[i], "byteLength", UINT64_MAX, path, where);
    if (len == UINT64_MAX) fail(path, where + ".byteLength is missing");
    std::vector<uint8_t> data;
    const auto uri = buffers[i].find("uri");
    if (uri != buffers[i].end()) {
      if (!uri->is_string()) fail(path, where + ".uri is not a string");
      data = buffer_from_uri(path, i, uri->get<std::string>());
    } else if (i == 0 && has_bin) {
      data = bin;
    } else if (!buffers[i].contains("extensions")) {
      fail(path, where + " has no uri and is not the GLB's BIN chunk");
    }
    if (!data.empty() && data.size() < len)
      fail(path, where + ".byteLength is " + std::to_string(len) + " but its data has " + std::to_string(data.size()) +
                     " bytes");
    if (!data.empty()) data.resize(len);
    doc.buffers.push_back(std::move(data));
  }
  check_buffer_views(doc);
  check_member_types(doc);
  return doc;
}

int add_buffer_view(Document& doc, std::vector<uint8_t> bytes, int target, int byte_stride) {
  json& buffers = doc.json["buffers"];
  if (!buffers.is_array()) buffers = json::array();
  json view = {{"buffer", buffers.size()}, {"byteLength", bytes.size()}};
  if (target) view["target"] = target;
  if (byte_stride) view["byteStride"] = byte_stride;
  buffers.push_back({{"byteLength", bytes.size()}});
  doc.buffers.push_back(std::move(bytes));
  json& views = doc.json["bufferViews"];
  if (!views.is_array()) views = json::array();
  views.push_back(std::move(view));
  return static_cast<int>(views.size() - 1);
}

ByteSpan buffer_view_bytes(const Document& doc, int64_t index, const std::string& where) {
  const json& views = array_or_empty(doc.json, "bufferViews");
  if (index < 0 || static_cast<uint64_t>(index) >= views.size())
    fail(doc.path, where + ": " + std::to_string(index) + " is not a bufferView (the asset has " +
                       std::to_string(views.size()) + ")");
  const json& v = views[static_cast<size_t>(index)];
  const size_t b = v.at("buffer").get<size_t>();
  const uint64_t off = v.value("byteOffset", uint64_t{0}), len = v.at("byteLength").get<uint64_t>();
  const std::vector<uint8_t>& data = doc.buffers[b];
  if (off > data.size() || len > data.size() - off)
    fail(doc.path, where + ": bufferViews[" + std::to_string(index) + "] has no data (buffers[" + std::to_string(b) +
                       "] holds " + std::to_string(data.size()) + " bytes)");
  return {data.data() + off, static_cast<size_t>(len)};
}

void declare_extension(Document& doc, const std::string& name, bool required) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (!required && std::strcmp(key, "extensionsRequired") == 0) continue;
    json& list = doc.json[key];
    if (!list.is_array()) list = json::array();
    if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
  }
}

void remove_extension_declaration(Document& doc, const std::string& name) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    auto it = doc.json.find(key);
    if (it == doc.json.end() || !it->is_array()) continue;
    it->erase(std::remove(it->begin(), it->end(), name), it->end());
    if (it->empty()) doc.json.erase(key);
  }
}

void compact(Document& doc) {
  json& j = doc.json;
  // Accessors in use.
  const size_t num_accessors = array_or_empty(j, "accessors").size();
  std::vector<int64_t> acc_map(num_accessors, -1);
  auto use_acc = [&](const json& v) {
    if (v.is_number_integer() && v.get<int64_t>() >= 0 && static_cast<size_t>(v.get<int64_t>()) < num_accessors)
      acc_map[static_cast<size_t>(v.get<int64_t>())] = 0;
  };
  auto for_each_acc_ref = [&](auto&& f) {
    if (j.contains("meshes"))
      for (json& m : j["meshes"])
        if (m.contains("primitives"))
          for (json& p : m["primitives"]) {
            if (p.contains("attributes"))
              for (auto& [k, v] : p["attributes"].items()) f(v);
            if (p.contains("indices")) f(p["indices"]);
            if (p.contains("targets"))
              for (json& t : p["targets"])
                for (auto& [k, v] : t.items()) f(v);
          }
    if (j.contains("skins"))
      for (json& s : j["skins"])
        if (s.contains("inverseBindMatrices")) f(s["inverseBindMatrices"]);
    if (j.contains("animations"))
      for (json& a : j["animations"])
        if (a.contains("samplers"))
          for (json& s : a["samplers"]) {
            if (s.contains("input")) f(s["input"]);
            if (s.contains("output")) f(s["output"]);
          }
    if (j.contains("nodes"))
      for (json& n : j["nodes"]) {
        auto e = n.find("extensions");
        if (e != n.end() && e->contains("EXT_mesh_gpu_instancing") &&
            (*e)["EXT_mesh_gpu_instancing"].contains("attributes"))
          for (auto& [k, v] : (*e)["EXT_mesh_gpu_instancing"]["attributes"].items()) f(v);
      }
  };
  for_each_acc_ref([&](json& v) { use_acc(v); });
  json kept_accessors = json::array();
  for (size_t i = 0; i < num_accessors; ++i)
    if (acc_map[i] == 0) {
      acc_map[i] = static_cast<int64_t>(kept_accessors.size());
      kept_accessors.push_back(j["accessors"][i]);
    }
  for_each_acc_ref([&](json& v) {
    if (v.is_number_integer() && v.get<int64_t>() >= 0 && static_cast<size_t>(v.get<int64_t>()) < num_accessors)
      v = acc_map[static_cast<size_t>(v.get<int64_t>())];
  });
  if (num_accessors) j["accessors"] = kept_accessors;
  if (j.contains("accessors") && j["accessors"].empty()) j.erase("accessors");

  // BufferViews in use.
  const size_t num_views = array_or_empty(j, "bufferViews").size();
  std::vector<int64_t> view_map(num_views, -1);
  auto for_each_view_ref = [&](auto&& f) {
    if (j.contains("accessors"))
      for (json& a : j["accessors"]) {
        if (a.contains("bufferView")) f(a["bufferView"]);
        if (a.contains("sparse")) {
          json& s = a["sparse"];
          if (s.contains("indices") && s["indices"].contains("bufferView")) f(s["indices"]["bufferView"]);
          if (s.contains("values") && s["values"].contains("bufferView")) f(s["values"]["bufferView"]);
        }
      }
    if (j.contains("images"))
      for (json& im : j["images"])
        if (im.contains("bufferView")) f(im["bufferView"]);
    if (j.contains("meshes"))
      for (json& m : j["meshes"])
        if (m.contains("primitives"))
          for (json& p : m["primitives"]) {
            auto e = p.find("extensions");
            if (e == p.end() || !e->is_object()) continue;
            for (auto& [name, ext] : e->items())
              if (ext.is_object() && ext.contains("bufferView")) f(ext["bufferView"]);
          }
  };
  for_each_view_ref([&](json& v) {
    if (v.is_number_integer() && v.get<int64_t>() >= 0 && static_cast<size_t>(v.get<int64_t>()) < num_views)
      view_map[static_cast<size_t>(v.get<int64_t>())] = 0;
  });
  // Every kept view's bytes go into one new buffer.
  std::vector<uint8_t> merged;
  json kept_views = json::array();
  for (size_t i = 0; i < num_views; ++i) {
    if (view_map[i] != 0) continue;
    json v = j["bufferViews"][i];
    const ByteSpan bytes = buffer_view_bytes(doc, static_cast<int64_t>(i), "bufferViews[" + std::to_string(i) + "]");
    merged.resize((merged.size() + kAlignment - 1) / kAlignment * kAlignment, 0);
    v["buffer"] = 0;
    v["byteOffset"] = merged.size();
    if (merged.size() == 0) v.erase("byteOffset");
    merged.insert(merged.end(), bytes.data, bytes.data + bytes.size);
    view_map[i] = static_cast<int64_t>(kept_views.size());
    kept_views.push_back(std::move(v));
  }
  for_each_view_ref([&](json& v) {
    if (v.is_number_integer() && v.get<int64_t>() >= 0 && static_cast<size_t>(v.get<int64_t>()) < num_views)
      v = view_map[static_cast<size_t>(v.get<int64_t>())];
  });
  if (kept_views.empty()) {
    j.erase("bufferViews");
    j.erase("buffers");
    doc.buffers.clear();
    return;
  }
  j["bufferViews"] = kept_views;
  merged.resize((merged.size() + kAlignment - 1) / kAlignment * kAlignment, 0);
  json buffer = {{"byteLength", merged.size()}};
  j["buffers"] = json::array({buffer});
  doc.buffers.assign(1, std::move(merged));
}

void write_document(Document& doc, const std::string& path, bool repack) {
  if (repack) compact(doc);
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::vector<uint8_t> out;
  if (ext == "glb") {
    if (doc.json.contains("buffers")) doc.json["buffers"][0].erase("uri");
    std::string text = doc.json.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const std::vector<uint8_t> empty;
    const std::vector<uint8_t>& bin = doc.buffers.empty() ? empty : doc.buffers[0];
    const size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size());
    put_u32(out, kGlbMagic);
    put_u32(out, 2);
    put_u32(out, static_cast<uint32_t>(total));
    put_u32(out, static_cast<uint32_t>(text.size()));
    put_u32(out, kChunkJson);
    out.insert(out.end(), text.begin(), text.end());
    if (!bin.empty()) {
      put_u32(out, static_cast<uint32_t>(bin.size()));
      put_u32(out, kChunkBin);
      out.insert(out.end(), bin.begin(), bin.end());
    }
  } else {
    if (doc.json.contains("buffers"))
      for (size_t i = 0; i < doc.buffers.size(); ++i)
        if (!doc.buffers[i].empty())
          doc.json["buffers"][i]["uri"] = "data:application/octet-stream;base64," + base64_encode(doc.buffers[i]);
    const std::string text = doc.json.dump(1);
    out.assign(text.begin(), text.end());
    out.push_back('\n');
  }
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError("cannot write '" + path + "'");
  f.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  if (!f) throw IoError("cannot write '" + path + "'");
}

}  // namespace prm::gltf
