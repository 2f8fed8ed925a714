// Accessors: glTF 2.0 §3.6 (data alignment, normalized integers §3.11, sparse accessors §3.6.2.3).
#include "prm/gltf/accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "prm/error.h"

namespace prm::gltf {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const Document& doc, const std::string& what) { throw InputError(doc.path + ": " + what); }

double read_component(const uint8_t* p, int type, bool normalized) {
  switch (type) {
    case kByte: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte:
      return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case kUnsignedInt: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case kFloat: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0;
}

void write_component(uint8_t* p, int type, double v) {
  switch (type) {
    case kUnsignedByte:
      p[0] = static_cast<uint8_t>(v);
      return;
    case kUnsignedShort: {
      const uint16_t x = static_cast<uint16_t>(v);
      std::memcpy(p, &x, 2);
      return;
    }
    case kUnsignedInt: {
      const uint32_t x = static_cast<uint32_t>(v);
      std::memcpy(p, &x, 4);
      return;
    }
    case kFloat: {
      const float x = static_cast<float>(v);
      std::memcpy(p, &x, 4);
      return;
    }
  }
}

int64_t get_index(const json& obj, const char* key, const Document& doc, const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) return -1;
  if (!it->is_number_integer() || it->get<int64_t>() < 0) fail(doc, where + "." + key + " must be an index (>= 0)");
  return it->get<int64_t>();
}

// Reads `count` elements of `elem` bytes at `stride` from bufferView `view` at `offset`.
const uint8_t* checked_elements(const Document& doc, int64_t view, uint64_t offset, uint64_t count, uint64_t elem,
                                uint64_t stride, const std::string& where) {
  const ByteSpan span = buffer_view_bytes(doc, view, where + ".bufferView");
  if (count == 0) return span.data;
  if (offset > span.size || span.size - offset < elem || (count - 1) > (span.size - offset - elem) / stride)
    fail(doc, where + ": " + std::to_string(count) + " elements of " + std::to_string(elem) + " bytes from byte " +
                  std::to_string(offset) + " reach past the end of bufferViews[" + std::to_string(view) + "] (" +
                  std::to_string(span.size) + " bytes)");
  return span.data + offset;
}

}  // namespace

int component_size(int t) {
  switch (t) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
  }
  return 0;
}

