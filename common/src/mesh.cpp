#include "prm/mesh.h"

#include <stdexcept>
#include <utility>

namespace prm {
namespace {

const Property* find(const std::vector<Property>& props, const std::string& name) {
  for (const Property& p : props)
    if (p.name == name) return &p;
  return nullptr;
}

Property& set(std::vector<Property>& props, size_t expected, const std::string& name, ScalarType type,
              std::vector<double> values) {
  if (values.size() != expected)
    throw std::invalid_argument("property '" + name + "' has " + std::to_string(values.size()) +
                                " values, expected " + std::to_string(expected));
  for (Property& p : props)
    if (p.name == name) {
      p.type = type;
      p.values = std::move(values);
      return p;
    }
  props.push_back(Property{name, type, std::move(values)});
  return props.back();
}

}  // namespace

const Property* Mesh::find_vertex_property(const std::string& name) const { return find(vertex_properties, name); }
const Property* Mesh::find_face_property(const std::string& name) const { return find(face_properties, name); }

Property& Mesh::set_vertex_property(const std::string& name, ScalarType type, std::vector<double> values) {
  return set(vertex_properties, positions.size(), name, type, std::move(values));
}
Property& Mesh::set_face_property(const std::string& name, ScalarType type, std::vector<double> values) {
  return set(face_properties, triangles.size(), name, type, std::move(values));
}

std::vector<std::vector<uint32_t>> faces_around_vertices(const Mesh& m) {
  std::vector<std::vector<uint32_t>> out(m.positions.size());
  for (uint32_t f = 0; f < m.triangles.size(); ++f)
    for (uint32_t v : m.triangles[f]) out[v].push_back(f);
  return out;
}

}  // namespace prm
