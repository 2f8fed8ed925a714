// The input's mesh boundary (its edges with one face) as a set of segments, for the distance from a point near it
// to it (issue 22: an open surface's boundary vertices are rounded to the quantization point nearest the input's
// boundary, quantized_separation.cpp; pack's general candidate measures its decoded boundary with it, pack_general.h),
// and the boundary vertices of a mesh.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "prm/mesh.h"
#include "prm/vec3.h"

namespace prm::remesh {

// 1 for each vertex of `m` on an edge that only one face has (either orientation), 0 otherwise.
std::vector<uint8_t> boundary_vertex_flags(const Mesh& m);

class BoundaryPolyline {
 public:
  // The boundary edges of `m`, bucketed in cubes of side `reach`: distance() finds every segment within `reach` of
  // the point (and maybe farther ones).
  BoundaryPolyline(const Mesh& m, double reach);
  bool empty() const { return segments_.empty(); }
  // The distance from p to the nearest boundary segment if one is within `reach` of p (else that of a farther one,
  // or HUGE_VAL).
  double distance(const Vec3& p) const;

 private:
  struct Key {
    int64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = 1469598103934665603ull;
      for (int64_t c : {k.x, k.y, k.z}) h = (h ^ static_cast<uint64_t>(c)) * 1099511628211ull;
      return static_cast<size_t>(h ^ (h >> 29));
    }
  };
  Key key_of(const Vec3& p) const;
  double cell_;
  std::vector<std::array<Vec3, 2>> segments_;
  std::unordered_map<Key, std::vector<uint32_t>, KeyHash> cells_;
};

}  // namespace prm::remesh
