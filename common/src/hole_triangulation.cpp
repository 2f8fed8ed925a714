#include "hole_triangulation.h"

#include <cmath>
#include <limits>

#include "prm/vec3.h"

namespace prm {

bool triangulate_hole(const Mesh& m, const std::vector<uint32_t>& loop, const std::vector<Vec3>& rim_normal,
                      const std::unordered_set<uint64_t>& edges, double min_area2, std::vector<Tri>& out) {
  const size_t n = loop.size();
  if (n < 3 || rim_normal.size() != n) return false;
  // For the chain loop[a..c] closed by the chord (a, c): the best triangulation's smallest cosine between adjacent
  // normals (larger is better; -inf: none), its area, its top triangle's middle corner and unit normal. A chain of
  // one edge is the rim face itself.
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  constexpr double kFlat = -2;  // a triangle without area: worse than any fold, kept only to say "no triangulation"
  std::vector<double> cosine(n * n, kNone), area(n * n, 0);
  std::vector<uint32_t> middle(n * n, 0);
  std::vector<Vec3> normal(n * n, Vec3{0, 0, 0});
  const auto at = [n](size_t a, size_t c) { return a * n + c; };
  for (size_t a = 0; a + 1 < n; ++a) {
    cosine[at(a, a + 1)] = 1;
    normal[at(a, a + 1)] = rim_normal[a];
  }
  for (size_t gap = 2; gap < n; ++gap) {
    for (size_t a = 0; a + gap < n; ++a) {
      const size_t c = a + gap;
      if (gap < n - 1 && edges.count(edge_key(loop[a], loop[c]))) continue;  // the chord is an edge already
      double best = kNone, best_area = 0;
      size_t best_m = 0;
      Vec3 best_normal{0, 0, 0};
      for (size_t k = a + 1; k < c; ++k) {
        const double left = cosine[at(a, k)], right = cosine[at(k, c)];
        if (left == kNone || right == kNone) continue;
        // The triangle (loop[c], loop[k], loop[a]): it traverses the chain's edges backwards, as the mesh's faces
        // across them require.
        const Vec3 cr = triangle_normal_area2(m.positions[loop[c]], m.positions[loop[k]], m.positions[loop[a]]);
        const double len = norm(cr);
        double worst = std::min(left, right);
        Vec3 u{0, 0, 0};
        if (len > min_area2) {
          u = cr * (1.0 / len);
          worst = std::min(worst, std::min(dot(u, normal[at(a, k)]), dot(u, normal[at(k, c)])));
          if (gap == n - 1) worst = std::min(worst, dot(u, rim_normal[n - 1]));  // across the closing rim edge
        } else {
          worst = kFlat;
        }
        const double total = area[at(a, k)] + area[at(k, c)] + 0.5 * len;
        if (worst > best || (worst == best && total < best_area)) {
          best = worst;
          best_area = total;
          best_m = k;
          best_normal = u;
        }
      }
      cosine[at(a, c)] = best;
      area[at(a, c)] = best_area;
      middle[at(a, c)] = static_cast<uint32_t>(best_m);
      normal[at(a, c)] = best_normal;
    }
  }
  if (!(cosine[at(0, n - 1)] >= -1)) return false;  // none, or one with a triangle without area
  std::vector<std::pair<size_t, size_t>> todo{{0, n - 1}};
  while (!todo.empty()) {
    const auto [a, c] = todo.back();
    todo.pop_back();
    if (c - a < 2) continue;
    const size_t k = middle[at(a, c)];
    out.push_back({loop[c], loop[k], loop[a]});
    todo.push_back({a, k});
    todo.push_back({k, c});
  }
  return true;
}

}  // namespace prm
