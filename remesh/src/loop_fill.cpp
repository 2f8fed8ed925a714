#include "loop_fill.h"

#include <algorithm>
#include <unordered_map>

namespace prm::remesh {
namespace {

uint64_t edge_key(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(std::min(a, b)), hi = static_cast<uint32_t>(std::max(a, b));
  return (static_cast<uint64_t>(lo) << 32) | hi;
}

struct SeamPoint {
  int32_t relief;
  double t;  // from the lower refined vertex
  int32_t vertex;
  uint8_t family;
  int64_t value;
};

}  // namespace

MergedMesh merge_reliefs(const ReliefMeshView& view, const std::vector<ResampledRelief>& reliefs) {
  MergedMesh out;
  const Mesh& mesh = *view.mesh;
  std::vector<int32_t> refined_to_merged(mesh.positions.size(), -1);
  std::unordered_map<uint64_t, std::vector<SeamPoint>> seams;

  for (size_t r = 0; r < reliefs.size(); ++r) {
    const ResampledRelief& rr = reliefs[r];
    std::vector<int32_t> id(rr.vertices.size());
    for (size_t v = 0; v < rr.vertices.size(); ++v) {
      const SliceVertex& sv = rr.vertices[v];
      if (sv.kind == SliceKind::Corner && sv.boundary) {
        int32_t& m = refined_to_merged[static_cast<size_t>(sv.refined_vertex)];
        if (m < 0) {
          m = static_cast<int32_t>(out.vertices.size());
          MergedVertex mv;
          mv.position = sv.position;
          mv.relief = -1;
          mv.source_face = sv.source_face;
          out.vertices.push_back(mv);
        }
        id[v] = m;
        continue;
      }
      id[v] = static_cast<int32_t>(out.vertices.size());
      MergedVertex mv;
      mv.position = sv.position;
      mv.relief = static_cast<int32_t>(r);
      mv.lattice = sv.kind == SliceKind::Lattice;
      mv.i = sv.i;
      mv.j = sv.j;
      mv.source_face = sv.source_face;
      out.vertices.push_back(mv);
      if (sv.kind == SliceKind::Crossing && sv.boundary)
        seams[edge_key(sv.edge_a, sv.edge_b)].push_back({static_cast<int32_t>(r), sv.t, id[v], sv.family, sv.value});
    }
    for (const auto& f : rr.faces) {
      out.faces.push_back({id[static_cast<size_t>(f[0])], id[static_cast<size_t>(f[1])], id[static_cast<size_t>(f[2])]});
      out.face_relief.push_back(static_cast<int32_t>(r));
    }
  }

  std::vector<std::pair<double, int32_t>> xs, ys;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const int32_t r1 = view.relief(static_cast<int32_t>(f));
    for (size_t k = 0; k < 3; ++k) {
      const int32_t g = view.opposite[f][k];
      if (g < 0) continue;  // an open edge: no loop (the remesher works on closed meshes)
      const int32_t r2 = view.relief(g);
      if (r2 == r1 || g < static_cast<int32_t>(f)) continue;
      const int32_t a = static_cast<int32_t>(mesh.triangles[f][k]);
      const int32_t b = static_cast<int32_t>(mesh.triangles[f][(k + 1) % 3]);
      const bool forward = a < b;  // seam parameters run from the lower vertex
      xs.clear();
      ys.clear();
      const auto it = seams.find(edge_key(a, b));
      if (it != seams.end())
        for (const SeamPoint& sp : it->second) {
          const double t = forward ? sp.t : 1.0 - sp.t;
          if (sp.relief == r1) xs.push_back({t, sp.vertex});
          if (sp.relief == r2) ys.push_back({t, sp.vertex});
        }
      std::sort(xs.begin(), xs.end());
      std::sort(ys.begin(), ys.end());
      // Two reliefs of one axis pair and one grid size share the grid planes: their vertices on ab coincide where
      // the same plane cuts it. They stay distinct here (a zero-length rung of the loop); optimize_seams() merges
      // each such pair when the link condition allows, which breaks the loop there. Reliefs of different grid sizes
      // share no plane (spec §8.4.2): their seam is joined like one between pairs.
      const bool shared_lattice = view.slot(r1) == view.slot(r2);
      if (shared_lattice && it != seams.end())
        for (const SeamPoint& p : it->second)
          for (const SeamPoint& q : it->second)
            if (p.relief == r1 && q.relief == r2 && p.family == q.family && p.value == q.value)
              out.coincident.push_back({p.vertex, q.vertex});
      const int32_t pa = refined_to_merged[static_cast<size_t>(a)], pb = refined_to_merged[static_cast<size_t>(b)];
      std::vector<int32_t> X{pa}, Y{pa};
      std::vector<double> tx{0.0}, ty{0.0};
      for (const auto& p : xs) {
        X.push_back(p.second);
        tx.push_back(p.first);
      }
      for (const auto& p : ys) {
        Y.push_back(p.second);
        ty.push_back(p.first);
      }
      X.push_back(pb);
      tx.push_back(1.0);
      Y.push_back(pb);
      ty.push_back(1.0);
      // Zipper between the two sides, in the order of the parameter along a -> b. Relief r1's boundary runs
      // a -> b, relief r2's runs b -> a; the fill triangles use the reversed half-edges.
      size_t i = 0, j = 0;
      while (i + 1 < X.size() || j + 1 < Y.size()) {
        const bool advance_x = j + 1 == Y.size() || (i + 1 < X.size() && tx[i + 1] <= ty[j + 1]);
        std::array<int32_t, 3> t;
        if (advance_x) {
          t = {X[i + 1], X[i], Y[j]};
          ++i;
        } else {
          t = {Y[j], Y[j + 1], X[i]};
          ++j;
        }
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
          out.faces.push_back(t);
          out.face_relief.push_back(-1);
          ++out.fill_triangles;
        }
      }
    }
  }
  return out;
}

}  // namespace prm::remesh
