// A remembered yes/no answer per ordered vertex triple (y, a, b): an open-addressing table (linear probing, 16
// bytes an entry, no allocation per entry). The seam collapses onto grid vertices (seam_collapses.cpp) ask
// triangle_ok of the same triangles again and again as neighbourhoods shrink (73% of the feline's queries at
// effort 0 are repeats, bench/README.md, tenth round); the vertices keep their data in that pass, so an answer
// stays valid while the pass runs.
#pragma once

#include <cstdint>
#include <vector>

namespace prm::remesh {

class TriangleAnswerMemo {
 public:
  // The remembered answer of (y, a, b): 1 yes, 0 no, -1 not known.
  int find(int32_t y, int32_t a, int32_t b) const {
    if (slots_.empty()) return -1;
    for (size_t i = home(y, a, b);; i = (i + 1) & mask()) {
      const Slot& s = slots_[i];
      if (s.state == kEmpty) return -1;
      if (s.y == y && s.a == a && s.b == b) return s.state == kYes ? 1 : 0;
    }
  }
  void add(int32_t y, int32_t a, int32_t b, bool ok) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    place(Slot{y, a, b, ok ? kYes : kNo});
    ++used_;
  }
  void clear() {
    std::vector<Slot>().swap(slots_);
    used_ = 0;
  }

 private:
  static constexpr uint32_t kEmpty = 0, kNo = 1, kYes = 2;
  struct Slot {
    int32_t y, a, b;
    uint32_t state;
  };
  size_t mask() const { return slots_.size() - 1; }
  size_t home(int32_t y, int32_t a, int32_t b) const {
    uint64_t h = static_cast<uint32_t>(y);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(a);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(b);
    h *= 0x9E3779B97F4A7C15ull;
    return static_cast<size_t>(h >> 32) & mask();
  }
  void place(const Slot& s) {
    size_t i = home(s.y, s.a, s.b);
    while (slots_[i].state != kEmpty) i = (i + 1) & mask();
    slots_[i] = s;
  }
  void grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(old.empty() ? size_t{1} << 12 : 2 * old.size(), Slot{0, 0, 0, kEmpty});
    for (const Slot& s : old)
      if (s.state != kEmpty) place(s);
  }

  std::vector<Slot> slots_;
  size_t used_ = 0;
};

}  // namespace prm::remesh