int component_count(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

AccessorData read_accessor(const Document& doc, int64_t index, const std::string& where) {
  const json& accessors = doc.json.contains("accessors") ? doc.json["accessors"] : json::array();
  if (index < 0 || static_cast<uint64_t>(index) >= accessors.size())
    fail(doc, where + ": accessor " + std::to_string(index) + " does not exist (the asset has " +
                  std::to_string(accessors.size()) + ")");
  const std::string aw = "accessors[" + std::to_string(index) + "]";
  const json& a = accessors[static_cast<size_t>(index)];
  if (!a.is_object()) fail(doc, aw + " is not an object");
  const int ctype = a.value("componentType", 0);
  const int csize = component_size(ctype);
  if (!csize) fail(doc, aw + ".componentType " + std::to_string(ctype) + " is not a glTF component type");
  const int ncomp = component_count(a.value("type", std::string()));
  if (!ncomp) fail(doc, aw + ".type is missing or unknown");
  if (!a.contains("count") || !a["count"].is_number_integer() || a["count"].get<int64_t>() <= 0)
    fail(doc, aw + ".count must be a positive integer");
  const bool normalized = a.value("normalized", false);
  AccessorData out;
  out.count = a["count"].get<size_t>();
  out.components = ncomp;
  const uint64_t elem = static_cast<uint64_t>(csize) * static_cast<uint64_t>(ncomp);
  const int64_t view = get_index(a, "bufferView", doc, aw);
  if (view < 0 && out.count > (uint64_t{1} << 28)) fail(doc, aw + ".count is implausibly large without data");
  if (view >= 0) {
    buffer_view_bytes(doc, view, aw + ".bufferView");  // checks the index
    const json& v = doc.json["bufferViews"][static_cast<size_t>(view)];
    const uint64_t stride = v.value("byteStride", uint64_t{0}) ? v["byteStride"].get<uint64_t>() : elem;
    const uint64_t offset = a.value("byteOffset", uint64_t{0});
    const uint8_t* p = checked_elements(doc, view, offset, out.count, elem, stride, aw);
    out.values.resize(out.count * static_cast<size_t>(ncomp));
    for (size_t i = 0; i < out.count; ++i)
      for (int c = 0; c < ncomp; ++c)
        out.values[i * static_cast<size_t>(ncomp) + static_cast<size_t>(c)] =
            read_component(p + i * stride + static_cast<size_t>(c * csize), ctype, normalized);
  } else {
    out.values.assign(out.count * static_cast<size_t>(ncomp), 0.0);
  }
  if (a.contains("sparse")) {
    const json& s = a["sparse"];
    const std::string sw = aw + ".sparse";
    const uint64_t n = s.value("count", uint64_t{0});
    if (n == 0 || n > out.count) fail(doc, sw + ".count must be in 1.." + std::to_string(out.count));
    if (!s.contains("indices") || !s.contains("values")) fail(doc, sw + " needs indices and values");
    const int itype = s["indices"].value("componentType", 0);
    if (itype != kUnsignedByte && itype != kUnsignedShort && itype != kUnsignedInt)
      fail(doc, sw + ".indices.componentType must be an unsigned integer type");
    const uint8_t* ip = checked_elements(doc, get_index(s["indices"], "bufferView", doc, sw + ".indices"),
                                         s["indices"].value("byteOffset", uint64_t{0}), n,
                                         static_cast<uint64_t>(component_size(itype)),
                                         static_cast<uint64_t>(component_size(itype)), sw + ".indices");
    const uint8_t* vp = checked_elements(doc, get_index(s["values"], "bufferView", doc, sw + ".values"),
                                         s["values"].value("byteOffset", uint64_t{0}), n, elem, elem, sw + ".values");
    for (uint64_t k = 0; k < n; ++k) {
      const double t = read_component(ip + k * static_cast<uint64_t>(component_size(itype)), itype, false);
      if (t >= static_cast<double>(out.count)) fail(doc, sw + ".indices: " + std::to_string(t) + " is out of range");
      for (int c = 0; c < ncomp; ++c)
        out.values[static_cast<size_t>(t) * static_cast<size_t>(ncomp) + static_cast<size_t>(c)] =
            read_component(vp + k * elem + static_cast<uint64_t>(c * csize), ctype, normalized);
    }
  }
  for (double v : out.values)
    if (!std::isfinite(v)) fail(doc, aw + " holds a NaN or infinite value");
  return out;
}

void set_min_max(json& accessor, const std::vector<double>& values, int components, int component_type) {
  std::vector<double> lo(static_cast<size_t>(components), std::numeric_limits<double>::infinity()),
      hi(static_cast<size_t>(components), -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < values.size(); ++i) {
    const size_t c = i % static_cast<size_t>(components);
    const double v = component_type == kFloat ? static_cast<double>(static_cast<float>(values[i])) : values[i];
    lo[c] = std::min(lo[c], v);
    hi[c] = std::max(hi[c], v);
  }
  accessor["min"] = lo;
  accessor["max"] = hi;
}

int add_accessor(Document& doc, const std::vector<double>& values, int component_type, const std::string& type,
                 int target, bool with_min_max) {
  const int ncomp = component_count(type);
  const size_t csize = static_cast<size_t>(component_size(component_type));
  const size_t count = values.size() / static_cast<size_t>(ncomp);
  // Vertex attributes' elements are 4-byte aligned (glTF 2.0 §3.6.2.4): pad small types to a stride of 4.
  size_t elem = csize * static_cast<size_t>(ncomp);
  size_t stride = elem;
  if (target == kArrayBuffer && elem % 4) stride = (elem + 3) / 4 * 4;
  std::vector<uint8_t> bytes(count * stride, 0);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < ncomp; ++c)
      write_component(bytes.data() + i * stride + static_cast<size_t>(c) * csize, component_type,
                      values[i * static_cast<size_t>(ncomp) + static_cast<size_t>(c)]);
  const int view = add_buffer_view(doc, std::move(bytes), target, stride != elem ? static_cast<int>(stride) : 0);
  json a = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (with_min_max) set_min_max(a, values, ncomp, component_type);
  json& accessors = doc.json["accessors"];
  if (!accessors.is_array()) accessors = json::array();
  accessors.push_back(std::move(a));
  return static_cast<int>(accessors.size() - 1);
}

int add_empty_accessor(Document& doc, size_t count, int component_type, const std::string& type,
                       const std::vector<double>* min_max_values) {
  json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
  if (min_max_values) set_min_max(a, *min_max_values, component_count(type), component_type);
  json& accessors = doc.json["accessors"];
  if (!accessors.is_array()) accessors = json::array();
  accessors.push_back(std::move(a));
  return static_cast<int>(accessors.size() - 1);
}

}  // namespace prm::gltf
