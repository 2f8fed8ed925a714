// The triangle mesh shared by the tools, the remesher and the benches.
// (The codec has its own, standard-library-only types: codec/include/prm/codec.h.)
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace prm {

using Vec3 = std::array<double, 3>;
using Tri = std::array<uint32_t, 3>;

// Scalar types of named properties, as PLY knows them.
enum class ScalarType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// A named per-vertex or per-face property (relief labels, lattice coordinates, colours...).
// Values are held as doubles, which represent every listed type exactly.
struct Property {
  std::string name;
  ScalarType type = ScalarType::Int32;
  std::vector<double> values;
};

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Tri> triangles;
  std::vector<Property> vertex_properties;  // each has positions.size() values
  std::vector<Property> face_properties;    // each has triangles.size() values
  std::vector<std::string> comments;        // free text kept by formats that have comments (PLY, OBJ, OFF)

  size_t num_vertices() const { return positions.size(); }
  size_t num_faces() const { return triangles.size(); }

  const Property* find_vertex_property(const std::string& name) const;
  const Property* find_face_property(const std::string& name) const;
  // Adds (or replaces) a property; values must have the right size.
  Property& set_vertex_property(const std::string& name, ScalarType type, std::vector<double> values);
  Property& set_face_property(const std::string& name, ScalarType type, std::vector<double> values);
};

// The triangles around each vertex: out[v] lists, in increasing order, the triangles with a corner at v (a triangle
// that uses v at two corners is listed twice). Every corner must be a vertex of m.
std::vector<std::vector<uint32_t>> faces_around_vertices(const Mesh& m);

}  // namespace prm
