// §6.2 Edgebreaker (Rossignac's corner-table CLERS traversal) over the closed mesh, and §6.3 the connectivity
// section it produces. The decoder side is clers_decode.cpp.
#include <algorithm>
#include <memory>
#include <string>

#include "clers.h"
#include "corner_table.h"
#include "range_encoder.h"
#include "status.h"
#include "stream_writer.h"

namespace prm::codec {
namespace {

constexpr uint32_t kNone = UINT32_MAX;

Status input_error(Error e, std::string message) { return make_status(e, "6.1", 0, std::move(message)); }

// §6.1 Every vertex must have one fan: walk it from any corner and compare with the number of its corners.
Status check_vertex_fans(const std::vector<uint32_t>& cv, const std::vector<int32_t>& opp, uint32_t nv,
                         const std::vector<uint32_t>& input_id) {
  const size_t nc = cv.size();
  std::vector<uint32_t> valence(nv, 0);
  std::vector<uint32_t> first(nv, kNone);
  for (size_t c = 0; c < nc; ++c) {
    ++valence[cv[c]];
    first[cv[c]] = static_cast<uint32_t>(c);
  }
  for (uint32_t v = 0; v < nv; ++v) {
    uint32_t c = first[v];
    // Rotate backwards (across incoming edges) to an end of the fan, or all the way round.
    uint32_t n = 0;
    for (;;) {
      const int32_t d = opp[corner_next(c)];
      if (d < 0) break;
      c = corner_next(static_cast<uint32_t>(d));
      if (c == first[v] || ++n > valence[v]) break;
    }
    const uint32_t start = c;
    uint32_t count = 0;
    for (;;) {
      ++count;
      const int32_t d = opp[corner_prev(c)];
      if (d < 0) break;
      c = corner_prev(static_cast<uint32_t>(d));
      if (c == start || count > valence[v]) break;
    }
    if (count != valence[v])
      return input_error(Error::non_manifold_vertex,
                         "vertex " + std::to_string(input_id[v]) + " has " + std::to_string(valence[v]) +
                             " triangles in more than one fan (a pinched, non-manifold vertex)");
  }
  return ok_status();
}

}  // namespace

Status plan_connectivity(const uint32_t* triangles, size_t num_triangles, size_t num_vertices,
                         ConnectivityPlan& plan) {
  plan = ConnectivityPlan{};
  if (num_triangles > (uint64_t{1} << 28) || num_vertices > (uint64_t{1} << 28))
    return input_error(Error::invalid_argument, "mesh too large for the format (2^28 triangles or vertices)");
  // Indices, degenerate triangles, referenced vertices.
  std::vector<uint32_t> compact(num_vertices, kNone);
  std::vector<uint32_t> input_id;
  std::vector<uint32_t> cv(3 * num_triangles);
  for (size_t t = 0; t < num_triangles; ++t) {
    const uint32_t* f = triangles + 3 * t;
    for (int k = 0; k < 3; ++k)
      if (f[k] >= num_vertices)
        return input_error(Error::invalid_argument, "triangle " + std::to_string(t) + " uses vertex " +
                                                        std::to_string(f[k]) + " of " + std::to_string(num_vertices));
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2])
      return input_error(Error::degenerate_triangle, "triangle " + std::to_string(t) + " uses a vertex twice");
    for (int k = 0; k < 3; ++k) {
      if (compact[f[k]] == kNone) {
        compact[f[k]] = static_cast<uint32_t>(input_id.size());
        input_id.push_back(f[k]);
      }
      cv[3 * t + k] = compact[f[k]];
    }
  }
  plan.unreferenced = static_cast<uint32_t>(num_vertices - input_id.size());
  uint32_t nv = static_cast<uint32_t>(input_id.size());

  std::vector<int32_t> opp;
  uint32_t bad = 0;
  switch (build_opposites(cv, nv, opp, &bad)) {
    case BuildResult::ok:
      break;
    case BuildResult::non_manifold_edge:
      return input_error(Error::non_manifold_edge,
                         "triangle " + std::to_string(bad) + " has an edge shared by three or more triangles");
    case BuildResult::inconsistent_orientation:
      return input_error(Error::inconsistent_orientation,
                         "triangle " + std::to_string(bad) +
                             " traverses an edge in the same direction as its neighbour (inconsistent orientation)");
  }
  PRM_TRY(check_vertex_fans(cv, opp, nv, input_id));

  // §6.7 Close every boundary loop with a dummy vertex fanned to it.
  const uint32_t real_vertices = nv;
  {
    std::vector<uint32_t> out_edge(nv, kNone);  // boundary corner whose open edge leaves the vertex
    size_t open = 0;
    for (size_t c = 0; c < cv.size(); ++c)
      if (opp[c] < 0) {
        out_edge[cv[corner_next(static_cast<uint32_t>(c))]] = static_cast<uint32_t>(c);
        ++open;
      }
    if (open > 0) {
      std::vector<uint8_t> done(cv.size(), 0);
      for (size_t c0 = 0; c0 < opp.size(); ++c0) {
        if (opp[c0] >= 0 || done[c0]) continue;
        const uint32_t dummy = nv++;
        input_id.push_back(kNone);
        uint32_t c = static_cast<uint32_t>(c0);
        while (!done[c]) {
          done[c] = 1;
          const uint32_t u = cv[corner_next(c)], w = cv[corner_prev(c)];  // open edge u -> w
          cv.push_back(w);
          cv.push_back(u);
          cv.push_back(dummy);
          c = out_edge[w];
        }
      }
      if (build_opposites(cv, nv, opp, &bad) != BuildResult::ok)
        return make_status(Error::internal, "6.7", 0, "closing the holes made a non-manifold mesh");
    }
  }
  const uint32_t nt = static_cast<uint32_t>(cv.size() / 3);

  // §6.2 Edgebreaker, component by component, each from its lowest-numbered input triangle.
  std::vector<uint8_t> visited_t(nt, 0), visited_v(nv, 0);
  std::vector<uint32_t> id(nv, kNone), forward_of(nt, kNone);
  auto& P = plan;
  P.symbols.reserve(nt);
  P.triangle_input.reserve(nt);
  P.triangle_rotation.reserve(nt);
  std::vector<uint32_t> fwd_cv;
  fwd_cv.reserve(cv.size());
  uint32_t next_id = 0;
  struct Gate {
    uint32_t corner;  // the tip corner of the triangle behind the gate
    uint32_t pusher;  // forward index of the S that pushed it
  };
  std::vector<Gate> stack;
  auto visit = [&](uint32_t t, uint32_t corner0, uint8_t symbol) {
    visited_t[t] = 1;
    forward_of[t] = static_cast<uint32_t>(P.symbols.size());
    P.symbols.push_back(symbol);
    P.triangle_input.push_back(t < num_triangles ? t : kNone);
    P.triangle_rotation.push_back(static_cast<uint8_t>(corner0 % 3));
    fwd_cv.push_back(cv[corner0]);
    fwd_cv.push_back(cv[corner_next(corner0)]);
    fwd_cv.push_back(cv[corner_prev(corner0)]);
  };
  auto discover = [&](uint32_t v) {
    visited_v[v] = 1;
    id[v] = next_id++;
  };
  for (uint32_t f = 0; f < num_triangles; ++f) {
    if (visited_t[f]) continue;
    const uint32_t first = static_cast<uint32_t>(P.symbols.size());
    visit(f, 3 * f, 0xFF);  // §6.2 the first triangle: gate = its edge corner 0 -> corner 1
    discover(cv[3 * f]);
    discover(cv[3 * f + 1]);
    discover(cv[3 * f + 2]);
    stack.push_back({static_cast<uint32_t>(opp[3 * f + 2]), kNone});
    while (!stack.empty()) {
      const Gate g = stack.back();
      stack.pop_back();
      uint32_t c = g.corner;
      if (visited_t[c / 3]) {
        // §6.4.6 The left branch of an S was consumed by its right branch: a handle.
        const uint32_t t = c / 3;
        const uint8_t canon = static_cast<uint8_t>((c % 3 + 3 - P.triangle_rotation[forward_of[t]]) % 3);
        P.handles.push_back({g.pusher, forward_of[t], canon});
        continue;
      }
      for (;;) {
        const uint32_t t = c / 3;
        const uint32_t v = cv[c];
        const uint32_t right = static_cast<uint32_t>(opp[corner_next(c)]);
        const uint32_t left = static_cast<uint32_t>(opp[corner_prev(c)]);
        if (!visited_v[v]) {
          visit(t, corner_next(c), kC);
          discover(v);
          c = right;
          continue;
        }
        const bool rv = visited_t[right / 3] != 0, lv = visited_t[left / 3] != 0;
        if (rv && lv) {
          visit(t, corner_next(c), kE);
          break;
        }
        if (rv) {
          visit(t, corner_next(c), kR);
          c = left;
        } else if (lv) {
          visit(t, corner_next(c), kL);
          c = right;
        } else {
          visit(t, corner_next(c), kS);
          stack.push_back({left, forward_of[t]});
          c = right;
        }
      }
    }
    P.component_sizes.push_back(static_cast<uint32_t>(P.symbols.size()) - first);
  }
  if (P.symbols.size() != nt || next_id != nv)
    return make_status(Error::internal, "6.2", 0, "Edgebreaker did not reach every triangle and vertex");
  std::sort(P.handles.begin(), P.handles.end(),
            [](const HandleEvent& a, const HandleEvent& b) { return a.triangle < b.triangle; });

  // Canonical ids (§6.6): forward order of discovery.
  P.vertex_input.assign(nv, kNone);
  P.mesh.num_vertices = nv;
  P.mesh.is_dummy.assign(nv, 0);
  for (uint32_t v = 0; v < nv; ++v) {
    P.vertex_input[id[v]] = input_id[v];
    if (v >= real_vertices) {
      P.mesh.is_dummy[id[v]] = 1;
      P.dummies.push_back(id[v]);
    }
  }
  std::sort(P.dummies.begin(), P.dummies.end());
  P.mesh.corner_vertex.resize(fwd_cv.size());
  for (size_t c = 0; c < fwd_cv.size(); ++c) P.mesh.corner_vertex[c] = id[fwd_cv[c]];
  // Opposites in canonical corners.
  auto canonical = [&](uint32_t c) {
    const uint32_t t = c / 3;
    return 3 * forward_of[t] + (c % 3 + 3 - P.triangle_rotation[forward_of[t]]) % 3;
  };
  P.mesh.opp.assign(opp.size(), -1);
  for (uint32_t c = 0; c < opp.size(); ++c)
    P.mesh.opp[canonical(c)] = static_cast<int32_t>(canonical(static_cast<uint32_t>(opp[c])));
  return ok_status();
}

