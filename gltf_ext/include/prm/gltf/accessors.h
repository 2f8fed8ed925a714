// Reading and writing accessors (glTF 2.0 §3.6): any component type, normalized integers (KHR_mesh_quantization),
// byteStride, sparse substitution; new accessors with their own bufferView and exact min/max.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prm/gltf/document.h"

namespace prm::gltf {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kModeTriangles = 4;

int component_size(int component_type);  // 0 for an unknown type
int component_count(const std::string& type);  // SCALAR 1 ... MAT4 16; 0 for an unknown type

struct AccessorData {
  size_t count = 0;
  int components = 0;
  std::vector<double> values;  // count * components, normalized integers mapped to [-1, 1] / [0, 1]
};

// The values of accessor `index`; InputError naming `where` and the field on anything malformed (type, count
// past the end of the bufferView, sparse indices out of range). An accessor without a bufferView reads as zeros.
AccessorData read_accessor(const Document& doc, int64_t index, const std::string& where);

// Appends an accessor of `type` with its own bufferView holding values as `component_type` (float or an unsigned
// integer type); min and max are set when `with_min_max`. Returns its index.
int add_accessor(Document& doc, const std::vector<double>& values, int component_type, const std::string& type,
                 int target, bool with_min_max);
// Appends an accessor without data (no bufferView): count, type and, for POSITION, min/max as given.
int add_empty_accessor(Document& doc, size_t count, int component_type, const std::string& type,
                       const std::vector<double>* min_max_values = nullptr);

// Component-wise minimum and maximum of values (count * components) rounded as the component type stores them.
void set_min_max(nlohmann::json& accessor, const std::vector<double>& values, int components, int component_type);

}  // namespace prm::gltf
