#include "relief_envelope.h"

#include <algorithm>

namespace prm::remesh {

EdgeEnvelope upper_envelope(const AxisValues& a, const AxisValues& b, double snap) {
  EdgeEnvelope e;
  AxisValues slope{};
  bool all_zero = true;
  for (size_t k = 0; k < kReliefAxes; ++k) {
    slope[k] = b[k] - a[k];
    all_zero = all_zero && a[k] == 0 && b[k] == 0;
  }
  if (all_zero) return e;

  // The largest field at t = 0, ties to the larger slope, then to the lower index.
  size_t cur = 0;
  for (size_t k = 1; k < kReliefAxes; ++k)
    if (a[k] > a[cur] || (a[k] == a[cur] && slope[k] > slope[cur])) cur = k;
  e.count = 1;
  e.start[0] = 0;
  e.axis[0] = static_cast<int8_t>(cur);
  // Walk the envelope: the next field to overtake the current one is the first crossing among the steeper fields.
  double t = 0;
  for (int guard = 0; guard < kReliefAxes; ++guard) {
    size_t next = kReliefAxes;
    double next_t = 1;
    for (size_t k = 0; k < kReliefAxes; ++k) {
      if (!(slope[k] > slope[cur])) continue;
      // Crossing of k and cur; rounding may put it a hair before t, where k is already no lower: clamp.
      const double tk = std::max(t, (a[cur] - a[k]) / (slope[k] - slope[cur]));
      if (tk < next_t || (tk == next_t && next < kReliefAxes && slope[k] > slope[next])) {
        next_t = tk;
        next = k;
      }
    }
    if (next == kReliefAxes || !(next_t < 1)) break;
    t = next_t;
    cur = next;
    if (e.start[static_cast<size_t>(e.count - 1)] == t) {
      e.axis[static_cast<size_t>(e.count - 1)] = static_cast<int8_t>(cur);  // several crossings at one point
    } else {
      e.start[static_cast<size_t>(e.count)] = t;
      e.axis[static_cast<size_t>(e.count)] = static_cast<int8_t>(cur);
      ++e.count;
    }
  }
  e.start[static_cast<size_t>(e.count)] = 1;

  // Snap: remove the shortest piece while it is shorter than `snap`; pieces shorter than 1e-6 of the edge are
  // rounding (a crossing at an end) and always go, even with snap = 0: they would leave flat triangles.
  const double min_piece = std::max(snap, 1e-6);
  auto erase = [&](int i) {
    for (int j = i; j < e.count; ++j) {
      e.start[static_cast<size_t>(j)] = e.start[static_cast<size_t>(j + 1)];
      if (j + 1 < e.count) e.axis[static_cast<size_t>(j)] = e.axis[static_cast<size_t>(j + 1)];
    }
    --e.count;
  };
  while (e.count > 1) {
    int shortest = 0;
    double len = 2;
    for (int i = 0; i < e.count; ++i) {
      const double l = e.start[static_cast<size_t>(i + 1)] - e.start[static_cast<size_t>(i)];
      if (l < len) {
        len = l;
        shortest = i;
      }
    }
    if (!(len < min_piece)) break;
    const size_t s = static_cast<size_t>(shortest);
    if (shortest == 0) {
      erase(0);  // its successor now starts at 0
      e.start[0] = 0;
    } else if (shortest == e.count - 1) {
      e.start[s] = 1;  // the predecessor runs to 1
      --e.count;
    } else {
      const double mid = 0.5 * (e.start[s] + e.start[s + 1]);
      erase(shortest);  // the successor moves into slot s and starts at the middle
      e.start[s] = mid;
      if (e.axis[s] == e.axis[s - 1]) erase(shortest);
    }
  }
  return e;
}

}  // namespace prm::remesh