// §6.3 The connectivity section: component sizes, handles, dummies (varints), then the range-coded symbols in
// decoding order (reverse forward order).
Status write_connectivity(const ConnectivityPlan& plan, bool seam_context, std::vector<uint8_t>& payload) {
  StreamWriter w;
  w.varint(static_cast<uint32_t>(plan.component_sizes.size()));
  for (uint32_t s : plan.component_sizes) w.varint(s);
  w.varint(static_cast<uint32_t>(plan.handles.size()));
  uint32_t prev = 0;
  for (const HandleEvent& h : plan.handles) {
    w.varint(h.triangle - prev);
    w.varint((h.partner - h.triangle - 1) << 2 | h.partner_corner);
    prev = h.triangle;
  }
  w.varint(static_cast<uint32_t>(plan.dummies.size()));
  prev = 0;
  for (uint32_t d : plan.dummies) {
    w.varint(d - prev);
    prev = d;
  }

  const uint32_t nt = plan.mesh.num_triangles();
  SpiraleReversi sr;
  sr.init(nt, plan.mesh.num_vertices, seam_context);
  sr.reserve(nt);  // the encoder's own counts
  RangeEncoder rc;
  auto models = std::make_unique<ClersModels>();
  // Component ends and handle lookup, walking backwards.
  std::vector<uint32_t> comp_end_of(plan.component_sizes.size());
  std::vector<uint8_t> is_first(nt, 0);
  {
    uint32_t s = 0;
    for (size_t k = 0; k < plan.component_sizes.size(); ++k) {
      is_first[s] = 1;
      s += plan.component_sizes[k];
      comp_end_of[k] = s;
    }
  }
  size_t comp = plan.component_sizes.size();
  size_t h = plan.handles.size();
  uint32_t prev1 = kE, prev2 = kE;
  for (uint32_t i = nt; i-- > 0;) {
    if (is_first[i]) {
      if (!sr.close_component(i)) return make_status(Error::internal, "6.4.7", 0, "encoder self-check: " + sr.error());
      --comp;
      continue;
    }
    if (h > 0 && plan.handles[h - 1].triangle == i) {
      --h;
      if (!sr.apply_handle(i, plan.handles[h], comp_end_of[comp - 1]))
        return make_status(Error::internal, "6.4.6", 0, "encoder self-check: " + sr.error());
      prev2 = prev1;
      prev1 = kS;
      continue;
    }
    const uint8_t s = plan.symbols[i];
    const uint32_t depth = sr.stack_depth();
    if (depth > 0) {  // §6.5.1 with no piece on the stack the symbol is E and is not coded
      BitModel* m = models->m[clers_context(prev1, prev2, sr.gate_start_count(), seam_context ? sr.gate_start_seam() : 0)];
      rc.encode_bit(m[0], s != kC);
      if (s != kC) {
        rc.encode_bit(m[1], s != kR);
        if (s != kR) {
          if (depth >= 2) rc.encode_bit(m[2], s != kS);
          if (s != kS) rc.encode_bit(m[3], s == kE);
        }
      }
    }
    if (!sr.apply(i, s)) return make_status(Error::internal, "6.4", 0, "encoder self-check: " + sr.error());
    prev2 = prev1;
    prev1 = s;
  }
  std::vector<uint32_t> rebuilt;
  if (!sr.finish(rebuilt) || rebuilt != plan.mesh.corner_vertex || sr.opposites() != plan.mesh.opp)
    return make_status(Error::internal, "6.4.8", 0, "encoder self-check: Spirale Reversi rebuilt another mesh " + sr.error());
  if (nt > 0) w.bytes(rc.finish());
  payload = std::move(w.buffer());
  return ok_status();
}

}  // namespace prm::codec
